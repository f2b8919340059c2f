"""calibrate for Hertz-Mindlin: from a bounce's normal restitution e (and, optionally, the contact
point's tangential restitution beta = -u'(out)/u'(in)) to LAMMPS's ``hertz/material`` +
``damping coeff_restitution`` + a Mindlin spring.

With the Hertzian force coeff_restitution's dashpot, sqrt(3/2) 2 sqrt(5/6) beta_e sqrt(m_eff kn a),
gives the restitution e_n at every impact speed, and with a Mindlin spring (its stiffness, and the
tangential dashpot x_t times the normal one, on the contact radius too) every contact is the same
one scaled: one restitution and one Omega at every speed (spinbounce.exact.contact_phases). So
e_n = e, and beta = -(1 + Omega) fixes one tangential number: the Poisson's ratio of LAMMPS's NULL
stiffness (k_t/kn = 3 (1 - nu)/(2 - nu)), or, with nu given, an explicit k_t. Young's modulus sets
only the contact's duration. Unreachable targets raise :class:`~.calibrate.Unreachable` with the
reachable range.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..exact.contact_phases import Law, exit_slips
from ..exact.linear import Omega_of_matrix
from ..model.contact import ContactModel
from .calibrate import Unreachable

__all__ = ["MindlinTargets", "calibrate_mindlin", "achieved", "beta_range", "measure_mindlin", "POISSON_GRID",
           "RATIO_GRID"]

#: Where the scans look for beta: Poisson's ratios of the NULL stiffness, and k_t/kn with nu held
#: (log-spaced: Omega turns fastest at small k_t/kn).
POISSON_GRID = np.linspace(-0.99, 0.5, 60)
RATIO_GRID = np.geomspace(1e-3, 10.0, 120)


@dataclass(frozen=True)
class MindlinTargets:
    """What a Hertz-Mindlin bounce should do, and what is held: the material's E (and nu, if
    given: then beta sets k_t), the Mindlin variant, X_T, the sphere."""

    e: float
    beta: float | None = None
    youngs_modulus: float = 1.0e4
    poisson_ratio: float | None = None
    tangential: str = "mindlin"
    x_t: float | None = None
    m: float = 1.0
    r: float = 0.5
    alpha: float = 0.4


def _model(t: MindlinTargets, poisson_ratio: float, mindlin_kt: float | None = None) -> ContactModel:
    return ContactModel(normal="hertz/material", youngs_modulus=t.youngs_modulus, poisson_ratio=poisson_ratio,
                        damping="coeff_restitution", e_n=t.e, x_t=t.x_t, tangential=t.tangential,
                        mindlin_kt=mindlin_kt, m=t.m, r=t.r, alpha=t.alpha)


def achieved(model: ContactModel) -> dict:
    """e and beta of the model's one matrix (the same at every speed)."""
    m3 = model.matrix()
    omega = Omega_of_matrix(m3, model.alpha)
    return {"e": float(-m3[0, 0]), "beta": float(-(1.0 + omega))}


def _axis(t: MindlinTargets):
    """(name, model of x, grid): what beta is solved with."""
    if t.poisson_ratio is None:
        return "poisson_ratio", (lambda nu: _model(t, float(nu))), POISSON_GRID
    kn = _model(t, t.poisson_ratio).kn
    return "mindlin_kt", (lambda q: _model(t, t.poisson_ratio, float(q) * kn)), RATIO_GRID


def _betas(models) -> np.ndarray:
    """beta = -u'(out)/u'(in) of each model of a scan, from one integration: the contact is the same
    one scaled (the module's docstring), so each model's exit is that of its own k_t/kn and x_t on
    the first model's normal motion (equal to :func:`achieved`'s to 1e-9, tests/test_calibrate_mindlin)."""
    laws = [Law.of(model) for model in models]
    first = laws[0]
    shared = ("m", "r", "alpha", "power", "spring_power", "force_history", "rescale", "damping_power", "tensile")
    assert all(getattr(law, name) == getattr(first, name) for law in laws for name in shared), "not one scan's laws"
    assert all((law.c_n > 0.0) == (first.c_n > 0.0) for law in laws), "not one scan's laws"
    springs = [law.k * first.K / law.K for law in laws]
    dashpots = [law.c_t * first.c_n / law.c_n if law.c_n else law.c_t for law in laws]
    return -exit_slips(first, springs, dashpots)


def beta_range(t: MindlinTargets) -> tuple[float, float, str, np.ndarray, np.ndarray]:
    """(lowest, highest) beta on the scan, the parameter solved for, its grid and beta on it."""
    name, model_of, grid = _axis(t)
    models = [model_of(x) for x in grid]
    models[0].check_overlap_resolved(-1.0)  # the scaled contact, at a unit speed: E = 1e308 once a traceback
    betas = _betas(models)
    return float(betas.min()), float(betas.max()), name, grid, betas


def calibrate_mindlin(t: MindlinTargets) -> ContactModel:
    """The Hertz-Mindlin model whose exact theory meets ``t`` (the first root along the scan)."""
    if t.beta is None:
        if t.poisson_ratio is None:
            raise Unreachable("poisson_ratio", None, "must be given without a beta to aim at (it sets the NULL "
                                                     "stiffness)")
        return _model(t, t.poisson_ratio)
    if not -1.0 <= t.beta <= 1.0:
        raise Unreachable("beta", t.beta, "must lie in [-1, 1] for a passive contact (|u'(out)| <= |u'(in)|; a "
                                          "Mindlin bounce can gain energy, but calibrating to a gain is refused)")
    low, high, name, grid, betas = beta_range(t)
    _, model_of, _ = _axis(t)
    excess = betas - t.beta
    crossing = np.flatnonzero(excess[:-1] * excess[1:] <= 0.0)
    if crossing.size == 0:
        raise Unreachable("beta", t.beta, f"with e = {t.e:g} and {t.tangential} the scan of {name} reaches beta in "
                                          f"[{low:.6g}, {high:.6g}]")
    k = int(crossing[0])

    def miss(v: float) -> float:
        return achieved(model_of(v))["beta"] - t.beta

    ends = miss(grid[k]), miss(grid[k + 1])  # each model's own bounce: the scan's agrees with it to ~1e-10
    if ends[0] * ends[1] >= 0.0:  # a target that close to a grid point's beta: that point
        return model_of(grid[k] if abs(ends[0]) <= abs(ends[1]) else grid[k + 1])
    x = brentq(miss, grid[k], grid[k + 1], xtol=1e-13, rtol=1e-12)
    # to the root's own tolerance: the digits beyond it differ from one scipy release to the next
    return model_of(float(f"{x:.12g}"))


def measure_mindlin(model: ContactModel, out, v_n: float = -1.0) -> dict:
    """e and beta of one LAMMPS bounce at the default step (u'(0) = 1, r omega = 0), and its run."""
    from pathlib import Path

    from ..pipeline import run_scene
    from ..scenes.collision import Collision

    result = run_scene(Collision(model, v_n=v_n, v_t=1.0, omega=0.0), Path(out) / "bounce")
    row = result.table.iloc[0]
    return {"e": float(row["v_n_lammps"] / -v_n), "beta": float(-(row["v_t_lammps"] + row["r_omega_lammps"])),
            "dt": result.scene.dt, "nsteps": result.scene.nsteps, "deck": str(Path(out) / "bounce" / "in.lammps")}
