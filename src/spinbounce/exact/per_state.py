"""References given a state at a time over an (n, 3) or (n, 6) array of initial states, for exact.choose: the
oracle's (a state whose LAMMPS outcome has no dt -> 0 limit, :class:`~spinbounce.errors.NoLimit`, refused, or NaN
with their number warned of) and the classic wall's theory.
"""

from __future__ import annotations

import warnings
from collections import OrderedDict

import numpy as np

from ..errors import NoLimit, PhysicsWarning

__all__ = ["oracle", "classic", "classic_wall", "KEPT"]


def oracle(model, initial, limitless: str = "raise") -> np.ndarray:
    """Final states from exact.oracle, one state at a time (``limitless``: :func:`.choose.predict`'s), each kept
    for the next batch that asks (a step probe's runs ask for the same states again, :data:`KEPT`)."""
    out, refused, fresh = np.empty(initial.shape), [], 0
    for k, state in enumerate(initial):
        key = (model, state.tobytes())
        if key not in _KEPT:
            _KEPT[key], fresh = _one(model, state), fresh + 1
        _KEPT.move_to_end(key)
        found = _KEPT[key]
        if isinstance(found, str):  # no limit: its reason
            if limitless != "nan":
                raise NoLimit(found)
            out[k] = np.nan
            refused.append(found)
        else:
            out[k] = found
    while len(_KEPT) > KEPT:
        _KEPT.popitem(last=False)
    if refused and fresh:  # told once, where first found
        warnings.warn(f"{len(refused)} of {len(initial)} state(s) have no reference (status no_limit), the first: "
                      f"{refused[0]}", PhysicsWarning, stacklevel=3)
    return out


def _one(model, state):
    """One state's final state by exact.oracle, or the reason it has no limit."""
    from . import oracle as by_oracle

    r = model.r
    spins = state[[2, 4, 5]] / r if state.size == 6 else (state[2] / r, 0.0, 0.0)
    try:
        final = by_oracle.bounce(model, state[0], state[1], spins[0], v_s=state[3] if state.size == 6 else 0.0,
                                 omega_s=spins[1], omega_n=spins[2]).final
    except NoLimit as exc:
        return str(exc)
    return final[:state.size]


#: States kept (oldest dropped first): a probe runs the same states at up to five steps.
KEPT = 4096
_KEPT: OrderedDict = OrderedDict()


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
