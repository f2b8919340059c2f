"""The normal sub-models, registered by LAMMPS keyword: one line each in :data:`NORMAL`."""

from __future__ import annotations

from ..base import Kind, NormalLaw, registry

__all__ = ["NORMAL", "NormalLaw", "normal_law", "normal_parameter", "normal_coefficients"]

#: The registry: one entry per sub-model, the module (here) that defines its ``LAW``.
MODULES = (
    "hooke",
    "hertz",
    "hertz_material",
)
#: Every normal sub-model, by its LAMMPS keyword.
NORMAL: dict[str, NormalLaw] = registry(__name__, MODULES, "LAW")


#: The kind: its parameter, its registry, its default and its deck's words.
KIND = Kind("normal", "normal force law", NORMAL, NormalLaw.default_keyword,
            "wall/gran granular NORMAL ... | pair_coeff * * NORMAL ...")
normal_law, normal_coefficients, normal_parameter = KIND.law, KIND.coefficients, KIND.parameter
