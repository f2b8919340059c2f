"""What LAMMPS integrates for two free spheres, solved to high accuracy: the exact reference.

``pair_style granular hooke KN ETA_N damping velocity tangential linear_history KT X_T MU``
(GranularModel::calculate_forces and the linear_history sub-model) between spheres a and
b, with d = x_a - x_b, n = d/|d| (from b to a, turning as the spheres move) and the
overlap delta = r_a + r_b - |d|, in contact while |d| < r_a + r_b:

* relative velocity v = v_a - v_b; slip rate u' = v - (v.n) n - (r_a w_a + r_b w_b) x n;
* normal force on a: (kn delta - eta_n v.n) n;
* tangential force on a: F_t = -kt xi - gamma_t u', where the history xi obeys xi' = u'.
  LAMMPS rotates xi back into the tangent plane only when |xi.n| kt > 1e-10 mu F_n; with
  the no-cap mu = 1e12 that never happens (LAMMPS_FACTS section 12), so xi keeps the
  normal component the turning of n gives it, and F_t carries it;
* torque on a and on b: -(r - delta/2) n x F_t, with each sphere's own r (the slip uses
  r, the torque the distance to the middle of the overlap);
* b feels minus a's force; the history is dropped when the contact ends.

``planar=True`` freezes n at its initial value and uses the lever arms r_a, r_b: the
assumptions of :mod:`.pair`, whose closed form it must then reproduce.

The equations are integrated by scipy's DOP853 with rtol 1e-12 and the contact's end
located as an event of the same dense output: the result is accurate to about 1e-10 of
the speeds (tests/test_pairs.py compares two tolerances).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

__all__ = ["PairOutcome", "solve", "RTOL", "longest_step", "start", "outcome"]

#: Relative tolerance of the integration (the absolute one is this times the speeds).
RTOL = 1e-12


def longest_step(tau: float, v_rel, n0, radsum: float) -> float:
    """The integrator's longest step: an eighth of the shorter of tau and the free-flight overlap
    2 |v.n| (r_a + r_b)/|v|^2, so that no step can carry a grazing pair from touch to separation
    unseen (the contact's end is found as a sign change between steps)."""
    v_rel = np.asarray(v_rel, dtype=float)
    return min(tau, 2.0 * abs(v_rel @ n0) * radsum / (v_rel @ v_rel)) / 8.0


@dataclass(frozen=True)
class PairOutcome:
    """Velocities and spins after the contact, its duration, and how far n turned (radians)."""

    v_a: np.ndarray
    v_b: np.ndarray
    w_a: np.ndarray
    w_b: np.ndarray
    contact_time: float
    turn: float


def _rates(t, state, n0, p, planar):
    d, v_a, v_b, w_a, w_b, xi = state.reshape(6, 3)
    radsum = p["r_a"] + p["r_b"]
    if planar:
        n, delta = n0, radsum - d @ n0
        lever_a, lever_b = p["r_a"], p["r_b"]
    else:
        dist = np.sqrt(d @ d)
        n, delta = d / dist, radsum - dist
        lever_a, lever_b = p["r_a"] - 0.5 * delta, p["r_b"] - 0.5 * delta
    v = v_a - v_b
    v_n = v @ n
    slip = v - v_n * n - np.cross(p["r_a"] * w_a + p["r_b"] * w_b, n)
    f_t = -p["kt"] * xi - p["gamma_t"] * slip
    force = (p["kn"] * delta - p["gamma_n"] * v_n) * n + f_t
    arm = -np.cross(n, f_t)
    return np.concatenate([v, force / p["m_a"], -force / p["m_b"], lever_a * arm / p["i_a"],
                           lever_b * arm / p["i_b"], slip])


def start(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, planar, rtol, **law):
    """What both pair references start from: (unit n0, coefficients, state (d, v_a, v_b, w_a, w_b)
    at first touch, v_a - v_b, contact time tau, longest step, absolute tolerance of that state)."""
    n0 = np.asarray(n, dtype=float)
    n0 = n0 / np.linalg.norm(n0)
    radsum = r_a + r_b
    p = {"r_a": r_a, "r_b": r_b, "m_a": m_a, "m_b": m_b, "i_a": alpha_a * m_a * r_a**2,
         "i_b": alpha_b * m_b * r_b**2, "kn": kn, "kt": kt, **law}
    state = np.concatenate([radsum * n0, v_a, v_b, w_a, w_b]).astype(float)
    v_rel = np.asarray(v_a, dtype=float) - np.asarray(v_b, dtype=float)
    if v_rel @ n0 >= 0.0:
        raise ValueError("the spheres must approach at first touch: (v_a - v_b).n < 0")
    speed = max(np.linalg.norm(v_rel), radsum * (np.linalg.norm(w_a) + np.linalg.norm(w_b)))
    m_star = m_a * m_b / (m_a + m_b)
    tau = np.pi * np.sqrt(m_star / kn)
    fast = np.sqrt(kn / m_star) + np.sqrt(kt * (1 / m_a + 1 / m_b + r_a**2 / p["i_a"] + r_b**2 / p["i_b"]))
    longest = tau / 8.0 if planar else longest_step(tau, v_rel, n0, radsum)
    return n0, p, state, v_rel, tau, longest, rtol * speed * min(radsum / speed, 1.0 / fast)


def outcome(end, n0, t) -> PairOutcome:
    """The outcome from the state (d, v_a, v_b, w_a, w_b, ...) at separation, time t."""
    d_end, v_a, v_b, w_a, w_b = end[:15].reshape(5, 3)
    turn = float(np.arccos(np.clip(d_end @ n0 / np.linalg.norm(d_end), -1.0, 1.0)))
    return PairOutcome(v_a=v_a, v_b=v_b, w_a=w_a, w_b=w_b, contact_time=float(t), turn=turn)


def solve(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, gamma_n=0.0, gamma_t=0.0,
          planar=False, rtol=RTOL) -> PairOutcome:
    """One pair from first touch (|d| = r_a + r_b, d along the unit vector ``n``) until it separates.

    Vectors are 3-sequences in LAMMPS's frame; angular velocities are LAMMPS's omega.
    """
    n0, p, state, _, tau, longest, atol = start(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b,
                                                kn, kt, planar, rtol, gamma_n=gamma_n, gamma_t=gamma_t)

    def separated(t, y, *_):
        d = y[:3]
        return (d @ n0 if planar else np.sqrt(d @ d)) - (r_a + r_b)

    separated.terminal, separated.direction = True, 1.0
    # the start (gap 0, closing) is no upward crossing; the end is the first one
    solution = solve_ivp(_rates, (0.0, 20.0 * tau), np.concatenate([state, np.zeros(3)]), method="DOP853",
                         args=(n0, p, planar), max_step=longest, rtol=rtol, atol=atol, events=separated)
    if solution.status != 1 or not len(solution.t_events[0]):
        raise RuntimeError(f"the pair did not separate within 20 contact times: {solution.message}")
    return outcome(solution.y_events[0][0], n0, solution.t_events[0][0])
