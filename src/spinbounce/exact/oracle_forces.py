"""The forces of a wall contact in the oracle's state, for any :class:`.wall_law.Law`.

The state is (delta, v_n, v (2), w = r omega (2), A (2)): the overlap, the normal velocity,
the tangential velocity and r times the spin in the directions t and s, and the trial force
A = spring + gamma_t u' of the slip history (u' = v + w). With the contact radius
a = sqrt(r delta):

* F_n = K delta^p + gamma_n a^s delta' (odd in delta beyond the exit, so that an event
  function stays smooth over a step that overshoots it);
* while it sticks (:func:`.oracle_kernel.stick_rate`), A' = k_t u' + R (A - gamma_t u') + gamma_t' u' +
  gamma_t u'', with k_t = k a^q, gamma_t = C_t a^s, and R = q a'/a for a displacement history (k a^q h, h' = u'),
  none for a force history (h' = -k a^q u'), plus a'/a while a shrinks with a rescale (h gains
  h a'/a): the continuous-time form of LAMMPS's ``GranSubModTangentialMindlin`` and
  ``linear_history`` (q = s = 0: k_t = kt, R = 0, the paper's spring).

Each is computed by :mod:`.oracle_kernel` (compiled: the oracle calls them at every stage of its
steps); knows nothing of LAMMPS or of the regimes (:mod:`.oracle`).
"""

from __future__ import annotations

import numpy as np

from . import oracle_kernel as kernel
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
        self.P = kernel.coefficients(law)

    def radius_power(self, y, s: float) -> tuple[float, float]:
        """(a^s, d(a^s)/dt) of the contact radius a = sqrt(r |delta|) (even past the exit);
        (1, 0) for s = 0, a coefficient that does not depend on a."""
        return kernel.radius_power(y, self.P, s)

    def normal(self, y) -> tuple[float, float]:
        """(F_n, dF_n/dt) before any cut at zero, continued smoothly past the exit.

        F_n = K delta^p + gamma_n a^s delta', odd in delta beyond the exit. Every event function
        stays smooth where a step overshoots a switch (the exit, the normal force's turn): scipy
        locates an event by a root search over the whole step, and a function held flat at zero
        there hands the search the step's far end as its root, which then hides an earlier event
        (a turn just before the exit).
        """
        return kernel.normal(y, self.P)

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
