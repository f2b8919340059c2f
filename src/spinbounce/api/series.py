"""The frozen contact from Python: ``frozen`` and its report."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..exact import choose
from ..records import run_folder
from .collisions import model

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["frozen", "FrozenReport", "FROZEN_COLUMNS", "FROZEN_SERIES"]

#: A frozen contact's time series: LAMMPS beside Eq. 10, one row per dumped step.
FROZEN_COLUMNS = ["t", "v_t", "omega", "r_omega", "v_t_theory", "r_omega_theory"]
#: The time series a frozen run writes into its folder.
FROZEN_SERIES = "frozen.csv"


@dataclass(frozen=True)
class FrozenReport:
    """A frozen contact in LAMMPS (or, with a tolerance, extrapolated from several runs) beside
    Eq. 10: ``table`` (the series, also written to ``csv``) and ``record`` (its provenance and
    accuracy, also written to ``record_path``)."""

    table: pd.DataFrame
    record: dict
    csv: Path
    record_path: Path


def frozen(z: float = 0.1, v_t: float = 1.0, omega: float = 0.0, t_end: float = 10.0, *, dt: float | None = None,
           every: int | None = None, tolerance: float | None = None, out: str | Path | None = None,
           force: bool = False, log=None, **model_parameters) -> FrozenReport:
    """Hold one sphere in contact at height ``z`` (v_n = 0) for ``t_end`` and set v_t(t) and
    omega(t) beside Eq. 10 (its exact damped form with gamma_t; with mu, the stick-slip under the
    constant cap, :mod:`spinbounce.exact.frozen_capped`). ``tolerance``: an accuracy to reach
    instead of a step (Richardson extrapolation over halving steps; with a cap, the error measured
    at halving steps). ``out``: the run folder
    (deck, dump, log, ``frozen.csv`` and the record). ``log(line)``: told about long runs and the
    extrapolation's progress. A named ``out`` holding an earlier run is refused unless ``force``."""
    from ..model.timestep import cost_notice
    from ..pipeline import run_series, series_record
    from ..records import check_run_folder, to_json, write_atomic
    from ..model.timestep import FROZEN_ACCURACY
    from ..scenes.frozen import Frozen

    check_run_folder(out, force)
    contact = model(**model_parameters)
    scene = Frozen(contact, z=z, v_t=v_t, omega=omega, t_end=t_end, dt=dt, every=every)  # checked before any run
    if tolerance is None and dt is None and scene.first_order_by_default:
        tolerance = FROZEN_ACCURACY  # no rule reaches the default accuracy: it is measured, as a tolerance is
    if tolerance is not None:
        table, record, folder = _frozen_to_tolerance(scene, tolerance, out, log)
    else:
        notice = cost_notice(scene.nsteps)
        if log is not None and notice:
            log(notice)
        folder = Path(out) if out is not None else run_folder(
            "frozen", {"model": scene.model.as_record(), "z": scene.z, "v_t": scene.v_t, "omega": scene.omega,
                       "nsteps": scene.nsteps, "dt": scene.dt, "every": scene.every})
        result = run_series(scene, folder)
        record = {**series_record(result), "rows": len(result.table),
                  "lammps_version": result.info.lammps_version}
        table = result.table[FROZEN_COLUMNS]
    csv = folder / FROZEN_SERIES
    write_atomic(csv, table.to_csv(index=False, float_format="%.17g"))
    record["csv"] = str(csv)
    record_path = folder / ("tolerance.json" if tolerance is not None else "result.json")
    write_atomic(record_path, to_json(record))
    return FrozenReport(table, record, csv, record_path)


#: Halvings of the step a capped frozen contact's measured route tries (its error is first order).
MEASURED_HALVINGS = 12


def _frozen_to_tolerance(scene, tolerance: float, out, log) -> tuple[pd.DataFrame, dict, Path]:
    import pandas as pd

    from ..extrapolation import frozen_to_tolerance, smooth_in_dt
    from ..records import software

    m = scene.model
    folder = Path(out) if out is not None else run_folder(
        "frozen", {"model": m.as_record(), "z": scene.z, "v_t": scene.v_t, "omega": scene.omega,
                   "t_end": scene.t_end, "tolerance": tolerance})
    if not smooth_in_dt(m):
        return _frozen_measured(scene, tolerance, folder, log or (lambda *_: None))
    result = frozen_to_tolerance(m, scene.z, scene.v_t, scene.omega, scene.t_end, tolerance, folder,
                                 log=log or (lambda *_: None))
    v_t_theory, rw_theory = choose.frozen(m, result.t, scene.v_t, scene.omega * m.r, scene.z)
    table = pd.DataFrame({"t": result.t, "v_t": result.values[:, 0], "omega": result.values[:, 1] / m.r,
                          "r_omega": result.values[:, 1], "v_t_theory": v_t_theory, "r_omega_theory": rw_theory,
                          "estimate": result.estimate[:, 0]})
    error = float(max(np.abs(table["v_t"] - v_t_theory).max(), np.abs(table["r_omega"] - rw_theory).max()))
    record = {"scene": "frozen", "model": m.as_record(), "z": scene.z, "v_t": scene.v_t, "omega": scene.omega,
              "t_end": scene.t_end, "tolerance": result.tolerance, "estimate": result.max_estimate,
              "max_abs_error": error, "steps": result.steps, "rows": len(table),
              "plain_steps_for_same_estimate": result.plain_steps_for(result.max_estimate),
              "levels": result.levels, **software()}
    return table, record, folder


def _frozen_measured(scene, tolerance: float, folder: Path, log) -> tuple[pd.DataFrame, dict, Path]:
    """A frozen contact whose error is not smooth in dt (a cap's stick-slip switches): runs at halving
    steps until its largest |LAMMPS - theory| (exact: :mod:`spinbounce.exact.frozen_capped`) is at most
    ``tolerance``; that measured error is its estimate."""
    from ..extrapolation import check_tolerance
    from ..pipeline import ResultError, run_series
    from ..records import software
    from ..scenes.frozen import Frozen

    tolerance, levels = check_tolerance(tolerance), []
    for k in range(MEASURED_HALVINGS):
        level = Frozen(scene.model, z=scene.z, v_t=scene.v_t, omega=scene.omega, t_end=scene.t_end,
                       dt=scene.dt / 2**k)
        result = run_series(level, folder / f"level-{k}")
        levels.append({"level": k, "dt": level.dt, "nsteps": level.nsteps, "run": str(folder / f"level-{k}"),
                       "max_abs_error": result.max_abs_error})
        log(f"  level {k}: {level.nsteps} steps, measured error {result.max_abs_error:.2e}")
        if result.max_abs_error <= tolerance:
            table = result.table[FROZEN_COLUMNS].assign(estimate=result.max_abs_error)
            record = {"scene": "frozen", "model": scene.model.as_record(), "z": scene.z, "v_t": scene.v_t,
                      "omega": scene.omega, "t_end": scene.t_end, "tolerance": tolerance,
                      "method": "measured: the error against the exact capped theory, at halving steps (a cap's "
                                "switches leave no smooth expansion in dt to extrapolate)",
                      "estimate": result.max_abs_error, "max_abs_error": result.max_abs_error,
                      "steps": sum(v["nsteps"] for v in levels), "rows": len(table),
                      "plain_steps_for_same_estimate": level.nsteps, "levels": levels, **software()}
            return table, record, folder
    raise ResultError(f"tolerance = {tolerance:g} not reached in {MEASURED_HALVINGS} halvings of dt (finest "
                      f"{levels[-1]['dt']:.3g}, error {levels[-1]['max_abs_error']:.2g}): ask for a looser tolerance")
