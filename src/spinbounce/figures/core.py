"""What every figure shares: the style, saving, run folders, the step choice, deviations.

Figures flow one way: scenes -> pipeline runs -> tables -> drawing. The helpers here
run scenes and measure them against the exact theory; the figure modules turn the
results into tables and draw only from those tables.

matplotlib is imported inside the functions that draw, so importing this module (and
the ``spinbounce figures`` command) stays cheap.
"""

from __future__ import annotations

import itertools
import math
import shutil
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from .. import __version__
from ..exact import linear
from ..pipeline import ResultError, RunResult, SeriesResult, run_scene, run_series, series_record
from ..outputs import check_outputs, write_output, write_output_with
from ..records import software, to_json, write_atomic
from ..model.parameters import SceneError
from ..scenes.collision import Collision
from ..model.contact import ContactModel
from ..scenes.frozen import Frozen
from ..model.timestep import align_mid_step

__all__ = [
    "ACCEPTANCE",
    "STYLE",
    "TARGET",
    "FigureData",
    "FigureRecord",
    "Tuned",
    "base_metadata",
    "collision_run",
    "default_runs",
    "finish_metadata",
    "frozen_run",
    "make",
    "new_figure",
    "save",
    "tune_dt",
]

#: The shipped style file; every figure is drawn inside ``matplotlib.style.context(STYLE)``.
STYLE = Path(__file__).with_name("spinbounce.mplstyle")
#: Largest deviation between LAMMPS and the exact theory a figure may show.
ACCEPTANCE = 1e-4
#: What the step choice aims for: a quarter of the acceptance limit, so that a slightly
#: different platform or LAMMPS build still passes.
TARGET = 2.5e-5
#: A first-order extrapolation lands on the target only approximately: aim a little lower.
SAFETY = 0.8
#: Refinements after the pilot run before giving up (each is aimed at the target).
MAX_REFINEMENTS = 3
#: Height of the frozen contact in Figs. 2, 3 and 7 (paper: z = 0.1).
FROZEN_Z = 0.1


@dataclass
class FigureData:
    """The tables a figure is drawn from, and its metadata so far."""

    tables: dict[str, pd.DataFrame]
    metadata: dict


@dataclass(frozen=True)
class FigureRecord:
    name: str
    png: Path
    pdf: Path
    json: Path
    metadata: dict = field(repr=False)


@dataclass(frozen=True)
class Tuned:
    """A run at the chosen step: its result, deviations from the exact theory, provenance."""

    result: object
    deviations: dict[str, float]
    dt: float
    run_dir: Path
    choice: dict

    @property
    def deviation(self) -> float:
        return max(self.deviations.values())


def new_figure(nrows: int = 1, ncols: int = 1, figsize=None, **subplots):
    """A Figure on an Agg canvas, without pyplot: no global figure list, no GUI backend.

    Call inside ``matplotlib.style.context(STYLE)`` so the style applies.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize)
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, squeeze=False, **subplots)
    return fig, axes


#: What every figure's numbers are in, printed in its corner and recorded in its JSON.
UNITS = "units: LAMMPS lj (mass, length and time as given: m, r, kn; velocities length/time, omega 1/time)"


def _note_units(fig) -> None:
    """:data:`UNITS` in the figure's bottom-left corner, in a strip its layout leaves free."""
    engine = fig.get_layout_engine()
    if engine is not None and hasattr(engine, "set") and "rect" in engine.get():
        engine.set(rect=(0.0, 0.03, 1.0, 0.97))
    else:
        fig.subplots_adjust(bottom=max(fig.subplotpars.bottom, 0.12))
    fig.text(0.003, 0.004, UNITS, ha="left", va="bottom", fontsize=5, color="0.45")


def save(fig, out: Path, name: str, metadata: dict, started: float | None = None) -> FigureRecord:
    """Write ``name``.png, ``name``.pdf and ``name``.json into ``out``, each atomically.

    The JSON names the two images relative to itself and is written last; with
    ``started`` (a ``time.perf_counter()`` value) it records the seconds since then as
    ``runtime_seconds``. Dates are left out of the PDF and PNG so that the images depend
    only on the data.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    _note_units(fig)
    metadata = {**metadata, "units": UNITS}
    check_outputs(out, figure_files(name))  # all three refused before any is written
    png, pdf, meta = (out / file for file in figure_files(name))
    write_output_with(png, lambda tmp: fig.savefig(tmp, format="png", metadata={"Software": None}))
    write_output_with(pdf, lambda tmp: fig.savefig(tmp, format="pdf", metadata={"CreationDate": None, "Creator": f"spinbounce {__version__}"}))
    if started is not None:
        metadata["runtime_seconds"] = time.perf_counter() - started
    record = {**metadata, "files": {"png": png.name, "pdf": pdf.name}}
    write_output(meta, to_json(record))
    return FigureRecord(name, png, pdf, meta, record)


#: Marks a folder as a figure's run folder, which the next make of that figure may empty.
RUNS_MARKER = ".spinbounce-figure-runs"


def default_runs(out: Path, runs: Path | None, name: str) -> Path:
    """A figure's LAMMPS run folder, emptied: ``runs`` if given, else OUT/runs/<name>.

    Runs of an earlier make (other steps, other states) would otherwise sit beside the
    new ones and look like their provenance. Only a folder carrying RUNS_MARKER is
    emptied; a non-empty folder without it is refused rather than touched.
    """
    folder = Path(runs) if runs is not None else Path(out) / "runs" / name
    if folder.exists():
        if (folder / RUNS_MARKER).exists():
            shutil.rmtree(folder)
        elif any(folder.iterdir()):
            raise SceneError("--runs" if runs is not None else "--out", str(folder),
                             "holds files that are not a figure's runs: give another folder")
    folder.mkdir(parents=True, exist_ok=True)
    write_atomic(folder / RUNS_MARKER, f"LAMMPS runs of {name}, remade with it (spinbounce figures)\n")
    return folder


def figure_files(name: str) -> tuple[str, str, str]:
    """The files :func:`save` writes for figure ``name``: its PNG, PDF and JSON record."""
    return tuple(f"{name}.{ext}" for ext in ("png", "pdf", "json"))


def make(compute, draw, name: str, out: Path, runs: Path | None, also: tuple[str, ...] = ()) -> FigureRecord:
    """Run, tabulate (``compute``), draw from the tables only (``draw``) and save; files of ``out`` it
    would replace (the figure's, and ``also``) are checked first (:mod:`spinbounce.outputs`).

    Drawing and saving both happen inside the style: savefig reads rcParams too.
    """
    import matplotlib.style

    check_outputs(out, figure_files(name) + also)
    started = time.perf_counter()
    data = compute(out, runs)
    with matplotlib.style.context(STYLE):
        fig = draw(data)
        return save(fig, out, name, data.metadata, started)


def base_metadata(name: str, title: str, paper: str) -> dict:
    return {
        "figure": name,
        "title": title,
        "paper": paper,
        **software(),
        "acceptance_limit": ACCEPTANCE,
        "dt_target": TARGET,
    }


def finish_metadata(meta: dict, runs: list[dict], out: Path) -> dict:
    """Add the runs, the per-series dt and the figure's largest deviation; raise if too large.

    ``runs``: one dict per series with keys series, tuned (a :class:`Tuned`) and anything
    else to record. The largest deviation between LAMMPS and the exact theory over the
    whole figure must be below :data:`ACCEPTANCE`.
    """
    records = []
    for run in runs:
        tuned: Tuned = run["tuned"]
        entry = {k: v for k, v in run.items() if k != "tuned"}
        entry.update(
            run_dir=_relative(tuned.run_dir, out),
            dt=tuned.dt,
            nsteps=int(tuned.result.scene.nsteps),
            max_deviation_exact=tuned.deviation,
            deviations_exact=tuned.deviations,
            dt_choice={**tuned.choice, "history": [  # superseded runs' folders stay, for the record
                {**h, "run_dir": _relative(h["run_dir"], out)} for h in tuned.choice["history"]]},
        )
        records.append(entry)
    worst = max(records, key=lambda e: e["max_deviation_exact"])
    meta.update(runs=records, dt={e["series"]: e["dt"] for e in records},
                max_deviation_exact=worst["max_deviation_exact"], max_deviation_exact_series=worst["series"])
    if not 0.0 < meta["max_deviation_exact"] < ACCEPTANCE:
        raise ResultError(
            f"{meta['figure']}: largest deviation between LAMMPS and the exact theory is "
            f"{meta['max_deviation_exact']:.3g} (series {worst['series']!r}), outside (0, {ACCEPTANCE:g})"
        )
    return meta


def _relative(path: Path, base: Path) -> str:
    path, base = Path(path).resolve(), Path(base).resolve()
    try:
        return str(path.relative_to(base))
    except ValueError:
        return str(path)


def dissipation_columns(table: pd.DataFrame, model: ContactModel) -> dict[str, np.ndarray]:
    """f = -Delta E/E(0) (Eq. 21) of a collision batch: LAMMPS's and the exact theory's."""
    initial, final, exact = (table[[f"{s}_{x}" for s in ("v_n", "v_t", "r_omega")]].to_numpy()
                             for x in ("initial", "lammps", "theory"))
    return {
        "f": linear.dissipation(initial, final, model.m, model.alpha),
        "f_theory": linear.dissipation(initial, exact, model.m, model.alpha),
    }


def tune_dt(run: Callable[[float], tuple[object, dict[str, float], Path]], dt0: float,
            snap: Callable[[float], float], what: str,
            problems: Callable[[object], list[str]] = lambda result: []) -> Tuned:
    """Run at the default step ``dt0``; refine until the largest deviation is below TARGET.

    ``run(dt)`` returns (result, deviations, run folder). The refinement assumes the
    error is first order in dt, which is what LAMMPS's damped step gives (its damping
    force sees the half-step velocity); the undamped error is second order, so for it
    the assumption only refines a little more than needed. ``snap`` turns a step into
    the nearest allowed one at or below it (a whole number of steps per run, or the
    collision's tau/(N + 1/2)). ``problems(result)`` lists what else is wrong with a
    run (say, energy gained); a run with problems is refined too (halving dt if its
    deviation is already on target). Raises :class:`ResultError` if the last run is not
    below ACCEPTANCE or still has problems.
    """
    history = []
    dt = snap(dt0)
    for attempt in range(MAX_REFINEMENTS + 1):
        result, deviations, folder = run(dt)
        worst = max(deviations.values())
        issues = problems(result)
        history.append({"dt": dt, "max_deviation_exact": worst, "run_dir": str(folder),
                        **({"problems": issues} if issues else {})})
        if (worst < TARGET and not issues) or attempt == MAX_REFINEMENTS:
            break
        # on target but with problems: no error to extrapolate from, so halve
        smaller = snap(dt * SAFETY * TARGET / worst) if worst >= TARGET else snap(0.5 * dt)
        dt = smaller if smaller < dt else snap(0.5 * dt)
    if not worst < ACCEPTANCE or issues:
        raise ResultError(
            f"{what}: largest deviation from the exact theory {worst:.3g} at dt = {dt:.6g} "
            f"(limit {ACCEPTANCE:g}){'; ' + '; '.join(issues) if issues else ''}, after {len(history)} run(s): "
            f"{history}"
        )
    if len(history) == 1:
        reason = (f"the scene's default step gives a largest deviation of {worst:.3g}, already below "
                  f"the target {TARGET:g} (a quarter of the acceptance limit {ACCEPTANCE:g})")
    else:
        first = history[0]
        orders = [math.log(a["max_deviation_exact"] / b["max_deviation_exact"]) / math.log(a["dt"] / b["dt"])
                  for a, b in itertools.pairwise(history)]
        why = f"gave {first['max_deviation_exact']:.3g}"
        if first["max_deviation_exact"] >= TARGET:
            why += f", above the target {TARGET:g}"
        if "problems" in first:
            why += f" and was refused: {'; '.join(first['problems'])}"
        reason = (
            f"the default step {first['dt']:.6g} {why}; the step was scaled down assuming an error "
            f"first order in dt (the order of LAMMPS's damped step, whose tangential damping force sees "
            f"the half-step velocity; an undamped step's error is second order and falls faster), to "
            f"{dt:.6g}, which gives {worst:.3g}; measured order of the error between successive runs: "
            f"{', '.join(f'{p:.2f}' for p in orders)}"
        )
    choice = {"reason": reason, "default_dt": history[0]["dt"], "history": history}
    return Tuned(result, deviations, dt, Path(folder), choice)


def frozen_run(model: ContactModel, v_t: float, omega: float, t_end: float, series_dir: Path,
               what: str) -> Tuned:
    """A frozen contact at z = FROZEN_Z, at a step chosen by :func:`tune_dt`, with its largest
    |LAMMPS - exact| in v_t, r*omega and omega (drawn in Figs. 2 and 7; with r < 1 the largest).

    Each run folder gets ``result.json`` (provenance and the deviation) beside the deck.
    """

    def run(dt):
        scene = Frozen(model, z=FROZEN_Z, v_t=v_t, omega=omega, t_end=t_end, dt=dt)
        folder = Path(series_dir) / f"dt_{scene.dt:.6e}"
        result: SeriesResult = run_series(scene, folder)
        t = result.table
        deviations = {"v_t": float(np.abs(t["v_t"] - t["v_t_theory"]).max()),
                      "r_omega": float(np.abs(t["r_omega"] - t["r_omega_theory"]).max()),
                      "omega": float(np.abs(t["omega"] - t["r_omega_theory"] / model.r).max())}
        record = series_record(result)
        record["deviations_exact"] = deviations
        write_atomic(folder / "result.json", to_json(record))
        return result, deviations, folder

    dt0 = Frozen(model, z=FROZEN_Z, v_t=v_t, omega=omega, t_end=t_end).dt
    return tune_dt(run, dt0, lambda dt: t_end / math.ceil(t_end / dt - 1e-9), what)  # whole steps in t_end


def collision_run(model: ContactModel, states: np.ndarray, series_dir: Path, what: str,
                  energy: bool = False) -> Tuned:
    """A batch of collisions (rows v_n, v_t, r*omega) in one LAMMPS run, at a step chosen by
    :func:`tune_dt`, with its largest |LAMMPS - exact Eq. 18| per final-state component. With
    ``energy`` the dissipation f joins the compared quantities.

    A run whose kinetic energy grew (the pipeline's warning) is refined like an inaccurate
    one, and refused if it still does at the last step tried: none of the models can gain energy.
    """
    states = np.asarray(states, dtype=float)

    def scene_at(dt):
        return Collision(model, v_n=states[:, 0], v_t=states[:, 1], omega=states[:, 2] / model.r, dt=dt)

    def run(dt):
        scene = scene_at(dt)
        folder = Path(series_dir) / f"dt_{scene.dt:.6e}"
        result: RunResult = run_scene(scene, folder, atoms="library")
        deviations = {s: float(np.abs(result.table[f"{s}_error"]).max())
                      for s in ("v_n", "v_t", "r_omega", "omega")}
        if energy:
            f = dissipation_columns(result.table, model)
            deviations["f"] = float(np.max(np.abs(f["f"] - f["f_theory"])))
        return result, deviations, folder

    # snapped to tau/(N + 1/2): the contact ends mid-step, where the cut-off error cancels (model.timestep);
    # the pipeline warns when kinetic energy grew, which none of these models can do
    return tune_dt(run, scene_at(None).dt, lambda dt: align_mid_step(model.tau, dt), what,
                   problems=lambda result: list(result.warnings))
