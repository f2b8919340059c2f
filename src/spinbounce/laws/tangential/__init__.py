"""The tangential sub-models, registered by LAMMPS keyword: one entry each in :data:`TANGENTIAL`.

Today one: ``linear_history`` (:mod:`.linear_history`), the paper's Cundall-Strack spring with
a Coulomb cap. LAMMPS's others (``mindlin`` and its variants, ...) come as modules here.
"""

from __future__ import annotations

from ..base import TangentialLaw, registry

__all__ = ["TANGENTIAL", "TangentialLaw"]

#: The registry: one entry per sub-model, the module (here) that defines its ``LAW``.
MODULES = (
    "linear_history",
)
#: Every tangential sub-model, by its LAMMPS keyword.
TANGENTIAL: dict[str, TangentialLaw] = registry(__name__, MODULES, "LAW")
