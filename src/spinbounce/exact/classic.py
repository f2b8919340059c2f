"""Exact theory of LAMMPS's classic granular wall as the pinned build integrates it.

``fix wall/gran hooke/history KN KT GAMMA_N GAMMA_T MU DAMPFLAG`` is assembled (in
``fix_wall_gran.cpp``, since the 28 Mar 2023 GRANULAR refactor) from the sub-models
normal ``hooke`` (coefficients KN, GAMMA_N), damping ``mass_velocity`` and tangential
``linear_history_classic`` with coefficients (KT, GAMMA_T/GAMMA_N, MU); DAMPFLAG = 0 sets
GAMMA_T = 0 first, so GAMMA_N = 0 gives 0/0 = NaN whatever DAMPFLAG is. Against a flat
wall (R_eff = r) LAMMPS computes, in the paper's variables (overlap delta = r - z, slip
rate u' = v_t + r omega, Eq. 2):

    F_n = kn delta + m gamma_n delta'                  (tensile allowed; cap uses |F_n|)
    F_t = -kt a xi - m gamma_t u',   a = sqrt(r delta)  (this build)
    xi' = u'  (the shear history, updated with the half-step velocities)
    m v_n' = F_n,   m v_t' = F_t,   alpha m (r omega)' = F_t
    |F_t| > mu |F_n|:  F_t -> sign(F_t) mu |F_n|,  xi -> -(F_t + m gamma_t u')/kt

In this build ``linear_history_classic`` sets ``contact_radius_flag = 1``: the spring
carries the contact radius a = sqrt(R_eff delta), which has the units of a length, so
kt a is not a stiffness and the result depends on the length unit. The cap's reset
divides by kt alone, not kt a. Upstream (LAMMPS PR #5007, 2026) drops the factor, a = 1,
which is the paper's Eq. 1 (and ``granular ... tangential linear_history`` here). The
older ``pair_style gran/hooke/history`` never had it.

The dt -> 0 limit of that is a hybrid system, solved here to about 1e-9:

* normal motion is closed form: delta = (V/w_d) exp(-beta t) sin(w_d t), beta =
  gamma_n/2, w_d^2 = kn/m - beta^2, contact time tau = pi/w_d, v_n(out) = V exp(-beta tau);
* stick: the linear ODE u'' = -K (kt a(t) u + m gamma_t u'), K = (1+alpha)/(alpha m),
  with no elementary solution (a ~ sqrt(sin w_d t)); integrated with DOP853 at rtol
  1e-12 in the phase phi of t = tau (1 - cos phi)/2, which makes sqrt(delta) smooth at
  both ends of the contact;
* the cap: reaching |F_t| = mu |F_n| resets xi; the next step's trial force is then
  F+ = a (s C + c u') - c u' (C = mu |F_n|, c = m gamma_t, s the sign). If |F+| < C the
  contact sticks again at once, with a spring force cut by a factor a (a sawtooth, a < 1);
  otherwise it slides, F_t = s C, for as long as (a - 1)(C + s c u') > 0. With a > 1 and
  no damping that holds whatever the slip does: the force keeps its direction even when
  the slip reverses, and the wall can give the sphere kinetic energy.

The frozen contact (fixed overlap delta0) is the paper's Eq. 10 with kt replaced by
kt sqrt(r delta0): its slip oscillates at sqrt(kt sqrt(r delta0) (1+alpha)/alpha / m).

Pure numpy and scipy; knows nothing of LAMMPS.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import groupby

import numpy as np
from scipy.integrate import solve_ivp

from . import linear

__all__ = ["ClassicWall", "ClassicResult", "bounce", "Omega_eff", "stiffness_group", "frozen_frequency",
           "frozen_velocities", "RTOL", "ATOL"]

RTOL = 1.0e-12
ATOL = 1.0e-14
#: More stick/slide switches than this in one contact: refuse rather than guess.
MAX_SWITCHES = 5000
#: A cap event with a this close below 1 enters the slide: the sawtooth's teeth shrink
#: geometrically as a -> 1 and their limit is the slide (error about this times C).
NEAR_ONE = 1.0e-10
#: A cap below this fraction of the tangential force scale m|u'|/tau is taken as zero:
#: the impulse it could still give is below 1e-9 m|u'|.
TINY_CAP = 1.0e-9


@dataclass(frozen=True)
class ClassicWall:
    """The classic wall's parameters, in LAMMPS's own units (lj here).

    gamma_n, gamma_t are ``mass_velocity`` rates (1/time): the dashpots are m*gamma.
    gamma_n = 0 is taken as its limit gamma_n -> 0+ (LAMMPS itself gives NaN there).
    mu = None is no cap at all, a limit the classic form cannot reach (MU <= 1e4).
    contact_radius: True for this build's spring kt*sqrt(r delta), False for the paper's
    (and the upstream fix's) kt.
    """

    kn: float
    kt: float
    gamma_n: float = 0.0
    gamma_t: float = 0.0
    mu: float | None = None
    alpha: float = 0.4
    r: float = 0.5
    m: float = 1.0
    contact_radius: bool = True

    def __post_init__(self):
        if self.kn <= 0 or self.kt < 0 or self.gamma_n < 0 or self.gamma_t < 0 or self.m <= 0 or self.r <= 0:
            raise ValueError(f"{self}: kn, m, r must be > 0 and kt, gamma_n, gamma_t >= 0")
        if self.gamma_n >= 2.0 * math.sqrt(self.kn / self.m):
            raise ValueError(f"gamma_n = {self.gamma_n!r} is at or above critical damping: no bounce")
        if self.mu is not None and not self.contact_radius:
            raise ValueError("with a = 1 and a finite mu use exact.oracle (the Coulomb wall)")

    @property
    def beta(self) -> float:
        return 0.5 * self.gamma_n

    @property
    def omega_d(self) -> float:
        return math.sqrt(self.kn / self.m - self.beta**2)

    @property
    def tau(self) -> float:
        """Contact time pi/w_d (Eq. 16 when gamma_n = 0)."""
        return math.pi / self.omega_d

    def tensile_time(self) -> float:
        """When F_n = kn delta + m gamma_n delta' turns tensile (tau if it never does)."""
        if self.gamma_n == 0.0:
            return self.tau
        c = self.m * self.gamma_n
        return (math.pi - math.atan2(c * self.omega_d, self.kn - c * self.beta)) / self.omega_d


@dataclass(frozen=True)
class ClassicResult:
    """One collision: initial and final (v_n, v_t, r omega), the regimes it went through
    as (t_start, 'stick' | 'slide+' | 'slide-'), and the kinetic energy gained,
    (E_out - E_in)/E_in (Eq. 21; > 0 means the wall gave the sphere energy)."""

    initial: np.ndarray
    final: np.ndarray
    regimes: tuple
    energy_gain: float


class _Collision:
    """One collision: the closed-form normal motion and the tangential right-hand sides."""

    def __init__(self, wall: ClassicWall, speed: float):
        self.w, self.V = wall, speed
        self.c = wall.m * wall.gamma_t

    def t_of(self, phi):
        return 0.5 * self.w.tau * (1.0 - math.cos(phi))

    def overlap(self, t: float) -> tuple[float, float]:
        """(delta, delta') at time t."""
        w = self.w
        decay = math.exp(-w.beta * t)
        s, co = math.sin(w.omega_d * t), math.cos(w.omega_d * t)
        return max(self.V / w.omega_d * decay * s, 0.0), self.V * decay * (co - w.beta / w.omega_d * s)

    def forces(self, phi: float, y) -> tuple[float, float, float, float]:
        """(trial F_t, cap C, a, slip rate) at phase phi, state y = (v_t, r omega, xi)."""
        delta, rate = self.overlap(self.t_of(phi))
        fn = self.w.kn * delta + self.w.m * self.w.gamma_n * rate
        slip = y[0] + y[1]
        a = math.sqrt(self.w.r * delta) if self.w.contact_radius else 1.0
        cap = math.inf if self.w.mu is None else self.w.mu * abs(fn)
        return -self.w.kt * a * y[2] - self.c * slip, cap, a, slip

    def rhs(self, sign: int):
        """d/dphi of (v_t, r omega, xi): sticking (sign 0) or sliding with F_t = sign*C."""
        w, half_tau = self.w, 0.5 * self.w.tau

        def f(phi, y):
            force, cap, _, slip = self.forces(phi, y)
            if sign:
                force, slip = sign * cap, 0.0  # xi is not used while sliding
            scale = half_tau * math.sin(phi)
            return [scale * force / w.m, scale * force / (w.alpha * w.m), scale * slip]

        return f

    def reset(self, phi: float, y, sign: int) -> float:
        """The history LAMMPS leaves after capping at sign*C: -(F_t + c u')/kt."""
        _, cap, _, slip = self.forces(phi, y)
        return -(sign * cap + self.c * slip) / self.w.kt

    def slide_margin(self, phi: float, y, sign: int) -> float:
        """> 0 while a slide at sign*C goes on: after each reset the next trial force
        s F+ = C + (a - 1)(C + s c u') stays beyond the cap. NEAR_ONE widens it a little:
        as the margin closes from below, the sawtooth's teeth shrink geometrically (a
        Zeno point) and their limit is the slide."""
        _, cap, a, slip = self.forces(phi, y)
        return (a - 1.0) * (cap + sign * self.c * slip) + NEAR_ONE * (cap + self.c * abs(slip))

    def after_cap(self, phi: float, y, sign: int) -> tuple[int, float]:
        """(0 = stick | +-1 = slide, xi) once the force is capped at sign*C at phase phi."""
        if self.slide_margin(phi, y, sign) > 0.0:
            return sign, self.reset(phi, y, sign)
        _, cap, a, slip = self.forces(phi, y)
        if (a - 1.0) * (cap + sign * self.c * slip) >= -2.0 * cap:  # |F+| <= C: stick at once
            return 0, self.reset(phi, y, sign)
        if self.slide_margin(phi, y, -sign) > 0.0:  # F+ beyond the cap on the other side
            return -sign, self.reset(phi, y, -sign)
        raise ValueError(f"the capped force chatters between signs at t = {self.t_of(phi):.6g}: not covered")

    def events(self, sign: int):
        """Terminal events of a regime: the cap reached (stick), the slide's end (slide)."""
        if sign == 0:
            def up(phi, y):
                f, cap, _, _ = self.forces(phi, y)
                return f - cap

            def down(phi, y):
                f, cap, _, _ = self.forces(phi, y)
                return f + cap

            up.terminal, up.direction = True, 1.0
            down.terminal, down.direction = True, -1.0
            return [up, down]

        def end(phi, y):
            return self.slide_margin(phi, y, sign)

        end.terminal, end.direction = True, -1.0
        return [end]

    def at_zero_cap(self, phi: float, y) -> tuple[int, float]:
        """(regime, xi) where F_n passes through zero (C = 0): LAMMPS's reset leaves
        xi = -c u'/kt and the trial force (a - 1) c u'; with no damping the spring restarts
        from xi = 0 and sticks if its rate kt a |u'| stays below the cap's rate mu |F_n'|."""
        w = self.w
        delta, rate = self.overlap(self.t_of(phi))
        _, _, a, slip = self.forces(phi, y)
        xi = -self.c * slip / w.kt
        trial = (a - 1.0) * self.c * slip
        if trial != 0.0:
            return (1 if trial > 0 else -1), xi
        cap_rate = w.mu * abs(w.kn * rate - w.gamma_n * w.kn * delta - w.m * w.gamma_n**2 * rate)
        if w.kt * a * abs(slip) > cap_rate:
            raise ValueError("the spring outruns the cap where F_n turns tensile: not covered")
        return 0, xi


#: A regime's name by the sign of its force: 0 sticks, +-1 slides that way.
_REGIME = {0: "stick", 1: "slide+", -1: "slide-"}


def bounce(wall: ClassicWall, v_n: float, v_t: float = 0.0, r_omega: float = 0.0) -> ClassicResult:
    """The final (v_n, v_t, r omega) of a sphere that touches the wall with v_n < 0.

    Integrates the hybrid system of the module docstring regime by regime; every change
    of regime is located as an event and the integration restarts there.
    """
    if not v_n < 0.0:
        raise ValueError(f"v_n = {v_n!r}: the sphere must approach the wall (v_n < 0)")
    collision = _Collision(wall, -v_n)
    y = np.array([v_t, r_omega, 0.0])
    tiny = TINY_CAP * wall.m * (abs(v_t + r_omega) + abs(v_n)) / wall.tau
    turn = wall.tensile_time()
    stops = [math.acos(1.0 - 2.0 * turn / wall.tau)] if turn < wall.tau and wall.mu is not None else []
    stops.append(math.pi)
    phi, (force, cap, _, _) = 0.0, collision.forces(0.0, y)  # first touch: the trial force is the dashpot's
    sign, y[2] = collision.after_cap(phi, y, 1 if force > 0 else -1) if abs(force) > cap else (0, 0.0)
    regimes = [(0.0, _REGIME[sign])]
    for _ in range(MAX_SWITCHES):
        stop = next(s for s in stops if s > phi)
        sol = solve_ivp(collision.rhs(sign), (phi, stop), y, method="DOP853", rtol=RTOL, atol=ATOL,
                        events=collision.events(sign) if wall.mu is not None else None, max_step=math.pi / 64)
        phi, y = float(sol.t[-1]), sol.y[:, -1].copy()
        if sol.status == 1:
            sign, y[2], phi = _switch(collision, sol, phi, y, sign, tiny, stop)
        if phi >= stop == math.pi:
            break
        if phi >= stop:
            sign, y[2] = collision.at_zero_cap(phi, y)
        regimes.append((collision.t_of(phi), _REGIME[sign]))
    else:
        raise ValueError(f"more than {MAX_SWITCHES} changes of regime in one contact: not covered")
    initial = np.array([v_n, v_t, r_omega])
    final = np.array([-v_n * math.exp(-wall.beta * wall.tau), y[0], y[1]])
    gain = linear.energy(final, wall.m, wall.alpha) / linear.energy(initial, wall.m, wall.alpha) - 1.0
    # consecutive entries of one regime (the sawtooth's resets) as one
    merged = (next(same) for _, same in groupby(regimes, key=lambda entry: entry[1]))
    return ClassicResult(initial, final, tuple(merged), float(gain))


def _switch(collision: _Collision, sol, phi: float, y, sign: int, tiny: float, stop: float):
    """(regime, xi, phi) after the event that ended a regime at phase phi."""
    if sign != 0:  # the slide ends: stick from the reset history
        return 0, collision.reset(phi, y, sign), phi
    _, cap, _, _ = collision.forces(phi, y)
    if cap < tiny:  # F_n is about to vanish: no impulse worth following is left before it
        return sign, y[2], stop
    capped = 1 if sol.t_events[0].size else -1
    return (*collision.after_cap(phi, y, capped), phi)


def stiffness_group(v_n: float, kn: float, kt: float, alpha: float, r: float, m: float = 1.0) -> float:
    """lambda = (kt/kn)(1+alpha)/alpha sqrt(r |v_n| sqrt(m/kn)): undamped and sticking,
    the slip obeys d^2u/ds^2 = -lambda sqrt(sin s) u in the phase s = t sqrt(kn/m), so
    Omega_eff depends on the parameters through lambda alone. lambda carries a length."""
    return kt / kn * (1.0 + alpha) / alpha * math.sqrt(r * abs(v_n) * math.sqrt(m / kn))


def Omega_eff(v_n: float, kn: float, kt: float, alpha: float, r: float, m: float = 1.0,
              gamma_n: float = 0.0, gamma_t: float = 0.0) -> float:
    """The sticking contact's Omega = u'(tau)/u'(0) - 1 (the paper's Eq. 18 definition)
    for this build's classic wall: no cap (mu -> infinity) and a = sqrt(r delta).

    The contact is linear in (v_t, r omega) at a given v_n, so Eq. 18's matrix holds with
    this Omega, which depends on v_n and on the length unit (the paper's does not).
    """
    wall = ClassicWall(kn, kt, gamma_n, gamma_t, None, alpha, r, m, contact_radius=True)
    result = bounce(wall, v_n, 1.0, 0.0)
    return float(result.final[1] + result.final[2]) - 1.0


def frozen_frequency(kt: float, alpha: float, r: float, delta0: float, m: float = 1.0) -> float:
    """The frozen contact's slip frequency, sqrt(kt sqrt(r delta0) (1+alpha)/(alpha m))
    (Eq. 8's sqrt(Q) with kt -> kt sqrt(r delta0))."""
    return math.sqrt(linear.Q(kt * math.sqrt(r * delta0), m, alpha))


def frozen_velocities(t, v_t0, r_omega0, kt: float, alpha: float, r: float, delta0: float, m: float = 1.0,
                      gamma_t: float = 0.0):
    """(v_t(t), r omega(t)) of the frozen contact at overlap delta0: Eq. 10 (its exact
    damped form for gamma_t > 0, a mass_velocity rate) with kt -> kt sqrt(r delta0)."""
    return linear.frozen_velocities(t, v_t0, r_omega0, kt * math.sqrt(r * delta0), m, alpha, m * gamma_t)
