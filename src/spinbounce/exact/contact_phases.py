"""The wall contact integrated phase by phase: any normal force K delta^p with a dashpot, any
tangential spring on the slip history, and LAMMPS's Coulomb cap, in the paper's plane.

Against a wall (R = r, m_eff = m) LAMMPS's granular model is, with the contact radius
a = sqrt(r delta), the slip rate u' = v_t + r omega and its history h:

* normal: F_n = K delta^p + c_n delta', c_n = C_n a^s (the damping sub-model's prefactor:
  s = 0 for velocity and mass_velocity and, with the Hookean force, tsuji and coeff_restitution;
  1/2 for those two with the Hertzian force, F/delta = kn a; 1 for viscoelastic), tensile allowed;
* tangential, a spring k a^q (q = 0: linear_history; q = 1: the Mindlin variants and this build's
  linear_history_classic) with a dashpot c_t = C_t a^s: with a displacement history F_t = -k a^q h
  - c_t u', h' = u'; with a force history (``/force``) F_t = h - c_t u', h' = -k a^q u'; a
  ``_rescale`` variant scales h by a_new/a_old while a shrinks (in continuous time h' gains h a'/a);
* m delta'' = -F_n, m v_t' = F_t, alpha m (r omega)' = F_t.

With a cap (``GranSubModTangentialMindlin::calculate_forces``) a trial force beyond mu |F_n| is
scaled back onto it and the history set to what gives that force: the contact sticks and slides in
turn,

* stick -> slip when |F_t| reaches mu |F_n|;
* slip -> stick when sticking would move |F_t| inward faster than the cap moves:
  d|F_t|/dt (sticking) < mu d|F_n|/dt;
* at first touch F_n and a vanish together: against the Hertzian force the trial force and the
  cap both grow as t^(3/2), so the contact starts sliding when k_t |u'(0)| (times 2/3 for a force
  history) exceeds mu kn |v_n| (Mindlin's and Cattaneo's criterion), and sticking otherwise;
  against the Hookean force the cap grows as t and the contact starts sticking.

Near its end the cap falls as delta^p while a sticking force falls as delta at most, so every
capped contact ends sliding (or with no slip). A cap is taken here with a spring on the contact
radius and no dashpot (others have references of their own: exact.oracle, exact.coulomb,
exact.classic).

Each collision is integrated with scipy's DOP853 (rtol 1e-12), restarting at every switch
(events) and at the deepest point (where the rescale starts); near the exit in the variable
sqrt(delta) (:func:`bounce`), where a's infinite slope in time is smooth. Planar only: a 3-D slide
turns its direction, which this module does not follow (without a cap the slip is linear and
each direction is the plane's; with one, exact.oracle follows it). With limit_damping the normal
force ends where it would turn to pull, and the sphere coasts out (the ``turn`` event).

Pure numpy and scipy; knows nothing of LAMMPS.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.integrate import solve_ivp

from .wall_law import Law, can_hold
from ..errors import contact_held

__all__ = ["Law", "bounce", "bounce_many", "exit_slips", "normal_exit", "RTOL"]

RTOL = 1.0e-12
ATOL = 1.0e-15
#: More switches than this in one contact mean the phases chatter: refuse.
MAX_PHASES = 200
# state: overlap, its rate, v_t, r omega, history, time
_D, _DR, _V, _W, _H, _T = range(6)


class _Contact:
    """One collision under a :class:`Law`: its forces, its phases' rates and switches."""

    def __init__(self, law: Law):
        self.law = law
        self.capped = math.isfinite(law.mu)

    def radius(self, y) -> tuple[float, float]:
        """(a, a'/a) of the contact radius a = sqrt(r delta) (a'/a = delta'/(2 delta))."""
        delta = max(y[_D], 0.0)
        return math.sqrt(self.law.r * delta), (y[_DR] / (2.0 * delta) if delta > 0 else 0.0)

    def dashpot(self, y) -> float:
        """a^s, the dashpots' factor of the contact."""
        s = self.law.damping_power
        return 1.0 if s == 0.0 else self.radius(y)[0] ** s

    def normal(self, y) -> float:
        law = self.law
        return law.K * max(y[_D], 0.0) ** law.power + law.c_n * self.dashpot(y) * y[_DR]

    def cap_rate(self, y) -> float:
        """d(mu |F_n|)/dt of the undamped force (a cap is taken without a dashpot)."""
        law, delta = self.law, max(y[_D], 0.0)
        return law.mu * law.K * law.power * delta ** (law.power - 1.0) * y[_DR] if delta > 0 else 0.0

    def spring(self, y) -> float:
        q = self.law.spring_power
        return self.law.k * (1.0 if q == 0.0 else self.radius(y)[0] ** q)

    def stick_force(self, y) -> float:
        damp = self.law.c_t * self.dashpot(y) * (y[_V] + y[_W]) if self.law.c_t else 0.0
        return (y[_H] if self.law.force_history else -self.spring(y) * y[_H]) - damp

    def stick_history_rate(self, y) -> float:
        """h' while sticking: u' (or -k a^q u'), plus h a'/a while a shrinks (``_rescale``)."""
        slip = y[_V] + y[_W]
        rate = -self.spring(y) * slip if self.law.force_history else slip
        if self.law.rescale and y[_DR] < 0.0:
            rate += y[_H] * self.radius(y)[1]
        return rate

    def pinned_history(self, y, sigma: float) -> float:
        """The history whose force is -sigma mu F_n (the cap; no dashpot)."""
        law = self.law
        if law.force_history:
            return -sigma * law.mu * law.K * max(y[_D], 0.0) ** law.power
        # mu K delta^p/(k sqrt(r delta)), written so that it vanishes with delta
        return sigma * law.mu * law.K * max(y[_D], 0.0) ** (law.power - 0.5) / (law.k * math.sqrt(law.r))

    def stick_magnitude_rate(self, y, sigma: float) -> float:
        """d|F_t|/dt if the contact stuck now, with F_t = -sigma |F_t| (a spring on a, no dashpot)."""
        a, shrink = self.radius(y)
        rate_h = self.stick_history_rate(y)
        if self.law.force_history:
            return -sigma * rate_h
        return sigma * self.law.k * (a * shrink * y[_H] + a * rate_h)

    def rhs(self, phase: str, sigma: float, tail: bool):
        """dy/dt; in the tail, dy/d(sqrt(delta)) = dy/dt 2 sqrt(delta)/delta' (see :func:`bounce`)."""
        law = self.law

        def f(x, y):
            force_n = self.normal(y)
            force_t = -sigma * law.mu * abs(force_n) if phase == "slip" else self.stick_force(y)
            h_rate = self.stick_history_rate(y) if phase == "stick" else 0.0
            rates = np.array([y[_DR], -force_n / law.m, force_t / law.m, force_t / (law.alpha * law.m), h_rate, 1.0])
            return rates * (2.0 * x / y[_DR]) if tail else rates
        return f

    def events(self, phase: str, sigma: float, leg: str):
        """The switches of ``phase``, and the end of ``leg``: the deepest point (load), x = x1 (unload)."""
        found = []
        if leg == "load":
            def deepest(t, y):
                return y[_DR]

            found.append(deepest)
        elif leg == "unload":
            def tail(t, y):
                return y[_D] - self.tail_overlap

            found.append(tail)
        if phase == "stick" and self.capped:
            def to_slip(t, y):
                return self.law.mu * abs(self.normal(y)) - abs(self.stick_force(y))

            found.append(to_slip)
        if leg != "load" and not self.law.tensile and self.law.c_n > 0.0:
            def turn(t, y):  # limit_damping: the force ends here, and the sphere coasts out
                return self.normal(y)

            found.append(turn)
        if phase == "slip":
            def to_stick(t, y):
                y = np.array(y)
                y[_H] = self.pinned_history(y, sigma)
                return self.stick_magnitude_rate(y, sigma) - self.cap_rate(y)

            found.append(to_stick)
        for event in found:
            event.terminal, event.direction = True, -1
        return found

    def first_phase(self, v: float, slip: float, span: float) -> tuple[str, float]:
        """(stick or slip, the first step) from first touch: the t -> 0 limits of the trial force,
        k a^q |u'| t (over 1 + q/2 for a force history), and the cap mu K (v t)^p. Where they grow
        alike (Hertz on a Mindlin spring) their ratio decides; where the cap grows faster at first
        (Hooke) the contact sticks until t*, where the trial force overtakes it: a t* far below the
        contact's time is taken as sliding from the start (its stick moves nothing, ~ (t*/T)^(p+1))."""
        law, first = self.law, span * 1e-9
        if not self.capped or slip == 0.0:
            return "stick", first
        q = law.spring_power
        trial = law.k * (law.r * v) ** (q / 2.0) * abs(slip) / (1.0 + q / 2.0 if law.force_history else 1.0)
        cap, growth = law.mu * law.K * v**law.power, 1.0 + q / 2.0 - law.power  # trial/cap ~ t^growth
        if growth <= 0.0:
            return ("slip" if trial > cap else "stick"), first
        t_star = (cap / trial) ** (1.0 / growth)
        return ("slip", first) if t_star < first else ("stick", min(first, 1e-3 * t_star))


#: The tail starts where the overlap is back to this fraction of its largest, and ends where
#: sqrt(delta) is this fraction of its value there: the force left beyond, ~ delta^p, moves the
#: velocities by ~ (1e-6)^(2 p + 2) of the speed (1e-24 at most), and a dashpot's ~ C_n delta by
#: 1e-12 of its delta_max: below it, rounding can make the cap and a vanishing force chatter.
TAIL_START = 0.5
TAIL_END = 1.0e-6
#: A contact whose dashpot can hold it (:func:`.wall_law.can_hold`) still open HELD_SPANS spans after first touch
#: (span: ten times the undamped depth over the impact speed, several contact times) is held closed by it
#: (:func:`spinbounce.errors.contact_held`).
HELD_SPANS = 2.0


def bounce(law: Law, v_n: float, v_t: float, r_omega: float) -> tuple[float, float, float, float]:
    """(v_n, v_t, r omega, contact time) at the exit of one collision starting to touch at
    (v_n < 0, v_t, r omega) (:func:`_bounce`)."""
    return _bounce(law, v_n, v_t, r_omega)[:4]


def _bounce(law: Law, v_n: float, v_t: float, r_omega: float) -> tuple[float, float, float, float, float]:
    """(v_n, v_t, r omega, contact time, the force's end) of one collision.

    Three legs, each restarted at every stick/slip switch: in time from first touch to the
    deepest point and back out to half the deepest overlap; then the tail in the variable
    x = sqrt(delta), down to TAIL_END of its start: near the exit a = sqrt(r delta) has an
    infinite slope in time (and a rescaled history a term h a'/a), which in x are smooth.
    """
    contact = _Contact(law)
    speed = -v_n
    y = np.array([0.0, speed, v_t, r_omega, 0.0, 0.0])
    slip = v_t + r_omega
    undamped_depth = ((law.power + 1.0) * law.m * speed**2 / (2.0 * law.K)) ** (1.0 / (law.power + 1.0))
    span = 10.0 * undamped_depth / speed  # several contact times
    phase, first = contact.first_phase(speed, slip, span)
    sigma = math.copysign(1.0, slip) if slip else 1.0
    leg, x, x_tail = "load", 0.0, 0.0
    holds = can_hold(law.c_n, law.power, law.damping_power, law.tensile)
    for _ in range(MAX_PHASES):
        tail = leg == "tail"
        end = x_tail * TAIL_END if tail else x + span
        events = contact.events(phase, sigma, leg) + ([_held(HELD_SPANS * span)] if tail and holds else [])
        sol = solve_ivp(contact.rhs(phase, sigma, tail), (x, end), y, method="DOP853", rtol=RTOL, atol=ATOL,
                        events=events, first_step=first if x == 0.0 else None)
        hit = [j for j, times in enumerate(sol.t_events) if times.size]
        if not hit:
            if not tail or sol.status != 0:
                if holds and leg == "unload":  # its overlap closing too slowly to reach the tail
                    raise contact_held(v_n)
                raise RuntimeError(f"a contact's {leg} did not end: {sol.message}")
            return -sol.y[_DR, -1], sol.y[_V, -1], sol.y[_W, -1], sol.y[_T, -1], sol.y[_T, -1]
        which = min(hit, key=lambda j: abs(sol.t_events[j][0] - x))
        x, y = float(sol.t_events[which][0]), np.array(sol.y_events[which][0])
        if tail and x <= end * (1.0 + 1e-9):  # a switch at the tail's end, where the forces have gone
            return -y[_DR], y[_V], y[_W], y[_T], y[_T]
        name = events[which].__name__
        if name == "held":
            raise contact_held(v_n)
        if name == "turn":  # no force from here: the overlap closes at the rate it has
            return -y[_DR], y[_V], y[_W], y[_T] + y[_D] / -y[_DR], y[_T]
        if name == "deepest":
            leg, contact.tail_overlap = "unload", TAIL_START * y[_D]
        elif name == "tail":
            leg, x = "tail", math.sqrt(y[_D])
            x_tail = x
        elif name == "to_slip":
            phase, sigma = "slip", math.copysign(1.0, -contact.stick_force(y))
        else:  # to_stick: the history starts from the cap's
            y[_H] = contact.pinned_history(y, sigma)
            phase = "stick"
    raise RuntimeError(f"more than {MAX_PHASES} stick and slip phases in one contact")


def _held(limit: float):
    """The tail's event where the contact has lasted ``limit`` (in time, which the tail carries as a state)."""
    def held(x, y):
        return limit - y[_T]

    held.terminal, held.direction = True, -1
    return held


@lru_cache(maxsize=65536)
def normal_exit(law: Law, speed: float) -> tuple[float, float, float]:
    """(restitution, contact time, the force's end) of the normal motion alone at impact speed
    ``speed`` (no slip; the force ends before the contact with limit_damping)."""
    v_n, _, _, time, force_end = _bounce(law, -speed, 0.0, 0.0)
    return v_n / speed, time, force_end


def bounce_many(law: Law, states) -> np.ndarray:
    """(n, 4) (v_n, v_t, r omega, contact time) at the exit of (n, 3) initial states
    (v_n, v_t, r omega), one collision each."""
    return np.array([bounce(law, *s) for s in np.atleast_2d(states)])


def exit_slips(law: Law, springs, dashpots, v_n: float = -1.0) -> np.ndarray:
    """Each uncapped contact's exit slip rate u'(out) for u'(in) = 1 (v_t = 1, r omega = 0), for ``law``
    with its spring k and tangential dashpot c_t taken from ``springs`` and ``dashpots`` in turn.

    The normal motion is the same for all, and without a cap each slip is linear and has no switches:
    one integration carries them all side by side (the legs of :func:`_bounce`), at the cost of about
    one. Each agrees with its own :func:`bounce` to the integrator's tolerance.
    """
    if math.isfinite(law.mu):
        raise ValueError("exit_slips takes uncapped laws (a cap switches each contact on its own)")
    k, c_t = np.asarray(springs, dtype=float), np.asarray(dashpots, dtype=float)
    n, contact = k.size, _Contact(law)  # its radius, normal force and dashpot factor read y[0], y[1] as here
    y = np.concatenate([[0.0, -v_n, 0.0], np.ones(n), np.zeros(2 * n)])  # overlap, its rate, time; v, w, h

    def rhs(tail: bool):
        def f(x, y):
            (a, shrink), rate = contact.radius(y), y[1]
            v, w, h = y[3:3 + n], y[3 + n:3 + 2 * n], y[3 + 2 * n:]
            spring, slip = k * a**law.spring_power, v + w
            force_t = (h if law.force_history else -spring * h) - c_t * contact.dashpot(y) * slip
            h_rate = -spring * slip if law.force_history else slip
            if law.rescale and rate < 0.0:  # a'/a, zero where the overlap is
                h_rate = h_rate + h * shrink
            rates = np.concatenate([[rate, -contact.normal(y) / law.m, 1.0], force_t / law.m,
                                    force_t / (law.alpha * law.m), h_rate])
            return rates * (2.0 * x / rate) if tail else rates
        return f

    def event(fn):
        fn.terminal, fn.direction = True, -1
        return fn

    def leg(x, end, y, events, tail=False, **options):
        """(the state where the leg's first event stops it, that event's index); the tail may instead reach
        its end (index None)."""
        sol = solve_ivp(rhs(tail), (x, end), y, method="DOP853", rtol=RTOL, atol=ATOL, events=events, **options)
        hit = [j for j, times in enumerate(sol.t_events) if times.size]
        if hit:
            return sol.y_events[hit[0]][0], hit[0]
        if not tail or sol.status != 0:
            raise RuntimeError(f"a contact's {'tail' if tail else 'leg'} did not end: {sol.message}")
        return sol.y[:, -1], None

    limit = [] if law.tensile or law.c_n == 0.0 else [event(lambda x, y: contact.normal(y))]  # limit_damping's turn
    depth = ((law.power + 1.0) * law.m * v_n**2 / (2.0 * law.K)) ** (1.0 / (law.power + 1.0))
    span = 10.0 * depth / -v_n
    y, _ = leg(0.0, span, y, [event(lambda x, y: y[1])], first_step=span * 1e-9)  # to the deepest point
    start = TAIL_START * y[0]
    y, which = leg(0.0, span, y, [event(lambda x, y: y[0] - start)] + limit)
    if which == 0:  # the force has not turned to pull (there the contact ends): the tail
        x = math.sqrt(y[0])
        y, _ = leg(x, x * TAIL_END, y, limit, tail=True)
    return y[3:3 + n] + y[3 + n:3 + 2 * n]
