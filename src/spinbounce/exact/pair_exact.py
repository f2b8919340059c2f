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
  normal component the turning of n gives it, and F_t carries it. A law that projects its
  history at every step (``projected``: this build's linear_history_classic) keeps it in the
  tangent plane instead: xi' = u' - (xi.n') n;
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

from typing import NamedTuple

import numpy as np

from ..errors import contact_held
from . import first_use, pair_kernel
from . import pair as pair_theory
from .wall_law import can_hold, on_contact_radius

__all__ = ["PairOutcome", "solve", "RTOL", "HOOKE", "longest_step", "start", "outcome", "free_flight", "window",
           "contact_radius_power", "pair_scales", "tolerance_scale", "cross", "EXAMPLE", "HERTZ_MINDLIN"]

#: Relative tolerance of the integration (the absolute one is this times the speeds).
RTOL = 1e-12


def longest_step(tau: float, v_rel, n0, radsum: float) -> float:
    """The integrator's longest step: an eighth of the shorter of tau and the free-flight overlap
    2 |v.n| (r_a + r_b)/|v|^2, so that no step can carry a grazing pair from touch to separation
    unseen (the contact's end is found as a sign change between steps). Vectors (..., 3): one pair or many."""
    v_rel = np.asarray(v_rel, dtype=float)
    closing = np.abs(np.sum(v_rel * n0, axis=-1))
    return np.minimum(tau, 2.0 * closing * radsum / np.sum(v_rel * v_rel, axis=-1)) / 8.0


class PairOutcome(NamedTuple):
    """Velocities and spins after the contact, its duration, how far n turned (radians) and a's centre
    less b's at separation (``d_end``). A named tuple: a batch makes tens of thousands of them."""

    v_a: np.ndarray
    v_b: np.ndarray
    w_a: np.ndarray
    w_b: np.ndarray
    contact_time: float
    turn: float
    d_end: np.ndarray | None = None


def cross(a, b) -> np.ndarray:
    """a x b of two 3-vectors: numpy's cross, written out (the references call it millions of times, and
    np.cross's axis handling costs ten times the product)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def contact_radius_power(p, delta: float, s: float) -> float:
    """a^s of the contact radius a = sqrt(R_eff |delta|) (1 for s = 0)."""
    return 1.0 if s == 0.0 else (p["r_eff"] * abs(delta)) ** (s / 2.0)


def _rates(t, state, n0, P, planar, overlap=np.nan):
    """d(state)/dt (:func:`.pair_kernel.free_rates`, ``P`` its coefficients); ``overlap``: the overlap where it
    is known better than from the centres (_tail)."""
    out = np.empty(18)
    pair_kernel.free_rates(state, P, n0, planar, overlap, out)
    return out


#: A contact not over within this many of its contact times is not a contact the references end.
CONTACT_TIMES = 20.0


def window(tau, m_a, m_b, kn, gamma_n, radial: bool = False):
    """How long the references follow a contact before giving it up: CONTACT_TIMES times the longer of
    its undamped time ``tau`` and, for Hooke's force, the damped one (half a damped period: a nearly
    critical dashpot's contact lasts many undamped times; an overdamped one has none, and keeps tau's).
    Scalars or arrays (N,)."""
    if radial:
        return CONTACT_TIMES * tau
    arrays = (np.asarray(x, dtype=float) for x in (tau, m_a, m_b, kn, gamma_n))
    tau, m_a, m_b, kn, gamma_n = np.broadcast_arrays(*arrays)
    longer = np.array(tau)
    under = gamma_n < 2.0 * np.sqrt(pair_theory.reduced_mass(m_a, m_b) * kn)
    if np.any(under):
        longer[under] = np.fmax(tau[under], pair_theory.contact_time(m_a[under], m_b[under], kn[under], gamma_n[under]))
    return CONTACT_TIMES * longer


#: The law of :func:`solve` beyond kn, kt and the dashpots: LAMMPS's Hookean force and linear_history.
HOOKE = {"power": 1.0, "spring_power": 0.0, "force_history": False, "rescale": False, "damping_power": 0.0,
         "projected": False}
#: A law on the contact radius: Hertz's force, Mindlin's spring and dashpots that grow as sqrt(delta).
HERTZ_MINDLIN = HOOKE | {"power": 1.5, "spring_power": 1.0, "damping_power": 0.5}
#: The pair the compiled references' examples solve (first_use): it slides, spins in 3-D and is damped.
EXAMPLE = {"n": (0.0, 0.0, 1.0), "v_a": (0.3, 0.1, -1.0), "v_b": (0.0, 0.0, 0.0), "w_a": (0.0, 0.5, 0.2),
           "w_b": (0.0, 0.0, 0.0), "m_a": 1.0, "r_a": 0.5, "alpha_a": 0.4, "m_b": 1.0, "r_b": 0.5, "alpha_b": 0.4,
           "kn": 1e4, "kt": 2e3, "gamma_n": 5.0, "gamma_t": 2.0}


def pair_scales(p, v_rel, n0, m_star):
    """(contact time, fastest rate) of the normal motion at the impact speed, undamped: the Hookean
    pi sqrt(m*/kn), or for K delta^p its time over the undamped depth, and the stiffest rates
    there (the spring k a^q at the deepest a). Vectors (..., 3) and coefficients (...): one pair or many."""
    speed = np.abs(np.sum(v_rel * n0, axis=-1))
    power, K = p["power"], p["K"]
    depth = ((power + 1.0) * m_star * speed**2 / (2.0 * K)) ** (1.0 / (power + 1.0))
    tau = np.pi * np.sqrt(m_star / K) if power == 1.0 else 2.0 * 1.5 * depth / speed
    normal = np.sqrt(K * power * depth ** (power - 1.0) / m_star)
    spring = p["kt"] * contact_radius_power(p, depth, p["spring_power"])
    mobility = 1 / p["m_a"] + 1 / p["m_b"] + p["r_a"] ** 2 / p["i_a"] + p["r_b"] ** 2 / p["i_b"]
    return tau, normal + np.sqrt(spring * mobility)


def tolerance_scale(rtol: float, v_rel, w_a, w_b, radsum, fast):
    """The absolute tolerance of a pair's state: rtol times its largest speed (relative or the spins'
    surface speeds), over the shorter of the time to cross r_a + r_b and the fastest rate's time.
    Vectors (..., 3): one pair or many."""
    def length(x):
        return np.sqrt(np.sum(np.square(x), axis=-1))

    speed = np.maximum(length(v_rel), radsum * (length(w_a) + length(w_b)))
    return rtol * speed * np.minimum(radsum / speed, 1.0 / fast)


def start(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, planar, rtol, **law):
    """What both pair references start from: (unit n0, coefficients, state (d, v_a, v_b, w_a, w_b)
    at first touch, v_a - v_b, contact time tau, longest step, absolute tolerance of that state).
    ``law``: gamma_n, gamma_t and the keys of :data:`HOOKE` (missing: Hooke's)."""
    n0 = np.asarray(n, dtype=float)
    n0 = n0 / np.linalg.norm(n0)
    radsum = r_a + r_b
    r_eff = r_a * r_b / radsum
    law = {**HOOKE, **law}
    p = {"r_a": r_a, "r_b": r_b, "m_a": m_a, "m_b": m_b, "i_a": alpha_a * m_a * r_a**2,
         "i_b": alpha_b * m_b * r_b**2, "kn": kn, "kt": kt, "r_eff": r_eff,
         "K": kn * r_eff ** (law["power"] - 1.0), **law}
    state = np.concatenate([radsum * n0, v_a, v_b, w_a, w_b]).astype(float)
    v_rel = np.asarray(v_a, dtype=float) - np.asarray(v_b, dtype=float)
    if v_rel @ n0 >= 0.0:
        raise ValueError("the spheres must approach at first touch: (v_a - v_b).n < 0")
    m_star = m_a * m_b / (m_a + m_b)
    tau, fast = pair_scales(p, v_rel, n0, m_star)
    longest = tau / 8.0 if planar else longest_step(tau, v_rel, n0, radsum)
    return n0, p, state, v_rel, tau, longest, tolerance_scale(rtol, v_rel, w_a, w_b, radsum, fast)


def outcome(end, t, n0) -> PairOutcome:
    """The outcome from the state (d, v_a, v_b, w_a, w_b, ...) at separation, time t."""
    d_end, v_a, v_b, w_a, w_b = (np.array(x) for x in end[:15].reshape(5, 3))  # own arrays, read-only: shared
    for x in (d_end, v_a, v_b, w_a, w_b):  # by every caller of a cached outcome (scenes.pair.contact)
        x.setflags(write=False)
    turn = float(np.arccos(np.clip(d_end @ n0 / np.linalg.norm(d_end), -1.0, 1.0)))
    return PairOutcome(v_a=v_a, v_b=v_b, w_a=w_a, w_b=w_b, contact_time=float(t), turn=turn, d_end=d_end)


def solve(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, gamma_n=0.0, gamma_t=0.0,
          planar=False, rtol=RTOL, tensile=True, **law) -> PairOutcome:
    """One pair from first touch (|d| = r_a + r_b, d along the unit vector ``n``) until it separates.

    Vectors are 3-sequences in LAMMPS's frame; angular velocities are LAMMPS's omega. ``law``: the
    keys of :data:`HOOKE` for a force or spring on the contact radius (kn is then LAMMPS's, the
    force kn R_eff^(p - 1) delta^p; kt the spring's k of k a^q; the dashpots gamma a^s). ``tensile``
    False (LAMMPS's ``limit_damping``): where the normal force would turn to pull, it is cut to zero,
    and with it the friction (the no-cap mu times |F_n|): the spheres part force-free (:func:`free_flight`).
    """
    from scipy.integrate import (
        solve_ivp,  # here: half a second to import, which a compiled batch never needs
    )

    first_use.once("pair")
    n0, p, state, v_rel, tau, longest, atol = start(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b,
                                                kn, kt, planar, rtol, gamma_n=gamma_n, gamma_t=gamma_t, **law)
    radial = on_contact_radius(p["power"], p["spring_power"], p["damping_power"])
    # a law on the contact radius leaves the time at TAIL_START of its depth for x = sqrt(delta) (_tail)
    depth = undamped_depth(p, state[3:6] - state[6:9], n0, m_a * m_b / (m_a + m_b)) * TAIL_START if radial else 0.0

    def gap(y) -> float:
        d = y[:3]
        return (d @ n0 if planar else np.sqrt(d @ d)) - (r_a + r_b)

    turned = _turned(n0, p, planar) if not tensile and gamma_n > 0.0 else None
    bound = float(window(tau, m_a, m_b, kn, gamma_n, radial))
    coefficients = pair_kernel.coefficients(p)

    def not_separated(why: str = f"the pair did not separate within {CONTACT_TIMES:g} contact times"):
        if can_hold(gamma_n, p["power"], p["damping_power"], tensile):  # the dashpot outlasts the force
            raise contact_held(-abs(float(v_rel @ n0)))
        raise RuntimeError(why)

    def follow(depth: float, y0, t0: float):
        """The contact from ``y0`` at ``t0`` until the overlap falls back to ``depth`` (the tail's start), or
        parts before it ever got that deep (a grazing pair), or the normal force turns: (solution, which event,
        state, time)."""
        if t0 >= bound:  # a tail that stalled past the window: no time left to follow
            not_separated()

        def separated(t, y, *_):
            return gap(y) + depth

        def parted(t, y, *_):
            return gap(y)

        separated.terminal = parted.terminal = True
        separated.direction = parted.direction = 1.0
        # the start (gap 0, closing) is no upward crossing; the end (or the tail's start) is the first one
        events = [separated] + ([parted] if depth > 0.0 else []) + ([turned] if turned else [])
        solution = solve_ivp(_rates, (t0, bound), y0, method="DOP853", args=(n0, coefficients, planar),
                             max_step=longest, rtol=rtol, atol=atol, events=events)
        fired = [k for k, times in enumerate(solution.t_events) if len(times)]
        if solution.status == -1 and depth > 0.0:  # (a grazing pair's end, its a'/a singular in time)
            return solution, "failed", None, None
        if solution.status == -1:
            raise RuntimeError(f"the pair's integration failed: {solution.message}")
        if solution.status != 1 or not fired:
            not_separated()
        k = fired[0]
        return solution, events[k].__name__, solution.y_events[k][0], solution.t_events[k][0]

    end, t_end = np.concatenate([state, np.zeros(3)]), 0.0
    for _ in range(MAX_STALLS + 1):
        start_state, start_time = end, t_end
        solution, which, end, t_end = follow(depth, start_state, start_time)
        if which in ("parted", "failed"):  # never as deep as the tail's start (a grazing pair): the tail from half
            reached = float(np.max(-_gaps(solution.y, n0, planar, r_a + r_b)))  # the depth it reached
            if not reached > 0.0:
                raise RuntimeError(f"the pair's integration failed at first touch: {solution.message}")
            solution, which, end, t_end = follow(TAIL_START * reached, start_state, start_time)
            if which == "failed":
                raise RuntimeError(f"the pair's integration failed before it parted: {solution.message}")
        if which == "turned":  # the normal force's turn: no force from here
            return outcome(*free_flight(end, t_end, n0, planar, -gap(end)), n0)
        if not (radial and which == "separated"):
            return outcome(end, t_end, n0)
        end, t_end, stalled = _tail(end, t_end, -gap(end), n0, p, planar, rtol, atol, turned, bound)
        if not stalled:
            return outcome(end, t_end, n0)
        depth = TAIL_START * -gap(end)  # back in time from where the parting stalled, to a tail of its own
    not_separated(f"the pair's parting stalled more than {MAX_STALLS} times")


def _gaps(states: np.ndarray, n0, planar: bool, radsum: float) -> np.ndarray:
    """|d| - (r_a + r_b) of each column of ``states`` (the integrator's steps)."""
    d = states[:3]
    return (n0 @ d if planar else np.sqrt(np.sum(d * d, axis=0))) - radsum


def _turned(n0, p, planar):
    """The event where the normal force falls through zero (``limit_damping`` cuts it there)."""
    coefficients = pair_kernel.coefficients(p)

    def turned(t, y, *_):
        n, dist, _, _ = pair_kernel.geometry(y, coefficients, n0, planar)
        return pair_kernel.normal_law(coefficients, p["r_a"] + p["r_b"] - dist, (y[3:6] - y[6:9]) @ np.array(n))[0]

    turned.terminal, turned.direction = True, -1.0
    return turned


def free_flight(state, t: float, n0, planar: bool, delta: float) -> tuple[np.ndarray, float]:
    """(state, time) where spheres parting force-free from ``state`` (overlap ``delta``) stop touching:
    each centre moves on at its velocity (the spins kept), so |d + v s| = |d| + delta, a quadratic in s
    (held fixed, n0: d.n0 grows by delta)."""
    d, v = state[:3], state[3:6] - state[6:9]
    if planar:
        s = delta / (v @ n0)
    else:
        c = 2.0 * np.sqrt(d @ d) * delta + delta * delta
        s = c / (d @ v + np.sqrt((d @ v) ** 2 + (v @ v) * c))
    end = state.copy()
    end[:3] = d + v * s
    return end, t + s


#: A law on the contact radius leaves the time for x = sqrt(delta) where its overlap is back to this
#: fraction of the undamped depth at its closing speed (a grazing pair that never gets that deep: of the
#: depth it reaches, integrated again from first touch), and ends where x is TAIL_END of its value
#: there: its rates, a'/a and a^s, are singular in time at the exit and regular in x (the wall's
#: exact.contact_phases does the same), the overlap there x^2 (not the centres' distance less
#: r_a + r_b, which rounding blurs by ~1e-16 (r_a + r_b)). What is left beyond, ~ 1e-12 of the
#: speed, is left.
TAIL_START = 0.5
TAIL_END = 1e-6
#: A tail whose parting speed v.n falls to STALL of its value at the tail's start hands back to the time:
#: a history that keeps its normal component (LAMMPS's linear_history without a cap) can pull the spheres
#: back together before they part, where x = sqrt(delta) stops falling; at most MAX_STALLS times a contact.
STALL = 0.1
MAX_STALLS = 8


def undamped_depth(p, v_rel, n0, m_star: float) -> float:
    """The undamped deepest overlap of the normal force K delta^p at the impact speed."""
    speed = abs(float(v_rel @ n0))
    return ((p["power"] + 1.0) * m_star * speed**2 / (2.0 * p["K"])) ** (1.0 / (p["power"] + 1.0))


def _tail(state, t: float, delta: float, n0, p, planar, rtol, atol, turned=None, bound: float = np.inf):
    """(state, time, stalled) at the end of the contact, integrated in x = sqrt(delta) from ``delta`` down:
    dy/dx = dy/dt 2 x/delta', the time a state of its own; ``turned``: the normal force's turn, from which the
    spheres part force-free. ``stalled``: the state is where the parting slowed to STALL of its start instead
    (:data:`STALL`), or where its time reached ``bound`` (the contact's window), from which the contact goes on
    in time."""
    from scipy.integrate import solve_ivp

    coefficients = pair_kernel.coefficients(p)

    def rates(x, y):
        core = y[:-1]
        d, v = core[:3], core[3:6] - core[6:9]
        n = n0 if planar else d / np.sqrt(d @ d)
        stretch = -2.0 * x / (v @ n)  # dt/dx = 2 x/delta', delta' = -v.n (> 0 while the spheres part)
        return np.append(_rates(0.0, core, n0, coefficients, planar, overlap=x * x) * stretch, stretch)

    x0 = np.sqrt(delta)
    tail_atol = np.append(np.broadcast_to(atol, state.shape), atol)

    def parting(y):
        n = n0 if planar else y[:3] / np.sqrt(y[:3] @ y[:3])
        return (y[3:6] - y[6:9]) @ n

    slowest = STALL * parting(state)

    def stall(x, y):
        return parting(y) - slowest

    def window_end(x, y):
        return bound - y[-1]

    stall.terminal = window_end.terminal = True
    stall.direction = window_end.direction = -1.0
    events = [stall, window_end]
    if turned:
        def turn(x, y):
            n = n0 if planar else y[:3] / np.sqrt(y[:3] @ y[:3])
            return pair_kernel.normal_law(coefficients, x * x, (y[3:6] - y[6:9]) @ n)[0]

        turn.terminal, turn.direction = True, -1.0  # F_n falls through zero as x falls (as time runs)
        events.append(turn)
    solution = solve_ivp(rates, (x0, x0 * TAIL_END), np.append(state, t), method="DOP853", rtol=rtol,
                         atol=tail_atol, events=events)
    if solution.status == 1 and (len(solution.t_events[0]) or len(solution.t_events[1])):
        y = (solution.y_events[0] if len(solution.t_events[0]) else solution.y_events[1])[0]
        return y[:-1], float(y[-1]), True  # stalled, or out of time: back to the time from here
    if solution.status == 1:  # the turn: from there force-free
        x, y = solution.t_events[2][0], solution.y_events[2][0]
        return (*free_flight(y[:-1], float(y[-1]), n0, planar, x * x), False)
    if solution.status != 0:
        raise RuntimeError(f"the pair's contact did not end: {solution.message}")
    return solution.y[:-1, -1], float(solution.y[-1, -1]), False


@first_use.example("pair", seconds=3)
def _example() -> None:
    """A law on the contact radius, held and free, cut by limit_damping."""
    solve(**EXAMPLE, **HERTZ_MINDLIN)
    solve(**EXAMPLE, **HERTZ_MINDLIN, planar=True, tensile=False)
