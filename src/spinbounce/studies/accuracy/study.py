"""The whole study: every case's ladder and default step, the summary, the costs, provenance.

The scenes' default step follows from a target accuracy (:mod:`spinbounce.model.timestep`,
:mod:`spinbounce.stepping`): :func:`policy_table` says what it costs and whether it delivers, case
by case; :func:`default_step_table` runs only the defaults (what ``spinbounce bench`` prints per model).
"""

from __future__ import annotations

import math
import os
import platform
import shutil
import tempfile
import time
import warnings
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ...errors import PhysicsWarning
from ...model.timestep import ACCURACY, FROZEN_ACCURACY, SAFETY, mid_step_dt
from ...records import software
from .cases import ANY, BOX, EDGE, FROZEN, FROZEN_T_END, FROZEN_Z, MID, Case, box_sample, cases
from .measure import (
    DEFAULT_FORMS,
    collision_scene,
    default_target,
    labelled_row,
    ladder,
    run_case,
    run_collision_level,
    run_default,
    warm_up,
)
from .orders import ERROR_FLOOR, FIT_LEVELS, TARGETS, summarise

__all__ = ["Study", "run_study", "default_costs", "COST_BATCH", "TIMING_REPEATS", "POLICY_COLUMNS",
           "policy_table", "default_step_table"]

#: Spheres in the batch that measures the cost per collision of a sweep-like run.
COST_BATCH = {False: 1000, True: 100}
#: Each run is timed this many times (the least counts): full study, quick study.
TIMING_REPEATS = {False: 2, True: 1}
#: The default-step table's columns: what the default chose (step_method: the rule, the probe,
#: a Hertzian batch's fixed resolution or the frozen rule), the steps of one run at it (a
#: collision's whole contact; a frozen contact's 10 time units), and the error it reached: the
#: largest |LAMMPS - theory| over the size of the initial state (the target's own measure), and
#: the same without that division (the study's ladder measure).
POLICY_COLUMNS = ("case", "label", "kind", "form", "step_method", "steps_per_collision", "steps_per_half_period",
                  "dt", "error_reached", "target", "within_target", "absolute_error", "worst_status", "estimate")


@dataclass
class Study:
    """The measured ladder (``table``, one row per run), its ``summary`` (one row per case
    and form), the default step of each case (``defaults``: :func:`policy_table`),
    the measured costs at the paper's parameters, the cases and the provenance."""

    table: pd.DataFrame
    summary: pd.DataFrame
    defaults: pd.DataFrame
    costs: list[dict]
    cases: list[Case]
    metadata: dict


@contextmanager
def _runs_folder(runs: Path | None, prefix: str):
    """``runs`` (kept), or a temporary folder removed afterwards."""
    root = Path(runs) if runs is not None else Path(tempfile.mkdtemp(prefix=prefix))
    root.mkdir(parents=True, exist_ok=True)
    try:
        yield root
    finally:
        if runs is None:
            shutil.rmtree(root, ignore_errors=True)


def policy_table(table: pd.DataFrame) -> pd.DataFrame:
    """The rows of a study's run table taken at the default step, as :data:`POLICY_COLUMNS`."""
    rows = table[table["default_dt"]]
    out = pd.DataFrame({
        "case": rows["case"], "label": rows["label"], "kind": rows["kind"], "form": rows["form"],
        "step_method": rows["step_method"], "steps_per_collision": rows["lammps_steps"].astype(int),
        "steps_per_half_period": rows["resolution"], "dt": rows["dt"], "error_reached": rows["relative_error"],
        "target": rows["target"], "within_target": rows["relative_error"] <= rows["target"],
        "absolute_error": rows["error"], "worst_status": rows["worst_status"],
        # an extrapolated default's own error estimate (over the state's size, the largest over its rows);
        # NaN for one run
        "estimate": rows["estimate"] if "estimate" in rows else np.nan})
    return out.reset_index(drop=True)[list(POLICY_COLUMNS)]


def default_step_table(names: list[str] | None = None, runs: Path | None = None,
                       log=lambda *_: None) -> pd.DataFrame:
    """Run each case of the study (or those ``names``) once at its default step: the table
    (:data:`POLICY_COLUMNS`, one row per case and default form) of the steps per collision
    the default chooses, the error it reaches and its target.

    LAMMPS runs go to ``runs`` (kept) or a temporary folder (removed). At the study's cases
    this is a few seconds of LAMMPS, most of it the Hertzian batch and the damped frozen
    contact, whose defaults are the finest.
    """
    all_cases = cases()
    known = {c.name for c in all_cases}
    unknown = sorted(set(names or ()) - known)
    if unknown:
        raise ValueError(f"unknown case(s) {', '.join(unknown)}: the study's cases are {', '.join(sorted(known))}")
    rows = []
    with _runs_folder(runs, "spinbounce-defaults-") as root:
        for case in (c for c in all_cases if names is None or c.name in names):
            for form in (f for f in case.forms if f in DEFAULT_FORMS):
                folder = root / case.name / form.replace(" ", "-")
                row = labelled_row(run_default(case, form, folder), case, form)
                log(f"  {case.name:<14}{form:<15}{row['lammps_steps']:>9} steps  error "
                    f"{row['relative_error']:.2e} (target {row['target']:g}, {row['step_method']})")
                rows.append(row)
    return policy_table(pd.DataFrame(rows))


def _largest_error(row: dict) -> float:
    return max(v for k, v in row.items() if k.startswith("error_"))


def _cost_at(case: Case, dt: float | None, folder: Path, batch: np.ndarray, worst: int, repeats: int) -> dict:
    """At step ``dt`` (None: the default step): the error reached over the case's states, and
    the cost of its worst state alone and of one collision in a batch of ``batch`` states."""
    states, _ = run_collision_level(case, dt, folder / "states")
    single, _ = run_collision_level(case, dt, folder / "single", states=[case.states[worst]], repeats=repeats)
    many, _ = run_collision_level(case, dt, folder / "batch", states=batch, repeats=repeats)
    return {"dt": states["dt"], "lammps_steps": states["lammps_steps"], "steps_per_half_period": states["resolution"],
            "error_reached": _largest_error(states), "relative_error_reached": states["relative_error"],
            "single_state": list(case.states[worst]), "single_error": _largest_error(single),
            "single_wall_seconds": single["wall_seconds"], "single_lammps_seconds": single["lammps_seconds"],
            "single_loop_seconds": single["loop_seconds"],
            "batch_spheres": len(batch), "batch_error": _largest_error(many),
            "batch_relative_error": many["relative_error"],
            "batch_wall_seconds": many["wall_seconds"], "batch_loop_seconds": many["loop_seconds"],
            "per_collision_wall_seconds": many["wall_seconds"] / len(batch),
            "per_collision_loop_seconds": many["loop_seconds"] / len(batch)}


def default_costs(case: Case, summary: pd.DataFrame, root: Path, batch_size: int, log,
                  repeats: int = 1) -> list[dict]:
    """At the case's parameters: first the default step (``step`` "default", its own target),
    then for each of TARGETS the steps plain refinement needs (``step`` "for the target"),
    each measured (:func:`_cost_at`): the error reached over the case's states, the cost of
    one collision alone and the cost per collision in a batch of ``batch_size`` states drawn
    from the sweep's box.

    The single collision is the case's worst state at the default step, so "alone" is one
    LAMMPS run that itself reaches the target.
    """
    row = summary[(summary["case"] == case.name) & (summary["form"] == MID)].iloc[0]
    batch = box_sample(batch_size, seed=0)
    # the case's state with the largest error at the default step
    probe, final = run_collision_level(case, None, root / "cost" / "probe")
    worst = int(np.argmax(np.abs(final - collision_scene(case, probe["dt"]).predicted()).max(axis=1)))
    out = [{"step": "default", "target": default_target(case), "steps_needed": float("nan"), "extrapolated": False,
            **_cost_at(case, None, root / "cost" / "default", batch, worst, repeats)}]
    for target in TARGETS:
        steps = float(row[f"steps_{target:.0e}"])
        # a run of dt = tau/(M + 1/2) takes M + 2 steps (timestep.steps_through): round M up
        dt = mid_step_dt(case.model.tau, max(1, math.ceil(steps - 2.0 - 1e-6)))
        out.append({"step": "for the target", "target": target, "steps_needed": steps,
                    "extrapolated": bool(row[f"extrapolated_{target:.0e}"]),
                    **_cost_at(case, dt, root / "cost" / f"{target:.0e}", batch, worst, repeats)})
    for entry in out:
        log(f"  {entry['step']}, {entry['target']:.0e}: {entry['lammps_steps']} steps, error "
            f"{entry['error_reached']:.2e} ({entry['relative_error_reached']:.2e} of the state); one alone "
            f"{entry['single_wall_seconds']:.3g} s, in a batch of {batch_size} "
            f"{entry['per_collision_wall_seconds']:.3g} s each")
    return out


def _parameters(quick: bool, steps: tuple[int, ...]) -> dict:
    return {
        "ladder_steps_per_half_period": list(steps),
        "forms": {MID: "dt = t_end/(M + 1/2) (model.timestep.mid_step_dt; Hertz: each speed's own t_end)",
                  EDGE: "dt = tau/M", ANY: "dt = pi/(n w), w the fastest mode at the largest |v_n|",
                  FROZEN: "dt = t_end/ceil(t_end n w/pi)"},
        "fit_levels": FIT_LEVELS,
        "error_floor": ERROR_FLOOR,
        "targets": list(TARGETS),
        "cost_batch_spheres": COST_BATCH[quick],
        "timing_repeats": TIMING_REPEATS[quick],
        "frozen": {"z": FROZEN_Z, "t_end": FROZEN_T_END},
        "box": {"v_n": list(BOX[0]), "v_t": list(BOX[1]), "r_omega": list(BOX[2])},
        "default_step": ("the scenes' own (dt = None): model.timestep's second-order rule for the paper's linear "
                         "contact, a probe against the exact theory otherwise (stepping.tune), "
                         "a Hertzian batch of several speeds time-scaled and probed (Collision.time_scales; "
                         "HERTZ_STEPS_PER_HALF_PERIOD with a dashpot), Frozen.default_dt"),
        "accuracy": ACCURACY, "frozen_accuracy": FROZEN_ACCURACY, "safety": SAFETY,
    }


def run_study(quick: bool = False, runs: Path | None = None, log=print) -> Study:
    """Run every case's ladder (``quick``: five levels) and its default step, and measure the
    costs at the paper's parameters (the first case).

    LAMMPS runs go to ``runs`` (kept) or to a temporary folder (removed afterwards). Runs
    are sequential in this process, so the seconds are one core's.
    """
    started = time.perf_counter()
    steps = ladder(quick)
    all_cases = cases()
    provenance = software()  # asks LAMMPS for its version: loads it once, outside every timing
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else None
    with _runs_folder(runs, "spinbounce-accuracy-") as root, warnings.catch_warnings():
        # the coarse levels are coarse on purpose; their warnings would drown the log
        warnings.simplefilter("ignore", PhysicsWarning)
        log(f"accuracy study: {len(all_cases)} cases, n = {steps[0]} .. {steps[-1]} steps per half-period")
        warm_up(all_cases, root)
        table = pd.DataFrame([row for case in all_cases
                              for row in run_case(case, steps, root, log, TIMING_REPEATS[quick])])
        summary = summarise(table, all_cases)
        log("cost at the paper's parameters:")
        costs = default_costs(all_cases[0], summary, root, COST_BATCH[quick], log, TIMING_REPEATS[quick])
    metadata = {
        "study": "accuracy",
        "title": "LAMMPS against theory: error against dt and cost",
        **provenance,
        "machine": {"platform": platform.platform(), "cpus": os.cpu_count(), "load_average_at_start": load},
        "quick": quick,
        "parameters": _parameters(quick, steps),
        "error": "largest |LAMMPS - theory| over the case's states and state columns (frozen: over the "
                 "time series); theory: each case's own (Eq. 18, Eq. 10, exact.hertz, the Coulomb oracle)",
        "runs": str(Path(runs)) if runs is not None else None,
        "study_seconds": time.perf_counter() - started,
    }
    return Study(table, summary, policy_table(table), costs, all_cases, metadata)
