"""``damping mass_velocity``: LAMMPS's normal dashpot ETA_N m_eff, a rate times the contact's
effective mass (the sphere's, against a wall): gamma_n = gamma_n_per_mass m_eff and
gamma_t = X_T gamma_n. Measured on this build: e = 0.779490 at dt = 1e-4 against the exact
0.779467 for m = 1, kn = 10, ETA_N = 0.5 (the step's first-order damping error).
"""

from __future__ import annotations

from ...declaration import Parameter
from .scaled import X_T, Scaled

__all__ = ["MassVelocity", "LAW", "GAMMA_N_PER_MASS"]

GAMMA_N_PER_MASS = Parameter(
    "gamma_n_per_mass", "damping mass_velocity: normal damping per effective mass, gamma_n/m_eff (LAMMPS's ETA_N); "
    "none for any other damping", "1/time", None, low=0.0, optional=True, why="negative damping would create energy",
    deck="granular hooke KN ETA_N damping mass_velocity")


class MassVelocity(Scaled):
    keyword = "mass_velocity"
    summary = "gamma_n = gamma_n_per_mass m_eff, gamma_t = x_t gamma_n"
    coefficient = GAMMA_N_PER_MASS
    coefficients = (GAMMA_N_PER_MASS, X_T)
    eta_time_power = -1  # ETA_N m_eff: the mass already brings s^2

    def gamma_n(self, values: dict, m_eff: float) -> float:
        return values[self.coefficient.name] * m_eff


LAW = MassVelocity()
