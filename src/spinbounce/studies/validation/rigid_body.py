"""Rigid-body impact theory and the measures the benchmarks quote deviations in.

Rows of a state array are (v_n, v_t, r omega); the slip rate at the contact point is
v_t + r omega (the package's signs: v_n < 0 towards the wall, omega anticlockwise).
"""

from __future__ import annotations

import numpy as np

from ...model.contact import ContactModel
from ...exact.rigid_body import walton

__all__ = ["first_touch_stick", "impact_speed", "walton"]


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
