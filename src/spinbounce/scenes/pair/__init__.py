"""Sphere-sphere collisions (theory.md): pairs of free spheres that meet once, many per run.

:mod:`.scene` (Sphere, PairContact, Pair, PairBatch), :mod:`.deck` (``pair.lmp.j2``),
:mod:`.table` (each pair beside the exact reference and the planar theory), :mod:`.kind`
(a pair as the wall's scene with sphere b in place of the wall).
"""

from .deck import QUANTITIES
from .scene import Pair, PairBatch, PairContact, Sphere

__all__ = ["Sphere", "PairContact", "Pair", "PairBatch", "QUANTITIES"]
