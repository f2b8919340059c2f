"""``damping coeff_restitution``: LAMMPS sets the dashpot from a normal restitution e (ETA_N).

With the Hookean force (``GranSubModDampingCoeffRestitution``) the prefactor is
2 beta sqrt(m_eff kn) with beta = -ln e/sqrt(pi^2 + ln^2 e): the damped oscillator's exact
restitution is then e, measured on this build as 0.5000008 for e = 0.5 at dt = 1e-4.
"""

from __future__ import annotations

import math

from .scaled import E_N, X_T, Scaled

__all__ = ["CoeffRestitution", "LAW"]


class CoeffRestitution(Scaled):
    keyword = "coeff_restitution"
    summary = "the dashpot that gives normal restitution e_n (Hookean: exactly)"
    coefficient = E_N
    coefficients = (E_N, X_T)
    eta_time_power = 0  # sqrt(m_eff kn) already brings s: a restitution does not follow time

    def gamma_n(self, values: dict, m_eff: float) -> float:
        log_e = math.log(values[self.coefficient.name])
        return -2.0 * log_e / math.sqrt(math.pi**2 + log_e**2) * math.sqrt(m_eff * values["kn"])


LAW = CoeffRestitution()
