"""Speed against accuracy: how LAMMPS's error against the exact theory falls with dt.

A convergence study over the timestep for collisions and frozen contacts, across named
cases (:func:`cases`). Each case runs a ladder of steps, n steps per half-period of its
fastest contact mode, and at every level records the largest error against the exact
theory, the LAMMPS steps and the seconds the run took. From the ladder come the observed
order of convergence (the slope of log error against log dt over the finest levels) and
the steps that plain refinement needs for a given accuracy.

Collisions run in two forms:

* ``mid-step end``: dt = tau/(M + 1/2), so the contact ends in the middle of a step
  (the scenes' default form);
* ``end on a step``: dt = tau/M, so the contact ends exactly on a step boundary.

Why a handful of states per case is enough: without a Coulomb cap the contact is linear
(Hookean springs, viscous dashpots) and the time the contact ends does not depend on the
state (the overlap is v_n times a function of time), so LAMMPS's discrete map is, like
the exact one, a linear map of (v_n, v_t, r omega). Its error is then linear in the
state too, and its largest value over a box of initial states sits at one of the box's
corners: the eight corners of the sweep's box bound the error over the whole box.

matplotlib is imported only when the figure is drawn; LAMMPS only when a run starts.
"""

from __future__ import annotations

import datetime
import math
import os
import platform
import shutil
import tempfile
import time
import warnings
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from .. import __version__
from ..compare import STATE
from ..pipeline import run_collision, run_frozen
from ..records import json_ready, write_atomic
from ..model.scenes import (
    COLLISION_STEPS_PER_HALF_PERIOD,
    FROZEN_STEPS_PER_HALF_PERIOD,
    Collision,
    ContactModel,
    Frozen,
    PhysicsWarning,
)

__all__ = [
    "EDGE",
    "FROZEN",
    "MID",
    "TARGETS",
    "Case",
    "Study",
    "cases",
    "collision_dt",
    "fit_order",
    "frozen_dt",
    "ladder",
    "make_accuracy",
    "run_study",
    "steps_for",
    "summarise",
    "write_study",
]

#: Steps per half-period of the fastest mode along the full ladder, and the quick one.
FULL_LADDER = tuple(2**k for k in range(5, 17))  # 32 .. 65536
QUICK_LADDER = (64, 128, 256, 512, 1024)
#: The order is fitted over this many of the finest levels (a factor 8 in dt).
FIT_LEVELS = 4
#: Errors below this are not truncation: round-off, the 1e-12 normal dashpot that carries a
#: tangential one in LAMMPS (decks.VANISHING_ETA_N), a reference run's own error. Left out of fits.
ERROR_FLOOR = 1e-11
#: The accuracies whose cost the study reports.
TARGETS = (1e-4, 1e-6, 1e-8)
#: Spheres in the batch that measures the cost per collision of a sweep-like run.
COST_BATCH = {False: 1000, True: 100}
#: Each run is timed this many times (the least counts): full study, quick study.
TIMING_REPEATS = {False: 2, True: 1}
#: A case without exact theory is measured against a run this many times finer than the ladder's finest.
REFERENCE_FACTOR = 16
#: Collision forms, and the frozen contact's single form.
MID, EDGE, FROZEN = "mid-step end", "end on a step", "frozen"
#: Duration and height of the frozen contacts (as in Figs. 2 and 7).
FROZEN_T_END = 10.0
FROZEN_Z = 0.1
#: The sweep's box of initial states: v_n in [-1.5, -0.1], v_t and r omega in [-2, 2].
BOX = ((-1.5, -0.1), (-2.0, 2.0), (-2.0, 2.0))


def _corners() -> tuple[tuple[float, float, float], ...]:
    return tuple((vn, vt, rw) for vn in BOX[0] for vt in BOX[1] for rw in BOX[2])


def _box_sample(n: int, seed: int) -> np.ndarray:
    lo, hi = np.array(BOX).T
    return np.random.default_rng(seed).uniform(lo, hi, size=(n, 3))


@dataclass(frozen=True)
class Case:
    """One row of the study: a scene kind, a model, its states and why it is here.

    ``states``: (v_n, v_t, r omega) per sphere for a collision; for a frozen contact one
    (0, v_t, r omega), held at height FROZEN_Z for FROZEN_T_END. ``expected`` is the order
    the reasoning in ``limit`` predicts for the mid-step form (or the frozen contact),
    ``expected_edge`` for the end-on-a-step form. ``exact = False`` marks a case with no
    exact theory (finite mu): its error is measured against a much finer run instead.
    """

    name: str
    label: str
    kind: str
    model: ContactModel
    states: tuple
    why: str
    limit: str
    expected: float
    expected_edge: float | None = None
    exact: bool = True

    @property
    def forms(self) -> tuple[str, ...]:
        return (FROZEN,) if self.kind == "frozen" else (MID, EDGE)

    def record(self) -> dict:
        return {"name": self.name, "label": self.label, "kind": self.kind, "model": asdict(self.model),
                "states": [list(s) for s in self.states], "why": self.why, "limit": self.limit,
                "expected_order": self.expected, "expected_order_end_on_step": self.expected_edge,
                "exact_theory": self.exact}


# ---------------------------------------------------------------------------
# The cases
# ---------------------------------------------------------------------------

#: What limits the order: the mechanisms, each named once. The contact starts on a step
#: (t = 0) with zero overlap and zero slip, so entry costs nothing in the undamped model;
#: what matters is the exit, the dashpots and the cap.
MECHANISMS = {
    "normal over-kick": (
        "with the end mid-step, the contact's last kick applies the normal spring at overlap "
        "|v_n| dt/2 for a whole half step, while the exact force fades to zero within it: the "
        "outgoing |v_n| comes out too large by |v_n| (w_n dt)^2/8, second order (w_n = sqrt(kn/m)). At "
        "the paper's defaults this is the largest error: 1.5 (pi/250.5)^2/8 = 2.95e-5 at the default step"),
    "tangential cut": (
        "the tangential spring force -kt u(tau) is still finite when the contact ends and drops to zero "
        "in one step. With the end mid-step the cut's first-order error cancels and second order is "
        "left; with the end on a step boundary the force is applied for a half step or not at all: "
        "first order, whatever the other terms do"),
    "normal end on a step": (
        "with the end on a step, the overlap there is only velocity Verlet's O(dt^2) phase slip, so "
        "the last half-kick is O(dt^3), and v_n sits at the flat bottom of its cosine: third order"),
    "phase error": (
        "velocity Verlet's phase error: second order, growing linearly with time; with no contact end "
        "it is the only error"),
    "dashpot lag": (
        "LAMMPS evaluates velocity-dependent forces with the half-step velocity, a first-order lag; a "
        "dashpot force -gamma v is also finite at entry and exit, so it is cut wherever the end falls: "
        "first order in the components it acts on, in both forms"),
    "Coulomb cap": (
        "|F_t| <= mu F_n and F_n -> 0 at the exit (and at entry), so every contact with u(tau) != 0 "
        "slides at its end: the cap brings F_t to zero continuously and so removes the tangential cut "
        "in both forms. The switches between sticking and sliding fall between steps, but they are "
        "kinks in the force (continuous, with a jump in slope), which velocity Verlet's trapezoidal "
        "kick integrates with a second-order error whose size depends on where in its step each "
        "switch falls: order 2, with local orders that wobble (the error is not a smooth series in dt)"),
}

_DEFAULT_LIMIT = ("mid-step: normal over-kick (v_n) and the cancelled tangential cut, both second order. "
                  "On a step: the tangential cut, first order; v_n is third order")


def cases() -> list[Case]:
    """The study's cases, in the order of the table."""
    d = ContactModel()
    corners = _corners()
    coulomb_states = tuple(map(tuple, np.vstack([np.array(corners), _box_sample(24, seed=1)]).tolist()))
    return [
        Case("defaults", "paper defaults", "collision", d, corners,
             "the paper's parameters (kt/kn = 1/10, alpha = 2/5) at the 8 corners of the sweep's box, "
             "which bound its error", _DEFAULT_LIMIT, 2.0, 1.0),
        Case("magic", "magic ratio kt/kn = 2/7", "collision", ContactModel(kt=20.0 / 7.0), corners,
             "tau sqrt(Q) = pi: the slip displacement u is back to 0 when the contact ends",
             "mid-step: normal over-kick, and the same over-kick in the slip (u(tau) = 0 like the overlap), "
             "second order. On a step: u(tau) = 0, "
             "so both forces vanish at the end, nothing is cut, and every component is third order",
             2.0, 3.0),
        Case("soft", "soft, kt/kn = 0.01", "collision", ContactModel(kt=0.1), corners,
             "a slow slip mode (tau sqrt(Q) = 0.19 pi); the normal mode sets dt", _DEFAULT_LIMIT, 2.0, 1.0),
        Case("stiff", "stiff, kt/kn = 5", "collision", ContactModel(kt=50.0), corners,
             "a fast slip mode (4.2 slip half-periods per contact) that sets dt",
             _DEFAULT_LIMIT + "; the slip mode sets dt, so the normal over-kick is 17 times smaller and the "
             "tangential terms set the error", 2.0, 1.0),
        Case("damped_t", "damped, gamma_t = 1", "collision", ContactModel(gamma_t=1.0), corners,
             "a tangential dashpot (exact damped Omega)",
             "dashpot lag: v_t and r omega first order in both forms; v_n keeps its undamped order "
             "(on a step, down to the 1e-12 normal dashpot that carries gamma_t in LAMMPS)", 1.0, 1.0),
        Case("damped_n", "damped, gamma_n = 1", "collision", ContactModel(gamma_n=1.0), corners,
             "a normal dashpot (restitution 0.37; the theory lets the normal force turn tensile and ends "
             "the contact at z = r, as LAMMPS does)",
             "dashpot lag: v_n first order in both forms; v_t and r omega keep their undamped orders "
             "(2 mid-step, 1 on a step)", 1.0, 1.0),
        Case("alpha_small", "alpha = 0.1", "collision", ContactModel(alpha=0.1), corners,
             "mass near the centre: a fast slip mode, run through fix rigid instead of nve/sphere",
             _DEFAULT_LIMIT + "; fix rigid's step is velocity Verlet too, so the integrator changes nothing",
             2.0, 1.0),
        Case("alpha_shell", "alpha = 2/3", "collision", ContactModel(alpha=2.0 / 3.0), corners,
             "a thin shell, the largest physical alpha, through fix rigid",
             _DEFAULT_LIMIT + "; fix rigid's step is velocity Verlet too, so the integrator changes nothing",
             2.0, 1.0),
        Case("grazing", "grazing, |v_n| = 0.01", "collision", d,
             ((-0.01, 1.0, 0.0), (-0.01, 0.0, 1.0), (-0.01, -1.0, 2.0)),
             "nearly tangential incidence with slip 1: the overlap stays below 1e-3 r",
             "the contact's timing does not depend on v_n: the defaults' mechanisms, with the normal "
             "over-kick scaled down by |v_n|, so the tangential terms set the error", 2.0, 1.0),
        Case("head_on", "head-on, no spin", "collision", d, ((-1.5, 0.0, 0.0), (-0.1, 0.0, 0.0)),
             "v_t = omega = 0: no slip, only the normal spring acts",
             "no tangential force. Mid-step: the normal over-kick, second order. On a step: nothing is cut "
             "and v_n is third order: here ending on a step beats ending mid-step", 2.0, 3.0),
        Case("head_on_spin", "head-on with spin", "collision", d, ((-1.0, 0.0, 1.0), (-1.0, 0.0, -2.0)),
             "v_t = 0: all the slip comes from r omega", _DEFAULT_LIMIT, 2.0, 1.0),
        Case("high_spin", "high spin, |r omega| = 20 |v_n|", "collision", d,
             ((-0.1, 0.0, 2.0), (-0.1, 0.0, -2.0), (-0.1, 1.0, -2.0)),
             "spin dominates: slip 20 times the normal speed", _DEFAULT_LIMIT, 2.0, 1.0),
        Case("frozen", "frozen, defaults", "frozen", d, ((0.0, 1.0, 0.0),),
             f"sphere held at z = {FROZEN_Z:g} for t = {FROZEN_T_END:g} (Fig. 2): no contact end",
             "phase error, second order", 2.0),
        Case("frozen_damped", "frozen, gamma_t = 1", "frozen", ContactModel(gamma_t=1.0), ((0.0, 1.0, 0.0),),
             f"the damped frozen contact (Fig. 7), held for t = {FROZEN_T_END:g}",
             "dashpot lag, first order, with no contact end to blame", 1.0),
        Case("coulomb", "Coulomb cap mu = 0.5 (vs finer run)", "collision", ContactModel(mu=0.5), coulomb_states,
             "a finite Coulomb cap (sliding): no exact theory, so each level is measured against a run "
             f"{REFERENCE_FACTOR} times finer than the ladder's finest; 8 corners and 24 states from the box "
             "(with sliding the map is no longer linear, so corners alone need not bound it)",
             "Coulomb cap: no cut at the end, kinks between steps; second order in both forms (v_n is the "
             "defaults': the cap acts on the tangential force only)", 2.0, 2.0, exact=False),
    ]


# ---------------------------------------------------------------------------
# Steps
# ---------------------------------------------------------------------------

def ladder(quick: bool = False) -> tuple[int, ...]:
    return QUICK_LADDER if quick else FULL_LADDER


def _steps_per_tau(model: ContactModel, n: float) -> int:
    """Whole steps in a contact time that resolve the fastest mode with ``n`` steps per half-period."""
    return math.ceil(n * model.fastest_rate(frozen=False) * model.tau / math.pi - 1e-9)


def collision_dt(model: ContactModel, n: float, form: str) -> float:
    """The collision step for ``n`` steps per half-period of the fastest mode, in ``form``.

    For n = COLLISION_STEPS_PER_HALF_PERIOD the mid-step form is the scenes' default dt.
    """
    m = _steps_per_tau(model, n)
    if form == MID:
        return model.tau / (m + 0.5)
    if form == EDGE:
        return model.tau / m
    raise ValueError(f"form = {form!r}: a collision runs in form {MID!r} or {EDGE!r}")


def frozen_dt(model: ContactModel, n: float, t_end: float = FROZEN_T_END) -> float:
    """The frozen step for ``n`` steps per half-period, snapped to a whole number of steps in
    t_end (the scenes' default for n = FROZEN_STEPS_PER_HALF_PERIOD)."""
    dt = math.pi / model.fastest_rate(frozen=True) / n
    return t_end / math.ceil(t_end / dt - 1e-9)


def _steps_of_dt(case: Case):
    """LAMMPS steps of a run at step dt (the scenes' own counts)."""
    if case.kind == "frozen":
        return lambda dt: math.ceil(FROZEN_T_END / dt - 1e-9)
    return lambda dt: math.floor(case.model.tau / dt) + 2


# ---------------------------------------------------------------------------
# Runs
# ---------------------------------------------------------------------------

def _collision_scene(case: Case, dt: float, states=None) -> Collision:
    s = np.asarray(case.states if states is None else states, dtype=float)
    return Collision(case.model, v_n=s[:, 0], v_t=s[:, 1], omega=s[:, 2] / case.model.r, dt=dt)


def _timed(run, repeats: int):
    """``run()`` ``repeats`` times: the result of the fastest repeat and its wall seconds.

    The fastest of a few repeats is the run's cost with the least interference from the
    other processes on a shared machine. The repeats must agree exactly: LAMMPS on one
    rank is deterministic, and a difference would mean a run depends on something else.
    """
    best, best_wall = None, math.inf
    for _ in range(repeats):
        started = time.perf_counter()
        result = run()
        wall = time.perf_counter() - started
        if best is not None and not best.table.equals(result.table):
            raise RuntimeError(f"{result.info.deck}: a repeated run gave a different result")
        if wall < best_wall:
            best, best_wall = result, wall
    return best, best_wall


def _run_collision(case: Case, dt: float, folder: Path, states=None, repeats: int = 1) -> tuple[dict, np.ndarray]:
    """One batch at ``dt``: largest errors against Eq. 18, steps and seconds; and the final states."""
    scene = _collision_scene(case, dt, states)
    result, wall = _timed(lambda: run_collision(scene, folder, atoms="library", record=False), repeats)
    t = result.table
    row = {"dt": scene.dt, "lammps_steps": scene.nsteps, "spheres": scene.n,
           "loop_seconds": result.info.loop_seconds, "lammps_seconds": result.info.wall_seconds,
           "wall_seconds": wall}
    for s in STATE:
        row[f"error_{s}"] = float(np.max(np.abs(t[f"{s}_error"])))
    return row, t[[f"{s}_final" for s in STATE]].to_numpy()


def _run_frozen(case: Case, dt: float, folder: Path, repeats: int = 1) -> dict:
    ((_, v_t, r_omega),) = case.states
    scene = Frozen(case.model, z=FROZEN_Z, v_t=v_t, omega=r_omega / case.model.r, t_end=FROZEN_T_END, dt=dt)
    result, wall = _timed(lambda: run_frozen(scene, folder), repeats)
    t = result.table
    return {"dt": scene.dt, "lammps_steps": scene.nsteps, "spheres": 1,
            "loop_seconds": result.info.loop_seconds, "lammps_seconds": result.info.wall_seconds,
            "wall_seconds": wall, "error_vn": 0.0,  # held: v_n = 0 exactly
            "error_vt": float(np.max(np.abs(t["vt"] - t["vt_theory"]))),
            "error_r_omega": float(np.max(np.abs(t["r_omega"] - t["r_omega_theory"])))}


def _warm_up(all_cases: list[Case], root: Path) -> None:
    """One short run of each scene kind and integrator, untimed: the first run in a process
    also pays for compiling its deck template and loading LAMMPS's styles."""
    seen = set()
    for case in all_cases:
        key = (case.kind, case.model.alpha != ContactModel().alpha)
        if key in seen:
            continue
        seen.add(key)
        folder = root / "warm-up" / case.name
        if case.kind == "frozen":
            _run_frozen(case, frozen_dt(case.model, 32), folder)
        else:
            _run_collision(case, collision_dt(case.model, 32, MID), folder)


def _levels(case: Case, steps: tuple[int, ...]) -> list[tuple[int, bool]]:
    """(n, at the scene's default dt) for the ladder plus the scene's default resolution."""
    default = FROZEN_STEPS_PER_HALF_PERIOD if case.kind == "frozen" else COLLISION_STEPS_PER_HALF_PERIOD
    levels = {n: n == default for n in steps}
    levels[default] = True
    return sorted(levels.items())


def _run_case(case: Case, steps: tuple[int, ...], root: Path, log, repeats: int = 1) -> list[dict]:
    rows = []
    reference = None
    if not case.exact:
        # one reference for both forms: they converge to the same answer
        folder = root / case.name / "reference"
        _, reference = _run_collision(case, collision_dt(case.model, REFERENCE_FACTOR * steps[-1], MID), folder)
    for form in case.forms:
        for n, is_default in _levels(case, steps):
            folder = root / case.name / form.replace(" ", "-") / f"n{n:06d}"
            if case.kind == "frozen":
                row = _run_frozen(case, frozen_dt(case.model, n), folder, repeats)
            else:
                row, final = _run_collision(case, collision_dt(case.model, n, form), folder, repeats=repeats)
                if reference is not None:
                    diff = np.abs(final - reference).max(axis=0)
                    row.update({f"error_{s}": float(diff[k]) for k, s in enumerate(STATE)})
            row.update(case=case.name, label=case.label, kind=case.kind, form=form, steps_per_half_period=n,
                       default_dt=is_default, in_ladder=n in steps, exact_theory=case.exact)
            row["error"] = max(row[f"error_{s}"] for s in STATE)
            rows.append(row)
    ends = [r for r in rows if r["in_ladder"] and r["steps_per_half_period"] in (steps[0], steps[-1])]
    log(f"  {case.name:<14}" + "  ".join(f"{r['form']} n={r['steps_per_half_period']}: {r['error']:.2e}"
                                         for r in ends))
    return rows


# ---------------------------------------------------------------------------
# Orders and costs
# ---------------------------------------------------------------------------

def fit_order(dt, error, levels: int = FIT_LEVELS, floor: float = ERROR_FLOOR) -> dict:
    """Slope of log(error) against log(dt) over the ``levels`` finest steps above ``floor``.

    Returns the order, the prefactor C of error ~ C dt^order, the steps fitted, and the
    local orders between successive levels (coarse to fine), which show where the
    asymptotic regime starts. Order and prefactor are nan with fewer than two usable levels.
    """
    dt = np.asarray(dt, dtype=float)
    error = np.asarray(error, dtype=float)
    if dt.shape != error.shape or dt.size == 0:
        raise ValueError("dt and error must be non-empty and of equal length")
    coarse_first = np.argsort(dt)[::-1]
    dt, error = dt[coarse_first], error[coarse_first]
    with np.errstate(divide="ignore", invalid="ignore"):
        local = np.log(error[:-1] / error[1:]) / np.log(dt[:-1] / dt[1:])
    keep = error > floor
    use_dt, use_err = dt[keep][-levels:], error[keep][-levels:]
    local = [float(x) if math.isfinite(x) else None for x in local]
    if use_dt.size < 2:
        return {"order": float("nan"), "prefactor": float("nan"), "fit_dt": use_dt.tolist(), "local_orders": local}
    slope, intercept = np.polyfit(np.log(use_dt), np.log(use_err), 1)
    return {"order": float(slope), "prefactor": float(np.exp(intercept)), "fit_dt": use_dt.tolist(),
            "local_orders": local}


def steps_for(steps, error, target: float, fit: dict, steps_of_dt) -> tuple[float, bool]:
    """LAMMPS steps that plain refinement needs for ``target``, and whether that is extrapolated.

    Inside the measured range: linear interpolation of log(error) against log(steps)
    between the two levels around the target. Outside it (finer or coarser): the fitted
    asymptotic line error = C dt^order, turned into steps by ``steps_of_dt``; without a
    usable fit, nan.
    """
    steps = np.asarray(steps, dtype=float)
    error = np.asarray(error, dtype=float)
    few_first = np.argsort(steps)
    steps, error = steps[few_first], error[few_first]
    for s0, e0, s1, e1 in zip(steps, error, steps[1:], error[1:]):
        if e1 <= target <= e0 and e1 < e0:
            x = math.log(target / e0) / math.log(e1 / e0)
            return float(s0 * (s1 / s0) ** x), False
    if not (math.isfinite(fit["order"]) and fit["order"] > 0):
        return float("nan"), True
    dt = (target / fit["prefactor"]) ** (1.0 / fit["order"])
    return float(steps_of_dt(dt)), True


def _order_of(group: pd.DataFrame, columns) -> float:
    fit = fit_order(group["dt"], group[list(columns)].max(axis=1))
    return fit["order"]


def summarise(table: pd.DataFrame, all_cases: list[Case]) -> pd.DataFrame:
    """One row per (case, form): observed order (overall and per component), error at the
    scene's default dt, and the steps plain refinement needs for each of TARGETS."""
    by_name = {c.name: c for c in all_cases}
    rows = []
    for (name, form), group in table.groupby(["case", "form"], sort=False):
        case = by_name[name]
        ladder_rows = group[group["in_ladder"]]
        fit = fit_order(ladder_rows["dt"], ladder_rows["error"])
        default = group[group["default_dt"]].iloc[0]
        row = {"case": name, "label": case.label, "kind": case.kind, "form": form,
               "observed_order": fit["order"], "prefactor": fit["prefactor"],
               "expected_order": case.expected_edge if form == EDGE else case.expected,
               "order_vn": _order_of(ladder_rows, ["error_vn"]),
               "order_tangential": _order_of(ladder_rows, ["error_vt", "error_r_omega"]),
               "local_orders": fit["local_orders"], "fit_dt": fit["fit_dt"],
               "default_dt": float(default["dt"]), "default_lammps_steps": int(default["lammps_steps"]),
               "error_at_default_dt": float(default["error"]),
               "finest_error": float(ladder_rows["error"].iloc[-1]),
               "exact_theory": case.exact}
        for target in TARGETS:
            steps, extrapolated = steps_for(ladder_rows["lammps_steps"], ladder_rows["error"], target, fit,
                                            _steps_of_dt(case))
            row[f"steps_{target:.0e}"] = steps
            row[f"extrapolated_{target:.0e}"] = extrapolated
        rows.append(row)
    return pd.DataFrame(rows)


def _default_costs(case: Case, summary: pd.DataFrame, root: Path, batch_size: int, log,
                   repeats: int = 1) -> list[dict]:
    """At the defaults, for each target: run at the steps plain refinement needs, and measure
    the error reached (over the case's states), the cost of one collision alone and the cost
    per collision in a batch of ``batch_size`` states drawn from the sweep's box.

    The single collision is the case's worst state at the default dt, so "alone" is one
    LAMMPS run that itself reaches the target.
    """
    row = summary[(summary["case"] == case.name) & (summary["form"] == MID)].iloc[0]
    batch = _box_sample(batch_size, seed=0)
    probe_dt = collision_dt(case.model, COLLISION_STEPS_PER_HALF_PERIOD, MID)
    _, final = _run_collision(case, probe_dt, root / "cost" / "probe")
    worst = int(np.argmax(np.abs(final - _collision_scene(case, probe_dt).predicted()).max(axis=1)))
    rate_tau = case.model.fastest_rate(frozen=False) * case.model.tau / math.pi
    out = []
    for target in TARGETS:
        steps = float(row[f"steps_{target:.0e}"])
        # a run of dt = tau/(M + 1/2) takes M + 2 steps: round M up, so the target is met
        m = max(1, math.ceil(steps - 2.0 - 1e-6))
        dt = case.model.tau / (m + 0.5)
        folder = root / "cost" / f"{target:.0e}"
        states, _ = _run_collision(case, dt, folder / "states")
        single, _ = _run_collision(case, dt, folder / "single", states=[case.states[worst]], repeats=repeats)
        many, _ = _run_collision(case, dt, folder / "batch", states=batch, repeats=repeats)
        entry = {"target": target, "steps_needed": steps, "extrapolated": bool(row[f"extrapolated_{target:.0e}"]),
                 "dt": dt, "lammps_steps": states["lammps_steps"], "steps_per_half_period": (m + 0.5) / rate_tau,
                 "error_reached": max(states[f"error_{s}"] for s in STATE),
                 "single_state": list(case.states[worst]), "single_error": max(single[f"error_{s}"] for s in STATE),
                 "single_wall_seconds": single["wall_seconds"], "single_lammps_seconds": single["lammps_seconds"],
                 "single_loop_seconds": single["loop_seconds"],
                 "batch_spheres": batch_size, "batch_error": max(many[f"error_{s}"] for s in STATE),
                 "batch_wall_seconds": many["wall_seconds"], "batch_loop_seconds": many["loop_seconds"],
                 "per_collision_wall_seconds": many["wall_seconds"] / batch_size,
                 "per_collision_loop_seconds": many["loop_seconds"] / batch_size}
        out.append(entry)
        log(f"  {target:.0e}: {entry['lammps_steps']} steps, error {entry['error_reached']:.2e}; "
            f"one alone {entry['single_wall_seconds']:.3g} s, in a batch of {batch_size} "
            f"{entry['per_collision_wall_seconds']:.3g} s each")
    return out


# ---------------------------------------------------------------------------
# The study
# ---------------------------------------------------------------------------

@dataclass
class Study:
    """The measured ladder (``table``, one row per run), its ``summary`` (one row per case
    and form), the measured costs at the defaults, the cases and the provenance."""

    table: pd.DataFrame
    summary: pd.DataFrame
    costs: list[dict]
    cases: list[Case]
    metadata: dict


def run_study(quick: bool = False, runs: Path | None = None, log=print) -> Study:
    """Run every case's ladder (``quick``: five levels) and measure the costs at the defaults.

    LAMMPS runs go to ``runs`` (kept) or to a temporary folder (removed afterwards). Runs
    are sequential in this process, so the seconds are one core's.
    """
    from ..lammps.runner import lammps_version

    started = time.perf_counter()
    steps = ladder(quick)
    all_cases = cases()
    root = Path(runs) if runs is not None else Path(tempfile.mkdtemp(prefix="spinbounce-accuracy-"))
    root.mkdir(parents=True, exist_ok=True)
    version = lammps_version()  # load LAMMPS once, outside every timing
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else None
    rows = []
    try:
        with warnings.catch_warnings():
            # the coarse levels are coarse on purpose; their warnings would drown the log
            warnings.simplefilter("ignore", PhysicsWarning)
            log(f"accuracy study: {len(all_cases)} cases, n = {steps[0]} .. {steps[-1]} steps per half-period")
            _warm_up(all_cases, root)
            for case in all_cases:
                rows.extend(_run_case(case, steps, root, log, TIMING_REPEATS[quick]))
            table = pd.DataFrame(rows)
            summary = summarise(table, all_cases)
            log("cost at the defaults:")
            costs = _default_costs(all_cases[0], summary, root, COST_BATCH[quick], log, TIMING_REPEATS[quick])
    finally:
        if runs is None:
            shutil.rmtree(root, ignore_errors=True)
    metadata = {
        "study": "accuracy",
        "title": "LAMMPS against the exact theory: error against dt and cost",
        "spinbounce_version": __version__,
        "lammps_version": version,
        "python": platform.python_version(),
        "numpy_version": np.__version__,
        "pandas_version": pd.__version__,
        "machine": {"platform": platform.platform(), "cpus": os.cpu_count(), "load_average_at_start": load},
        "created": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "quick": quick,
        "parameters": {
            "ladder_steps_per_half_period": list(steps),
            "forms": {MID: "dt = tau/(M + 1/2)", EDGE: "dt = tau/M",
                      FROZEN: "dt = t_end/ceil(t_end n sqrt(Q)/pi)"},
            "fit_levels": FIT_LEVELS,
            "error_floor": ERROR_FLOOR,
            "targets": list(TARGETS),
            "cost_batch_spheres": COST_BATCH[quick],
            "timing_repeats": TIMING_REPEATS[quick],
            "reference_factor": REFERENCE_FACTOR,
            "frozen": {"z": FROZEN_Z, "t_end": FROZEN_T_END},
            "box": {"v_n": list(BOX[0]), "v_t": list(BOX[1]), "r_omega": list(BOX[2])},
            "collision_default_steps_per_half_period": COLLISION_STEPS_PER_HALF_PERIOD,
            "frozen_default_steps_per_half_period": FROZEN_STEPS_PER_HALF_PERIOD,
        },
        "error": "largest |LAMMPS - exact theory| over the case's states and over v_n, v_t and r omega "
                 "(frozen: over the time series); the Coulomb case against a finer run",
        "runs": str(root) if runs is not None else None,
        "study_seconds": time.perf_counter() - started,
    }
    return Study(table, summary, costs, all_cases, metadata)


# ---------------------------------------------------------------------------
# Outputs: figure, JSON, markdown
# ---------------------------------------------------------------------------

def _records(frame: pd.DataFrame) -> list[dict]:
    return [json_ready(r) for r in frame.to_dict(orient="records")]


#: Cases whose end-on-a-step curve the figure shows (dashed): first order, and the two third-order ones.
EDGE_SHOWN = ("defaults", "magic", "head_on")


def draw(study: Study):
    """Error against LAMMPS steps and against wall seconds: one curve per case (the contact
    ending mid-step), plus dashed end-on-a-step curves for EDGE_SHOWN; the legend gives each
    curve's observed order. Call inside ``matplotlib.style.context(STYLE)``."""
    import matplotlib

    from ..figures.core import new_figure

    fig, axes = new_figure(1, 2, figsize=(11.5, 5.8), sharey=True)
    ax_steps, ax_wall = axes[0]
    colours = list(matplotlib.colormaps["tab10"].colors) + ["black", "navy", "darkgoldenrod", "teal"]
    markers = "osD^v<>phH*Xd8P"
    table = study.table
    orders = {(r["case"], r["form"]): r["observed_order"] for r in study.summary.to_dict(orient="records")}

    def curve(name, form):
        return table[(table["case"] == name) & (table["form"] == form) & table["in_ladder"]
                     & (table["error"] > ERROR_FLOOR)]

    # cases whose curve lies on the first case's (the same v_n error sets both) would hide it:
    # the first case is drawn wide and underneath, and the legend names the ones on top of it
    first = study.cases[0]
    base = curve(first.name, MID)["error"].to_numpy()
    same = [c.label for c in study.cases[1:] if c.kind == first.kind and c.exact
            and np.array_equal(curve(c.name, MID)["lammps_steps"], curve(first.name, MID)["lammps_steps"])
            and np.allclose(curve(c.name, MID)["error"], base, rtol=1e-6, atol=0.0)]
    for k, case in enumerate(study.cases):
        colour = "0.45" if not case.exact else colours[k % len(colours)]
        for form in case.forms:
            edge = form == EDGE
            if edge and case.name not in EDGE_SHOWN:
                continue
            rows = curve(case.name, form)
            label = f"{case.label}{', end on a step' if edge else ''}: order {orders[(case.name, form)]:.2f}"
            style = {"color": colour, "marker": markers[k % len(markers)], "markersize": 3.5,
                     "linestyle": "--" if edge else (":" if not case.exact else "-"),
                     "linewidth": 1.0 if edge else 1.3, "markerfacecolor": "none" if edge else colour}
            if case is first and not edge and same:
                label += f" (wide; under {', '.join(same)})"
                style.update(linewidth=5.0, alpha=0.35, zorder=1, markersize=0)
            ax_steps.loglog(rows["lammps_steps"], rows["error"], label=label, **style)
            ax_wall.loglog(rows["wall_seconds"], rows["error"], **style)
    for target in TARGETS:
        for ax in (ax_steps, ax_wall):
            ax.axhline(target, color="0.8", linewidth=0.7, zorder=0)
    ax_steps.set_xlabel("LAMMPS steps per run")
    ax_steps.set_ylabel("largest |LAMMPS $-$ exact theory|")
    ax_wall.set_xlabel("wall seconds per run (one LAMMPS instance, 1 to 32 spheres)")
    ax_steps.set_ylim(ERROR_FLOOR / 2, 0.3)
    ax_steps.set_title("error against steps (solid: the contact ends mid-step; dashed: on a step)")
    ax_wall.set_title("error against wall time (start-up dominates below ~10$^4$ steps)")
    handles, labels = ax_steps.get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=7.5)
    return fig


def _fmt_steps(steps: float, extrapolated: bool) -> str:
    if not math.isfinite(steps):
        return "n/a"
    text = f"{steps:.1e}".replace("e+0", "e") if steps >= 1e5 else f"{math.ceil(steps):,}"
    return f"{text}*" if extrapolated else text


def _fmt_order(order) -> str:
    return "-" if order is None or not math.isfinite(order) else f"{order:.2f}"


def _cell(text: str) -> str:
    """Text for a markdown table cell: a bare | would end the cell."""
    return text.replace("|", r"\|")


def markdown(study: Study) -> str:
    """ACCURACY.md: the orders and steps per case, the defaults' costs, and what limits each order."""
    s = study.summary
    meta = study.metadata
    by_name = {c.name: c for c in study.cases}
    steps = meta["parameters"]["ladder_steps_per_half_period"]
    lines = [
        "# Speed against accuracy",
        "",
        (f"Regenerated by `spinbounce accuracy{' --quick' if meta['quick'] else ''}` "
        f"(spinbounce {meta['spinbounce_version']}, LAMMPS {meta['lammps_version']}, {meta['created']}); "
        "figure `accuracy.png`, every run in `accuracy.json`."),
        "",
        (f"Each case runs a ladder of n = {steps[0]} to {steps[-1]} steps per half-period of its fastest "
        "contact mode. Error: the largest |LAMMPS - exact theory| over the case's states and over v_n, v_t "
        "and r omega (frozen: over the whole time series). Collisions run with the contact's end in the "
        "middle of a step (dt = tau/(M + 1/2), the default form) and on a step boundary (dt = tau/M). "
        f"Observed order: the slope of log error against log dt over the {FIT_LEVELS} finest levels with an "
        f"error above {ERROR_FLOOR:g}; in brackets the same for v_n alone and for v_t and r omega. Steps "
        "for a target: interpolated on the measured log-log curve, or (marked *) extrapolated along the "
        "fitted line beyond the measured range. Steps are per run: a collision's whole contact, a frozen "
        f"contact's {FROZEN_T_END:g} time units."),
        "",
        ("| case | order, mid-step end (v_n; v_t, r omega) | order, end on a step (v_n; v_t, r omega) "
        "| expected (mid-step, on a step) | error at the default dt | steps for 1e-4 | 1e-6 | 1e-8 "
        "| end on a step: steps for 1e-4 |"),
        "|---|---|---|---|---|---|---|---|---|",
    ]

    def orders(r):
        return (f"**{_fmt_order(r['observed_order'])}** ({_fmt_order(r['order_vn'])}; "
                f"{_fmt_order(r['order_tangential'])})")

    for name, group in s.groupby("case", sort=False):
        case = by_name[name]
        main = group[group["form"] != EDGE].iloc[0]
        edge = group[group["form"] == EDGE]
        edge = edge.iloc[0] if len(edge) else None
        expected = f"{main['expected_order']:g}" + ("" if edge is None else f", {edge['expected_order']:g}")
        cells = [
            _cell(case.label) + ("" if case.exact else " †"),
            orders(main) + (" (frozen)" if edge is None else ""),
            "" if edge is None else orders(edge),
            expected,
            f"{main['error_at_default_dt']:.2e}",
            *(_fmt_steps(main[f"steps_{t:.0e}"], main[f"extrapolated_{t:.0e}"]) for t in TARGETS),
            "" if edge is None else _fmt_steps(edge["steps_1e-04"], edge["extrapolated_1e-04"]),
        ]
        lines.append("| " + " | ".join(cells) + " |")
    lines += [
        "",
        ("Frozen contacts have one form (no contact end) and hold v_n = 0. "
        f"† No exact theory: errors against a run {REFERENCE_FACTOR} times finer than the ladder's finest."),
        "",
        "## Cost at the paper's defaults",
        "",
        ("Runs at the steps the table gives (mid-step end), measured again: the error reached over the "
        "8 corners of the sweep's box; one collision alone (the worst corner, in a LAMMPS instance of its "
        "own, start-up included); and one collision's share of a batch of "
        f"{meta['parameters']['cost_batch_spheres']} states drawn from the box. Wall seconds on one core "
        "of a shared machine; LAMMPS's own loop time in brackets."),
        "",
        ("| target | LAMMPS steps | n per half-period | error reached | one collision alone, s "
        "| per collision in a batch, s |"),
        "|---|---|---|---|---|---|",
    ]
    for c in study.costs:
        lines.append(
            f"| {c['target']:.0e}{'*' if c['extrapolated'] else ''} | {c['lammps_steps']:,} | "
            f"{c['steps_per_half_period']:.1f} | {c['error_reached']:.2e} | {c['single_wall_seconds']:.2g} "
            f"({c['single_loop_seconds']:.2g}) | {c['per_collision_wall_seconds']:.2g} "
            f"({c['per_collision_loop_seconds']:.2g}) |"
        )
    d = s[(s["case"] == study.cases[0].name) & (s["form"] == MID)].iloc[0]
    lines += [
        "",
        (f"The default step (n = {COLLISION_STEPS_PER_HALF_PERIOD}, {d['default_lammps_steps']} steps) gives "
        f"{d['error_at_default_dt']:.2e}."),
        "",
        "## What limits the order",
        "",
        "Mechanisms:",
        "",
        *(f"- **{name}**: {text}." for name, text in MECHANISMS.items()),
        "",
        "Per case:",
        "",
        *(f"- **{case.label}** ({case.why}): {case.limit}." for case in study.cases),
        "",
        ("Why a few states per case: without a Coulomb cap the contact is linear and its end does not "
        "depend on the state, so LAMMPS's map, like the exact one, is linear in (v_n, v_t, r omega); the "
        "error's largest value over the sweep's box sits at one of its 8 corners, and grazing, head-on and "
        "high-spin incidence probe single columns of that linear error."),
        "",
    ]
    return "\n".join(lines)


def write_study(study: Study, out: Path) -> dict[str, Path]:
    """Write accuracy.png, accuracy.pdf, accuracy.json and ACCURACY.md into ``out``, each atomically."""
    import matplotlib.style

    from ..figures.core import STYLE, save

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    record = dict(study.metadata)
    record["cases"] = [c.record() for c in study.cases]
    record["summary"] = _records(study.summary)
    record["default_costs"] = json_ready(study.costs)
    record["runs_table"] = _records(study.table)
    record["markdown"] = "ACCURACY.md"
    with matplotlib.style.context(STYLE):
        fig = draw(study)
        saved = save(fig, out, "accuracy", json_ready(record))
    md = out / "ACCURACY.md"
    write_atomic(md, markdown(study))
    return {"png": saved.png, "pdf": saved.pdf, "json": saved.json, "markdown": md}


def make_accuracy(out: Path, quick: bool = False, runs: Path | None = None, log=print) -> tuple[Study, dict]:
    """Run the study and write its files: what ``spinbounce accuracy`` does."""
    study = run_study(quick=quick, runs=runs, log=log)
    return study, write_study(study, out)
