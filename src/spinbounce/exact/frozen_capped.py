"""The frozen contact under a Coulomb cap: a tangential spring (and dashpot) whose force may not
exceed a constant cap.

Held at a fixed height the normal force F_n is constant, so the cap F_c = mu F_n is too. With
the slip u = v_t + r omega and the spring's history xi (its stretch), the tangential force is
F = -(kt xi + gamma_t u) while it sticks (|kt xi + gamma_t u| < F_c): xi' = u and
u' = K F, K = (1 + alpha)/(alpha m) (the sphere's m dv_t/dt = F and I domega/dt = r F). When
|kt xi + gamma_t u| reaches F_c the contact slips: F = -s F_c (s the sign of the spring's
force's opposite), u falls at the constant rate K F_c, and the history is held where the force
is the cap, xi = (s F_c - gamma_t u)/kt (LAMMPS's ``linear_history`` resets it there each step).
A force beyond the cap (a dashpot's, at the start) is brought to it the same way, by the history.
It sticks again once the unconstrained force would fall back inside the cap:
s (kt u + gamma_t u') < 0, that is s u < gamma_t K F_c/kt (u = 0 without a dashpot). An
undamped spring then oscillates with the cap as its amplitude and never slips again.

``linear_history_classic`` (``reset_k``: this build's classic spring, kt a on the history, reset by kt
alone) leaves the history at (s F_c - gamma_t u)/kt instead, so the force after a capped step is
f s F_c + (1 - f) gamma_t u with f = a: it sticks again at once below the cap (a sawtooth), or slides
while gamma_t |u| >= F_c (:mod:`.oracle_classic`, whose Zeno point after a slide it checks the same way).

Stick phases are integrated (scipy's DOP853 at rtol 1e-12, the cap an event), slip phases are
exact straight lines. Every force acts on v_t and r omega in the ratio alpha : 1 (Eq. 13), so
v_t = v_t0 + alpha/(1 + alpha) (u - u0) and r omega = r omega0 + (u - u0)/(1 + alpha).
"""

from __future__ import annotations

import numpy as np

from .oracle_classic import NEAR_ONE, check_limit, is_zeno, reset

__all__ = ["frozen_velocities", "slip"]

#: Most stick-slip switches followed (an undamped spring touches its cap twice a period).
MAX_SWITCHES = 100_000


def frozen_velocities(t, v_t0: float, r_omega0: float, kt: float, m: float, alpha: float, gamma_t: float,
                      cap: float, reset_k: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(v_t(t), r omega(t)) of the frozen contact with the force capped at ``cap`` = mu F_n (``reset_k``: the
    classic spring's k alone, which the history is reset by; :class:`.NoLimit` where its teeth after a slide
    set the outcome)."""
    u0, t, K = float(v_t0) + float(r_omega0), np.asarray(t, dtype=float), (1.0 + alpha) / (alpha * m)
    zeno: list[bool] = []
    found = slip(t, u0, kt, K, gamma_t, cap, reset_k, NEAR_ONE, zeno)
    if zeno:
        check_limit(found, lambda cut: slip(t, u0, kt, K, gamma_t, cap, reset_k, NEAR_ONE * cut), max(abs(u0), 1e-300),
                    f"the frozen contact from u = {u0:.6g}")
    delta = found - u0
    return v_t0 + alpha / (1.0 + alpha) * delta, r_omega0 + delta / (1.0 + alpha)


def slip(t: np.ndarray, u0: float, kt: float, K: float, gamma_t: float, cap: float, reset_k: float | None = None,
         hold: float = NEAR_ONE, zeno: list | None = None) -> np.ndarray:
    """The slip u at the times ``t`` (>= 0), from u0 with an unstretched spring (``reset_k``, ``hold``: a classic
    spring's k, and how far its slide is held on; ``zeno`` gets an entry where a stick after a slide is capped
    again at once)."""
    out = np.full(t.shape, np.nan)
    if cap == 0.0:  # no force at all
        return np.full(t.shape, u0)
    classic = reset_k is not None and reset_k != kt
    f = 1.0 if reset_k is None else kt / reset_k  # the classic spring's a (1: the plain cap)
    t_end, start, xi, u, slid = float(np.max(t, initial=0.0)), 0.0, 0.0, u0, -np.inf
    period = 2.0 * np.pi / np.sqrt(K * kt)
    for _ in range(MAX_SWITCHES):
        force = kt * xi + gamma_t * u
        # beyond the cap (a dashpot's force at first touch), or for the classic spring on it: the history is reset
        if abs(force) > cap or classic and abs(force) >= cap * (1.0 - 1e-12):
            force = reset(f, cap, np.sign(force), gamma_t * u)
            xi = (force - gamma_t * u) / kt
        s = float(np.sign(force))
        # a slide ends where sticking would no longer push the force out (the classic spring: where its dashpot
        # alone falls below the cap, held on by ``hold``)
        floor = cap * (1.0 - hold) / gamma_t if classic and gamma_t else gamma_t * K * cap / kt
        if abs(force) >= cap * (1.0 - 1e-12) and s * u > floor:  # slipping
            stop = start + (s * u - floor) / (K * cap)
            inside = (t >= start) & (t <= stop)
            out[inside] = u - s * K * cap * (t[inside] - start)
            u = u - s * K * cap * (min(stop, t_end) - start)
            xi, start, slid = (reset(f, cap, s, gamma_t * u) - gamma_t * u) / kt, stop, stop
        else:
            start, xi, u = _stick(t, out, start, xi, u, kt, K, gamma_t, cap, t_end)
            if zeno is not None and classic and is_zeno(start, slid, period):
                zeno.append(True)
        if start >= t_end:
            return out
    raise RuntimeError(f"more than {MAX_SWITCHES} stick-slip switches before t = {t_end:g}")


def _stick(t, out, start, xi, u, kt, K, gamma_t, cap, t_end):
    """Integrate a stick phase from ``start`` until the force reaches the cap (or t_end), filling
    ``out`` there; the phase's end (start, xi, u)."""
    from scipy.integrate import solve_ivp

    def rates(_, y):
        return [y[1], -K * (kt * y[0] + gamma_t * y[1])]

    def at_cap(_, y):
        return abs(kt * y[0] + gamma_t * y[1]) - cap

    at_cap.terminal, at_cap.direction = True, 1.0
    scale = max(abs(u), cap / kt, 1e-300)
    sol = solve_ivp(rates, (start, t_end), [xi, u], method="DOP853", rtol=1e-12, atol=1e-14 * scale,
                    events=at_cap, dense_output=True)
    stop = float(sol.t_events[0][0]) if sol.t_events[0].size else t_end
    inside = (t >= start) & (t <= stop)
    if inside.any():
        out[inside] = sol.sol(t[inside])[1]
    xi, u = sol.sol(stop)
    if stop < t_end and stop <= start:  # a cap touched at the phase's start: step past it
        return np.nextafter(stop, np.inf), xi, u
    return stop, xi, u
