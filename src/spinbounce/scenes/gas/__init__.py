"""A gas of frictional spheres: N equal spheres in a periodic box, their translational and rotational
temperatures in LAMMPS beside the two-temperature theory of a dilute rough-sphere gas
(:mod:`spinbounce.exact.kinetic`) with its collisions' energy changes from the paper's matrix and from
the project's pair outcomes (:mod:`.collisions`). See theory.md.

``scene.py`` (the :class:`Gas`, checked when built), ``deck.py`` and ``gas.lmp.j2`` (its deck, which
runs in process or on K ranks under ``mpiexec``), ``table.py`` (its series) and ``collisions.py``
(the pair-level energy changes, by the exact references or by LAMMPS at the gas's step).
"""

from .parameters import GAS

__all__ = ["GAS"]
