"""spinbounce: LAMMPS reproduction of a frictional sphere's scattering from a flat wall.

The Python API (:mod:`spinbounce.api`, whose docstring shows it at work) is at the top:
``spinbounce.collide``, ``theory``, ``frozen``, ``sweep``, ``fit`` and ``gas``. Importing the package never
imports LAMMPS; only :mod:`spinbounce.lammps.runner` does, when a run starts, and the API's
modules load on first use.
"""

import importlib

#: The package's version, declared here once: the build reads it (pyproject.toml's [tool.hatch.version]). A
#: literal, not importlib.metadata's lookup, which cost every process 0.12 s of imports before its first line.
__version__ = "0.1.0"

__all__ = ["__version__", "collide", "theory", "frozen", "sweep", "fit", "gas", "parameters"]

#: The API's functions. None of them shares its name with a module of the package: importing
#: a submodule sets the package's attribute of that name, which would hide a function.
_API = ("collide", "theory", "frozen", "sweep", "fit", "gas")


def __getattr__(name: str):
    if name in _API:
        return getattr(importlib.import_module(".api", __name__), name)
    if name == "parameters":  # the declaration: every parameter's name, unit, default and range
        return importlib.import_module(".model.parameters", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
