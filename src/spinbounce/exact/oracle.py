"""An independent, high-accuracy oracle for one sphere hitting the wall: any scene.

The closed forms of :mod:`theory` cover the spring model without a Coulomb limit. With
a finite friction coefficient the contact sticks and slides in turn, and nothing closed
is known; this module integrates the continuous-time equations instead, with scipy's
adaptive DOP853 at a relative tolerance of 1e-12, and locates every change of regime
as an event (end of contact, stick -> slip, slip -> stick, and the normal force's end
under ``limit_damping``), restarting the integration there so no step straddles a kink.

The model is the continuous-time limit of LAMMPS's ``granular`` wall contact with a cap, written
in the paper's variables and in 3-D, for any normal force K delta^p with a dashpot gamma_n a^s and
any tangential spring of :class:`.wall_law.Law` (the paper's ``linear_history`` and the
Mindlin variants, whose stiffness k a, dashpot and history grow or shrink with the contact radius
a = sqrt(r delta); their forces: :mod:`.oracle_forces`):

* normal: m v_n' = F_n (tensile allowed, or cut at zero with ``limit_damping``);
* tangential, a 2-vector per quantity (directions t and s): velocity v, r*omega with the
  paper's sign (so the slip rate is u' = v + r*omega in each direction, see
  :mod:`scenes`), and the elastic 'trial force' A = spring + gamma_t u' of the history;
  m v' = F_t and alpha m (r omega)' = F_t; the spin about the normal never changes;
* sticking (|A| < mu |F_n|): F_t = -A, A' as :func:`.oracle_kernel.stick_rate`
  (the paper's spring: kt u' + gamma_t u'');
* sliding (|A| = mu |F_n|): F_t = -mu |F_n| s with s the unit vector of A. LAMMPS rescales
  the history so that |A| stays on the cap; in continuous time the cap's radius follows
  mu |F_n| and s turns towards the slip velocity, s' = k_x u'_perp / (mu |F_n|), with u'_perp
  the part of u' across s (zero in the plane; stiff in 3-D near the contact's ends, see
  ``_Contact.integrate``) and k_x the sticking A' per unit slip across s. Sliding lasts while
  the sticking rate of A would carry it beyond the cap: s . A'_stick > d(mu |F_n|)/dt.

A contact whose coefficients grow with a starts a hair after first touch and ends a hair before
the exit (FIRST_TOUCH, LAST_OVERLAP), where a's rates are infinite; a rescale's start, the
deepest point, is an event.

The cap mu |F_n| uses the magnitude of the total normal force, as LAMMPS does: a normal
force that turns tensile (gamma_n > 0 without ``limit_damping``) still holds friction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy.integrate import solve_ivp

from . import oracle_classic
from . import oracle_kernel as kernel
from .oracle_forces import A as _A, D as _D, V as _V, VN as _VN, W as _W, Forces
from .wall_law import Law

if TYPE_CHECKING:  # the oracle reads a model's fields; it needs nothing else of model/
    from ..model.contact import ContactModel  # noqa: F401

__all__ = ["OracleResult", "bounce", "bounce_many", "RTOL", "ATOL"]

METHOD = "DOP853"
RTOL = 1.0e-12  # a Hertzian contact gets a tenth: at 1e-12 an extreme slide (mu ~ 1e3) kept 1.2e-8
ATOL = 1.0e-14
#: A 3-D slide's absolute tolerance on log |u'_perp|: a relative 1e-3 of a slip across s
#: that starts at rounding level (the history starts at zero, so A is along u' at first touch).
LOG_ACROSS_ATOL = 1.0e-3
#: Below this fraction of its typical size (mu m |v_n| / tau) a 3-D slide's cap turns s no faster than
#: at it. Where the slip opposes s, u'_perp grows at kt |p| / c: unchecked, rounding would grow 1e12-fold
#: and turn s faster than any step; the slower turn bends a force that small by about u'_perp / |u'|.
TURN_FLOOR = 1.0e-8
#: A contact whose force, spring or dashpot grows with the contact radius a = sqrt(r delta) starts this
#: many contact times after first touch (at a = 0 the rates of a^s are infinite); what the first stretch
#: would have done is there to its leading order (:meth:`_Contact.first_touch`), the rest ~ 1e-12.
FIRST_TOUCH = 1.0e-12
#: Such a contact ends where its overlap is back to this fraction of the undamped largest: its forces
#: ~ a^s vanish there with infinite rates; what they would still do, ~ (1e-12)^(1 + s/2), is left.
LAST_OVERLAP = 1.0e-12
#: More regime switches than this in one contact mean the regimes chatter: refuse.
MAX_SWITCHES = 200
#: A cap on the step (in contact times): no event function crosses zero twice within one step unseen.
MIN_STEPS_PER_CONTACT = 64

# state layout (oracle_forces): delta, v_n, v (2), w = r*omega (2), A or s (2)
# a 3-D slide's state (see _Contact.integrate): the same up to w, then the angle of s, the
# log of |u'_perp| and its sign (constant): _TURNING slots in all
_THETA, _LOG_ACROSS, _SIDE, _TURNING = kernel.THETA, kernel.LOG_ACROSS, kernel.SIDE, kernel.TURNING
#: The regimes by name, as :func:`.oracle_kernel.rates` takes them.
_REGIMES = {"free": kernel.FREE, "coast": kernel.COAST, "stick": kernel.STICK, "slip": kernel.SLIP}


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

    def __init__(self, model: ContactModel, cut: float = 1.0):
        if model.mu is None:
            raise ValueError("the oracle models LAMMPS's Coulomb cap: give a finite mu "
                             "(theory.scattering_matrix is exact without one)")
        law = self.law = Law.of(model)
        self.forces = Forces(law)
        self.m, self.r, self.alpha, self.mu = law.m, law.r, law.alpha, law.mu
        self.gn = law.c_n  # the normal dashpot's prefactor: gamma_n a^s
        self.tensile = not model.limit_damping
        self.classic = law.classic_cap  # the cap resets the history by k alone (oracle_classic)
        self.cut, self.zeno, self.now, self.last_cap = cut, False, 0.0, -math.inf  # oracle_classic.tooth
        self.nonlinear = self.forces.nonlinear
        self.slip_mass = self.forces.slip_mass
        # set per collision (bounce): a force and a rate of force negligible against the
        # contact's own, the margins by which a switching function must pass zero to count
        self.floor = self.floor_rate = 0.0
        self.turn_floor = 0.0  # a 3-D slide turns s no faster than at this cap (TURN_FLOOR)
        self.turned = False  # whether F_n has passed through zero on the way out
        self.unloading = False  # whether the overlap has passed its deepest point
        self.exit_overlap = 0.0  # where the contact counts as ended (LAST_OVERLAP)

    def cap(self, y) -> tuple[float, float]:
        """(mu |F_n|, its rate), after limit_damping's cut, continued smoothly past a turn.

        F_n >= 0 until the normal force turns (the ``force_zero`` event sets ``turned``)
        and <= 0 after it, so |F_n| = F_n or -F_n by the phase, never by a value that
        rounding may leave a hair on the wrong side of zero. Within a step that overshoots
        the turn the cap goes on smoothly below zero (the event cuts the step there).
        """
        return kernel.cap(y, self.forces.P, self.turned, self.tensile)

    def rhs(self, phase: str):
        regime, P = _REGIMES[phase], self.forces.P

        def f(t, y):
            dy = np.empty(y.size)
            kernel.rates(y, regime, P, self.turned, self.tensile, self.turn_floor, dy)
            return dy

        return f

    # -- events -----------------------------------------------------------------------
    def events(self, phase: str):
        def exit_(t, y):
            return y[_D] - self.exit_overlap

        out = [exit_]
        if phase == "stick":
            def to_slip(t, y):
                c, _ = self.cap(y)
                return c - math.hypot(*y[_A]) + self.floor

            out.append(to_slip)
        elif phase == "slip":
            def to_stick(t, y):
                c, dc = self.cap(y)
                if self.classic:
                    return oracle_classic.slide_margin(self.forces, y, c, self.cut, self.floor)
                return self.push(y, self.slide_direction(y), c) - dc + self.floor_rate

            def cap_gone(t, y):
                return self.cap(y)[0] - self.floor

            out += [to_stick, cap_gone]
        if phase != "free" and self.gn > 0.0 and not self.turned:
            # the normal force ends (limit_damping) or turns tensile: there the cap is zero
            # and grows again, a kink the step-wise event search could miss inside one step
            def force_zero(t, y):
                return self.forces.normal(y)[0]

            out.append(force_zero)
        if self.law.rescale and not self.unloading and phase != "free":
            def deepest(t, y):  # a rescale starts here: a kink in A' no step should straddle
                return -y[_VN]

            out.append(deepest)
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
        if name == "deepest":
            self.unloading = True
            return phase
        if name == "force_zero":
            self.turned = True  # F_n stays below zero from here to the exit
            if not self.tensile:
                return "free"
            if phase == "slip":
                y[_A] = 0.0  # a slide's cap is zero here
            return self.start(y, cap_rising=True)
        if name == "cap_gone" or (cap < self.floor and dcap <= 0.0):
            y[_A] = 0.0  # the cap is gone or going: no tangential force left to speak of
            if self.gn > 0.0 and not self.turned and self.forces.normal(y)[1] < 0.0:
                # F_n ~ 0 and falling: the turn is here (an event starting at its root may miss it)
                return self.switch("force_zero", y, "coast")
            return "coast"
        if name == "to_slip":
            return self.on_cap(y, cap, dcap)
        if self.classic:  # to_stick: the slide's end resets the history as any capped step does, and sticks
            return oracle_classic.after_slide(self, y, cap)
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
        (q = 0) stays so (LSODA, BDF and Radau on s failed or let s drift off the slip).
        """
        atol = ATOL
        if phase == "slip" and (y[3] or y[5] or y[7]) and not self.classic:  # a classic slide's s stays put
            s = y[_A]
            across = float(s[0] * (y[5] + y[3]) - s[1] * (y[4] + y[2]))  # q = u' . (-s_y, s_x)
            y = np.concatenate([y[:_THETA], [math.atan2(s[1], s[0]),
                                             math.log(abs(across)) if across else 0.0,
                                             math.copysign(1.0, across) if across else 0.0]])
            atol = np.full(_TURNING, ATOL)
            atol[_LOG_ACROSS] = LOG_ACROSS_ATOL
        rtol = RTOL / 10 if self.nonlinear else RTOL
        return solve_ivp(self.rhs(phase), (t, horizon), y, method=METHOD, rtol=rtol, atol=atol,
                         events=events, max_step=tau / MIN_STEPS_PER_CONTACT)

    def push(self, y, s, c: float) -> float:
        """How fast sticking would carry A outwards along s, with A on a cap of radius c:
        s . A' (sticking), the sticking force being -c s."""
        return kernel.push(y, self.forces.P, s[0], s[1], c)

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

    def first_phase(self, y) -> str:
        """The regime at first touch (:meth:`start`), in the limit of a start at t -> 0.

        A displacement history on the contact radius (k a^q h, q > 0) with a tangential dashpot a^s,
        s < q (:attr:`.wall_law.Law.first_touch_runaway`), is the one case where that limit is not
        the start at FIRST_TOUCH: with the first trial force gamma_t u' beyond the cap (led by the
        normal dashpot, or without one starting at zero), A is set on the cap and the history to the
        elastic part c - gamma_t |u'|, against the slip. Sticking, that part grows as a^q (R = q a'/a),
        faster than the cap, and reaches the cap's far side within a time proportional to the start
        (measured: 1e5 starts at 1.04 times the threshold), so it starts sliding here.
        """
        phase = self.start(y)
        if self.law.first_touch_runaway and phase == "stick" and math.hypot(*y[_A]) >= self.cap(y)[0] * (1.0 - 1e-12):
            y[_A] = -y[_A] / math.hypot(*y[_A])  # s: the slide's direction, against the trial force
            return "slip"
        return phase

    def on_cap(self, y, c: float, dc: float) -> str:
        """With A on the cap c (rising at dc), or just past it: slide if sticking would
        push A outwards faster than the cap grows, else stick with A on the cap (the classic cap:
        :func:`.oracle_classic.after_cap`)."""
        if self.classic:
            return oracle_classic.tooth(self, y, c)
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
    ``omega_n`` is the spin about the wall's normal (a classic cap: :mod:`.oracle_classic`).
    """
    if not v_n < 0.0:
        raise ValueError(f"v_n = {v_n!r}: must be < 0 (towards the wall)")
    state, c = (v_n, v_t, omega, v_s, omega_s, omega_n), _Contact(model)
    if c.classic:
        return oracle_classic.bounce(model, state, lambda cut: _classic(model, state, cut))
    return _bounce(c, model, *state)


def _classic(model, state, cut: float) -> tuple[OracleResult, bool]:
    """A classic cap's result with its cuts scaled by ``cut``, and whether it met a Zeno point."""
    c = _Contact(model, cut)
    return _bounce(c, model, *state), c.zeno


def _bounce(c: _Contact, model, v_n: float, v_t: float, omega: float, v_s: float, omega_s: float,
            omega_n: float) -> OracleResult:
    tau = float(model.contact_times(v_n)[0])
    # a slide whose cap has shrunk below 1e-12 of its typical value (mu m |v_n| / tau)
    # coasts to the exit or to the tensile turn with no tangential force
    c.floor, c.tau = 1e-12 * c.cut * (model.mu * model.m * abs(v_n) / tau or 1.0), tau
    c.floor_rate = c.floor / tau
    c.turn_floor = TURN_FLOOR * c.floor / 1e-12
    r = model.r
    initial = np.array([v_n, v_t, r * omega, v_s, r * omega_s, r * omega_n])
    t = FIRST_TOUCH * c.cut * tau if c.nonlinear else 0.0
    c.exit_overlap = LAST_OVERLAP * float(model.max_overlap(abs(v_n))) if c.nonlinear else 0.0
    y = c.forces.first_touch(initial, t)
    phase = c.first_phase(y)
    regimes = [(t, phase)]
    nfev = 0
    # a generous horizon: the contact must end well within it (checked below)
    horizon = 50.0 * tau
    for _ in range(limit := oracle_classic.MAX_SWITCHES if c.classic else MAX_SWITCHES):
        events = c.events(phase)
        sol = c.integrate(phase, events, y, t, horizon, tau)
        nfev += sol.nfev
        if sol.status != 1:
            raise RuntimeError(f"oracle: the contact did not end by t = {horizon:g} ({sol.message})")
        hit = min((k for k, te in enumerate(sol.t_events) if te.size), key=lambda k: sol.t_events[k][0])
        t = float(sol.t_events[hit][0])
        y = sol.y_events[hit][0]
        y = np.concatenate([y[:_THETA], c.slide_direction(y)])  # 8 slots (a 3-D slide's angle back to s)
        if hit == 0 or (y[_D] <= c.exit_overlap and y[_VN] > 0.0):  # exit (a switch can fall on it)
            break
        c.now = t
        phase = c.switch(events[hit].__name__, y, phase)
        regimes.append((t, phase))
    else:
        raise RuntimeError(f"oracle: more than {limit} regime switches (chattering)")
    final = np.array([y[_VN], y[_V][0], y[_W][0], y[_V][1], y[_W][1], r * omega_n])
    return OracleResult(initial, final, t, tuple(regimes), nfev)


def bounce_many(model: ContactModel, v_n, v_t, omega, v_s=None, omega_s=None, omega_n=None) -> np.ndarray:
    """(n, 6) final states for equal-length sequences of initial states."""
    v_n = np.atleast_1d(np.asarray(v_n, dtype=float))
    others = [np.zeros(v_n.size) if x is None else np.broadcast_to(np.asarray(x, dtype=float), v_n.shape)
              for x in (v_t, omega, v_s, omega_s, omega_n)]
    return np.array([bounce(model, *row[:3], v_s=row[3], omega_s=row[4], omega_n=row[5]).final
                     for row in np.column_stack([v_n, *others]).tolist()])
