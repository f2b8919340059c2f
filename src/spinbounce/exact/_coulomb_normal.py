"""The normal side of :mod:`.coulomb`: where the cap c = mu |F_n| stands at every time.

A *phase* is a stretch of the contact over which the cap is one smooth function,
c = sign mu F_n, with sign = -1 once a damped Hookean force has turned tensile. It serves
the solver, per unit |v_n| of each sphere: the cap and its rates, the sliding function H
(g = K + H while sliding, K per sphere), the overlap rate x' (whose change times m is the
normal impulse), all on a grid of times and exactly at any time; and the sticking
propagator over whole numbers of grid steps.

* Hookean (Eq. 15, with damping): everything is proportional to |v_n|, so one set of
  tables per model serves every sphere;
* Hertzian (``normal = "hertz"``, gamma_n = 0): m x'' = -K x^(3/2), K = kn sqrt(r), is
  self-similar: x = L X(t/T) with L = (m v^2/K)^(2/5), T = L/v. Energy gives
  X'^2 = 1 - (4/5) X^(5/2), and t(X) is an incomplete beta function
  (:mod:`.hertz`'s contact integral), so X(tau) is scipy's ``betaincinv``: exact.
  The grid is shared in tau = t/T; the times, the cap's scale and the sticking
  propagator are per sphere.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special

__all__ = ["HookeNormal", "HookePhase", "HertzPhase"]


class HookeNormal:
    """Overlap rate, force and the force's rates per unit |v_n| (Eq. 15 with damping)."""

    def __init__(self, m: float, kn: float, gamma_n: float):
        self.m, self.beta = m, gamma_n / (2.0 * m)
        self.w0_sq = kn / m
        self.wd = math.sqrt(self.w0_sq - self.beta**2)
        self.t_exit = math.pi / self.wd
        # F_n = 0 on the way out: kn x + gamma_n x' = 0 (the oracle's force_zero)
        self.t_turn = (math.pi - math.atan2(2.0 * self.beta * self.wd,
                                             self.w0_sq - 2.0 * self.beta**2)) / self.wd

    def at(self, t):
        """(x', F, F', F'', F''') at times t, x being the overlap, for |v_n| = 1."""
        t = np.asarray(t, dtype=float)
        decay = np.exp(-self.beta * t)
        sin, cos = np.sin(self.wd * t), np.cos(self.wd * t)
        x = [decay * sin / self.wd, decay * (cos - self.beta / self.wd * sin)]
        forces = []
        for k in range(4):  # F^(k) = m (w0^2 x^(k) + 2 beta x^(k+1)), and x^(k+2) = -F^(k)/m
            forces.append(self.m * (self.w0_sq * x[k] + 2.0 * self.beta * x[k + 1]))
            x.append(-forces[-1] / self.m)
        return (x[1], *forces)


class _Phase:
    """What both normal laws share: the sliding function from the cap."""

    def __init__(self, contact, sign: float):
        self.contact, self.sign = contact, sign
        self.scale = sign * contact.mu

    def _push(self, rate, c, c1, c2, c3):
        """H = kt s sign mu m x' - gamma_t s c - c' and its two rates (m x'' = -F_n)."""
        ks, gts = self.contact.kt * self.contact.s, self.contact.gts
        push = ks * self.scale * self.contact.m * rate - gts * c - c1
        with np.errstate(invalid="ignore"):  # Hertz: F'' is infinite where the overlap is 0
            return push, -ks * c - gts * c1 - c2, -ks * c1 - gts * c2 - c3

    def cap_and_push(self, rows, t):
        rate, c, c1, c2, c3 = self._normal(rows, t)
        return (c, c1, *self._push(rate, c, c1, c2, c3))

    def cap(self, rows, t):
        return self._normal(rows, t)[1:4]

    def rate(self, rows, t):
        return self._normal(rows, t)[0]


class HookePhase(_Phase):
    """One Hookean phase [t_a, t_b]: tables shared by every sphere."""

    def __init__(self, contact, normal: HookeNormal, t_a, t_b, sign, intervals: int):
        super().__init__(contact, sign)
        self.normal, self.t_a, self.t_b = normal, t_a, t_b
        self.grid = np.linspace(t_a, t_b, intervals + 1)
        self.last = intervals
        self.t_scale = normal.t_exit
        c, c1, push, push_rate, _ = self.cap_and_push(None, self.grid)
        self.grid_table = (c, c1, push, push_rate)
        self.cap_size = float(np.abs(c).max())
        self.push_size = float(np.abs(push).max() + np.abs(c1).max())
        self.step_table = contact.stick.propagator(self.grid - t_a)

    def _normal(self, rows, t):
        rate, *forces = self.normal.at(t)
        return (rate, *(self.scale * f for f in forces))

    def end(self, rows):
        return self.t_b

    def first_index(self, rows, t):
        return np.searchsorted(self.grid, t, side="right")

    def times(self, rows, k):
        return self.grid[k]

    def on_grid(self, rows, k):
        """(cap, its rate, H, its rate) at grid indices k."""
        return tuple(table[k] for table in self.grid_table)

    def steps(self, rows, offsets):
        return tuple(e[offsets] for e in self.step_table)

    def cap_scale(self, rows):
        return self.cap_size

    def push_scale(self, rows):
        return self.push_size


#: Hertz in tau = t/T: X(tau_apex) = (5/4)^(2/5) is the deepest overlap, reached at
#: tau_apex = (2/5) (4/5)^(-2/5) B(2/5, 1/2); the contact ends at 2 tau_apex.
HERTZ_APEX = 0.4 * 0.8**-0.4 * special.beta(0.4, 0.5)


def hertz_shape(tau):
    """(X, X') of X'' = -X^(3/2), X(0) = 0, X'(0) = 1, for 0 <= tau <= 2 tau_apex.

    With z = (4/5) X^(5/2), tau/tau_apex = I_z(2/5, 1/2) on the way in, so z comes from
    betaincinv; near the apex 1 - z (= X'^2) comes from the complementary inverse, so
    that X' keeps its full precision where it is small.
    """
    tau = np.asarray(tau, dtype=float)
    outward = tau > HERTZ_APEX
    y = np.clip(np.where(outward, 2.0 * HERTZ_APEX - tau, tau) / HERTZ_APEX, 0.0, 1.0)
    early = y <= 0.5
    z = np.where(early, special.betaincinv(0.4, 0.5, y), 0.0)
    w = np.where(early, 1.0 - z, special.betaincinv(0.5, 0.4, 1.0 - y))
    z = np.where(early, z, 1.0 - w)
    return (z / 0.8) ** 0.4, np.where(outward, -1.0, 1.0) * np.sqrt(w)


def hertz_forces(x, rate):
    """F = X^(3/2) and its first three rates along X'' = -X^(3/2) (infinite at X = 0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        root = np.sqrt(x)
        f2 = 0.75 * rate**2 / root - 1.5 * x**2
        f3 = -0.375 * rate**3 / (x * root) - 4.5 * x * rate
    return x * root, 1.5 * root * rate, f2, f3


class HertzPhase(_Phase):
    """The whole Hertzian contact of a batch of spheres (no tensile turn: gamma_n = 0)."""

    def __init__(self, contact, speed, kn_r: float, fastest_tangential: float,
                 min_intervals: int, grid_step: float):
        super().__init__(contact, 1.0)
        m = contact.m
        overlap = (m * speed**2 / kn_r) ** 0.4
        self.period = overlap / speed  # T: tau = t/T
        self.cap_factor = contact.mu * m / self.period  # mu K L^(3/2)/v: the cap per F(tau)
        self.t_b = 2.0 * HERTZ_APEX * self.period
        self.t_scale = float(self.t_b.max()) if self.t_b.size else 1.0
        # fastest normal rate ~ 1.3/T at the apex; the tangential rates in tau grow with T
        span = 2.0 * HERTZ_APEX * max(1.5, fastest_tangential * float(self.period.max(initial=0.0)))
        self.last = max(min_intervals, math.ceil(span / grid_step))
        self.tau_step = 2.0 * HERTZ_APEX / self.last
        self.tau = self.tau_step * np.arange(self.last + 1)
        x, rate = hertz_shape(self.tau)
        self.shape = (rate, *hertz_forces(x, rate))
        self.cap_unit = float(np.abs(self.shape[1]).max())

    @staticmethod
    def _scaled(period, factor, rate, f0, f1, f2, f3):
        """x' and the cap with its rates, per unit |v_n|, from the shape's X' and F(tau)."""
        return rate, factor * f0, factor / period * f1, factor / period**2 * f2, factor / period**3 * f3

    def _normal(self, rows, t):
        period = self.period[rows]
        x, rate = hertz_shape(t / period)
        return self._scaled(period, self.cap_factor[rows], rate, *hertz_forces(x, rate))

    def end(self, rows):
        return self.t_b[rows]

    def first_index(self, rows, t):
        k = np.searchsorted(self.tau, t / self.period[rows], side="right")
        k = np.minimum(k, self.last)
        return k + (self.times(rows, k) <= t)  # the grid's times are period * tau, rounded

    def times(self, rows, k):
        period = self.period[rows]
        return (period[:, None] if k.ndim == 2 else period) * self.tau[k]

    def on_grid(self, rows, k):
        values = self._scaled(self.period[rows][:, None], self.cap_factor[rows][:, None],
                              *(table[k] for table in self.shape))
        return (*values[1:3], *self._push(*values)[:2])

    def steps(self, rows, offsets):
        return self.contact.stick.propagator(self.period[rows][:, None] * (self.tau_step * offsets))

    def cap_scale(self, rows):
        return self.cap_factor[rows] * self.cap_unit

    def push_scale(self, rows):
        ks, gts = self.contact.kt * self.contact.s, self.contact.gts
        cap_rate = 2.0 / self.period[rows] * self.cap_scale(rows)  # |F'| < 2 max F / T
        return ks * self.contact.mu * self.contact.m + gts * self.cap_scale(rows) + cap_rate
