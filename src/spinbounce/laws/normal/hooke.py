"""``hooke``: the paper's linear spring, F = kn delta (Eq. 1), with LAMMPS's ``damping velocity``.

Exact reference: the damped oscillator of Eq. 15 (:mod:`spinbounce.exact.linear`); its contact
time does not depend on the impact speed, so the paper's matrix (Eq. 18) holds for every state.
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
        return np.full(v.shape, linear.exit_time(model.m, model.kn, model.gamma_n, not model.limit_damping))

    def force_times(self, model, v_n) -> np.ndarray:
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        return np.full(v.shape, linear.collision_time(model.m, model.kn, model.gamma_n, not model.limit_damping))

    def tunnelling_speed(self, model) -> float:
        return model.r / float(linear.max_overlap(1.0, model.m, model.kn, model.gamma_n))

    def max_overlap(self, model, speed) -> np.ndarray:
        return np.asarray(linear.max_overlap(speed, model.m, model.kn, model.gamma_n), dtype=float)

    def normal_mode(self, model, speed: float | None) -> tuple[float, float]:
        return math.sqrt(model.kn / model.m), model.gamma_n / model.m


LAW = Hooke()
