"""The damping sub-models, registered by LAMMPS keyword: one entry each in :data:`DAMPING`.

Today one: ``velocity`` (:mod:`.velocity`), the paper's viscous damping. LAMMPS's others
(``mass_velocity``, ``viscoelastic``, ``tsuji``, ``coeff_restitution``) come as modules here.
"""

from __future__ import annotations

from ..base import DampingLaw, registry

__all__ = ["DAMPING", "DampingLaw"]

#: The registry: one entry per sub-model, the module (here) that defines its ``LAW``.
MODULES = (
    "velocity",
)
#: Every damping sub-model, by its LAMMPS keyword.
DAMPING: dict[str, DampingLaw] = registry(__name__, MODULES, "LAW")
