"""``damping velocity``: viscous dashpots, the normal force -ETA_N v_n and the tangential one
-(X_T ETA_N) u' on the slip rate (LAMMPS's granular form, measured on this build). The paper's
gamma_n and gamma_t are those two: ETA_N = gamma_n, X_T = gamma_t/gamma_n.
"""

from __future__ import annotations

import math

from ...declaration import Parameter
from ..base import DampingLaw

__all__ = ["Velocity", "LAW", "GAMMA_N", "GAMMA_T", "VANISHING_ETA_N"]

GAMMA_N = Parameter("gamma_n", "normal viscous damping (below critical 2 sqrt(m kn))", "mass/time", 0.0, low=0.0,
                    why="negative damping would create energy", deck="granular ... ETA_N damping velocity")
GAMMA_T = Parameter("gamma_t", "tangential viscous damping on the slip rate", "mass/time", 0.0, low=0.0,
                    why="negative damping would create energy",
                    deck="tangential linear_history KT X_T (X_T ETA_N = gamma_t)")
#: With gamma_n = 0 but gamma_t > 0, LAMMPS's tangential damping is X_T * ETA_N, so ETA_N
#: must not be 0. This relative size (of critical normal damping) changes the normal
#: restitution by about 1e-12, far below any other error.
VANISHING_ETA_N = 1.0e-12


class Velocity(DampingLaw):
    keyword = "velocity"
    summary = "viscous dashpots gamma_n and gamma_t, the paper's"
    coefficients = (GAMMA_N, GAMMA_T)

    def from_lammps(self, eta_n: float, x_t: float) -> dict:
        return {"gamma_n": eta_n, "gamma_t": x_t * eta_n}

    def dashpots(self, model) -> tuple[float, float, bool, list[str]]:
        if model.gamma_t == 0.0 and model.gamma_n == 0.0:
            return 0.0, 0.0, False, []
        if model.gamma_n > 0.0:
            return model.gamma_n, model.gamma_t / model.gamma_n, True, []
        eta_n = VANISHING_ETA_N * 2.0 * math.sqrt(model.m * model.kn)
        return eta_n, model.gamma_t / eta_n, True, [
            f"gamma_n = 0, gamma_t = {model.gamma_t!r}: ETA_N = {eta_n!r} is a vanishing normal damping so that "
            f"X_T * ETA_N = gamma_t"]


LAW = Velocity()
