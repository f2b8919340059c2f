"""The normal sub-models, registered by LAMMPS keyword: one line each in :data:`NORMAL`."""

from __future__ import annotations

from ...declaration import Parameter
from ..base import NormalLaw, lookup, registry

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
    return tuple(dict.fromkeys(p for law in NORMAL.values() for p in law.coefficients))


def normal_parameter() -> Parameter:
    """The ``normal`` choice: one of the registered keywords."""
    laws = "; ".join(f"{law.keyword}: {law.summary}" for law in NORMAL.values())
    return Parameter("normal", f"normal force law ({laws})", "-", NormalLaw.default_keyword, kind="choice",
                     choices=tuple(NORMAL),
                     deck="wall/gran granular NORMAL ... | pair_coeff * * NORMAL ...")
