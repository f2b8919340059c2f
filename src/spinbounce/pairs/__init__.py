"""Sphere-sphere collisions: the pair analogue of the wall's scene, deck and run.

:mod:`.scene` (Sphere, PairContact, Pair, PairBatch), :mod:`.deck` (``lammps_inputs/pair.lmp.j2``),
:mod:`.run` (run_pairs and the per-pair table), :mod:`.studies` (the claims, the validity map
and the cost against the wall).
"""

from .deck import PairDeck, render_pairs
from .run import QUANTITIES, PairResult, pair_table, run_pairs
from .scene import Pair, PairBatch, PairContact, Sphere

__all__ = ["Sphere", "PairContact", "Pair", "PairBatch", "PairDeck", "render_pairs", "PairResult", "run_pairs",
           "pair_table", "QUANTITIES"]
