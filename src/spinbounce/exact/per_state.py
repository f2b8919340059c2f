"""References given a state at a time over an (n, 3) or (n, 6) array of initial states, for exact.choose: the
oracle's (a state whose LAMMPS outcome has no dt -> 0 limit, :class:`~spinbounce.errors.NoLimit`, refused, or NaN
with their number warned of) and the classic wall's theory.
"""

from __future__ import annotations

import warnings

import numpy as np

from ..errors import NoLimit, PhysicsWarning

__all__ = ["oracle", "classic", "classic_wall"]


def oracle(model, initial, limitless: str = "raise") -> np.ndarray:
    """Final states from exact.oracle, one state at a time (``limitless``: :func:`.choose.predict`'s)."""
    from . import oracle as by_oracle

    if limitless == "nan":
        return _limitless_nan(lambda state: oracle(model, state[None, :]), initial)
    r = model.r
    spins = initial[:, [2, 4, 5]] / r if initial.shape[1] == 6 else np.column_stack([initial[:, 2] / r,
                                                                                      np.zeros((len(initial), 2))])
    v_s = initial[:, 3] if initial.shape[1] == 6 else None
    return by_oracle.bounce_many(model, initial[:, 0], initial[:, 1], spins[:, 0], v_s, spins[:, 1],
                                 spins[:, 2])[:, :initial.shape[1]]


def _limitless_nan(one, initial) -> np.ndarray:
    """``one(state)`` for each state, NaN where it has no limit (:class:`NoLimit`), their number warned of."""
    out, refused = np.full(initial.shape, np.nan), []
    for k, state in enumerate(initial):
        try:
            out[k] = one(state)[0]
        except NoLimit as exc:
            refused.append(str(exc))
    if refused:
        warnings.warn(f"{len(refused)} of {len(initial)} state(s) have no reference (status no_limit), the first: "
                      f"{refused[0]}", PhysicsWarning, stacklevel=3)
    return out


def classic(model, initial) -> np.ndarray:
    """The classic wall's theory (:mod:`.classic`), one state (v_n, v_t, r omega) at a time."""
    from . import classic as exact_classic

    wall = classic_wall(model)
    return np.array([exact_classic.bounce(wall, *state).final for state in initial])


def classic_wall(model):
    """The classic wall's own parameters, as its style gives them to the deck (its dashpots are
    rates gamma/m, its cap at most 1e4: :class:`spinbounce.laws.styles.Classic`); or, for the
    classic spring inside ``granular`` (``linear_history_classic``), the model's own."""
    from . import classic as exact_classic

    if model.style.tangential_contact_radius:
        values = model.style.coefficients(model)
    else:
        values = {"kn": model.kn, "kt": model.kt, "gamma_n": model.gamma_n / model.m,
                  "gamma_t": model.gamma_t / model.m, "mu": model.mu}
    return exact_classic.ClassicWall(**values, alpha=model.alpha, r=model.r, m=model.m)
