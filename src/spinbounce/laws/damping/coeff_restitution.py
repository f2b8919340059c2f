"""``damping coeff_restitution``: LAMMPS sets the dashpot from a normal restitution e (ETA_N).

With the Hookean force (``GranSubModDampingCoeffRestitution``) the prefactor is
2 beta sqrt(m_eff kn) with beta = -ln e/sqrt(pi^2 + ln^2 e): the damped oscillator's exact
restitution is then e, measured on this build as 0.5000008 for e = 0.5 at dt = 1e-4.
"""

from __future__ import annotations

import math

from .scaled import FromRestitution

__all__ = ["CoeffRestitution", "LAW"]


class CoeffRestitution(FromRestitution):
    keyword = "coeff_restitution"
    summary = "the dashpot that gives normal restitution e_n (Hookean: exactly)"

    def factor(self, e: float, normal) -> float:
        log_e = math.log(e)
        beta = -log_e / math.sqrt(math.pi**2 + log_e**2)
        # LAMMPS: 2 beta for hooke; sqrt(3/2) 2 sqrt(5/6) beta (with sqrt(m_eff F/delta)) for any other
        return (math.sqrt(1.5) * 2.0 * math.sqrt(5.0 / 6.0) if normal.contact_radius else 2.0) * beta


LAW = CoeffRestitution()
