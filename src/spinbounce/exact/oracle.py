"""An independent, high-accuracy oracle for one sphere hitting the wall: any scene.

The closed forms of :mod:`theory` cover the spring model without a Coulomb limit. With
a finite friction coefficient the contact sticks and slides in turn, and nothing closed
is known; this module integrates the continuous-time equations instead, with scipy's
adaptive DOP853 at a relative tolerance of 1e-12, and locates every change of regime
as an event (end of contact, stick -> slip, slip -> stick, and the normal force's end
under ``limit_damping``), restarting the integration there so no step straddles a kink.

The model is the continuous-time limit of LAMMPS's ``granular hooke ... tangential
linear_history`` wall contact, written in the paper's variables and in 3-D:

* normal: overlap delta = r - z, F_n = kn delta + gamma_n delta' (or kn sqrt(r) delta^(3/2)
  + gamma_n delta' with ``normal = "hertz"``; tensile allowed, or cut at zero with
  ``limit_damping``), m v_n' = F_n;
* tangential, a 2-vector per quantity (directions t and s): velocity v, r*omega with the
  paper's sign (so the slip rate is u' = v + r*omega in each direction, see
  :mod:`scenes`), and the elastic 'trial force' A = kt xi + gamma_t u' of the history xi;
  m v' = F_t and alpha m (r omega)' = F_t; the spin about the normal never changes;
* sticking (|A| < mu |F_n|): F_t = -A and A' = kt u' + gamma_t u'';
* sliding (|A| = mu |F_n|): F_t = -mu |F_n| s with s the unit vector of A. LAMMPS rescales
  the history so that |A| stays on the cap (``linear_history``'s rescale); in continuous
  time the cap's radius follows mu |F_n| and s turns towards the slip velocity,
  s' = kt u'_perp / (mu |F_n|), with u'_perp the part of u' across s (zero in the plane;
  stiff in 3-D near the contact's ends, see ``_Contact.integrate``). Sliding lasts while
  the sticking rate of A would carry it beyond the cap: s . (kt u' + gamma_t u''_stick)
  > d(mu |F_n|)/dt.

The cap mu |F_n| uses the magnitude of the total normal force, as LAMMPS does: a normal
force that turns tensile (gamma_n > 0 without ``limit_damping``) still holds friction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the oracle reads a model's fields; it needs nothing else of model/
    from ..model.contact import ContactModel  # noqa: F401

__all__ = ["OracleResult", "bounce", "bounce_many", "RTOL", "ATOL"]

METHOD = "DOP853"
RTOL = 1.0e-12  # a Hertzian contact gets a tenth: at 1e-12 an extreme slide (mu ~ 1e3) kept 1.2e-8
ATOL = 1.0e-14
#: A 3-D slide's absolute tolerance on log |u'_perp|: a relative 1e-3 of a slip across s
#: that starts at rounding level (the history starts at zero, so A is along u' at first touch).
LOG_ACROSS_ATOL = 1.0e-3
#: Below this fraction of its typical size (mu m |v_n| / tau) a 3-D slide's cap turns s no
#: faster than at it. Where the slip opposes s (the cap shrinking fast), u'_perp grows at
#: kt |p| / c: unchecked, rounding would grow by 1e12 before the cap's end and turn s at a
#: rate no step can follow. The slower turn only bends a force that small, through an angle
#: the size of u'_perp / |u'|.
TURN_FLOOR = 1.0e-8
#: More regime switches than this in one contact mean the regimes chatter: refuse.
MAX_SWITCHES = 200
#: Events are found from sign changes between steps; a cap on the step (in contact
#: times) keeps an event function from crossing zero twice within one step unseen.
MIN_STEPS_PER_CONTACT = 64

# state layout: delta, v_n, v (2), w = r*omega (2), A or s (2)
_D, _VN, _V, _W, _A = 0, 1, slice(2, 4), slice(4, 6), slice(6, 8)
# a 3-D slide's state (see _Contact.integrate): the same up to w, then the angle of s, the
# log of |u'_perp| and its sign (constant): _TURNING slots in all
_THETA, _LOG_ACROSS, _SIDE, _TURNING = 6, 7, 8, 9


@dataclass(frozen=True)
class OracleResult:
    """Final state of one collision and the regimes it went through.

    ``final`` is (v_n, v_t, r omega, v_s, r omega_s, r omega_n), the 3-D state order used
    across spinbounce; ``regimes`` lists (t_start, name) with name in stick, slip, coast
    (sliding with a cap below 1e-12 of its peak: no tangential force) and free (no force).
    """

    initial: np.ndarray
    final: np.ndarray
    t_exit: float
    regimes: tuple[tuple[float, str], ...]
    nfev: int = 0

    @property
    def pattern(self) -> str:
        """The regimes in order, e.g. 'stick-slip' (leaving out 'coast', a slide's last
        1e-12 of force, and 'free', the force-free drift out under limit_damping)."""
        names = [name for _, name in self.regimes if name not in ("free", "coast")]
        return "-".join(n for i, n in enumerate(names) if i == 0 or n != names[i - 1])


class _Contact:
    """Forces and their rates for one model, in the paper's variables."""

    def __init__(self, model: ContactModel):
        if model.mu is None:
            raise ValueError("the oracle models LAMMPS's Coulomb cap: give a finite mu "
                             "(theory.scattering_matrix is exact without one)")
        self.m, self.r, self.alpha = model.m, model.r, model.alpha
        self.kn, self.kt = model.kn, model.kt
        self.gn, self.gt, self.mu = model.gamma_n, model.gamma_t, model.mu
        self.tensile = not model.limit_damping
        self.hertz = model.normal_law.contact_radius
        self.slip_mass = (1.0 + 1.0 / self.alpha) / self.m  # u'' = slip_mass * F_t
        # set per collision (bounce): a force and a rate of force negligible against the
        # contact's own, the margins by which a switching function must pass zero to count
        self.floor = self.floor_rate = 0.0
        self.turn_floor = 0.0  # a 3-D slide turns s no faster than at this cap (TURN_FLOOR)
        self.turned = False  # whether F_n has passed through zero on the way out

    def normal(self, y) -> tuple[float, float]:
        """(F_n, dF_n/dt) before any cut at zero, continued smoothly past the exit.

        Every event function stays smooth where a step overshoots a switch (the exit, the
        normal force's turn): scipy locates an event by a root search over the whole step,
        and a function held flat at zero there hands the search the step's far end as
        its root, which then hides an earlier event (a turn just before the exit).
        """
        delta, rate = y[_D], -y[_VN]
        if self.hertz:  # F = kn sqrt(r) delta^(3/2) (LAMMPS's hertz wall), odd beyond the exit
            root = math.sqrt(self.r * abs(delta))
            f = self.kn * root * delta + self.gn * rate
            stiffness = 1.5 * self.kn * root
        else:
            f = self.kn * delta + self.gn * rate
            stiffness = self.kn
        accel = -f / self.m  # delta'' = -v_n'
        return f, stiffness * rate + self.gn * accel

    def cap(self, y) -> tuple[float, float]:
        """(mu |F_n|, its rate), after limit_damping's cut, continued smoothly past a turn.

        F_n >= 0 until the normal force turns (the ``force_zero`` event sets ``turned``)
        and <= 0 after it, so |F_n| = F_n or -F_n by the phase, never by a value that
        rounding may leave a hair on the wrong side of zero. Within a step that overshoots
        the turn the cap goes on smoothly below zero (the event cuts the step there).
        """
        f, df = self.normal(y)
        if self.turned:
            if not self.tensile:
                return 0.0, 0.0
            return -self.mu * f, -self.mu * df
        return self.mu * f, self.mu * df

    def rhs(self, phase: str):
        kt, gt, m, alpha = self.kt, self.gt, self.m, self.alpha

        def f(t, y):
            dy = np.zeros(y.size)
            dy[_D] = -y[_VN]
            if phase == "free":
                return dy
            dy[_VN] = 0.0 if self.turned and not self.tensile else self.normal(y)[0] / self.m
            if phase == "coast":
                return dy
            u_rate = y[_V] + y[_W]
            if phase == "stick":
                force = -y[_A]
                dy[_A] = kt * u_rate + gt * self.slip_mass * force
            else:  # slip: A = c s rides on the cap, s turning towards the slip
                c, _ = self.cap(y)
                s = self.slide_direction(y)
                force = -c * s
                if y.size == _TURNING and y[_SIDE]:  # in the plane (and at q = 0) s stays put
                    rate = kt / math.hypot(c, self.turn_floor)
                    # |q| <= |u'|: bounds a trial step that overshoots log |q| (then rejected)
                    across = min(math.exp(min(y[_LOG_ACROSS], 700.0)), math.hypot(*u_rate))
                    dy[_THETA] = rate * y[_SIDE] * across
                    dy[_LOG_ACROSS] = -rate * float(np.dot(s, u_rate))
            dy[_V] = force / m
            dy[_W] = force / (alpha * m)
            return dy

        return f

    # -- events -----------------------------------------------------------------------
    def events(self, phase: str):
        def exit_(t, y):
            return y[_D]

        out = [exit_]
        if phase == "stick":
            def to_slip(t, y):
                c, _ = self.cap(y)
                return c - math.hypot(*y[_A]) + self.floor

            out.append(to_slip)
        elif phase == "slip":
            def to_stick(t, y):
                c, dc = self.cap(y)
                return self.push(y, self.slide_direction(y), c) - dc + self.floor_rate

            def cap_gone(t, y):
                return self.cap(y)[0] - self.floor

            out += [to_stick, cap_gone]
        if phase != "free" and self.gn > 0.0 and not self.turned:
            # the normal force ends (limit_damping) or turns tensile: there the cap is zero
            # and grows again, a kink the step-wise event search could miss inside one step
            def force_zero(t, y):
                return self.normal(y)[0]

            out.append(force_zero)
        for event in out:  # each stops the integration where it falls through zero
            event.terminal, event.direction = True, -1.0
        return out

    def switch(self, name: str, y, phase: str) -> str:
        """The regime after the event ``name`` (puts A on or inside the cap).

        A switching function must fall below zero by a negligible margin (``floor``,
        ``floor_rate``) to count, and at a tangency the new regime would be left as soon
        as entered: the function it starts with is zero, and the first step's rounding may
        put it below zero, a spurious event at the switch itself. So a switch into a
        slide is checked as on the cap at first touch (``on_cap``): a contact that would leave the
        cap no faster than the cap grows sticks on it instead.
        """
        cap, dcap = self.cap(y)
        if name == "force_zero":
            self.turned = True  # F_n stays below zero from here to the exit
            if not self.tensile:
                return "free"
            if phase == "slip":
                y[_A] = 0.0  # a slide's cap is zero here
            return self.start(y, cap_rising=True)
        if name == "cap_gone" or (cap < self.floor and dcap <= 0.0):
            y[_A] = 0.0  # the cap is gone or going: no tangential force left to speak of
            if self.gn > 0.0 and not self.turned and self.normal(y)[1] < 0.0:
                # F_n ~ 0 and falling: the turn is here (an event starting at its root may miss it)
                return self.switch("force_zero", y, "coast")
            return "coast"
        if name == "to_slip":
            return self.on_cap(y, cap, dcap)
        y[_A] = cap * y[_A]  # to_stick: A rides the cap along s
        return "stick"

    def slide_direction(self, y) -> np.ndarray:
        """A slide's unit vector s of A: as stored in the plane, from its angle in 3-D."""
        if y.size == _TURNING:
            return np.array([math.cos(y[_THETA]), math.sin(y[_THETA])])
        return y[_A]

    def integrate(self, phase: str, events, y, t: float, horizon: float, tau: float):
        """One regime from t to its first event (scipy's ``solve_ivp``).

        A 3-D slide turns s towards the slip: with theta the angle of s, p = u'.s and
        q = u'_perp the slip along and across s, theta' = kt q / c, and since the friction
        force lies along s, q' = -theta' p = -(kt p / c) q. That rate grows without bound
        as the cap shrinks at first touch and at the exit, a stiff decay (growth, where the
        slip opposes s) that an explicit method cannot follow; but q' is linear in q, so
        the slide integrates log |q| (its rate -kt p / c a mere quadrature) and keeps q's
        sign, which never changes. s stays a unit vector, and a slip exactly along s
        (q = 0) stays so. (LSODA on s stopped in 1 of 7 random 3-D contacts; BDF and
        Radau, their Jacobian stale as c changes by decades, let s drift off the slip by
        up to 1 rad.)
        """
        atol = ATOL
        if phase == "slip" and (y[3] or y[5] or y[7]):
            s = y[_A]
            across = float(s[0] * (y[5] + y[3]) - s[1] * (y[4] + y[2]))  # q = u' . (-s_y, s_x)
            y = np.concatenate([y[:_THETA], [math.atan2(s[1], s[0]),
                                             math.log(abs(across)) if across else 0.0,
                                             math.copysign(1.0, across) if across else 0.0]])
            atol = np.full(_TURNING, ATOL)
            atol[_LOG_ACROSS] = LOG_ACROSS_ATOL
        rtol = RTOL / 10 if self.hertz else RTOL
        return solve_ivp(self.rhs(phase), (t, horizon), y, method=METHOD, rtol=rtol, atol=atol,
                         events=events, max_step=tau / MIN_STEPS_PER_CONTACT)

    def push(self, y, s, c: float) -> float:
        """How fast sticking would carry A outwards along s, with A on a cap of radius c:
        s . (kt u' + gamma_t u''), the sticking force being -c s."""
        return float(np.dot(s, self.kt * (y[_V] + y[_W]))) - self.gt * self.slip_mass * c

    def start(self, y, cap_rising: bool = False) -> str:
        """The regime at first touch (or where the cap restarts); puts A on or inside the cap.

        At first touch the cap may be zero, and A = gamma_t u' need not be: LAMMPS's first
        step then projects the trial force onto the cap. Whether the contact goes on
        sliding is decided, as at any later time on the cap, by comparing the rate at
        which sticking would push A outwards with the rate at which the cap grows.
        """
        c, dc = self.cap(y)
        if cap_rising:  # at a tensile turn the cap restarts from zero
            c, dc = 0.0, abs(dc)
        if math.hypot(*y[_A]) < c:
            return "stick"
        return self.on_cap(y, c, dc)

    def on_cap(self, y, c: float, dc: float) -> str:
        """With A on the cap c (rising at dc), or just past it: slide if sticking would
        push A outwards faster than the cap grows, else stick with A on the cap."""
        # s: the direction of A, else of the slip, else t
        vec = next((v for v in (y[_A], y[_V] + y[_W]) if math.hypot(*v) > 0.0), None)
        s = np.array([1.0, 0.0]) if vec is None else vec / math.hypot(*vec)
        if self.push(y, s, c) > dc:
            y[_A] = s
            return "slip"
        y[_A] = c * s
        return "stick"


def bounce(model: ContactModel, v_n: float, v_t: float = 0.0, omega: float = 0.0, *,
           v_s: float = 0.0, omega_s: float = 0.0, omega_n: float = 0.0) -> OracleResult:
    """One sphere that starts touching the wall (delta = 0) with velocity v_n < 0.

    ``omega`` (paper's sign) couples with ``v_t``, ``omega_s`` with ``v_s``, and
    ``omega_n`` is the spin about the wall's normal.
    """
    if not v_n < 0.0:
        raise ValueError(f"v_n = {v_n!r}: must be < 0 (towards the wall)")
    c = _Contact(model)
    tau = float(model.contact_times(v_n)[0])
    # a slide whose cap has shrunk below 1e-12 of its typical value (mu m |v_n| / tau)
    # coasts to the exit or to the tensile turn with no tangential force
    c.floor = 1e-12 * (model.mu * model.m * abs(v_n) / tau or 1.0)
    c.floor_rate = c.floor / tau
    c.turn_floor = TURN_FLOOR * c.floor / 1e-12
    r = model.r
    initial = np.array([v_n, v_t, r * omega, v_s, r * omega_s, r * omega_n])
    # (delta, v_n, v, r omega, A): the history starts at zero, so A = gamma_t u'
    y = np.concatenate([[0.0], initial[[0, 1, 3, 2, 4]], model.gamma_t * (initial[[1, 3]] + initial[[2, 4]])])
    phase = c.start(y)
    t = 0.0
    regimes = [(0.0, phase)]
    nfev = 0
    # a generous horizon: the contact must end well within it (checked below)
    horizon = 50.0 * tau
    for _ in range(MAX_SWITCHES):
        events = c.events(phase)
        sol = c.integrate(phase, events, y, t, horizon, tau)
        nfev += sol.nfev
        if sol.status != 1:
            raise RuntimeError(f"oracle: the contact did not end by t = {horizon:g} ({sol.message})")
        hit = min((k for k, te in enumerate(sol.t_events) if te.size), key=lambda k: sol.t_events[k][0])
        t = float(sol.t_events[hit][0])
        y = sol.y_events[hit][0]
        y = np.concatenate([y[:_THETA], c.slide_direction(y)])  # 8 slots (a 3-D slide's angle back to s)
        if hit == 0 or (y[_D] <= 0.0 and y[_VN] > 0.0):  # exit (a switch can fall on it)
            break
        phase = c.switch(events[hit].__name__, y, phase)
        regimes.append((t, phase))
    else:
        raise RuntimeError(f"oracle: more than {MAX_SWITCHES} regime switches (chattering)")
    final = np.array([y[_VN], y[_V][0], y[_W][0], y[_V][1], y[_W][1], r * omega_n])
    return OracleResult(initial, final, t, tuple(regimes), nfev)


def bounce_many(model: ContactModel, v_n, v_t, omega, v_s=None, omega_s=None, omega_n=None) -> np.ndarray:
    """(n, 6) final states for equal-length sequences of initial states."""
    v_n = np.atleast_1d(np.asarray(v_n, dtype=float))
    others = [np.zeros(v_n.size) if x is None else np.broadcast_to(np.asarray(x, dtype=float), v_n.shape)
              for x in (v_t, omega, v_s, omega_s, omega_n)]
    return np.array([bounce(model, *row[:3], v_s=row[3], omega_s=row[4], omega_n=row[5]).final
                     for row in np.column_stack([v_n, *others]).tolist()])
