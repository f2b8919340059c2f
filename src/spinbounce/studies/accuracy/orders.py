"""From a ladder of runs to the observed order of convergence and the steps a target needs."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .cases import Case
from .measure import steps_of_dt

__all__ = ["FIT_LEVELS", "ERROR_FLOOR", "TARGETS", "fit_order", "steps_for", "summarise"]

#: The order is fitted over this many of the finest levels (a factor 8 in dt).
FIT_LEVELS = 4
#: Errors below this are not truncation: round-off, the 1e-12 normal dashpot that carries a
#: tangential one in LAMMPS (laws.damping.velocity.VANISHING_ETA_N), the oracle's own error. Left out of fits.
ERROR_FLOOR = 1e-11
#: The accuracies whose cost the study reports.
TARGETS = (1e-4, 1e-6, 1e-8)


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


def steps_for(steps, error, target: float, fit: dict, steps_of) -> tuple[float, bool]:
    """LAMMPS steps that plain refinement needs for ``target``, and whether that is extrapolated.

    Inside the measured range: linear interpolation of log(error) against log(steps)
    between the two levels around the target. Outside it (finer or coarser): the fitted
    asymptotic line error = C dt^order, turned into steps by ``steps_of`` (dt -> steps);
    without a usable fit, nan.
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
    return float(steps_of(dt)), True


def _order_of(group: pd.DataFrame, columns) -> float:
    """The order of the largest error over ``columns`` (nan if the case has none of them)."""
    present = [c for c in columns if c in group and group[c].notna().all()]
    if not present:
        return float("nan")
    return fit_order(group["dt"], group[present].max(axis=1))["order"]


#: The summary's columns of the run at the scenes' default step: (column, run table's column, type).
_DEFAULT_COLUMNS = (
    ("default_dt", "dt", float), ("default_lammps_steps", "lammps_steps", int),
    ("default_steps_per_half_period", "resolution", float), ("default_step_method", "step_method", str),
    ("error_at_default_dt", "error", float), ("relative_error_at_default_dt", "relative_error", float),
    ("default_target", "target", float))


def _default_columns(group: pd.DataFrame) -> dict:
    """The run at the scenes' default step; a form that no default step takes (the end on a
    step boundary) has nan (no step method)."""
    rows = group[group["default_dt"]]
    if rows.empty:
        return {key: None if kind is str else float("nan") for key, _, kind in _DEFAULT_COLUMNS}
    return {key: kind(rows.iloc[0][column]) for key, column, kind in _DEFAULT_COLUMNS}


def _summary_row(case: Case, form: str, group: pd.DataFrame) -> dict:
    ladder_rows = group[group["in_ladder"]]
    fit = fit_order(ladder_rows["dt"], ladder_rows["error"])
    tangential = [f"error_{s}" for s in case.state_names[1:]]
    row = {"case": case.name, "label": case.label, "kind": case.kind, "form": form,
           "observed_order": fit["order"], "prefactor": fit["prefactor"],
           "expected_order": case.expected[form],
           "order_v_n": _order_of(ladder_rows, ["error_v_n"]),
           "order_tangential": _order_of(ladder_rows, tangential),
           "local_orders": fit["local_orders"], "fit_dt": fit["fit_dt"], **_default_columns(group),
           "finest_error": float(ladder_rows["error"].iloc[-1]), "theory": case.theory}
    for target in TARGETS:
        steps, extrapolated = steps_for(ladder_rows["lammps_steps"], ladder_rows["error"], target, fit,
                                        steps_of_dt(case))
        row[f"steps_{target:.0e}"] = steps
        row[f"extrapolated_{target:.0e}"] = extrapolated
    return row


def summarise(table: pd.DataFrame, all_cases: list[Case]) -> pd.DataFrame:
    """One row per (case, form): observed order (overall, of v_n, and of the tangential
    columns), the scenes' default step and the error it reaches (where the form has one), and
    the steps plain refinement needs for each of TARGETS."""
    by_name = {c.name: c for c in all_cases}
    rows = [_summary_row(by_name[name], form, group)
            for (name, form), group in table.groupby(["case", "form"], sort=False)]
    return pd.DataFrame(rows)
