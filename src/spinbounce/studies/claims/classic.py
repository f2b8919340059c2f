"""The claim that LAMMPS's implementation of Silbert et al.'s contact is the paper's model."""

from __future__ import annotations

import numpy as np

from ... import exact
from ...model.contact import ContactModel
from ...exact import classic
from .ledger import COLLISION_TOL, Claim, Runs, checked, final, g

#: Impact speeds that show Omega's dependence on v_n (all below the tunnelling speed 1.58).
SPEEDS = (0.25, 1.0, 1.5)


def classic_wall_is_eq1(runs: Runs) -> Claim:
    """Sec. 1 uses "an implementation of this model [Silbert et al.], available in the LAMMPS
    package": the classic ``hooke/history`` form. In this build its wall's tangential spring is
    kt sqrt(r delta), so Omega depends on v_n; the granular form (and the classic pair style)
    give Eq. 1. LAMMPS's classic wall is set against both theories, sticking (MU = 1e4)."""
    model = ContactModel(wall="classic")
    speeds = np.asarray(SPEEDS)
    scene, t = runs.collide("classic-wall", model, -speeds, 1.0, 0.0)
    measured = final(t)[:, 1] + final(t)[:, 2] - 1.0
    contact_radius = np.array([classic.Omega_eff(-v, model.kn, model.kt, model.alpha, model.r, model.m)
                               for v in speeds])
    paper = exact.Omega(model.kn, model.kt, model.alpha)
    agrees = bool(np.abs(measured - contact_radius).max() <= COLLISION_TOL)
    c = Claim("lammps-classic-wall", "LAMMPS's implementation of the Cundall-Strack contact (Silbert et al.'s "
              "hooke/history) is the model of Eq. 1, with Omega = -1.2838 at the paper's parameters (in the LAMMPS "
              "build at hand)",
              "Sec. 1, refs. [19, 20]", paper, float(measured[1]), float(contact_radius[1]), runs=["classic-wall"])
    c.verdict = checked(agrees and abs(measured[1] - paper) > 100 * COLLISION_TOL, "contradicted")
    c.evidence = (f"this build's fix wall/gran hooke/history at |v_n| = {', '.join(g(v, 3) for v in speeds)}: "
                  f"Omega = {', '.join(g(x, 6) for x in measured)} (LAMMPS), "
                  f"{', '.join(g(x, 6) for x in contact_radius)} (spring kt sqrt(r delta), exact.classic), "
                  f"against Eq. 18's {g(paper, 6)} at every speed; the granular form's linear_history and the "
                  "classic pair style gran/hooke/history give Eq. 1 (spinbounce doctor); the classic wall gave it "
                  "before the March 2023 refactor of LAMMPS's GRANULAR package and again after its fix upstream "
                  f"(LAMMPS PR #5007); dt = {scene.dt:.4g}")
    return c
