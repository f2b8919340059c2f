"""The files a deck reads beside it: the data file of spheres (``read_data``) and the rigid
bodies' file (``fix rigid ... infile``), one writer each, for every scene.

A sphere whose alpha is not fix nve/sphere's 2/5 is a rigid body of two atoms: the sphere,
holding half its mass, and a point (diameter 0) at its centre holding the other half, whose
inertia the bodies file sets. Numbers are written in their shortest round-trip form, so
LAMMPS reads exactly the values the scene holds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import __version__

__all__ = ["Atoms", "data_file", "bodies_file", "table", "deck_number"]


def deck_number(x) -> str:
    """A float in full precision (repr round-trips exactly)."""
    v = float(x)
    if not math.isfinite(v):
        raise ValueError(f"non-finite number {v!r} in a deck")
    return repr(v + 0.0)  # + 0.0 turns -0.0 into 0.0


def table(columns: list[np.ndarray]) -> str:
    """Space-separated rows; every float in its shortest round-trip form (exact on reading).

    Written by Arrow's CSV writer: about five times faster than ``numpy.savetxt``.
    """
    import pyarrow as pa
    import pyarrow.csv as pacsv

    arrays = pa.table({f"c{i}": np.asarray(c) for i, c in enumerate(columns)})
    sink = pa.BufferOutputStream()
    pacsv.write_csv(arrays, sink, pacsv.WriteOptions(include_header=False, delimiter=" ", quoting_style="none"))
    return sink.getvalue().to_pybytes().decode()


@dataclass(frozen=True)
class Atoms:
    """The atoms of a data file: ids, types, diameters and masses, positions x, velocities v and
    angular velocities w ((n, 3) each). A point (diameter 0) is written with its mass as its
    'density', as LAMMPS reads it; a sphere with mass over volume."""

    ids: np.ndarray
    types: np.ndarray
    diameter: np.ndarray
    mass: np.ndarray
    x: np.ndarray
    v: np.ndarray
    w: np.ndarray

    @property
    def density(self) -> np.ndarray:
        d = np.asarray(self.diameter, dtype=float)
        volume = math.pi * d**3 / 6.0
        return np.where(d > 0.0, np.asarray(self.mass, dtype=float) / np.where(d > 0.0, volume, 1.0), self.mass)


def data_file(title: str, atoms: Atoms, ntypes: int, box: tuple) -> str:
    """A data file (atom_style sphere): ``box`` is ((xlo, xhi), (ylo, yhi), (zlo, zhi)); atoms in
    id order."""
    order = np.argsort(atoms.ids, kind="stable")
    x, v, w = (np.asarray(a, dtype=float)[order] for a in (atoms.x, atoms.v, atoms.w))
    ids = np.asarray(atoms.ids)[order]
    rows = table([ids, np.asarray(atoms.types)[order], np.asarray(atoms.diameter, dtype=float)[order],
                  atoms.density[order], x[:, 0], x[:, 1], x[:, 2]])
    velocities = table([ids, v[:, 0], v[:, 1], v[:, 2], w[:, 0], w[:, 1], w[:, 2]])
    sides = "".join(f"{deck_number(lo)} {deck_number(hi)} {axis}lo {axis}hi\n" for axis, (lo, hi) in zip("xyz", box))
    return (f"spinbounce {__version__}: {title}\n\n{len(ids)} atoms\n{ntypes} atom types\n\n{sides}\n"
            f"Atoms # sphere\n\n{rows}\nVelocities\n\n{velocities}")


def bodies_file(ids: np.ndarray, mass: np.ndarray, x: np.ndarray, inertia: np.ndarray, v: np.ndarray,
                w: np.ndarray) -> str:
    """fix rigid infile: id mass xcm ycm zcm ixx iyy izz ixy ixz iyz vxcm vycm vzcm lx ly lz ix iy iz,
    one body per sphere (a sphere's moment of inertia is the same about every axis)."""
    n = len(ids)
    i, zeros = np.asarray(inertia, dtype=float), np.zeros(n)
    x, v, w = (np.asarray(a, dtype=float) for a in (x, v, w))
    columns = [np.asarray(ids), np.asarray(mass, dtype=float), x[:, 0], x[:, 1], x[:, 2], i, i, i, zeros, zeros, zeros,
               v[:, 0], v[:, 1], v[:, 2], i * w[:, 0], i * w[:, 1], i * w[:, 2], zeros, zeros, zeros]
    return f"{n}\n" + table(columns)
