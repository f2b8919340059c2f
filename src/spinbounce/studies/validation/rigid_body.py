"""Rigid-body impact theory and the measures the benchmarks quote deviations in.

Rows of a state array are (v_n, v_t, r omega); the slip rate at the contact point is
v_t + r omega (the package's signs: v_n < 0 towards the wall, omega anticlockwise).
"""

from __future__ import annotations

import numpy as np

from ...model.scenes import ContactModel

__all__ = ["first_touch_stick", "impact_speed", "walton"]


def walton(model: ContactModel, states: np.ndarray, e: float, beta0: float) -> tuple[np.ndarray, list[str]]:
    """Walton's rigid-body impact law: final (v_n, v_t, r omega) and the regime of each state.

    The normal impulse is m (1 + e) |v_n|. The contact point's tangential velocity
    s = v_t + r omega would reverse to -beta0 s under the impulse
    J* = m alpha/(1 + alpha) (1 + beta0) s (the reduced mass of the slip); the impulse
    taken is J = sign(s) min(|J*|, mu m (1 + e) |v_n|). Sliding (the Coulomb bound reached)
    when alpha/(1 + alpha) (1 + beta0) |s| >= mu (1 + e) |v_n|. Then
    Delta v_t = -J/m and Delta(r omega) = -J/(alpha m). For a solid sphere
    alpha/(1 + alpha) = 2/7, the 3.5 mu (1 + e) |v_n| threshold of the literature.
    """
    states = np.asarray(states, dtype=float)
    v_n, v_t, w = states.T
    a = model.alpha
    s = v_t + w
    bound = model.mu * (1.0 + e) * np.abs(v_n)
    wanted = a / (1.0 + a) * (1.0 + beta0) * s
    sliding = np.abs(wanted) >= bound
    impulse = np.where(sliding, np.sign(s) * bound, wanted)
    final = np.column_stack([-e * v_n, v_t - impulse, w - impulse / a])
    return final, ["sliding" if k else "sticking" for k in sliding]


def first_touch_stick(model: ContactModel, states: np.ndarray) -> np.ndarray:
    """Estimated shortfall in r omega of a damped sliding contact from the rigid-body outcome.

    With gamma_n > 0 the cap starts at c0 = mu gamma_n |v_n| > 0, so a contact that slides
    for the rest of the impact first sticks while the spring force kt |u'| t grows to the
    cap, for about t0 = c0/(kt |u'|); the friction impulse falls short of mu times the
    normal impulse by about c0 t0/2, and r omega (which takes 1/alpha of it per unit mass)
    by c0^2/(2 kt |u'| alpha m). Zero without damping."""
    states = np.asarray(states, dtype=float)
    c0 = model.mu * model.gamma_n * np.abs(states[:, 0])
    slip = np.abs(states[:, 1] + states[:, 2])
    with np.errstate(divide="ignore"):
        return np.where(slip > 0.0, c0**2 / (2.0 * model.kt * slip * model.alpha * model.m), np.inf)


def impact_speed(states: np.ndarray) -> np.ndarray:
    """The contact point's speed at first touch, sqrt(v_n^2 + (v_t + r omega)^2).

    Deviations are quoted relative to it: it sets the size of every outgoing component
    (for a pure spin drop it is the spin's surface speed, for an oblique impact |v|)."""
    states = np.asarray(states, dtype=float)
    return np.hypot(states[:, 0], states[:, 1] + states[:, 2])
