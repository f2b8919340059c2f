"""The forces of a wall contact in the oracle's state, for any :class:`.wall_law.Law`.

The state is (delta, v_n, v (2), w = r omega (2), A (2)): the overlap, the normal velocity,
the tangential velocity and r times the spin in the directions t and s, and the trial force
A = spring + gamma_t u' of the slip history (u' = v + w). With the contact radius
a = sqrt(r delta):

* F_n = K delta^p + gamma_n a^s delta' (odd in delta beyond the exit, so that an event
  function stays smooth over a step that overshoots it);
* while it sticks, A' = k_t u' + R (A - gamma_t u') + gamma_t' u' + gamma_t u'', with
  k_t = k a^q, gamma_t = C_t a^s, and R = q a'/a for a displacement history (k a^q h, h' = u'),
  none for a force history (h' = -k a^q u'), plus a'/a while a shrinks with a rescale (h gains
  h a'/a): the continuous-time form of LAMMPS's ``GranSubModTangentialMindlin`` and
  ``linear_history`` (q = s = 0: k_t = kt, R = 0, the paper's spring).

Pure numpy; knows nothing of LAMMPS or of the regimes (:mod:`.oracle`).
"""

from __future__ import annotations

import numpy as np

from .wall_law import Law

__all__ = ["Forces", "D", "VN", "V", "W", "A"]

# state layout: delta, v_n, v (2), w = r*omega (2), A (2)
D, VN, V, W, A = 0, 1, slice(2, 4), slice(4, 6), slice(6, 8)


class Forces:
    """A :class:`Law`'s forces and their rates in the oracle's state."""

    def __init__(self, law: Law):
        self.law = law
        self.r, self.m, self.gn = law.r, law.m, law.c_n
        self.nonlinear = law.on_contact_radius
        self.slip_mass = (1.0 + 1.0 / law.alpha) / law.m  # u'' = slip_mass * F_t

    def radius_power(self, y, s: float) -> tuple[float, float]:
        """(a^s, d(a^s)/dt) of the contact radius a = sqrt(r |delta|) (even past the exit);
        (1, 0) for s = 0, a coefficient that does not depend on a."""
        if s == 0.0:
            return 1.0, 0.0
        a_s = (self.r * abs(y[D])) ** (s / 2.0)
        return a_s, (s * a_s * -y[VN] / (2.0 * y[D]) if y[D] else 0.0)

    def normal(self, y) -> tuple[float, float]:
        """(F_n, dF_n/dt) before any cut at zero, continued smoothly past the exit.

        F_n = K delta^p + gamma_n a^s delta', odd in delta beyond the exit. Every event function
        stays smooth where a step overshoots a switch (the exit, the normal force's turn): scipy
        locates an event by a root search over the whole step, and a function held flat at zero
        there hands the search the step's far end as its root, which then hides an earlier event
        (a turn just before the exit).
        """
        law, delta, rate = self.law, y[D], -y[VN]
        depth = abs(delta) ** (law.power - 1.0) if law.power != 1.0 else 1.0
        damp, damp_rate = self.radius_power(y, law.damping_power)
        f = law.K * depth * delta + self.gn * damp * rate
        accel = -f / self.m  # delta'' = -v_n'
        return f, law.K * law.power * depth * rate + self.gn * (damp * accel + damp_rate * rate)

    def tangential(self, y) -> tuple[float, float, float, float]:
        """(k_t, R, gamma_t, gamma_t') of the trial force A = k_t-spring + gamma_t u' while it
        sticks: A' = k_t u' + R (A - gamma_t u') + gamma_t' u' + gamma_t u''.

        k_t = k a^q and gamma_t = C_t a^s; R = q a'/a with a displacement history h (spring
        k a^q h, h' = u'), none with a force history (h' = -k a^q u'), and a'/a more while a
        shrinks with a rescale (h gains h a'/a). The paper's spring (q = s = 0): k_t = kt, R = 0.
        """
        law = self.law
        k, _ = self.radius_power(y, law.spring_power)
        gt, gt_rate = self.radius_power(y, law.damping_power)
        scale = (0.0 if law.force_history else law.spring_power) + (1.0 if law.rescale and y[VN] > 0.0 else 0.0)
        shrink = -y[VN] / (2.0 * y[D]) if scale and y[D] else 0.0
        return law.k * k, scale * shrink, law.c_t * gt, law.c_t * gt_rate

    def stick_rate(self, y, force, u_rate) -> np.ndarray:
        """A' while sticking, the friction force being ``force`` (-A)."""
        k, scale, gt, gt_rate = self.tangential(y)
        rate = (k + gt_rate) * u_rate + gt * self.slip_mass * force
        return rate + scale * (-force - gt * u_rate) if scale else rate

    def across_stiffness(self, y) -> float:
        """The rate at which a slide's A turns per unit slip across it, times c: the part of the
        sticking A' across s (u'' lies along s): k_t - R gamma_t + gamma_t'."""
        k, scale, gt, gt_rate = self.tangential(y)
        return k - scale * gt + gt_rate

    def first_touch(self, initial: np.ndarray, t: float) -> np.ndarray:
        """(delta, v_n, v, r omega, A) a time t after first touch, the velocities as they were
        (their change, ~ F t/m, is below 1e-12 of the speed for t = FIRST_TOUCH tau): the history
        has grown from zero by u' t (a displacement; a force: -k a^q u' t/(1 + q/2))."""
        law = self.law
        y = np.concatenate([[-initial[0] * t], initial[[0, 1, 3, 2, 4]], [0.0, 0.0]])
        slip = initial[[1, 3]] + initial[[2, 4]]
        spring = law.k * self.radius_power(y, law.spring_power)[0] * t
        if law.force_history:
            spring /= 1.0 + law.spring_power / 2.0
        y[A] = (spring + law.c_t * self.radius_power(y, law.damping_power)[0]) * slip
        return y
