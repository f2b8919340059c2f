"""``damping tsuji``: LAMMPS sets the dashpot from a restitution e (ETA_N) through Marshall's
(2009, Eq. 53) polynomial fit, alpha(e) sqrt(m_eff F/delta), which for the Hookean force is
alpha(e) sqrt(m_eff kn).

This build (22 Jul 2025) uses alpha(e) as the polynomial gives it; a later LAMMPS multiplies it
by sqrt(2) for Tsuji's effective-mass convention. Measured: hooke kn = 10, m = 1, e = 0.5 gives a
restitution of 0.58094 (the polynomial alone: exact 0.58094; with sqrt(2) it would be 0.458).
The restitution it gives is not e: e is the polynomial's argument.
"""

from __future__ import annotations

import math

from .scaled import E_N, X_T, Scaled

__all__ = ["Tsuji", "LAW", "MARSHALL"]

#: Marshall's polynomial in e, lowest power first (LAMMPS's GranSubModDampingTsuji::init).
MARSHALL = (1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218)


class Tsuji(Scaled):
    keyword = "tsuji"
    summary = "the dashpot alpha(e_n) sqrt(m_eff kn) of Marshall's fit (its restitution is not e_n)"
    coefficient = E_N
    coefficients = (E_N, X_T)
    eta_time_power = 0  # sqrt(m_eff kn) already brings s: a restitution does not follow time

    def gamma_n(self, values: dict, m_eff: float) -> float:
        e = values[self.coefficient.name]
        alpha = sum(c * e**k for k, c in enumerate(MARSHALL))
        return alpha * math.sqrt(m_eff * values["kn"])


LAW = Tsuji()
