"""The paper's prediction for nonlinear contacts, for the Hertzian force with the paper's spring
and with LAMMPS's Mindlin spring.

The Conclusions: with a nonlinear normal force the contact time depends on v_n(0), so the
energy-conserving bounce (Omega = -2) is "restricted to special values of the initial normal
velocity". With the paper's linear tangential spring that holds (spinbounce.exact.hertz: kt*
grows as |v_n|^(2/5)). With a Mindlin spring the tangential stiffness grows with the contact
radius as the normal one does, and Omega does not depend on v_n at all (spinbounce.exact.mindlin):
at k_t/kn = alpha/(1 + alpha) every speed conserves energy.
"""

from __future__ import annotations

import numpy as np

from ...exact import choose, contact_phases, hertz
from ...model.contact import ContactModel
from .ledger import COLLISION_TOL, Claim, Runs, checked, g

#: Three impact speeds, a factor 7.5 apart at the ends (kn = 1e4 keeps the overlap below r/4).
SPEEDS = np.array([-0.2, -0.7, -1.5])
SPEED_LIST = ", ".join(f"{-v:g}" for v in SPEEDS)
KN = 1.0e4
#: The initial slip rate (v_t, r omega = 0): Omega is read from the slip ratio.
V_T = 1.0
#: An Omega this far from -2 is not an energy-conserving bounce (its energy loss is ~1e-2 of the
#: tangential energy), far beyond the runs' error.
OFF_MAGIC = 1e-2


def _omegas(runs: Runs, name: str, model: ContactModel) -> tuple[np.ndarray, np.ndarray]:
    """(LAMMPS, exact) Omega at each speed, from the slip ratio of one batch."""
    _, t = runs.collide(name, model, SPEEDS, V_T, 0.0)
    lammps = (t["v_t_lammps"] + t["r_omega_lammps"]).to_numpy() / V_T - 1.0
    return lammps, choose.omega_per_sphere(model, SPEEDS)


def _listed(values) -> str:
    return ", ".join(f"{x:.6f}" for x in values)


def hertz_special_speed(runs: Runs) -> Claim:
    """Conclusions, with the paper's spring: the energy-conserving kt serves one speed only."""
    alpha, m, r = ContactModel().alpha, ContactModel().m, ContactModel().r
    kt = float(hertz.energy_conserving_kt(SPEEDS[1], m, KN, r, alpha))
    model = ContactModel(normal="hertz", kn=KN, kt=kt)
    lammps, exact = _omegas(runs, "hertz-special-speed", model)
    special = abs(exact[1] + 2.0) < 1e-9 and bool(np.all(np.abs(exact[[0, 2]] + 2.0) > OFF_MAGIC))
    c = Claim("hertz-special-speed", "with a nonlinear normal force the energy-conserving bounce (Omega = -2) is "
              "restricted to special values of v_n(0): Hertzian force, the paper's spring", "Conclusions",
              "special v_n(0) only", _listed(lammps), _listed(exact), runs=["hertz-special-speed"])
    c.verdict = checked(float(np.abs(lammps - exact).max()) <= COLLISION_TOL, "reproduced" if special else
                        "contradicted")
    c.evidence = (f"kt = {g(kt)} conserves energy at |v_n| = {-SPEEDS[1]:g} (Hertzian kn = {KN:g}); Omega at "
                  f"|v_n| = {SPEED_LIST}: LAMMPS {_listed(lammps)}, exact {_listed(exact)}: only the middle "
                  "speed reverses the slip (kt* grows as |v_n|^(2/5))")
    return c


def mindlin_every_speed(runs: Runs) -> Claim:
    """Conclusions, with LAMMPS's Mindlin spring: Omega is the same at every speed."""
    alpha = ContactModel().alpha
    model = ContactModel(normal="hertz", kn=KN, tangential="mindlin", mindlin_kt=KN * alpha / (1.0 + alpha))
    lammps, exact = _omegas(runs, "mindlin-every-speed", model)
    material = ContactModel(normal="hertz/material", youngs_modulus=KN, poisson_ratio=0.3, tangential="mindlin")
    lammps_null, exact_null = _omegas(runs, "mindlin-null-every-speed", material)
    # the speed-free Omega is one scaled solve; the contact integrated in time at each speed must agree
    in_time = np.array([sum(contact_phases.bounce(contact_phases.Law.of(material), v, V_T, 0.0)[1:3]) / V_T - 1.0
                        for v in SPEEDS])
    every = bool(np.all(np.abs(exact + 2.0) < 1e-9)) and float(np.abs(in_time - exact_null).max()) < 1e-9
    agree = max(np.abs(lammps - exact).max(), np.abs(lammps_null - exact_null).max()) <= COLLISION_TOL
    c = Claim("mindlin-every-speed", "the same, with LAMMPS's Mindlin tangential spring (tangential mindlin, its "
              "stiffness growing with the contact radius)", "Conclusions", "special v_n(0) only", _listed(lammps),
              _listed(exact), runs=["mindlin-every-speed", "mindlin-null-every-speed"])
    c.verdict = checked(agree, "contradicted" if every else "reproduced")
    c.evidence = (f"k_t/kn = alpha/(1 + alpha) (lam = (1 + alpha)/alpha k_t/kn = 1; Hertzian kn = {KN:g}): Omega at "
                  f"|v_n| = {SPEED_LIST}: LAMMPS {_listed(lammps)}, exact {_listed(exact)}: every speed "
                  "conserves energy, as the history follows the overlap. Omega depends on lam alone: with LAMMPS's "
                  f"NULL stiffness (E = {KN:g}, nu = 0.3) LAMMPS gives {_listed(lammps_null)} at the same speeds "
                  f"(exact {exact_null[0]:.6f} at each). So a magic Poisson's ratio would replace the magic speed, "
                  "but for a solid sphere none exists in (-1, 1/2] (k_t/kn = 3 (1 - nu)/(2 - nu) >= 1)")
    return c
