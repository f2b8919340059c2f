"""``tangential linear_history KT X_T MU``: the paper's Cundall-Strack spring kt on the slip
history, capped at |F_t| <= mu |F_n|.

LAMMPS always applies the cap; the paper's model has none, so no cap is written as
:data:`~spinbounce.laws.base.NO_CAP_MU`.
"""

from __future__ import annotations

import math

from ...declaration import Parameter
from ..base import NO_CAP_MU, TangentialLaw

__all__ = ["LinearHistory", "LAW", "KT", "MU", "NO_CAP_MU"]

KT = Parameter("kt", "linear_history: tangential spring constant on the slip history (Cundall-Strack)", "force/length",
               1.0, low=0.0, why="a negative spring would push the slip away", deck="tangential linear_history KT")
MU = Parameter("mu", "Coulomb friction coefficient, |F_t| <= mu |F_n|; none (or inf; tables hold inf): the paper's "
               "model (no cap)", "1", None, low=0.0, optional=True, none_value=math.inf,
               why="a friction coefficient is not negative",
               deck="tangential linear_history|mindlin... ... MU (none: 1e12)")


class LinearHistory(TangentialLaw):
    keyword = "linear_history"
    summary = "the paper's Cundall-Strack spring kt on the slip history"
    coefficients = (KT, MU)

    def slip_stiffness(self, model, speed: float | None) -> float:
        return model.kt

    def frozen_stiffness(self, model, overlap: float | None) -> float:
        return model.kt


LAW = LinearHistory()
