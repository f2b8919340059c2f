"""What the benchmarks plot and measure: the literature's normalised quantities of an impact,
rigid-body theory and the measures deviations are quoted in.

Rows of a state array are (v_n, v_t, r omega), ' marks the rebound; the slip rate at the
contact point is v_t + r omega (the package's signs: v_n < 0 towards the wall, omega
anticlockwise).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ...model.contact import ContactModel
from ...exact.rigid_body import walton

__all__ = ["QUANTITIES", "first_touch_stick", "impact_speed", "quantity", "restitution", "walton"]


def restitution(model: ContactModel, states) -> np.ndarray:
    """Each state's normal restitution (the Hookean one's constant; a Hertzian one's per speed)."""
    return model.normal_law.restitutions(model, np.atleast_2d(np.asarray(states, dtype=float))[:, 0])


def _q(label: str, unit: str, f: Callable) -> dict:
    return {"label": label, "unit": unit, "f": f}


#: name -> label, unit and f(initial (n, 3), final (n, 3), model) -> values.
QUANTITIES: dict[str, dict] = {
    "theta": _q(r"incidence angle $\theta$ (deg)", "deg",
                lambda i, f, m: np.degrees(np.arctan2(i[:, 1], -i[:, 0]))),
    "e_t": _q(r"$e_t = v_t'/v_t$", "", lambda i, f, m: f[:, 1] / i[:, 1]),
    "omega_out": _q(r"$\omega'$ (rad/s)", "rad/s", lambda i, f, m: f[:, 2] / m.r),
    "rebound_contact": _q(r"contact-point rebound angle (deg)", "deg",
                          lambda i, f, m: np.degrees(np.arctan((f[:, 1] + f[:, 2]) / f[:, 0]))),
    "rebound_centre": _q(r"centre-of-mass rebound angle (deg)", "deg",
                         lambda i, f, m: np.degrees(np.arctan(f[:, 1] / f[:, 0]))),
    "psi1": _q(r"$\Psi_1 = 2 v_t/(\mu(1+e)|v_n|)$", "",
               lambda i, f, m: 2.0 * (i[:, 1] + i[:, 2]) / (m.mu * (1.0 + restitution(m, i)) * np.abs(i[:, 0]))),
    "psi2": _q(r"$\Psi_2 = 2(v_t'+r\omega')/(\mu(1+e)|v_n|)$", "",
               lambda i, f, m: 2.0 * (f[:, 1] + f[:, 2])
               / (m.mu * (1.0 + restitution(m, i)) * np.abs(i[:, 0]))),
    "spin_thornton": _q(r"$2r\omega'/(\mu(1+e)|v_n|)$", "",
                        lambda i, f, m: 2.0 * f[:, 2] / (m.mu * (1.0 + restitution(m, i)) * np.abs(i[:, 0]))),
    "incident_co5": _q(r"$V_{st}/(\mu V_{cn})$", "",
                       lambda i, f, m: (i[:, 1] + i[:, 2]) / (m.mu * np.abs(i[:, 0]))),
    "recoil_co5": _q(r"$V'_{st}/(\mu V'_{cn})$", "", lambda i, f, m: (f[:, 1] + f[:, 2]) / (m.mu * f[:, 0])),
    "spin_co5": _q(r"$r\omega'/(\mu V_{cn})$", "", lambda i, f, m: f[:, 2] / (m.mu * np.abs(i[:, 0]))),
    "x_co6": _q(r"$3.5\mu(1+e)V_{cn}/V_{st}$", "",
                lambda i, f, m: 3.5 * m.mu * (1.0 + restitution(m, i)) * np.abs(i[:, 0]) / (i[:, 1] + i[:, 2])),
    "beta_co6": _q(r"$\beta = -V'_{st}/V_{st}$", "", lambda i, f, m: -(f[:, 1] + f[:, 2]) / (i[:, 1] + i[:, 2])),
    "tan_incident": _q(r"$V_{st}/V_{cn}$", "", lambda i, f, m: (i[:, 1] + i[:, 2]) / np.abs(i[:, 0])),
    "tan_recoil": _q(r"$V'_{st}/V'_{cn}$", "", lambda i, f, m: (f[:, 1] + f[:, 2]) / f[:, 0]),
}


def quantity(name: str, initial, final, model: ContactModel) -> np.ndarray:
    """The quantity ``name`` of :data:`QUANTITIES` for initial and final states (rows or arrays of rows)."""
    return np.asarray(QUANTITIES[name]["f"](np.atleast_2d(initial), np.atleast_2d(final), model), dtype=float)


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
