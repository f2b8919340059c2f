"""scene -> deck -> run -> dump -> table -> theory comparison, for one scene.

Each run lives in its own folder: the deck (which alone reproduces the run with
``lmp -in in.lammps``), LAMMPS's log and dump, and ``result.json`` with the provenance.
A run's output is checked before it is returned: non-finite values, lost spheres and a
contact that had not finished are errors, not results.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from .exact import choose
from .records import software, to_json, write_atomic, write_parquet_atomic
from . import checks
from .compare import collision_table, frozen_table
from .lammps.decks import DUMP_NAME, INLINE_SPHERES, Deck, render_collision, render_frozen, wall_parameters
from .lammps.dumps import read_dump
from .lammps.runner import RunInfo, run_deck
from .model.scenes import Collision, Frozen
from .model.timestep import ACCURACY, StepChoice
from .stepping import tune
from .errors import ResultError

__all__ = [
    "ResultError",
    "CollisionResult",
    "FrozenResult",
    "run_collision",
    "run_frozen",
    "prepare_run_dir",
    "write_atomic",
    "write_parquet_atomic",
    "to_json",
    "provenance",
]

#: A batch's per-sphere table, beside result.json.
RESULT_TABLE = "result.parquet"


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


def prepare_run_dir(out_dir: Path, deck: Deck) -> Path:
    """``out_dir`` made ready to run ``deck`` (created, earlier outputs removed, the deck and the
    files it reads written); the deck's path. For decks run outside :func:`run_collision`, such
    as the speed measurement's padded ones."""
    out_dir = Path(out_dir).resolve()
    out_dir.mkdir(parents=True, exist_ok=True)
    for stale in (DUMP_NAME, "log.lammps", "result.json", RESULT_TABLE):
        (out_dir / stale).unlink(missing_ok=True)
    for name, text in deck.files.items():
        write_atomic(out_dir / name, text)
    deck_path = out_dir / deck.name
    write_atomic(deck_path, deck.text)
    return deck_path


def _check_finite(frames: pd.DataFrame, where: Path) -> None:
    values = frames.drop(columns=["step", "id"]).to_numpy(dtype=float)
    if not np.all(np.isfinite(values)):
        bad = frames[~np.isfinite(values).all(axis=1)]
        raise ResultError(
            f"{where}: non-finite positions or velocities (first at step {int(bad['step'].iloc[0])}, "
            f"atom {int(bad['id'].iloc[0])}): the integration blew up"
        )


#: Per-sphere columns of a collision frame, as LAMMPS names them (the dump's columns).
FRAME_COLUMNS = ("x", "y", "z", "vx", "vy", "vz", "omegax", "omegay", "omegaz")


def _probe_errors(scene: Collision, folder: Path) -> np.ndarray:
    """A probe's rows' relative errors (:func:`stepping.tune`): a plain run, nothing recorded;
    inf if the step was too coarse for the run to finish the contact."""
    try:
        return run_collision(scene, folder, atoms="library", record=False).table["error"].to_numpy()
    except ResultError as exc:
        if "had not finished" not in str(exc):
            raise
        return np.array([np.inf])


def _check_finished(scene: Collision, columns: dict, source: Path) -> None:
    touching = np.flatnonzero(columns["z_final"] <= scene.model.r)
    if touching.size:
        first = touching[0]
        raise ResultError(
            f"{source}: {touching.size} sphere(s) still touch the wall after {scene.nsteps} steps "
            f"(first: id {int(columns['id'][first])}, z = {float(columns['z_final'][first])!r}): "
            "the contact had not finished"
        )


def _memory_frames(info: RunInfo, nsteps: int) -> dict[int, dict[str, np.ndarray]]:
    """A library-route run's sphere states (type-1 atoms) at steps 0 and nsteps, in id order."""
    frames = {}
    for step, state in ((0, info.initial), (nsteps, info.final)):
        keep = state["type"] == 1
        frame = {"id": state["id"][keep].astype(np.int64)}
        for k, axis in enumerate("xyz"):
            frame[axis] = state["x"][keep, k]
            frame[f"v{axis}"] = state["v"][keep, k]
            frame[f"omega{axis}"] = state["omega"][keep, k]
        frames[step] = frame
    return frames


def _dump_frames(frames: pd.DataFrame) -> dict[int, dict[str, np.ndarray]]:
    """A dump's rows, split into frames by step."""
    step = frames["step"].to_numpy()
    out = {}
    for value in np.unique(step):
        rows = frames[step == value]
        out[int(value)] = {name: rows[name].to_numpy() for name in ("id", *FRAME_COLUMNS)}
    return out


def _collision_frames(scene: Collision, frames: dict, where: Path) -> tuple[dict, dict]:
    """Checked initial and final frames (one entry per sphere, id order) of a collision run."""
    steps = sorted(frames)
    if steps != [0, scene.nsteps]:
        raise ResultError(f"{where}: expected frames at steps 0 and {scene.nsteps}, found {steps}")
    ids = np.arange(1, scene.n + 1)
    for step in steps:
        frame = frames[step]
        if len(frame["id"]) != scene.n:
            raise ResultError(f"{where}: {len(frame['id'])} of {scene.n} spheres at step {step} (lost atoms)")
        if not np.array_equal(frame["id"], ids):
            raise ResultError(f"{where}: sphere ids at step {step} are not 1..{scene.n} in order")
        finite = np.logical_and.reduce([np.isfinite(frame[c]) for c in FRAME_COLUMNS])
        if not finite.all():
            raise ResultError(
                f"{where}: non-finite positions or velocities (first at step {step}, "
                f"atom {int(frame['id'][~finite][0])}): the integration blew up"
            )
    return frames[0], frames[scene.nsteps]


@dataclass(frozen=True)
class CollisionResult:
    scene: Collision
    table: pd.DataFrame
    info: RunInfo
    dump: Path | None  # None for a library-route run (no dump)
    warnings: tuple[str, ...]
    step: StepChoice | None = None  # how dt was chosen

    @property
    def max_abs_error(self) -> float:
        return float(np.max(np.abs(self.table[[f"{s}_error" for s in self.scene.state_names]].to_numpy())))


def run_collision(scene: Collision, out_dir: Path, atoms: str | None = None, record: bool = True,
                  runner=run_deck, probe_states: Collision | None = None, target: float = ACCURACY) -> CollisionResult:
    """Run one collision scene in ``out_dir`` and compare every sphere with its theory.

    A scene whose dt is the default first gets the step its accuracy needs
    (:func:`stepping.tune`; ``probe_states``: the states to probe with, if not its own;
    ``target``: the accuracy the probe's step is chosen for).
    ``atoms`` picks how the deck receives its spheres (:data:`decks.ATOM_ROUTES`); with
    ``record`` the run folder gets ``result.json`` (and, past INLINE_SPHERES spheres, the
    per-sphere table as ``result.parquet``). ``runner``: :func:`runner.run_deck` (in this
    process) or :func:`runner.run_deck_lmp` (the ``lmp`` executable).
    """
    scene, step = tune(scene, Path(out_dir) / "probe", _probe_errors, probe_states, target)
    deck = render_collision(scene, atoms)
    deck_path = prepare_run_dir(out_dir, deck)
    info = runner(deck_path, atoms=deck.atoms)
    if deck.dump is None:
        source = info.log
        frames = _memory_frames(info, scene.nsteps)
    else:
        source = deck_path.parent / deck.dump
        frames = _dump_frames(read_dump(source))
    initial, final = _collision_frames(scene, frames, source)
    columns = collision_table(scene, initial, final, as_frame=False)
    _check_finished(scene, columns, source)
    names = scene.state_names
    checks.add_row_checks(columns, names, scene.model)
    notes = checks.notes(columns["status"])
    m = scene.model
    table = pd.DataFrame(columns)
    dump_path = None if deck.dump is None else deck_path.parent / deck.dump
    result = CollisionResult(scene, table, info, dump_path, tuple(notes), step)
    if record:
        if m.normal_law.contact_radius:  # per sphere: the contact time and Omega depend on v_n
            tau = m.contact_times(scene.v_n).tolist()
            omega = choose.omega_per_sphere(m, scene.v_n).tolist()
        else:
            tau, omega = m.tau, m.Omega
        parameters = {"model": m.as_record(), "dt": scene.dt, "nsteps": scene.nsteps,
                      "tau": tau, "Omega": omega, "wall": wall_parameters(m),
                      "integrator": "rigid" if deck.rigid else "nve/sphere",
                      "atoms": "library" if deck.atoms is not None else ("data_file" if deck.files else "inline")}
        out = provenance(info, "collision", parameters)
        out["dump"] = None if dump_path is None else str(dump_path)
        out["warnings"] = list(notes)
        out["max_abs_error"] = result.max_abs_error
        out["step"] = step.record()
        out["status"] = checks.summary(table["status"])
        if scene.n <= INLINE_SPHERES:
            out["spheres"] = table.to_dict(orient="records")
        else:  # a JSON record per sphere would cost more than the run
            write_parquet_atomic(deck_path.parent / RESULT_TABLE, table)
            out["spheres"] = RESULT_TABLE
        write_atomic(deck_path.parent / "result.json", to_json(out))
    return result


@dataclass(frozen=True)
class FrozenResult:
    scene: Frozen
    table: pd.DataFrame
    info: RunInfo
    dump: Path

    @property
    def max_abs_error(self) -> float:
        t = self.table
        return float(
            max(np.max(np.abs(t["vt"] - t["vt_theory"])), np.max(np.abs(t["r_omega"] - t["r_omega_theory"])))
        )


def run_frozen(scene: Frozen, out_dir: Path) -> FrozenResult:
    """Run a frozen contact in ``out_dir`` and set its time series beside Eq. 10."""
    deck = render_frozen(scene)
    deck_path = prepare_run_dir(out_dir, deck)
    info = run_deck(deck_path)
    dump_path = deck_path.parent / deck.dump
    frames = read_dump(dump_path)
    _check_finite(frames, dump_path)
    expected = scene.nsteps // scene.every + 1
    if frames["step"].nunique() != expected or frames["step"].max() != scene.nsteps:
        raise ResultError(f"{dump_path}: expected {expected} frames ending at step {scene.nsteps}")
    table = frozen_table(scene, frames)
    if np.max(np.abs(table["z"] - scene.z)) > 1e-12 * max(1.0, scene.z):
        raise ResultError(f"{dump_path}: the sphere moved off its held height z = {scene.z!r}")
    return FrozenResult(scene, table, info, dump_path)


def frozen_metadata(result: FrozenResult) -> dict:
    scene = result.scene
    parameters = {"model": scene.model.as_record(), "z": scene.z, "v_t": scene.v_t,
                  "omega": scene.omega, "t_end": scene.nsteps * scene.dt, "dt": scene.dt,
                  "nsteps": scene.nsteps, "every": scene.every, "wall": wall_parameters(scene.model)}
    record = provenance(result.info, "frozen", parameters)
    record["dump"] = str(result.dump)
    record["max_abs_error"] = result.max_abs_error
    return record
