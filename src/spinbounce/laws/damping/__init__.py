"""The damping sub-models, registered by LAMMPS keyword: one entry each in :data:`DAMPING`.

``velocity`` (:mod:`.velocity`) is the paper's viscous damping; ``mass_velocity``, ``tsuji``,
``coeff_restitution`` and ``viscoelastic`` make dashpots from a coefficient LAMMPS scales by the
contact (:mod:`.scaled`): constant with the Hookean force except viscoelastic's, which grows
with the contact radius, as tsuji's and coeff_restitution's do with the Hertzian force.
"""

from __future__ import annotations

from ..base import DampingLaw, Kind, registry

__all__ = ["DAMPING", "DampingLaw", "damping_law", "damping_coefficients", "damping_parameter"]

#: The registry: one entry per sub-model, the module (here) that defines its ``LAW``.
MODULES = (
    "velocity",
    "mass_velocity",
    "tsuji",
    "coeff_restitution",
    "viscoelastic",
)
#: Every damping sub-model, by its LAMMPS keyword.
DAMPING: dict[str, DampingLaw] = registry(__name__, MODULES, "LAW")


#: The kind: its parameter, its registry, its default and its deck's words.
KIND = Kind("damping", "damping model", DAMPING, DampingLaw.default_keyword,
            "granular NORMAL KN ETA_N damping DAMPING")
damping_law, damping_coefficients, damping_parameter = KIND.law, KIND.coefficients, KIND.parameter
