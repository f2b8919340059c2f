"""Running a sweep: chunks in parallel, resumable, into one Parquet dataset.

The output folder holds ``sweep.json`` (the spec and its digest),
``chunks/chunk-GGGG-CCCCCC.parquet`` (the dataset: read it with :func:`read_results`) and
``runs/`` (each chunk's deck and log). A chunk's Parquet file is written atomically and
only after its run has been checked, so a killed sweep rerun with the same command
recomputes exactly the chunks that have no file.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import gc
import json
import math
import os
import shutil
import sys
import time
from pathlib import Path

import numpy as np

from .. import __version__
from .. import workers as workers_
from ..records import TEMP_SUFFIX
from ..model import parameters
from ..scenes.collision import Collision, scaled_contact_time
from ..stepping import PROBE_SPHERES
from ..exact import choose
from .ladder import estimate_columns, extrapolates, ladder_columns, tolerance_of
from .spec import SweepError, SweepSpec, spec_from_dict

__all__ = ["run_sweep", "run_one_chunk", "chunk_table", "chunk_path", "run_chunk", "write_chunk", "spread_over",
           "missing_chunks"]


def chunk_path(out: Path, group: int, chunk: int) -> Path:
    return out / "chunks" / f"chunk-{group:04d}-{chunk:06d}.parquet"


def missing_chunks(spec: SweepSpec, out: Path) -> list[tuple[int, int, int, int]]:
    """The sweep's chunks (:meth:`SweepSpec.chunks`) that have no file in ``out`` yet."""
    return [c for c in spec.chunks() if not chunk_path(out, c[0], c[1]).exists()]


def run_chunk(raw: dict | SweepSpec, out: str, group: int, chunk: int, start: int, stop: int,
              write=None) -> tuple[int, float, float]:
    """Run one chunk of the sweep ``raw`` (its description, as a worker process receives it, or the
    spec itself) and write its Parquet file atomically (``write(path, columns, labels)``: by default
    :func:`write_chunk`, now).

    Returns (collisions, seconds in this call, seconds in LAMMPS's run loop). The wall's
    spheres reach LAMMPS in memory (the library route): no data file to write, no dump to
    parse; a pair scene's chunk is one pair batch (:func:`spinbounce.sweeps.pairs.pair_chunk`).
    """
    started = time.perf_counter()
    with _heap_frozen():
        return _run_chunk(raw, out, group, chunk, start, stop, write, started)


@contextlib.contextmanager
def _heap_frozen():
    """What the process held before a chunk kept out of Python's cycle collections during it (gc.freeze): a
    chunk builds tens of thousands of small objects (a pair chunk's pairs, keys and outcomes), and each full
    collection would scan the whole heap again meanwhile (0.2 to 0.4 s of a 20,000-pair chunk's 1.4 s). The
    chunk's own cycles (scipy's, a pair solved one at a time) are collected as usual; all is given back after."""
    gc.freeze()
    try:
        yield
    finally:
        gc.unfreeze()


def _run_chunk(raw, out: str, group: int, chunk: int, start: int, stop: int, write, started: float):
    from ..records import lammps_version

    spec = raw if isinstance(raw, SweepSpec) else _spec_of(raw)
    out = Path(out)
    model, dt = spec.model(group)
    states = spec.initial_states(group, start, stop)
    run_dir = out / "runs" / f"chunk-{group:04d}-{chunk:06d}"
    if run_dir.exists():
        shutil.rmtree(run_dir)  # a killed earlier attempt
    n = stop - start
    columns = {"group": np.full(n, group), "chunk": np.full(n, chunk), "index": np.arange(start, stop)}
    # a default step is probed with the group's first rows: every chunk of a group gets the same step
    probe = spec.initial_states(group, 0, min(spec.n, PROBE_SPHERES))
    if spec.scene == "pair":  # sphere b instead of the wall: the wall's columns and both spheres'
        from .pairs import pair_chunk

        pair_columns, dt, nsteps, loop = pair_chunk(model, spec.sphere_b(group), states, dt, run_dir, probe)
        columns.update(pair_columns)
    else:
        dt, nsteps, loop = _wall_columns(columns, spec, model, dt, states, probe, run_dir, tolerance_of(spec, group))
    labels = _model_columns(columns, model, n)
    columns["dt"] = np.full(n, dt)  # the group's step; with a tolerance: the finest run's
    columns["nsteps"] = np.full(n, nsteps)  # with a tolerance or a pair's ladder: all of the row's runs' steps
    if spec.scene == "pair":
        labels.update(_pair_columns(columns, spec, group, model, n))
    else:
        columns["Omega_theory"] = choose.omega_per_sphere(model, states[:, 0])  # NaN where none (Coulomb)
        labels["theory"] = choose.which(model).kind
    labels.update({"scene_hash": spec.digest, "lammps_version": lammps_version(), "spinbounce_version": __version__})
    (write or write_chunk)(chunk_path(out, group, chunk), columns, labels)
    return stop - start, time.perf_counter() - started, loop


#: The last sweep description a worker process validated, by its JSON text: {text: spec}.
_PARSED: dict[str, SweepSpec] = {}


def _spec_of(raw: dict) -> SweepSpec:
    """The description's spec, validated once per worker process and sweep (each chunk a worker runs
    arrives as the same description)."""
    try:
        key = json.dumps(raw, sort_keys=True)
    except TypeError:  # not JSON (an API caller's own objects): validated each time
        return spec_from_dict(raw)
    if key not in _PARSED:
        _PARSED.clear()
        _PARSED[key] = spec_from_dict(raw)
    return _PARSED[key]


def _wall_columns(columns: dict, spec: SweepSpec, model, dt, states: np.ndarray, probe: np.ndarray,
                  run_dir: Path, tolerance: float | None):
    """Run a wall chunk of ``states``, its rows into ``columns``; (dt, steps, LAMMPS loop seconds). A
    time-scaled batch's rows each ran at dt/time_scale in their own time (Collision.row_dt): the
    ``time_scale`` column. ``tolerance``: a ladder of runs extrapolated to it instead (:mod:`.ladder`)."""
    from ..pipeline import run_scene

    # at the default step a batch of Hertzian speeds is time-scaled: every chunk of the group and
    # its probe to the slowest possible sphere's contact, so that one step ends them all mid-step
    scaled_to = scaled_contact_time(model, -np.array(spec.normal_speeds())) if dt is None else None

    def batch(rows):  # rows (v_n, v_t, omega[, v_s, omega_s, omega_n])
        return Collision(model, v_n=rows[:, 0], v_t=rows[:, 1], omega=rows[:, 2], dt=dt,
                         deck_contact_time=scaled_to,
                         **dict(zip(("v_s", "omega_s", "omega_n"), rows[:, 3:].T, strict=False)))

    scene = batch(states)
    # a ladder of runs per chunk, extrapolated, each row with its error estimate; a damped default whose
    # ladder fails (a rung too coarse) is one probed run instead
    laddered = None if tolerance is None else ladder_columns(scene, tolerance, run_dir, spec.tolerance is None)
    if laddered is not None:
        columns.update(laddered[0])
        columns["time_scale"] = np.ones(scene.n)
        return laddered[1:]
    result = run_scene(scene, run_dir, atoms="library", record=False, probe_states=batch(probe))
    columns.update({name: np.asarray(values) for name, values in result.columns.items() if name != "id"})
    columns["time_scale"] = result.scene.time_scales
    if extrapolates(spec):  # another group's chunks carry estimates: the same columns here
        columns.update(estimate_columns(scene.state_names, scene.n))
    return result.scene.dt, result.scene.nsteps, result.info.loop_seconds


def _model_columns(columns: dict, model, n: int) -> dict[str, str]:
    """Every declared model parameter as a column (none as the parameter's none_value: mu inf,
    others NaN); text ones as labels."""
    labels = {}
    for p in parameters.MODEL:
        value = getattr(model, p.name)
        if p.kind == "choice":
            labels[p.column] = value
        else:
            columns[p.column] = np.full(n, p.to_column(value))
    return labels


def _pair_columns(columns: dict, spec: SweepSpec, group: int, model, n: int) -> dict[str, str]:
    """A pair group's scene columns (sphere b's, and the pair's Omega); its labels."""
    from ..scenes.pair.kind import no_planar_matrix, planar_Omega, theory_kind

    for name in parameters.PAIR_SPHERE:
        columns[parameters.by_name(name).column] = np.full(n, spec.groups[group][name])
    # the planar theory's Omega (the wall's at equal alpha); none for a law on the contact radius
    radial = no_planar_matrix(model.replace(mu=None)) is not None
    columns["Omega_theory"] = np.full(n, np.nan if radial else planar_Omega(model, spec.sphere_b(group)))
    return {"scene": "pair", "theory": theory_kind(model)}


def write_chunk(path: Path, columns: dict[str, np.ndarray], labels: dict[str, str]) -> Path:
    """A chunk's columns and labels as its Parquet file, atomically."""
    from ..records import arrow_table, write_parquet_atomic

    return write_parquet_atomic(path, arrow_table(columns, labels))


def _lock(path: Path, shared: bool = False, what: str = "another sweep is writing into this folder"):
    """A lock on a file in the output folder, refused at once when held (:func:`~spinbounce.records.locked`).

    A whole sweep holds the folder's lock exclusively; single-chunk jobs (``--chunk``, as
    a workflow engine runs them) share it and each holds its own chunk's lock exclusively.
    """
    from ..records import locked

    return locked(path, shared, busy=SweepError(f"{path.parent}: {what}"))


def _claim(out: Path, spec: SweepSpec) -> None:
    """Record the sweep in ``out/sweep.json``, or refuse a folder that holds another sweep."""
    from ..records import to_json, write_atomic

    if not _check_earlier(out, spec):
        write_atomic(out / "sweep.json",
                     to_json({"scene_hash": spec.digest, "spec": spec.raw, "spinbounce_version": __version__}))


def _check_earlier(out: Path, spec: SweepSpec) -> bool:
    """Whether ``out`` holds this sweep begun earlier (its record readable, its chunks resumable); a
    folder holding another sweep, or a broken record or chunk, is refused. Reads only."""
    from ..records import read_json

    record = out / "sweep.json"
    if not record.exists():
        if any((out / "chunks").glob("chunk-*.parquet")):
            raise SweepError(f"{out} holds chunk files but no sweep record (sweep.json): not a sweep this one can "
                             "resume; use another --out")
        return False
    previous = read_json(record, "sweep record")
    if previous.get("scene_hash") != spec.digest:
        raise SweepError(f"{out} holds sweep {previous.get('scene_hash')}, not this one ({spec.digest}): "
                         "use another --out")
    _check_columns(out, spec)
    return True


def _check_columns(out: Path, spec: SweepSpec) -> None:
    """Refuse to resume into chunks whose columns this version would not write the same (a damped sweep
    begun before a damped default carried error estimates): a dataset reads the first file's columns."""
    import pyarrow.parquet as pq

    written = next(iter(sorted((out / "chunks").glob("chunk-*.parquet"))), None)
    if written is None:
        return
    try:
        names = pq.read_schema(written).names
    except (OSError, ValueError) as exc:  # pyarrow's errors for a corrupt or foreign file
        raise SweepError(f"{written}: not a readable sweep chunk ({exc}): remove it to run that chunk again, "
                         "or sweep into another --out") from None
    if extrapolates(spec) != ("tolerance" in names):
        raise SweepError(f"{out} holds chunks of this sweep written by an earlier spinbounce, with other columns "
                         "(a damped default's estimates): sweep into another --out")


def run_sweep(spec: SweepSpec, out: Path, workers: int | None = None, log=print) -> Path:
    """Run every chunk that has no Parquet file yet; return the dataset folder. A sweep that
    fails or is stopped before its first chunk is written removes the folder it made."""
    out = Path(out)
    made = not out.exists()
    _check_earlier(out, spec)  # before anything is written: a broken or foreign folder is left as it was
    (out / "chunks").mkdir(parents=True, exist_ok=True)
    try:
        return _run_chunks(spec, out, workers, log)
    except BaseException:
        if made and not any((out / "chunks").glob("*.parquet")):
            shutil.rmtree(out, ignore_errors=True)
        raise


def _run_chunks(spec: SweepSpec, out: Path, workers: int | None, log) -> Path:
    from tqdm import tqdm

    with _lock(out / ".lock"):
        _claim(out, spec)
        for stale in (out / "chunks").glob(f".chunk-*{TEMP_SUFFIX}"):  # a killed writer's; no one writes now
            stale.unlink(missing_ok=True)
        todo = missing_chunks(spec, out)
        total = spec.n * len(spec.groups)
        done = total - sum(stop - start for _, _, start, stop in todo)
        if done:
            log(f"resuming: {done} of {total} collisions already done")
        workers = max(1, min(workers or workers_.cores(), len(todo) or 1))
        bar = tqdm(total=total, initial=done, unit="coll", unit_scale=True, dynamic_ncols=True,
                   disable=not sys.stderr.isatty(), desc="collisions")
        if workers == 1:  # no pool: one process start fewer, and plain tracebacks
            _run_in_turn(spec, out, todo, bar)
        else:
            with concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=workers_.context(),
                                                        initializer=workers_.die_with_parent,
                                                        initargs=(os.getpid(),)) as pool:
                with workers_.main_unseen():  # the workers start as the chunks are submitted
                    futures = [pool.submit(run_chunk, spec.raw, str(out), *c) for c in todo]
                try:
                    for future in concurrent.futures.as_completed(futures):
                        n, *_ = future.result()
                        bar.update(n)
                except BaseException:
                    for f in futures:  # the chunks not started are dropped; those running finish
                        f.cancel()  # and write their files whole (the workers ignore Ctrl-C)
                    raise
        bar.close()
    return out / "chunks"


def _run_in_turn(spec: SweepSpec, out: Path, todo: list, bar) -> None:
    """The chunks one after the other in this process, each one's columns made into its file by a
    thread while the next one runs (LAMMPS and the Parquet writer both release the GIL); a failed
    write stops the sweep at the next chunk, and every write has ended when this returns."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=1, thread_name_prefix="chunk-writer") as writer:
        pending: list[concurrent.futures.Future] = []

        def write(path, columns, labels):  # absolute now: a LAMMPS run changes the working folder meanwhile
            pending.append(writer.submit(write_chunk, Path(path).absolute(), columns, labels))

        try:
            for c in todo:
                n, *_ = run_chunk(spec, str(out), *c, write=write)
                for done in [f for f in pending if f.done()]:
                    done.result()  # raises a failed write's error here
                    pending.remove(done)
                bar.update(n)
        except BaseException as exc:  # a write that failed meanwhile is told too, not lost
            for f in pending:
                if f.exception() is not None:
                    exc.add_note(f"a chunk's file was not written either: {f.exception()}")
            raise
        for f in pending:
            f.result()


def spread_over(spec: SweepSpec, workers: int, out: Path) -> SweepSpec:
    """The sweep with chunks enough for ``workers`` workers to be busy, where it has fewer and no chunk
    size was given (each group cut into equal chunks); a sweep begun in ``out`` keeps the chunks it began
    with, whatever ``workers`` is now (its record's description, when it is this one but for them)."""
    from ..records import read_json

    if spec.chunk_size is not None:
        return spec
    record = Path(out) / "sweep.json"
    if record.exists():
        begun = read_json(record, "sweep record").get("spec")
        if isinstance(begun, dict) and _but_chunking(begun) == _but_chunking(spec.raw):
            return spec_from_dict(begun)
        return spec
    if workers <= 1 or len(spec.chunks()) >= workers:
        return spec
    pieces = math.ceil(workers / len(spec.groups))
    return spec_from_dict({**spec.raw, "chunk_size": min(min(spec.chunk_sizes), math.ceil(spec.n / pieces))})


def _but_chunking(raw: dict) -> str:
    return json.dumps({k: v for k, v in raw.items() if k != "chunk_size"}, sort_keys=True, default=str)


def run_one_chunk(spec: SweepSpec, out: Path, k: int, log=print) -> Path:
    """Run chunk number ``k`` (in :meth:`SweepSpec.chunks` order) alone, in this process.

    Several such jobs may write into one folder at once (a workflow engine's chunk jobs);
    a whole sweep into that folder is refused meanwhile. A chunk already written is kept.
    """
    out = Path(out)
    chunks = spec.chunks()
    if not 0 <= k < len(chunks):
        raise SweepError(f"chunk = {k}: must lie in [0, {len(chunks) - 1}] for this sweep ({len(chunks)} chunks)")
    group, chunk, start, stop = chunks[k]
    _check_earlier(out, spec)  # before anything is written: a broken or foreign folder is left as it was
    (out / "chunks").mkdir(parents=True, exist_ok=True)
    final = chunk_path(out, group, chunk)
    with _lock(out / ".lock", shared=True, what="a whole sweep is writing into this folder"):
        with _lock(out / "chunks" / f".{final.stem}.lock", what=f"chunk {k} is already being run"):
            _claim(out, spec)
            if final.exists():
                log(f"chunk {k} is already done: {final}")
            else:
                run_chunk(spec.raw, str(out), group, chunk, start, stop)
    return final


def chunk_table(spec: SweepSpec, out: Path | None = None) -> list[dict]:
    """Every chunk: its number k, model group, index within the group, row range and file."""
    return [{"k": k, "group": group, "chunk": chunk, "start": start, "stop": stop,
             "path": str(chunk_path(Path("."), group, chunk)),
             **({} if out is None else {"done": chunk_path(Path(out), group, chunk).exists()})}
            for k, (group, chunk, start, stop) in enumerate(spec.chunks())]
