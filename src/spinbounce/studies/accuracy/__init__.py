"""Speed against accuracy: how LAMMPS's error against theory falls with dt, across cases.

The convergence study: for each named case (:mod:`.cases`: the paper's model and its
variations, damping, 3-D spin, a Hertzian wall, a finite Coulomb cap against the oracle,
frozen contacts) a ladder of plain LAMMPS runs, n steps per half-period of the fastest
contact mode, each measured against the case's theory (:mod:`.measure`), and one run at
the step the scenes choose by default. From the ladder come the observed order of
convergence and the steps plain refinement needs for a given accuracy (:mod:`.orders`);
from the default runs, the steps per collision the default chooses and the error it reaches
(:func:`default_step_table` runs only those). :mod:`.study` runs it all with its
provenance, :mod:`.report` writes the figure, the JSON record and ACCURACY.md.

Not to be confused with :mod:`spinbounce.extrapolation`, which reaches a requested
accuracy for one scene by Richardson extrapolation. The two climb the same rungs (the
study takes them from there), and this study measures the raw orders tolerance assumes.

matplotlib is imported only when the figure is drawn; LAMMPS only when a run starts.
"""

from __future__ import annotations

from pathlib import Path

from .cases import ANY, BOX, EDGE, FROZEN, FROZEN_T_END, FROZEN_Z, MECHANISMS, MID, Case, box_sample, cases, corners
from .measure import (
    DEFAULT_FORMS,
    FULL_LADDER,
    QUICK_LADDER,
    collision_dt,
    collision_scene,
    default_target,
    frozen_dt,
    ladder,
    run_collision_level,
    run_default,
    steps_of_dt,
)
from .orders import ERROR_FLOOR, FIT_LEVELS, TARGETS, fit_order, steps_for, summarise
from .report import draw, markdown, write_study
from .study import POLICY_COLUMNS, Study, default_step_table, policy_table, run_study

__all__ = [
    "ANY", "BOX", "DEFAULT_FORMS", "EDGE", "ERROR_FLOOR", "FIT_LEVELS", "FROZEN", "FROZEN_T_END", "FROZEN_Z",
    "FULL_LADDER", "MECHANISMS", "MID", "POLICY_COLUMNS", "QUICK_LADDER", "TARGETS", "Case", "Study", "box_sample",
    "cases", "collision_dt", "collision_scene", "corners", "default_step_table", "default_target", "draw",
    "fit_order", "frozen_dt", "ladder", "make_accuracy", "markdown", "policy_table", "run_collision_level",
    "run_default", "run_study", "steps_for", "steps_of_dt", "summarise", "write_study",
]


def make_accuracy(out: Path, quick: bool = False, runs: Path | None = None, log=print) -> tuple[Study, dict]:
    """Run the study and write its files: what ``spinbounce accuracy`` does."""
    from ...figures.core import figure_files
    from ...outputs import check_outputs

    check_outputs(out, (*figure_files("accuracy"), "ACCURACY.md"))
    study = run_study(quick=quick, runs=runs, log=log)
    return study, write_study(study, out)
