"""The tangential sub-models, registered by LAMMPS keyword: one entry each in :data:`TANGENTIAL`.

``linear_history`` (:mod:`.linear_history`) is the paper's Cundall-Strack spring;
``linear_history_classic`` (:mod:`.linear_history_classic`) the classic wall's; the Mindlin
variants (:mod:`.mindlin`: ``mindlin``, ``mindlin/force``, ``mindlin_rescale``,
``mindlin_rescale/force``) grow their stiffness with the contact radius.
"""

from __future__ import annotations

from ..base import Kind, TangentialLaw, registry

__all__ = ["TANGENTIAL", "TangentialLaw", "tangential_law", "tangential_coefficients", "tangential_parameter"]

#: The registry: one entry per sub-model, the module (here) that defines its ``LAW``.
MODULES = (
    "linear_history",
    "linear_history_classic",
    "mindlin",
    "mindlin_force",
    "mindlin_rescale",
    "mindlin_rescale_force",
)
#: Every tangential sub-model, by its LAMMPS keyword.
TANGENTIAL: dict[str, TangentialLaw] = registry(__name__, MODULES, "LAW")


#: The kind: its parameter, its registry, its default and its deck's words.
KIND = Kind("tangential", "tangential force law", TANGENTIAL, TangentialLaw.default_keyword,
            "wall/gran granular ... tangential TANGENTIAL ... | pair_coeff * * ... tangential TANGENTIAL ...")
tangential_law, tangential_coefficients, tangential_parameter = KIND.law, KIND.coefficients, KIND.parameter
