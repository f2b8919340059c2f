"""``damping tsuji``: LAMMPS sets the dashpot from a restitution e (ETA_N) through Marshall's
(2009, Eq. 53) polynomial fit, alpha(e) sqrt(m_eff F/delta), which for the Hookean force is
alpha(e) sqrt(m_eff kn).

This build (22 Jul 2025) uses alpha(e) as the polynomial gives it; a later LAMMPS multiplies it
by sqrt(2) for Tsuji's effective-mass convention. Measured: hooke kn = 10, m = 1, e = 0.5 gives a
restitution of 0.58094 (the polynomial alone: exact 0.58094; with sqrt(2) it would be 0.458).
The restitution it gives is not e: e is the polynomial's argument.
"""

from __future__ import annotations

from .scaled import FromRestitution

__all__ = ["Tsuji", "LAW", "MARSHALL"]

#: Marshall's polynomial in e, lowest power first (LAMMPS's GranSubModDampingTsuji::init).
MARSHALL = (1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218)


class Tsuji(FromRestitution):
    keyword = "tsuji"
    summary = "the dashpot alpha(e_n) sqrt(m_eff kn) of Marshall's fit (its restitution is not e_n)"

    def factor(self, e: float, normal) -> float:
        return sum(c * e**k for k, c in enumerate(MARSHALL))


LAW = Tsuji()
