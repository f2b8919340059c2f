"""``damping viscoelastic``: LAMMPS's normal dashpot ETA_N m_eff a, growing with the contact radius
a = sqrt(R delta) whatever the normal force (``GranSubModDampingViscoelastic``: its
``contact_radius_flag``); the tangential one X_T times it. Measured on this build: hooke kn = 10,
m = 1, ETA_N = 0.5 gives e = 0.9423403 against the integrated 0.94234033; hertz 10 gives
0.8827918 against 0.8827921.

The model holds gamma_n = ETA_N m_eff and gamma_t = X_T gamma_n, the coefficients of a: its
dashpots are gamma a. No closed form: the reference is the contact integrated in time
(:mod:`spinbounce.exact.contact_phases`).
"""

from __future__ import annotations

from ...declaration import Parameter
from .scaled import X_T, Scaled

__all__ = ["Viscoelastic", "LAW", "GAMMA_N_PER_MASS_RADIUS"]

GAMMA_N_PER_MASS_RADIUS = Parameter(
    "gamma_n_per_mass_radius", "damping viscoelastic: normal damping per effective mass and contact radius, "
    "gamma_n/(m_eff a) (LAMMPS's ETA_N); none for any other damping", "1/(time length)", None, low=0.0,
    optional=True, why="negative damping would create energy", deck="granular NORMAL KN ETA_N damping viscoelastic")


class Viscoelastic(Scaled):
    keyword = "viscoelastic"
    summary = "dashpots gamma_n_per_mass_radius m_eff a and x_t times it, on the contact radius a"
    coefficient = GAMMA_N_PER_MASS_RADIUS
    coefficients = (GAMMA_N_PER_MASS_RADIUS, X_T)
    eta_time_power = -1  # ETA_N m_eff a: the mass brings s^2, a none

    def gamma_n(self, values: dict, m_eff: float) -> float:
        return values[self.coefficient.name] * m_eff

    def radius_power(self, normal) -> float:
        return 1.0


LAW = Viscoelastic()
