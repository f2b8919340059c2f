"""What the benchmarks plot: the literature's normalised quantities of an impact."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ...model.contact import ContactModel

__all__ = ["QUANTITIES", "quantity"]


def _e(model):
    return model.restitution


def _q(label: str, unit: str, f: Callable) -> dict:
    return {"label": label, "unit": unit, "f": f}


#: name -> label, unit and f(initial (n, 3), final (n, 3), model) -> values.
#: Rows are (v_n, v_t, r omega); ' marks the rebound.
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
               lambda i, f, m: 2.0 * (i[:, 1] + i[:, 2]) / (m.mu * (1.0 + _e(m)) * np.abs(i[:, 0]))),
    "psi2": _q(r"$\Psi_2 = 2(v_t'+r\omega')/(\mu(1+e)|v_n|)$", "",
               lambda i, f, m: 2.0 * (f[:, 1] + f[:, 2]) / (m.mu * (1.0 + _e(m)) * np.abs(i[:, 0]))),
    "spin_thornton": _q(r"$2r\omega'/(\mu(1+e)|v_n|)$", "",
                        lambda i, f, m: 2.0 * f[:, 2] / (m.mu * (1.0 + _e(m)) * np.abs(i[:, 0]))),
    "incident_co5": _q(r"$V_{st}/(\mu V_{cn})$", "",
                       lambda i, f, m: (i[:, 1] + i[:, 2]) / (m.mu * np.abs(i[:, 0]))),
    "recoil_co5": _q(r"$V'_{st}/(\mu V'_{cn})$", "", lambda i, f, m: (f[:, 1] + f[:, 2]) / (m.mu * f[:, 0])),
    "spin_co5": _q(r"$r\omega'/(\mu V_{cn})$", "", lambda i, f, m: f[:, 2] / (m.mu * np.abs(i[:, 0]))),
    "x_co6": _q(r"$3.5\mu(1+e)V_{cn}/V_{st}$", "",
                lambda i, f, m: 3.5 * m.mu * (1.0 + _e(m)) * np.abs(i[:, 0]) / (i[:, 1] + i[:, 2])),
    "beta_co6": _q(r"$\beta = -V'_{st}/V_{st}$", "", lambda i, f, m: -(f[:, 1] + f[:, 2]) / (i[:, 1] + i[:, 2])),
    "tan_incident": _q(r"$V_{st}/V_{cn}$", "", lambda i, f, m: (i[:, 1] + i[:, 2]) / np.abs(i[:, 0])),
    "tan_recoil": _q(r"$V'_{st}/V'_{cn}$", "", lambda i, f, m: (f[:, 1] + f[:, 2]) / f[:, 0]),
}


def quantity(name: str, initial, final, model: ContactModel) -> np.ndarray:
    """The quantity ``name`` of :data:`QUANTITIES` for initial and final states (rows or arrays of rows)."""
    return np.asarray(QUANTITIES[name]["f"](np.atleast_2d(initial), np.atleast_2d(final), model), dtype=float)

