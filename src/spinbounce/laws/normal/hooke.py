"""``hooke``: the paper's linear spring, F = kn delta (Eq. 1), with LAMMPS's ``damping velocity``.

Exact reference: the damped oscillator of Eq. 15 (:mod:`spinbounce.exact.linear`); its contact
time does not depend on the impact speed, so the paper's matrix (Eq. 18) holds for every state.
With a dashpot on the contact radius (``viscoelastic``) the contact is integrated in time
(:meth:`NormalLaw.integrated_exits`), and its restitution depends on the speed.
"""

from __future__ import annotations

import math

import numpy as np

from ...exact import linear
from ..base import NormalLaw

__all__ = ["Hooke", "LAW"]


class Hooke(NormalLaw):
    keyword = "hooke"
    summary = "the paper's linear spring, F = kn delta"

    def contact_times(self, model, v_n) -> np.ndarray:
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        if self.integrated(model):
            return self.integrated_exits(model, v)[:, 1]
        return np.full(v.shape, linear.exit_time(model.m, model.kn, model.gamma_n, not model.limit_damping))

    def force_times(self, model, v_n) -> np.ndarray:
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        if self.integrated(model):
            return self.integrated_exits(model, v)[:, 2]
        return np.full(v.shape, linear.collision_time(model.m, model.kn, model.gamma_n, not model.limit_damping))

    def restitutions(self, model, v_n) -> np.ndarray:
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        if self.integrated(model):
            return self.integrated_exits(model, v)[:, 0]
        return np.full(v.shape, linear.restitution(model.m, model.kn, model.gamma_n, not model.limit_damping))

    def _constant_dashpot(self, model) -> float:
        """gamma_n where it is the contact's constant dashpot; 0 (the undamped bound) where it grows."""
        return 0.0 if self.integrated(model) else model.gamma_n

    def tunnelling_speed(self, model) -> float:
        return model.r / float(linear.max_overlap(1.0, model.m, model.kn, self._constant_dashpot(model)))

    def max_overlap(self, model, speed) -> np.ndarray:
        return np.asarray(linear.max_overlap(speed, model.m, model.kn, self._constant_dashpot(model)), dtype=float)

    def normal_mode(self, model, speed: float | None) -> tuple[float, float]:
        if self.integrated(model):
            if speed is None:
                raise ValueError("a dashpot on the contact radius needs the fastest |v_n| (speed)")
            return math.sqrt(model.kn / model.m), self.dashpot_rate(model, speed)
        return math.sqrt(model.kn / model.m), model.gamma_n / model.m


LAW = Hooke()
