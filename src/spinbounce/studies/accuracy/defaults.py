"""The default step, case by case: how many steps it chooses and the error it reaches.

No fixed resolution is the default any more: a collision's step follows from the target
accuracy (:data:`spinbounce.model.timestep.ACCURACY` of the size of the initial state),
by the a priori second-order rule for the paper's linear contact and by a probe against
the exact theory for damped, capped and Hertzian ones (:mod:`spinbounce.stepping`). This
table says what that costs and whether it delivers, for every case of the study.
:func:`default_step_table` runs only the defaults (what ``spinbounce bench`` prints per
model); the study takes the same table from its own runs (:func:`policy_table`).
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

import pandas as pd

from .cases import Case, cases
from .measure import DEFAULT_FORMS, labelled_row, run_default

__all__ = ["POLICY_COLUMNS", "policy_table", "default_step_table"]

#: The table's columns: what the default chose (step_method: the rule, the probe, a Hertzian
#: batch's fixed resolution or the frozen rule), the steps of one run at it (a collision's
#: whole contact; a frozen contact's 10 time units), and the error it reached: the largest
#: |LAMMPS - theory| over the size of the initial state (the target's own measure), and the
#: same without that division (the study's ladder measure).
POLICY_COLUMNS = ("case", "label", "kind", "form", "step_method", "steps_per_collision", "steps_per_half_period",
                  "dt", "error_reached", "target", "within_target", "absolute_error", "worst_status")


def policy_table(table: pd.DataFrame) -> pd.DataFrame:
    """The rows of a study's run table taken at the default step, as :data:`POLICY_COLUMNS`."""
    rows = table[table["default_dt"]]
    out = pd.DataFrame({
        "case": rows["case"], "label": rows["label"], "kind": rows["kind"], "form": rows["form"],
        "step_method": rows["step_method"], "steps_per_collision": rows["lammps_steps"].astype(int),
        "steps_per_half_period": rows["resolution"], "dt": rows["dt"], "error_reached": rows["relative_error"],
        "target": rows["target"], "within_target": rows["relative_error"] <= rows["target"],
        "absolute_error": rows["error"], "worst_status": rows["worst_status"]})
    return out.reset_index(drop=True)[list(POLICY_COLUMNS)]


def _default_rows(chosen: list[Case], root: Path, log) -> list[dict]:
    rows = []
    for case in chosen:
        for form in (f for f in case.forms if f in DEFAULT_FORMS):
            row = run_default(case, form, root / case.name / form.replace(" ", "-"))
            labelled_row(row, case, form, row["resolution"], in_ladder=False)
            log(f"  {case.name:<14}{form:<15}{row['lammps_steps']:>9} steps  error {row['relative_error']:.2e} "
                f"(target {row['target']:g}, {row['step_method']})")
            rows.append(row)
    return rows


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
    chosen = [c for c in all_cases if names is None or c.name in names]
    root = Path(runs) if runs is not None else Path(tempfile.mkdtemp(prefix="spinbounce-defaults-"))
    try:
        return policy_table(pd.DataFrame(_default_rows(chosen, root, log)))
    finally:
        if runs is None:
            shutil.rmtree(root, ignore_errors=True)
