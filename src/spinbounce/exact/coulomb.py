"""Exact Coulomb-capped wall collisions in the paper's plane, many spheres at once.

The model is :mod:`.oracle`'s (read its docstring), restricted to the plane (v_n, v_t,
r omega). There every piece of the contact problem has a closed form, so nothing is
integrated:

* the normal motion is the damped oscillator of Eq. 15 (with gamma_n): the overlap, the
  force F_n and so the cap c = mu |F_n| are explicit functions of time, all proportional
  to |v_n|. The cap is mu F_n until F_n turns tensile (at ``collision_time(tensile=False)``)
  and -mu F_n after it, up to the exit (or zero, under ``limit_damping``). The Hertzian
  overlap (``normal = "hertz"``) is exact too (:mod:`._coulomb_normal`);
* sticking: the trial force A = kt xi + gamma_t u' and the slip rate u' obey
  A' = kt u' - gamma_t s A, u'' = -s A with s = (1 + 1/alpha)/m (the slip's inverse
  reduced mass, as in Eq. 8): a 2x2 linear system solved by its matrix exponential;
* sliding: A = sigma c with sigma = +-1, so u'' = -s sigma c, and the integral of c is
  the normal impulse, m times the change of the overlap rate: u' is explicit too.

A stick ends at the first downward zero of h = c - |A|; a slide ends at the first
downward zero of g = sigma kt u' - gamma_t s c - c' (the rate at which sticking would push
A outwards, less the cap's growth: the oracle's ``to_stick``), both located by
:mod:`._coulomb_search`. A switching function counts as crossed only once it is below zero
by more than its rounding noise, so ties (a contact that rides the cap, as at the magic
ratio of Eq. 20) do not chatter. The sphere enters only through u'(0)/|v_n|; the final
velocities follow from the change of u' as in Eq. 10.
"""

from __future__ import annotations

import math
from collections import namedtuple
from functools import lru_cache

import numpy as np

from ._coulomb_normal import HertzPhase, HookeNormal, HookePhase
from ._coulomb_search import first_crossing, root

__all__ = ["bounce_2d", "bounce_3d", "MAX_SWITCHES"]

#: More regime switches than this in one contact mean the regimes chatter: refuse.
MAX_SWITCHES = 200
#: Grid step times the fastest rate of the contact (normal or tangential, oscillation or decay).
GRID_STEP = 0.2
#: Fewest grid intervals per normal phase.
MIN_INTERVALS = 24
#: A switching function must fall below zero by this much of its rounding scale to count.
NOISE = 1e-13


class _Stick:
    """y = (A, u') with y' = M y, M = [[-gamma_t s, kt], [-s, 0]] while the contact sticks.

    E(tau) = e^(a tau) [C I + S (M - a I)], a = -gamma_t s / 2: C, S are cos and sin/w
    (underdamped), cosh and sinh/w (overdamped), written without overflow or cancellation.
    """

    def __init__(self, kt: float, gts: float, s: float):
        self.kt, self.gts, self.s = kt, gts, s
        self.a = -0.5 * gts
        self.disc = self.a**2 - kt * s  # < 0: the stuck slip oscillates

    def fastest_rate(self) -> float:
        """The larger decay rate (overdamped) or |a| plus the frequency (underdamped)."""
        return abs(self.a) + math.sqrt(abs(self.disc))

    def propagator(self, tau):
        tau = np.asarray(tau, dtype=float)
        if self.disc < 0.0:
            w = math.sqrt(-self.disc)
            grow = np.exp(self.a * tau)
            e_c, e_s = grow * np.cos(w * tau), grow * np.sin(w * tau) / w
        else:
            kappa = math.sqrt(self.disc)
            slow, fast = np.exp((self.a + kappa) * tau), np.exp((self.a - kappa) * tau)
            z = 2.0 * kappa * tau
            ratio = np.where(z > 0.0, -np.expm1(-z) / np.where(z > 0.0, z, 1.0), 1.0)
            e_c, e_s = 0.5 * (slow + fast), tau * slow * ratio
        return e_c + self.a * e_s, self.kt * e_s, -self.s * e_s, e_c - self.a * e_s

    def advance(self, tau, force, slip_rate):
        e11, e12, e21, e22 = self.propagator(tau)
        return e11 * force + e12 * slip_rate, e21 * force + e22 * slip_rate


#: The parts of a ContactModel the solver reads (a cache key whatever the model class), the
#: normal law's contact_radius last: the normal force grows with it (Hertzian).
_Fields = namedtuple("_Fields", "m r alpha kn kt gamma_n gamma_t mu limit_damping contact_radius")


def _sign(x, fallback):
    """sign(x), else sign(fallback), else +1: the oracle's choice of a direction."""
    return np.where(x != 0.0, np.sign(x), np.where(fallback != 0.0, np.sign(fallback), 1.0))


class _Solver:
    """One model: its coefficients, its phases, and the stick/slide segments of a batch."""

    def __init__(self, model):
        if model.mu is None:
            raise ValueError("a Coulomb solver needs a finite mu (theory.scattering_matrix is "
                             "exact without one)")
        self.hertz = model.contact_radius
        self.mu, self.kt, self.alpha, self.m = model.mu, model.kt, model.alpha, model.m
        self.s = (1.0 + 1.0 / model.alpha) / model.m
        self.gts = model.gamma_t * self.s
        self.stick = _Stick(self.kt, self.gts, self.s)
        self.kn_r = model.kn * math.sqrt(model.r)
        if self.hertz:  # one phase per batch: its times depend on each sphere's speed
            return
        normal = HookeNormal(model.m, model.kn, model.gamma_n)
        turn = normal.t_turn if model.gamma_n > 0.0 else normal.t_exit
        fastest = max(math.sqrt(model.kn / model.m), normal.beta, self.stick.fastest_rate())

        def phase(t_a, t_b, sign):
            intervals = max(MIN_INTERVALS, math.ceil((t_b - t_a) * fastest / GRID_STEP))
            return HookePhase(self, normal, t_a, t_b, sign, intervals)

        self.hooke_phases = [phase(0.0, turn, 1.0)]
        if model.gamma_n > 0.0 and not model.limit_damping:
            self.hooke_phases.append(phase(turn, normal.t_exit, -1.0))

    def phases(self, speed):
        if not self.hertz:
            return self.hooke_phases
        return [HertzPhase(self, speed, self.kn_r, self.stick.fastest_rate(), MIN_INTERVALS,
                           GRID_STEP)]

    # -- the contact ------------------------------------------------------------------
    def final_slip_rate(self, slip_rate, speed):
        """u' at the end of the contact, per unit |v_n|, from u'(0) per unit |v_n|."""
        u = np.array(slip_rate, dtype=float)
        everyone = np.arange(u.size)
        force = self.gts / self.s * u  # A = gamma_t u' at first touch: no history yet
        for k, phase in enumerate(self.phases(speed)):
            t = np.full(u.shape, 0.0 if k == 0 else phase.t_a)
            end = phase.end(everyone)
            c, rate, _ = phase.cap(everyone, t)
            if k:  # the tensile turn: the cap restarts from zero, the force with it
                force, c, rate = np.zeros_like(u), 0.0, np.abs(rate)
            force, sliding, direction = self._start(force, u, c, rate)
            for _ in range(MAX_SWITCHES + 1):
                live = t < end
                if not live.any():
                    break
                stuck = np.flatnonzero(live & ~sliding)
                if stuck.size:
                    self._stick_segment(phase, stuck, t, force, u, sliding, direction)
                slides = np.flatnonzero((t < end) & sliding)
                if slides.size:
                    self._slide_segment(phase, slides, t, force, u, sliding, direction)
            else:
                raise RuntimeError(f"more than {MAX_SWITCHES} regime switches (chattering)")
        return u

    def _start(self, force, u, c, c_rate):
        """The regime where the cap starts (first touch or tensile turn), as the oracle's
        ``start``: stick inside the cap; on it, slide if sticking would push A outwards
        faster than the cap grows, else stick on the cap."""
        inside = np.abs(force) < c
        direction = _sign(force, u)
        sliding = ~inside & (direction * self.kt * u - self.gts * c > c_rate)
        return np.where(inside, force, direction * c), sliding, direction

    def _segment_end(self, phase, rows, t_s, k0, noise, on_grid, exact):
        """(switched, time) per sphere: its first switch after t_s, else the phase's end."""
        f_s, d_s, _ = exact(np.arange(rows.size), t_s)
        lo, hi, f_lo, f_hi = first_crossing(lambda sel, k: phase.times(rows[sel], k), phase.last, k0, t_s,
                                            f_s, d_s, noise, on_grid, exact, phase.t_scale)
        event = np.isfinite(hi)
        ends = np.broadcast_to(phase.end(rows), rows.shape).copy()
        if event.any():
            sel = np.flatnonzero(event)
            ends[sel] = root(lambda which, x: exact(sel[which], x)[:2], lo[sel], hi[sel],
                             f_lo[sel], f_hi[sel], phase.t_scale)
        return event, ends

    def _stick_segment(self, phase, rows, t, force, u, sliding, direction):
        t_s, a_s, u_s = t[rows], force[rows], u[rows]
        k0 = phase.first_index(rows, t_s)
        a0, u0 = self.stick.advance(phase.times(rows, k0) - t_s, a_s, u_s)

        def on_grid(sel, offsets, k):
            e11, e12, e21, e22 = phase.steps(rows[sel], offsets)
            a = e11 * a0[sel, None] + e12 * u0[sel, None]
            v = e21 * a0[sel, None] + e22 * u0[sel, None]
            c, c1, _, _ = phase.on_grid(rows[sel], k)
            return c - np.abs(a), c1 - np.sign(a) * (self.kt * v - self.gts * a)

        def exact(sel, times):
            a, v = self.stick.advance(times - t_s[sel], a_s[sel], u_s[sel])
            c, c1, c2 = phase.cap(rows[sel], times)
            d1 = self.kt * v - self.gts * a  # A'
            d2 = -self.kt * self.s * a - self.gts * d1  # A''
            sg = np.sign(a)
            return c - np.abs(a) + noise[sel], c1 - sg * d1, c2 - sg * d2

        noise = NOISE * (phase.cap_scale(rows) + np.abs(a_s)
                         + self.kt * np.abs(u_s) * phase.t_scale)
        event, ends = self._segment_end(phase, rows, t_s, k0, noise, on_grid, exact)
        a_e, u_e = self.stick.advance(ends - t_s, a_s, u_s)
        t[rows], force[rows], u[rows] = ends, a_e, u_e
        sliding[rows] = event
        direction[rows] = np.where(event, _sign(a_e, u_e), direction[rows])

    def _slide_segment(self, phase, rows, t, force, u, sliding, direction):
        t_s, u_s, sigma = t[rows], u[rows], direction[rows]
        impulse = phase.sign * self.mu * self.m  # integral of c = impulse * (x'(t_s) - x'(t))
        rate_s = phase.rate(rows, t_s)
        offset = sigma * self.kt * u_s - self.kt * self.s * impulse * rate_s  # g = offset + H

        def on_grid(sel, offsets, k):
            _, _, push, push_rate = phase.on_grid(rows[sel], k)
            return offset[sel, None] + push, push_rate

        def exact(sel, times):
            _, _, push, push_rate, push_accel = phase.cap_and_push(rows[sel], times)
            return offset[sel] + push + noise[sel], push_rate, push_accel

        noise = NOISE * (self.kt * np.abs(u_s) + phase.push_scale(rows))
        event, ends = self._segment_end(phase, rows, t_s, phase.first_index(rows, t_s), noise, on_grid, exact)
        u_e = u_s - self.s * sigma * impulse * (rate_s - phase.rate(rows, ends))
        t[rows], u[rows] = ends, u_e
        force[rows] = sigma * phase.cap(rows, ends)[0]
        sliding[rows] = ~event


@lru_cache(maxsize=16)
def _solver(*fields) -> _Solver:
    """One solver per model: its tables are built once for every batch it solves."""
    return _Solver(_Fields(*fields))


def _slip_change(model, v_n, slip):
    """(speed |v_n|, restitution, Delta u') for slip rates u'(0) along one line."""
    if not np.all(v_n < 0.0):
        raise ValueError("every v_n must be < 0 (towards the wall)")
    speed = -v_n
    fields = (getattr(model, name) for name in _Fields._fields[:-1])
    solver = _solver(*fields, model.normal_law.contact_radius)
    start = slip / speed
    restitution = 1.0 if solver.hertz else model.restitution  # Hertz here has gamma_n = 0
    return speed, restitution, (solver.final_slip_rate(start, speed) - start) * speed


def _states(*columns):
    return np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float)) for x in columns))


def bounce_2d(model, v_n, v_t, omega) -> np.ndarray:
    """(n, 3) final (v_n, v_t, r omega) of spheres that start touching the wall with
    velocity v_n < 0, tangential velocity v_t and spin omega (the paper's sign).

    Same contract as :func:`.oracle.bounce_many` for states in the plane, Hookean or
    Hertzian, exact to rounding: the normal outcome is Eq. 15's (restitution e; 1 for
    Hertz, which has no normal damping), the tangential one follows the stick and slide
    segments in closed form.
    """
    v_n, v_t, omega = _states(v_n, v_t, omega)
    r_omega = model.r * omega
    speed, restitution, change = _slip_change(model, v_n, v_t + r_omega)
    share = model.alpha / (1.0 + model.alpha)  # Delta v_t / Delta u' (Eq. 10's weights)
    return np.column_stack([restitution * speed, v_t + share * change,
                            r_omega + change / (1.0 + model.alpha)])


def bounce_3d(model, v_n, v_t, omega, v_s, omega_s, omega_n) -> np.ndarray:
    """(n, 6) final states in the order of ``STATE_3D`` (v_n, v_t, r omega, v_s,
    r omega_s, r omega_n), as :func:`.oracle.bounce_many` gives them.

    The 3-D contact is the plane's along the first slip direction, exactly: the history
    starts at zero, so the trial force A = gamma_t u' is parallel to the slip rate u' at
    first touch; sticking moves A and u' by kt u' - gamma_t s A and -s A, sliding moves
    u' by -s c (A/|A|), and turns A only by the part of u' across it (the oracle's
    s' = kt u'_perp/c), which is zero. So A and u' stay on the line of u'(0) (reversing
    along it as in the plane), and the solver of the plane gives the slip along it.
    The spin about the normal never changes.
    """
    v_n, v_t, omega, v_s, omega_s, omega_n = _states(v_n, v_t, omega, v_s, omega_s, omega_n)
    r = model.r
    slip = np.stack([v_t + r * omega, v_s + r * omega_s])
    size = np.hypot(*slip)
    line = np.divide(slip, size, out=np.zeros_like(slip), where=size > 0.0)
    speed, restitution, change = _slip_change(model, v_n, size)
    share = model.alpha / (1.0 + model.alpha)
    dv = share * change * line
    dr_omega = change * line / (1.0 + model.alpha)
    return np.column_stack([restitution * speed, v_t + dv[0], r * omega + dr_omega[0],
                            v_s + dv[1], r * omega_s + dr_omega[1], r * omega_n])
