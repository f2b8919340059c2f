"""Rigid-body impact with Coulomb friction: the one definition of the sliding impulse.

A contact that slides the whole impact in one direction takes, per unit mass, the
tangential impulse mu times the normal one, (1 + e)|v_n|, against the slip. That is
exact for the spring-dashpot contact whenever F_n >= 0 throughout (gamma_n = 0, or
``limit_damping``): :func:`gross_slip`. Walton's law (:func:`walton`) caps the impulse of
a rigid impact with a tangential restitution beta0 at that bound. Rows of a state array
are (v_n, v_t, r omega) with the paper's signs: the slip rate is v_t + r omega.
"""

from __future__ import annotations

import numpy as np

__all__ = ["sliding_bound", "gross_slip", "walton"]


def sliding_bound(model, v_n, e: float) -> np.ndarray:
    """mu (1 + e)|v_n|: the largest tangential impulse per unit mass, the one of a full slide."""
    return model.mu * (1.0 + e) * np.abs(np.asarray(v_n, dtype=float))


def gross_slip(model, v_n, v_t, omega, e: float) -> np.ndarray:
    """(v_n, v_t, r omega) after a contact that slides from first touch to exit in one direction
    (array arguments broadcast; the last axis of the result holds the state). A slip of
    exactly zero counts as positive, as a slide needs a direction."""
    v_n, v_t, omega = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (v_n, v_t, omega)))
    r_omega = model.r * omega
    dv = -sliding_bound(model, v_n, e) * np.copysign(1.0, v_t + r_omega)
    return np.stack([-e * v_n, v_t + dv, r_omega + dv / model.alpha], axis=-1)


def walton(model, states: np.ndarray, e: float, beta0: float) -> tuple[np.ndarray, list[str]]:
    """Walton's rigid-body impact law: final (v_n, v_t, r omega) and the regime of each state.

    The contact point's tangential velocity s = v_t + r omega would reverse to -beta0 s under
    the impulse J* = m alpha/(1 + alpha)(1 + beta0) s (the slip's reduced mass); the impulse
    taken is sign(s) min(|J*|, :func:`sliding_bound`), and it slides where the bound is
    reached. Then Delta v_t = -J/m and Delta(r omega) = -J/(alpha m). For a solid sphere
    alpha/(1 + alpha) = 2/7: the 3.5 mu (1 + e)|v_n| threshold of the literature.
    """
    states = np.asarray(states, dtype=float)
    v_n, v_t, w = states.T
    a = model.alpha
    s = v_t + w
    bound = sliding_bound(model, v_n, e)
    wanted = a / (1.0 + a) * (1.0 + beta0) * s
    sliding = np.abs(wanted) >= bound
    impulse = np.where(sliding, np.sign(s) * bound, wanted)
    final = np.column_stack([-e * v_n, v_t - impulse, w - impulse / a])
    return final, ["sliding" if k else "sticking" for k in sliding]
