"""A batch of pairs as arrays, one per quantity: what the deck, the references and the checks read."""

from __future__ import annotations

from itertools import chain
from operator import attrgetter

import numpy as np

__all__ = ["pair_columns"]

_VECTORS = ("normal", "v_a", "v_b", "w_a", "w_b")
_SPHERE = ("m", "r", "alpha", "rigid")


def _floats(rows, shape: tuple[int, ...]) -> np.ndarray:
    """An array of ``shape`` from ``rows`` (its first axis), each row a tuple (of tuples, for a third axis) of
    floats: read as one stream (numpy reads nested tuples several times slower)."""
    flat = chain.from_iterable(rows)
    for _ in shape[2:]:
        flat = chain.from_iterable(flat)
    return np.fromiter(flat, dtype=float, count=int(np.prod(shape))).reshape(shape)


def pair_columns(pairs) -> dict[str, np.ndarray]:
    """The pairs as arrays: per sphere ``x`` of ``a`` and ``b``, its ``m_x``, ``r_x``, ``alpha_x`` and ``rigid_x``
    (N,) and its ``v_x`` and ``w_x`` (N, 3); and the ``normal`` (N, 3). Each pair's vectors read in one call, each
    distinct sphere's properties once (a batch's pairs mostly share their spheres)."""
    pairs = list(pairs)
    vectors = _floats(map(attrgetter(*_VECTORS), pairs), (len(pairs), len(_VECTORS), 3))
    out = {k: np.ascontiguousarray(vectors[:, i]) for i, k in enumerate(_VECTORS)}
    for side in ("a", "b"):
        spheres = list(map(attrgetter(side), pairs))
        rows = {key: tuple(float(getattr(s, k)) for k in _SPHERE) for key, s in {id(s): s for s in spheres}.items()}
        table = _floats((rows[id(s)] for s in spheres), (len(pairs), len(_SPHERE)))
        out |= {f"{k}_{side}": table[:, i].astype(bool) if k == "rigid" else np.ascontiguousarray(table[:, i])
                for i, k in enumerate(_SPHERE)}
    return out
