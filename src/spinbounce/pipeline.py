"""scene -> deck -> run -> table -> checks -> record: one pipeline for every scene
(:mod:`spinbounce.scenes` says what a scene answers).

Each run lives in its own folder: the deck (which alone reproduces the run with
``lmp -in in.lammps``), the files it reads, LAMMPS's log and dump, and ``result.json``
with the provenance. A run's output is checked before it is returned: non-finite values,
lost spheres and a contact that had not finished are errors, not results.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from . import checks
from .errors import ResultError
from .lammps.decks import Deck, INLINE_SPHERES, RESULT_TABLE, prepare_run_dir
from .lammps.runner import RunInfo, run_deck
from .model.timestep import ACCURACY, StepChoice
from .records import software, to_json, write_atomic, write_parquet_atomic
from .stepping import FALLBACK, reachable, tune

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["ResultError", "RunResult", "SeriesResult", "run_scene", "run_series", "prepare_run_dir", "provenance",
           "write_record", "RESULT_TABLE"]

#: What a probe's run says when its step was too coarse to see the contact end.
UNFINISHED = "had not finished"


def provenance(info: RunInfo, scene_kind: str, parameters: dict) -> dict:
    """A run's record: its scene, parameters, deck and log, and :func:`records.software`."""
    return {
        "scene": scene_kind,
        "parameters": parameters,
        **software(),
        "deck": str(info.deck),
        "log": str(info.log),
        "lammps_wall_seconds": info.wall_seconds,
    }


def write_record(folder: Path, info: RunInfo, kind: str, parameters: dict, **fields) -> Path:
    """``result.json`` in ``folder``: the run's :func:`provenance` and ``fields`` (its accuracy,
    its step, its rows: inline, or as :data:`RESULT_TABLE` past INLINE_SPHERES rows)."""
    record = provenance(info, kind, parameters)
    table = fields.pop("table", None)
    if table is not None:
        if len(table) <= INLINE_SPHERES:
            fields["rows"] = table.to_dict(orient="records")
        else:  # a JSON record per row would cost more than the run
            write_parquet_atomic(folder / RESULT_TABLE, table)
            fields["rows"] = RESULT_TABLE
    path = folder / "result.json"
    write_atomic(path, to_json({**record, **fields}))
    return path


@dataclass(frozen=True)
class RunResult:
    """A run of a collision scene: its checked columns (one row per collision; as a DataFrame:
    :attr:`table`), how its step was chosen, and the largest absolute deviation of any row from
    its reference."""

    scene: object
    columns: dict[str, np.ndarray]
    info: RunInfo
    deck: Deck
    dump: Path | None  # None for a library-route run (no dump)
    warnings: tuple[str, ...]
    step: StepChoice
    max_abs_error: float

    @cached_property
    def table(self) -> pd.DataFrame:
        """The columns as a DataFrame, made when first asked (a sweep writes the columns as they are)."""
        import pandas as pd

        return pd.DataFrame(self.columns)

    @property
    def max_error(self) -> float:
        """The largest row error (each relative to its row's scale), but of rows without a reference (no_limit);
        NaN if every row is one."""
        errors = np.asarray(self.columns["error"])[np.asarray(self.columns["status"]) != "no_limit"]
        return float(np.max(errors)) if errors.size else float("nan")


def _probe_errors(scene, folder: Path) -> np.ndarray:
    """A probe's rows' relative errors (:func:`stepping.tune`): a plain run, nothing recorded; inf if the
    step was too coarse for the run to finish the contact; rows without a limit (no reference) left out, none
    if every row is one (no error can be measured: :data:`.stepping.UNMEASURED`)."""
    try:
        columns = run_scene(scene, folder, atoms="library", record=False).columns
        measured = np.asarray(columns["status"]) != "no_limit"  # no reference, no error: the others decide
        return np.asarray(columns["error"])[measured]
    except ResultError as exc:
        if UNFINISHED not in str(exc):
            raise
        return np.array([np.inf])


def run_scene(scene, out_dir: Path, atoms: str | None = None, record: bool = True, runner=run_deck,
              probe_states=None, target: float = ACCURACY) -> RunResult:
    """Run a collision scene (the wall's, the pairs') in ``out_dir`` and check every row against
    its reference (:mod:`spinbounce.checks`).

    A scene whose dt is the default first gets the step ``target`` needs
    (:func:`stepping.tune`; ``probe_states``: a scene whose rows to probe with, if not its own).
    ``atoms``: how the deck receives its spheres (:data:`~spinbounce.lammps.decks.ATOM_ROUTES`; a
    pair deck reads a data file, or with "library" receives them in memory, as a sweep's chunks do). With ``record`` the folder gets ``result.json``
    (:func:`write_record`). ``runner``: :func:`runner.run_deck` (in this process) or
    :func:`runner.run_deck_lmp` (the ``lmp`` executable).
    """
    given, (scene, step) = scene, tune(scene, Path(out_dir) / "probe", _probe_errors, probe_states, target)
    deck, deck_path, info, columns, deviation = _run(scene, out_dir, atoms, runner, target, record)
    for attempt in range(RETUNES):  # the probe's step, chosen on a sample, may miss the target on the whole scene
        folder = Path(out_dir) / f"probe-again-{attempt}"
        finer = _finer(given, scene, step, columns, folder, target, own_probe=probe_states is None)
        if finer is None:
            break
        scene, step = finer
        deck, deck_path, info, columns, deviation = _run(scene, out_dir, atoms, runner, target, record)
    notes = tuple(checks.notes(columns["status"], target))
    dump = None if deck.dump is None else deck_path.parent / deck.dump
    result = RunResult(scene, columns, info, deck, dump, notes, step, deviation)
    if record:
        write_record(deck_path.parent, info, scene.kind, scene.record(deck), dump=None if dump is None else str(dump),
                     warnings=list(notes), max_abs_error=deviation, max_error=result.max_error, step=step.record(),
                     status=checks.summary(columns["status"]), table=result.table)
    return result


#: How often a scene whose probed step missed the target on some rows is probed again on those rows.
RETUNES = 2


def _finer(given, scene, step, columns: dict, out: Path, target: float, own_probe: bool = True):
    """(scene, step) to run again when the probed step erred above ``target`` on rows it could reach: the
    scene's fine rule if it has one, else (``own_probe``: the scene chose its step from its own rows) the
    step a probe of the rows that erred asks for; None if none is finer (each row's error is reported
    either way). A sweep's chunk keeps its group's step, which every chunk of the group shares."""
    worst = _worst(columns, given) if step.method.startswith("probe") else 0.0
    if worst <= target:
        return None
    fine = given.fallback()
    if fine is not None:
        return (fine, replace(step, dt=fine.dt, method=f"{FALLBACK}; the probe's step erred {worst:.2g}",
                              predicted_error=None)) if fine.dt < scene.dt else None
    if not own_probe:
        return None
    erred = _resolvable(columns, given)
    erred = erred[np.asarray(columns["error"])[erred] > target]
    again, choice = tune(given, out, _probe_errors, given.rows(erred), target)
    if again.dt >= scene.dt:
        return None
    return again, replace(choice, method=f"probe of the {erred.size} row(s) the first probe's step left above "
                                         f"{target:g} (it erred {worst:.2g})")


def _resolvable(columns: dict, scene) -> np.ndarray:
    """The rows a finer step can help: not beyond any affordable step's reach, nor grazing (their error is
    double precision's, at every step), nor without a limit (no reference)."""
    rows = reachable(scene)
    return rows[~np.isin(np.asarray(columns["status"])[rows], ("grazing", "no_limit"))]


def _worst(columns: dict, scene) -> float:
    """The largest row error but on rows no finer step helps (:func:`_resolvable`); 0 if there are none."""
    rows = _resolvable(columns, scene)
    return float(np.max(np.asarray(columns["error"])[rows])) if rows.size else 0.0


def _run(scene, out_dir: Path, atoms, runner, target: float, durable: bool = True):
    """One run of ``scene`` in ``out_dir``: (deck, its path, LAMMPS's info, the checked columns, the
    largest absolute deviation). ``durable``: its deck forced to disk (a recorded run)."""
    deck = scene.render(atoms)
    deck_path = prepare_run_dir(out_dir, deck, durable)
    info = runner(deck_path, atoms=deck.atoms)
    columns = scene.read(info, deck, deck_path.parent)
    deviation = checks.add_row_checks(columns, scene.row_states(columns), target)
    return deck, deck_path, info, columns, deviation


@dataclass(frozen=True)
class SeriesResult:
    """A run of a time-series scene: its table, checked by the scene, and the largest deviation
    from its reference (the scene's :meth:`max_abs_error`)."""

    scene: object
    table: pd.DataFrame
    info: RunInfo
    dump: Path

    @property
    def max_abs_error(self) -> float:
        return self.scene.max_abs_error(self.table)


def run_series(scene, out_dir: Path) -> SeriesResult:
    """Run a time-series scene (the frozen contact) in ``out_dir``: its checked table."""
    deck = scene.render()
    deck_path = prepare_run_dir(out_dir, deck)
    info = run_deck(deck_path)
    dump = deck_path.parent / deck.dump
    return SeriesResult(scene, scene.read(info, deck, deck_path.parent), info, dump)


def series_record(result: SeriesResult) -> dict:
    """A time-series run's record: :func:`provenance` with its scene's parameters and accuracy."""
    return {**provenance(result.info, result.scene.kind, result.scene.record()), "dump": str(result.dump),
            "max_abs_error": result.max_abs_error}
