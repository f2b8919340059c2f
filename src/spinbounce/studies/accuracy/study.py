"""The whole study: every case's ladder, the summary, the costs at the defaults, provenance."""

from __future__ import annotations

import math
import os
import platform
import shutil
import tempfile
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ...model.scenes import COLLISION_STEPS_PER_HALF_PERIOD, FROZEN_STEPS_PER_HALF_PERIOD, PhysicsWarning
from ...model.timestep import mid_step_dt
from ...records import software
from .cases import ANY, BOX, EDGE, FROZEN, FROZEN_T_END, FROZEN_Z, MID, Case, box_sample, cases
from .measure import collision_dt, collision_scene, ladder, run_case, run_collision_level, warm_up
from .orders import ERROR_FLOOR, FIT_LEVELS, TARGETS, summarise

__all__ = ["Study", "run_study", "default_costs", "COST_BATCH", "TIMING_REPEATS"]

#: Spheres in the batch that measures the cost per collision of a sweep-like run.
COST_BATCH = {False: 1000, True: 100}
#: Each run is timed this many times (the least counts): full study, quick study.
TIMING_REPEATS = {False: 2, True: 1}


@dataclass
class Study:
    """The measured ladder (``table``, one row per run), its ``summary`` (one row per case
    and form), the measured costs at the defaults, the cases and the provenance."""

    table: pd.DataFrame
    summary: pd.DataFrame
    costs: list[dict]
    cases: list[Case]
    metadata: dict


def _worst_state(case: Case, root: Path) -> int:
    """The case's state with the largest error at the default dt."""
    probe_dt = collision_dt(case.model, COLLISION_STEPS_PER_HALF_PERIOD, MID)
    _, final = run_collision_level(case, probe_dt, root / "cost" / "probe")
    return int(np.argmax(np.abs(final - collision_scene(case, probe_dt).predicted()).max(axis=1)))


def _largest_error(row: dict) -> float:
    return max(v for k, v in row.items() if k.startswith("error_"))


def default_costs(case: Case, summary: pd.DataFrame, root: Path, batch_size: int, log,
                  repeats: int = 1) -> list[dict]:
    """At the defaults, for each target: run at the steps plain refinement needs, and measure
    the error reached (over the case's states), the cost of one collision alone and the cost
    per collision in a batch of ``batch_size`` states drawn from the sweep's box.

    The single collision is the case's worst state at the default dt, so "alone" is one
    LAMMPS run that itself reaches the target.
    """
    row = summary[(summary["case"] == case.name) & (summary["form"] == MID)].iloc[0]
    batch = box_sample(batch_size, seed=0)
    worst = _worst_state(case, root)
    rate = case.model.fastest_rate(frozen=False)
    out = []
    for target in TARGETS:
        steps = float(row[f"steps_{target:.0e}"])
        # a run of dt = tau/(M + 1/2) takes M + 2 steps (timestep.steps_through): round M up
        m = max(1, math.ceil(steps - 2.0 - 1e-6))
        dt = mid_step_dt(case.model.tau, m)
        folder = root / "cost" / f"{target:.0e}"
        states, _ = run_collision_level(case, dt, folder / "states")
        single, _ = run_collision_level(case, dt, folder / "single", states=[case.states[worst]], repeats=repeats)
        many, _ = run_collision_level(case, dt, folder / "batch", states=batch, repeats=repeats)
        entry = {"target": target, "steps_needed": steps, "extrapolated": bool(row[f"extrapolated_{target:.0e}"]),
                 "dt": dt, "lammps_steps": states["lammps_steps"], "steps_per_half_period": math.pi / (rate * dt),
                 "error_reached": _largest_error(states),
                 "single_state": list(case.states[worst]), "single_error": _largest_error(single),
                 "single_wall_seconds": single["wall_seconds"], "single_lammps_seconds": single["lammps_seconds"],
                 "single_loop_seconds": single["loop_seconds"],
                 "batch_spheres": batch_size, "batch_error": _largest_error(many),
                 "batch_wall_seconds": many["wall_seconds"], "batch_loop_seconds": many["loop_seconds"],
                 "per_collision_wall_seconds": many["wall_seconds"] / batch_size,
                 "per_collision_loop_seconds": many["loop_seconds"] / batch_size}
        out.append(entry)
        log(f"  {target:.0e}: {entry['lammps_steps']} steps, error {entry['error_reached']:.2e}; "
            f"one alone {entry['single_wall_seconds']:.3g} s, in a batch of {batch_size} "
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
        "collision_default_steps_per_half_period": COLLISION_STEPS_PER_HALF_PERIOD,
        "frozen_default_steps_per_half_period": FROZEN_STEPS_PER_HALF_PERIOD,
    }


def _measure(all_cases: list[Case], steps: tuple[int, ...], root: Path, quick: bool, log):
    """The ladders, their summary and the costs at the defaults (the first case)."""
    with warnings.catch_warnings():
        # the coarse levels are coarse on purpose; their warnings would drown the log
        warnings.simplefilter("ignore", PhysicsWarning)
        log(f"accuracy study: {len(all_cases)} cases, n = {steps[0]} .. {steps[-1]} steps per half-period")
        warm_up(all_cases, root)
        rows = []
        for case in all_cases:
            rows.extend(run_case(case, steps, root, log, TIMING_REPEATS[quick]))
        table = pd.DataFrame(rows)
        summary = summarise(table, all_cases)
        log("cost at the defaults:")
        costs = default_costs(all_cases[0], summary, root, COST_BATCH[quick], log, TIMING_REPEATS[quick])
    return table, summary, costs


def run_study(quick: bool = False, runs: Path | None = None, log=print) -> Study:
    """Run every case's ladder (``quick``: five levels) and measure the costs at the defaults.

    LAMMPS runs go to ``runs`` (kept) or to a temporary folder (removed afterwards). Runs
    are sequential in this process, so the seconds are one core's.
    """
    started = time.perf_counter()
    steps = ladder(quick)
    all_cases = cases()
    root = Path(runs) if runs is not None else Path(tempfile.mkdtemp(prefix="spinbounce-accuracy-"))
    root.mkdir(parents=True, exist_ok=True)
    provenance = software()  # asks LAMMPS for its version: loads it once, outside every timing
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else None
    try:
        table, summary, costs = _measure(all_cases, steps, root, quick, log)
    finally:
        if runs is None:
            shutil.rmtree(root, ignore_errors=True)
    metadata = {
        "study": "accuracy",
        "title": "LAMMPS against theory: error against dt and cost",
        **provenance,
        "machine": {"platform": platform.platform(), "cpus": os.cpu_count(), "load_average_at_start": load},
        "quick": quick,
        "parameters": _parameters(quick, steps),
        "error": "largest |LAMMPS - theory| over the case's states and state columns (frozen: over the "
                 "time series); theory: each case's own (Eq. 18, Eq. 10, theory.hertz, the Coulomb oracle)",
        "runs": str(root) if runs is not None else None,
        "study_seconds": time.perf_counter() - started,
    }
    return Study(table, summary, costs, all_cases, metadata)
