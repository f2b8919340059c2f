"""A batch of pairs as arrays, one per quantity: what the deck, the references and the checks read."""

from __future__ import annotations

import numpy as np

__all__ = ["pair_columns"]


def pair_columns(pairs) -> dict[str, np.ndarray]:
    """The pairs as arrays: per sphere ``x`` of ``a`` and ``b``, its ``m_x``, ``r_x``, ``alpha_x`` and ``rigid_x``
    (N,) and its ``v_x`` and ``w_x`` (N, 3); and the ``normal`` (N, 3)."""
    out = {k: np.array([getattr(p, k) for p in pairs], dtype=float).reshape(-1, 3)
           for k in ("normal", "v_a", "v_b", "w_a", "w_b")}
    for side in ("a", "b"):
        spheres = [getattr(p, side) for p in pairs]
        out |= {f"{k}_{side}": np.array([getattr(s, k) for s in spheres]) for k in ("m", "r", "alpha", "rigid")}
    return out
