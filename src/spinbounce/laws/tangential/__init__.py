"""The tangential sub-models, registered by LAMMPS keyword: one entry each in :data:`TANGENTIAL`.

``linear_history`` (:mod:`.linear_history`) is the paper's Cundall-Strack spring;
``linear_history_classic`` (:mod:`.linear_history_classic`) the classic wall's; the Mindlin
variants (:mod:`.mindlin`: ``mindlin``, ``mindlin/force``, ``mindlin_rescale``,
``mindlin_rescale/force``) grow their stiffness with the contact radius.
"""

from __future__ import annotations

from ...declaration import Parameter
from ..base import TangentialLaw, choice, coefficients, lookup, registry

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


def tangential_law(keyword: str) -> TangentialLaw:
    """The sub-model of ``keyword``, or a :class:`SceneError` listing the registered ones."""
    return lookup(TANGENTIAL, "tangential", keyword)


def tangential_coefficients() -> tuple[Parameter, ...]:
    """Every tangential sub-model's coefficients, each once, in registry order."""
    return coefficients(TANGENTIAL)


def tangential_parameter() -> Parameter:
    """The ``tangential`` choice: one of the registered keywords."""
    return choice("tangential", "tangential force law", TANGENTIAL, TangentialLaw.default_keyword,
                  "wall/gran granular ... tangential TANGENTIAL ... | pair_coeff * * ... tangential TANGENTIAL ...")
