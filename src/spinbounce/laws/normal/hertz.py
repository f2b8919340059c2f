"""``hertz``: LAMMPS's Hertzian force F = kn a delta, with contact radius a = sqrt(r delta).

kn is LAMMPS's K (force/length^2); against a flat wall m delta'' = -kn sqrt(r) delta^(3/2).
Exact reference: :mod:`spinbounce.exact.hertz` (the contact time grows as |v_n|^(-1/5), so
Omega depends on the impact speed, sphere by sphere); with normal damping the contact integrated
in time, :mod:`spinbounce.exact.contact_phases` (restitution and contact time per speed).
"""

from __future__ import annotations

import numpy as np

from ...exact import hertz
from ..base import NormalLaw

__all__ = ["Hertz", "LAW"]


class Hertz(NormalLaw):
    keyword = "hertz"
    summary = "Hertz, F = kn a delta with contact radius a = sqrt(r delta)"
    contact_radius = True
    power = 1.5

    def contact_times(self, model, v_n) -> np.ndarray:
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        if self.integrated(model):
            return self.integrated_exits(model, v)[:, 1]
        return np.asarray(hertz.contact_time(v, model.m, model.kn, model.r), dtype=float)

    def restitutions(self, model, v_n) -> np.ndarray:
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        return self.integrated_exits(model, v)[:, 0] if self.integrated(model) else np.ones(v.shape)

    def tunnelling_speed(self, model) -> float:
        return hertz.tunnelling_speed(model.m, model.kn, model.r)

    def max_overlap(self, model, speed) -> np.ndarray:
        return np.asarray(hertz.max_overlap(speed, model.m, model.kn, model.r), dtype=float)

    def normal_mode(self, model, speed: float | None) -> tuple[float, float]:
        if speed is None:
            raise ValueError("a Hertzian collision's normal mode needs the fastest |v_n| (speed)")
        return float(hertz.normal_frequency(speed, model.m, model.kn, model.r)), self.dashpot_rate(model, speed)


LAW = Hertz()
