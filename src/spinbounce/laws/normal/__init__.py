"""The normal sub-models, registered by LAMMPS keyword: one line each in :data:`NORMAL`."""

from __future__ import annotations

from ...declaration import Parameter
from ..base import NormalLaw, choice, coefficients, lookup, registry

__all__ = ["NORMAL", "NormalLaw", "normal_law", "normal_parameter", "normal_coefficients"]

#: The registry: one entry per sub-model, the module (here) that defines its ``LAW``.
MODULES = (
    "hooke",
    "hertz",
    "hertz_material",
)
#: Every normal sub-model, by its LAMMPS keyword.
NORMAL: dict[str, NormalLaw] = registry(__name__, MODULES, "LAW")


def normal_law(keyword: str) -> NormalLaw:
    """The sub-model of ``keyword``, or a :class:`SceneError` listing the registered ones."""
    return lookup(NORMAL, "normal", keyword)


def normal_coefficients() -> tuple[Parameter, ...]:
    """Every normal sub-model's coefficients, each once, in registry order."""
    return coefficients(NORMAL)


def normal_parameter() -> Parameter:
    """The ``normal`` choice: one of the registered keywords."""
    return choice("normal", "normal force law", NORMAL, NormalLaw.default_keyword,
                  "wall/gran granular NORMAL ... | pair_coeff * * NORMAL ...")
