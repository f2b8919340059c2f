"""Claims about the contact time: Eq. 16, normal damping, the Hertzian and hard-sphere walls."""

from __future__ import annotations

import math

import numpy as np

from ...model.contact import ContactModel
from ...exact import hertz
from ...scenes.collision import HERTZ_STEPS_PER_HALF_PERIOD
from .ledger import Claim, Runs, checked, contact_time, damped_dt, g

#: Speeds of the contact-time runs: a factor 30 in |v_n|.
SPEEDS = np.array([-0.05, -0.1, -0.3, -0.6, -1.0, -1.5])
#: The Hertzian wall of kn = 10, r = 0.5 tunnels above |v_n| ~ 1: its speeds stop below that.
HERTZ_SPEEDS = np.array([-0.03, -0.1, -0.3, -0.9])
#: Hertzian stiffnesses of the hard-sphere limit, at one speed.
HARD_STIFFNESS = (10.0, 1e2, 1e3, 1e4)
HARD_SPEED = -0.5
#: A measured Hertzian contact time is held to about one step (at the default step a batch
#: of speeds runs time-scaled, every contact ending mid-step: 9.3e-6 measured at dt = 7.3e-3).
HERTZ_STEPS_TOL = 1.0
#: The undamped contact time at the default dt: 6.5e-6 measured, second order in dt.
TAU_TOL = 2e-5
#: With gamma_n the dashpot uses the half-step velocity and the contact time is first order in
#: dt: 0.245 dt short, measured at dt/8, dt/32 and dt/128 (mid-step). Half a step is allowed.
TAU_DAMPED_STEPS = 0.5


def _loglog_slope(x, y) -> float:
    return float(np.polyfit(np.log(np.abs(x)), np.log(y), 1)[0])


def tau_independent(runs: Runs) -> Claim:
    model = ContactModel()
    scene, t = runs.collide("tau-vs-vn", model, SPEEDS, 0.3, 0.0)
    tau = contact_time(scene, t)
    exact = model.tau
    off = float(np.abs(tau - exact).max())
    c = Claim("tau", "contact time tau = pi sqrt(m/kn), independent of v_n(0)", "Eq. 16",
              math.pi * math.sqrt(model.m / model.kn), f"{g(tau.min(), 8)} .. {g(tau.max(), 8)}",
              exact, runs=["tau-vs-vn"])
    c.verdict = checked(off <= TAU_TOL, "reproduced")
    c.evidence = (f"LAMMPS contact time for |v_n| from 0.05 to 1.5 (from each sphere's free flight after "
                  f"contact): spread {tau.max() - tau.min():.1e}, largest difference from pi sqrt(m/kn) "
                  f"{off:.1e} (dt = {scene.dt:.3g})")
    return c


def _damped_taus(runs: Runs) -> tuple[ContactModel, np.ndarray, float, bool]:
    """(model, LAMMPS contact times over SPEEDS at gamma_n = 1, the run's dt, whether they are
    within TAU_DAMPED_STEPS of exact)."""
    model = ContactModel(gamma_n=1.0)
    scene, t = runs.collide("tau-gamma-n", model, SPEEDS, 0.0, 0.0, dt=damped_dt(model))
    tau = contact_time(scene, t)
    return model, tau, scene.dt, float(np.abs(tau - model.tau).max()) <= TAU_DAMPED_STEPS * scene.dt


def tau_damped_longer(runs: Runs) -> Claim:
    """First half of the Sec. 5 parenthesis: gamma_n > 0 lengthens the contact."""
    model, tau, dt, agree = _damped_taus(runs)
    undamped = ContactModel().tau
    c = Claim("tau-gamma-n-longer", "gamma_n > 0 increases the contact time tau", "Sec. 5 (parenthesis), "
              "first half", f"tau > {g(undamped, 6)}", f"{g(tau.min(), 7)} .. {g(tau.max(), 7)}",
              model.tau, runs=["tau-gamma-n"])
    c.verdict = checked(agree, "reproduced" if tau.min() > undamped else "contradicted")
    c.evidence = (f"at gamma_n = 1 the contact lasts pi/omega_d = {g(model.tau, 7)}, longer than pi sqrt(m/kn) = "
                  f"{g(undamped, 7)}; LAMMPS (dt = {dt:.3g}, mid-step): {g(tau.min(), 7)} .. {g(tau.max(), 7)}, "
                  f"{(model.tau - tau.mean()) / dt:.3f} dt short (first order in dt with a dashpot)")
    return c


def tau_damped_vn(runs: Runs) -> Claim:
    """Second half of the Sec. 5 parenthesis: ... and makes tau depend on v_n(0)."""
    model, tau, dt, agree = _damped_taus(runs)
    spread = float(tau.max() - tau.min())
    c = Claim("tau-gamma-n-vn", "with gamma_n > 0 the contact time depends on v_n(0)", "Sec. 5 (parenthesis), "
              "second half", "depends on v_n", f"spread {spread:.1e} over |v_n| = 0.05..1.5", "independent of v_n",
              runs=["tau-gamma-n"])
    # the spheres share every step, so the first-order error is the same for all of them
    c.verdict = checked(agree, "contradicted" if spread < TAU_TOL else "reproduced")
    c.evidence = (f"at gamma_n = 1, LAMMPS (dt = {dt:.3g}) gives the same contact time for every v_n(0) from -0.05 "
                  f"to -1.5: spread {spread:.1e}. The linear spring-dashpot m z'' = -kn z - gamma_n z' is linear "
                  "in v_n(0), so z(t) only scales with it and the time of its zero cannot move; a nonlinear "
                  "(e.g. Hertzian) force would make tau depend on v_n (claim hertz-tau)")
    return c


def _hertz_taus(runs: Runs, name: str, model: ContactModel, speeds,
                dt: float | None = None) -> tuple[np.ndarray, np.ndarray, float]:
    """(LAMMPS contact times, exact ones, the run's dt) of a Hertzian wall (dt None: the default step)."""
    scene, t = runs.collide(name, model, speeds, 0.0, 0.0, dt=dt)
    return contact_time(scene, t), hertz.contact_time(speeds, model.m, model.kn, model.r), scene.dt


def hertz_tau(runs: Runs) -> Claim:
    """Sec. 4 after Eq. 16 and the conclusions: a nonlinear force makes tau fall with |v_n(0)|."""
    model = ContactModel(normal="hertz")
    # one fine plain step for every speed (the fixed rule of a batch that is not time-scaled): the
    # contact times to 1e-10, where the batch's time-scaled default holds them to 1e-5
    fine = math.pi / model.fastest_rate(frozen=False, speed=float(np.max(np.abs(HERTZ_SPEEDS))))
    tau, exact, dt = _hertz_taus(runs, "hertz-tau", model, HERTZ_SPEEDS, fine / HERTZ_STEPS_PER_HALF_PERIOD)
    slope = _loglog_slope(HERTZ_SPEEDS, tau)
    c = Claim("hertz-tau", "with a nonlinear (Hertzian) force the contact time is a decreasing function of "
              "|v_n(0)|", "Sec. 4 after Eq. 16; Conclusions", "decreasing in |v_n|",
              f"{g(tau[0], 5)} .. {g(tau[-1], 5)}, slope {slope:.4f}",
              f"{g(exact[0], 5)} .. {g(exact[-1], 5)}, slope -0.2", runs=["hertz-tau"])
    agree = float(np.abs(tau - exact).max()) <= HERTZ_STEPS_TOL * dt
    c.verdict = checked(agree, "reproduced" if np.all(np.diff(tau) < 0) else "contradicted")
    c.evidence = (f"Hertzian wall (F = kn sqrt(r) delta^1.5, kn = {model.kn:g}): LAMMPS contact times at |v_n| = "
                  + ", ".join(f"{abs(v):g}" for v in HERTZ_SPEEDS) + ": "
                  + ", ".join(f"{x:.5f}" for x in tau) + " (exact " + ", ".join(f"{x:.5f}" for x in exact)
                  + f"; within {np.abs(tau - exact).max():.1e}, dt = {dt:.2g}); log-log slope {slope:.4f}, "
                  "exactly -1/5 in theory (tau ~ |v_n|^(-1/5))")
    return c


def hard_sphere(runs: Runs) -> Claim:
    """Sec. 4 after Eq. 16: 'for a hard sphere-wall interaction we would have tau = 2r/v_n(0)'."""
    names = [f"hard-{k:.0e}" for k in HARD_STIFFNESS]
    walls = [ContactModel(normal="hertz", kn=k) for k in HARD_STIFFNESS]
    measured, exact, steps = np.array([np.hstack(_hertz_taus(runs, name, wall, [HARD_SPEED]))
                                       for name, wall in zip(names, walls, strict=True)]).T
    slope = _loglog_slope(HARD_STIFFNESS, measured)
    r = ContactModel().r
    c = Claim("hard-sphere", "for a hard sphere-wall interaction tau = 2r/v_n(0)", "Sec. 4 after Eq. 16",
              f"2r/v_n(0) = {2 * r / HARD_SPEED:g} (r = {r:g}, v_n(0) = {HARD_SPEED:g}; negative)",
              f"{g(measured[0], 4)} .. {g(measured[-1], 4)} (kn = 10 .. 1e4)",
              f"-> 0 as kn^{slope:.3f}", runs=names)
    agree = bool(np.all(np.abs(measured - exact) <= HERTZ_STEPS_TOL * steps))
    c.verdict = checked(agree, "ill-posed")
    c.evidence = (f"2r/v_n(0) = {2 * r / HARD_SPEED:g} is negative for an incoming sphere (v_n(0) < 0) and is the "
                  "time to cross one diameter, which no contact law gives. The hard wall is the limit kn -> inf "
                  f"of a soft one, where the contact time vanishes: at v_n(0) = {HARD_SPEED:g} LAMMPS's Hertzian "
                  "contact lasts " + ", ".join(f"{x:.4g}" for x in measured) + " for kn = "
                  + ", ".join(f"{k:.0e}" for k in HARD_STIFFNESS) + f" (log-log slope {slope:.4f}; exact "
                  "tau ~ kn^(-2/5)), the Hookean one pi sqrt(m/kn) ~ kn^(-1/2). What stays finite in the limit "
                  "is the outcome, and only if kt/kn is held fixed (Omega depends on kt/kn alone)")
    return c
