"""Sweeps: many collisions, in chunks, in parallel, resumable, into one Parquet dataset.

A sweep is a scene file (TOML) or the same content from flags::

    seed = 1
    chunk_size = 25000          # spheres per LAMMPS run (the default)

    [model]                     # a number, or a list of numbers: a grid over groups
    kt = [1.0, 2.857142857142857]
    alpha = 0.4

    [states]                    # seeded uniform samples over [low, high] ...
    n = 100000
    v_n = [-1.5, -0.1]
    v_t = [-2.0, 2.0]
    r_omega = [-2.0, 2.0]       # or omega = [low, high]
    # tolerance = 1e-6 (top level) instead of model.dt: each chunk runs a ladder of steps,
    # extrapolated to dt = 0, and every row gets its error estimate (*_estimate columns)
    # instead of v_n and v_t: speed = [low, high] and angle_deg = [low, high], the
    # incidence angle from the wall's normal in degrees (v_n = -speed cos, v_t = speed sin)

    # ... or a grid: [states] mode = "grid" with lists of values (all combinations)

Every model group (one point of the model grid) gets the same sampled states. The output
folder holds ``sweep.json`` (the spec and its hash), ``chunks/chunk-GGGG-CCCCCC.parquet``
(the dataset: read it with ``pandas.read_parquet(OUT / "chunks")``) and ``runs/`` (each
chunk's deck, data file, dump and log). A chunk's Parquet file is written atomically and
only after its run has been checked, so a killed sweep rerun with the same command
recomputes exactly the chunks that have no file.
"""

from __future__ import annotations

import concurrent.futures
import dataclasses
import fcntl
import hashlib
import itertools
import json
import math
import multiprocessing
import os
import shutil
import sys
import time
import tomllib
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from . import __version__
from .model.scenes import Collision, ContactModel, SceneError

__all__ = ["SweepError", "SweepSpec", "load_spec", "spec_from_dict", "run_sweep", "run_one_chunk", "chunk_table",
           "chunk_path", "read_results"]

MODEL_KEYS = ("m", "r", "alpha", "kn", "kt", "kt_over_kn", "gamma_n", "gamma_t", "mu", "dt")
STATE_KEYS = ("v_n", "v_t", "speed", "angle_deg", "omega", "r_omega",
              "v_s", "omega_s", "r_omega_s", "omega_n", "r_omega_n")
#: Optional out-of-plane states (3-D): each given as an angular velocity or times r.
EXTRA_KEYS = (("v_s",), ("omega_s", "r_omega_s"), ("omega_n", "r_omega_n"))
#: The two ways to give the velocity: components, or speed and incidence angle (degrees
#: from the wall's normal; positive angles give v_t > 0). Spin: omega or r_omega.
VELOCITY_KEYS = {"components": ("v_n", "v_t"), "polar": ("speed", "angle_deg")}
TOP_KEYS = ("name", "seed", "chunk_size", "tolerance", "model", "states")
DEFAULT_CHUNK = 25_000


class SweepError(ValueError):
    """A sweep cannot start: a bad scene file, or an output folder that is not ours."""


def _fail(key: str, value, why: str):
    raise SweepError(f"{key} = {value!r}: {why}")


def _number(key: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        _fail(key, value, "must be a number")
    if not math.isfinite(value):
        _fail(key, value, "must be finite")
    return float(value)


def _numbers(key: str, value) -> list[float]:
    values = value if isinstance(value, list) else [value]
    if not values:
        _fail(key, value, "is an empty list")
    return [_number(key, v) for v in values]


def _integer(key: str, value, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        _fail(key, value, "must be a whole number")
    if value < low:
        _fail(key, value, f"must be >= {low}")
    return value


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: model groups and the initial states each of them runs."""

    raw: dict
    groups: tuple[dict, ...]
    seed: int
    chunk_size: int
    mode: str
    n: int
    states: dict
    tolerance: float | None = None

    @property
    def digest(self) -> str:
        return hashlib.sha256(json.dumps(self.raw, sort_keys=True).encode()).hexdigest()[:16]

    def model(self, group: int) -> tuple[ContactModel, float | None]:
        params = dict(self.groups[group])
        dt = params.pop("dt", None)
        return ContactModel(**params), dt

    def initial_states(self, group: int, start: int = 0, stop: int | None = None) -> np.ndarray:
        """States (v_n, v_t, omega) of rows [start, stop), then (v_s, omega_s, omega_n) for a
        3-D sweep: the same for every group, set by the seed.

        Random states are three seeded uniform columns of n draws each; a chunk's rows are
        drawn alone by jumping the generator ahead (one 64-bit draw per number), so a
        chunk costs the same whatever its place in a long sweep.
        """
        s = self.states
        stop = self.n if stop is None else stop
        axes = [s["a"], s["b"], s["spin"]] + [s[key] for key in s["extra"]]
        if self.mode == "grid":
            arr = np.array(list(itertools.product(*axes)), dtype=float)[start:stop]
        else:
            columns = []
            for k, (lo, hi) in enumerate(axes):
                bits = np.random.PCG64(self.seed)
                bits.advance(k * self.n + start)
                columns.append(np.random.Generator(bits).uniform(lo, hi, stop - start))
            arr = np.column_stack(columns)
        if s["velocity"] == "polar":
            speed, angle = arr[:, 0], np.radians(arr[:, 1])
            arr[:, 0], arr[:, 1] = -speed * np.cos(angle), speed * np.sin(angle)
        if s["spin_key"] == "r_omega":
            arr[:, 2] = arr[:, 2] / self.groups[group]["r"]
        for k, key in enumerate(s["extra"], start=3):
            if key.startswith("r_"):
                arr[:, k] = arr[:, k] / self.groups[group]["r"]
        return arr

    def normal_speeds(self) -> tuple[float, float]:
        """The fastest and the slowest |v_n| the states can reach (sampled ranges: their bounds)."""
        s = self.states
        if s["velocity"] == "components":
            vn = np.abs(np.asarray(s["a"]))
            return float(vn.max()), float(vn.min())
        speed, angle = np.asarray(s["a"]), np.asarray(s["b"])
        cos = np.cos(np.radians(angle))
        top = 1.0 if (self.mode == "random" and angle[0] <= 0.0 <= angle[1]) or 0.0 in angle else cos.max()
        return float(speed.max() * top), float(speed.min() * cos.min())

    def chunks(self) -> list[tuple[int, int, int, int]]:
        """(group, chunk, start, stop) for every chunk, in order."""
        out = []
        for g in range(len(self.groups)):
            for c, start in enumerate(range(0, self.n, self.chunk_size)):
                out.append((g, c, start, min(start + self.chunk_size, self.n)))
        return out


def load_spec(path: Path) -> SweepSpec:
    path = Path(path)
    try:
        raw = tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise SweepError(f"scene file {path} does not exist") from None
    except tomllib.TOMLDecodeError as exc:
        raise SweepError(f"{path}: not valid TOML: {exc}") from None
    return spec_from_dict(raw)


def spec_from_dict(raw: dict) -> SweepSpec:
    """Validate a sweep description; every error names the key and its value."""
    for key in raw:
        if key not in TOP_KEYS:
            _fail(key, raw[key], f"unknown key (allowed: {', '.join(TOP_KEYS)})")
    seed = _integer("seed", raw.get("seed", 0), 0)
    chunk_size = _integer("chunk_size", raw.get("chunk_size", DEFAULT_CHUNK), 1)
    tolerance = raw.get("tolerance")
    if tolerance is not None:
        from .studies.tolerance import check_tolerance

        tolerance = _number("tolerance", tolerance)
        try:
            check_tolerance(tolerance)
        except SceneError as exc:
            raise SweepError(str(exc)) from None
        if "dt" in raw.get("model", {}):
            _fail("tolerance", tolerance, "give model.dt or tolerance, not both: a tolerance chooses the steps")
    model = raw.get("model", {})
    if not isinstance(model, dict):
        _fail("model", model, "must be a table")
    for key in model:
        if key not in MODEL_KEYS:
            _fail(f"model.{key}", model[key], f"unknown key (allowed: {', '.join(MODEL_KEYS)})")
    if "kt" in model and "kt_over_kn" in model:
        _fail("model.kt_over_kn", model["kt_over_kn"], "give kt or kt_over_kn, not both")
    axes = {key: _numbers(f"model.{key}", value) for key, value in model.items()}
    names = list(axes)
    defaults = dataclasses.asdict(ContactModel())
    groups = []
    for combo in itertools.product(*(axes[k] for k in names)):
        params = {**defaults, **dict(zip(names, combo, strict=True))}
        if "kt_over_kn" in params:
            params["kt"] = params.pop("kt_over_kn") * params["kn"]
        groups.append(params)

    states = raw.get("states")
    if not isinstance(states, dict):
        _fail("states", states, "a [states] table is required")
    mode = states.get("mode", "random")
    if mode not in ("random", "grid"):
        _fail("states.mode", mode, 'must be "random" or "grid"')
    allowed = ("mode", "n", *STATE_KEYS) if mode == "random" else ("mode", *STATE_KEYS)
    for key in states:
        if key not in allowed:
            _fail(f"states.{key}", states[key], f"unknown key for mode {mode!r} (allowed: {', '.join(allowed)})")
    if "omega" in states and "r_omega" in states:
        _fail("states.r_omega", states["r_omega"], "give omega or r_omega, not both")
    if any(k in states for k in VELOCITY_KEYS["polar"]):
        if any(k in states for k in VELOCITY_KEYS["components"]):
            _fail("states.speed", states.get("speed"), "give v_n and v_t, or speed and angle_deg, not both")
        velocity = "polar"
    else:
        velocity = "components"
    spin_key = "r_omega" if "r_omega" in states else "omega"
    parsed = {"spin_key": spin_key, "velocity": velocity}
    first, second = VELOCITY_KEYS[velocity]
    parsed["extra"] = []
    if any(k in states for keys in EXTRA_KEYS for k in keys):  # 3-D: every out-of-plane axis
        for keys in EXTRA_KEYS:
            given = [k for k in keys if k in states]
            if len(given) != 1:
                _fail(f"states.{keys[0]}", states.get(keys[0]),
                      f"a 3-D sweep needs exactly one of {' or '.join(keys)}")
            parsed["extra"].append(given[0])
        if tolerance is not None:
            _fail("tolerance", tolerance, "is for the paper's plane only: a 3-D sweep takes model.dt or the default")
    for key, target in ((first, "a"), (second, "b"), (spin_key, "spin"), *((k, k) for k in parsed["extra"])):
        if key not in states:
            _fail(f"states.{key}", None, "is required")
        values = _numbers(f"states.{key}", states[key])
        if mode == "random":
            if len(values) != 2:
                _fail(f"states.{key}", states[key], "must be a range [low, high]")
            if not values[0] < values[1]:
                _fail(f"states.{key}", states[key], "is an empty range: low must be below high")
        parsed[target] = values
    if velocity == "polar":
        if min(parsed["a"]) <= 0.0:
            _fail("states.speed", states["speed"], "must be > 0")
        if max(abs(a) for a in parsed["b"]) >= 90.0:
            _fail("states.angle_deg", states["angle_deg"], "must lie in (-90, 90): 90 degrees never meets the wall")
    if mode == "random":
        n = _integer("states.n", states.get("n", 0), 1)
    else:
        n = math.prod(len(parsed[k]) for k in ("a", "b", "spin", *parsed["extra"]))
    spec = SweepSpec(raw=raw, groups=tuple(groups), seed=seed, chunk_size=chunk_size, tolerance=tolerance,
                     mode=mode, n=n, states=parsed)
    _check_physics(spec)
    return spec


def _check_physics(spec: SweepSpec) -> None:
    """Build every group's model and its most demanding collision now, before any run."""
    fast, slow = spec.normal_speeds()
    key_vn = "states.v_n" if spec.states["velocity"] == "components" else "states.speed"
    for g in range(len(spec.groups)):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                model, dt = spec.model(g)
        except SceneError as exc:
            key = "model.kt_over_kn" if exc.parameter == "kt" and "kt_over_kn" in spec.raw.get("model", {}) else f"model.{exc.parameter}"
            raise SweepError(f"{key}: {exc}") from None
        try:
            Collision(model, v_n=[-fast, -slow], v_t=0.0, omega=0.0, dt=dt)
        except SceneError as exc:
            key = key_vn if exc.parameter.startswith("v_n") else f"model.{exc.parameter}"
            raise SweepError(f"{key}: {exc}") from None


# ---------------------------------------------------------------------------------------
# Running
# ---------------------------------------------------------------------------------------

def chunk_path(out: Path, group: int, chunk: int) -> Path:
    return out / "chunks" / f"chunk-{group:04d}-{chunk:06d}.parquet"


def run_chunk(raw: dict, out: str, group: int, chunk: int, start: int, stop: int) -> tuple[int, float, float]:
    """Run one chunk and write its Parquet file atomically.

    Returns (collisions, seconds in this call, seconds in LAMMPS's run loop). The spheres
    reach LAMMPS in memory (the library route): no data file to write, no dump to parse.
    """
    from .pipeline import run_collision  # keeps a parent process free of LAMMPS
    from .records import write_parquet_atomic

    started = time.perf_counter()
    spec = spec_from_dict(raw)
    out = Path(out)
    model, dt = spec.model(group)
    states = spec.initial_states(group, start, stop)
    extra = dict(zip(("v_s", "omega_s", "omega_n"), states[:, 3:].T, strict=False))
    scene = Collision(model, v_n=states[:, 0], v_t=states[:, 1], omega=states[:, 2], dt=dt, **extra)
    run_dir = out / "runs" / f"chunk-{group:04d}-{chunk:06d}"
    if run_dir.exists():
        shutil.rmtree(run_dir)  # a killed earlier attempt
    n = stop - start
    columns = {"group": np.full(n, group), "chunk": np.full(n, chunk), "index": np.arange(start, stop)}
    if spec.tolerance is None:
        result = run_collision(scene, run_dir, atoms="library", record=False)
        columns.update({name: values.to_numpy() for name, values in result.table.drop(columns=["id"]).items()})
        dt, nsteps, loop = scene.dt, scene.nsteps, result.info.loop_seconds
    else:  # a ladder of runs per chunk, extrapolated; each row carries its error estimate
        from .studies.tolerance import collide_to_tolerance, collision_frame

        extrapolated, finest = collide_to_tolerance(model, scene.v_n, scene.v_t, scene.omega, spec.tolerance,
                                                    run_dir)
        columns.update({name: values.to_numpy() for name, values in collision_frame(extrapolated, finest).items()})
        columns["omega_0"] = np.asarray(scene.omega)
        columns["tolerance"] = np.full(n, spec.tolerance)
        dt, nsteps = finest.dt, extrapolated.steps
        loop = sum(level["loop_seconds"] for level in extrapolated.levels)
    for key, value in dataclasses.asdict(model).items():
        columns[key] = np.full(n, np.nan if value is None else value)
    columns["dt"] = np.full(n, dt)  # with a tolerance: the finest run's
    columns["nsteps"] = np.full(n, nsteps)  # with a tolerance: all runs' steps together
    columns["Omega_theory"] = np.full(n, model.Omega)
    from .lammps.runner import lammps_version

    labels = {"scene_hash": spec.digest, "lammps_version": lammps_version(), "spinbounce_version": __version__}
    write_parquet_atomic(chunk_path(out, group, chunk), _arrow_table(columns, labels))
    return stop - start, time.perf_counter() - started, loop


def _arrow_table(columns: dict[str, np.ndarray], labels: dict[str, str]):
    """Numeric columns as they are, and constant text labels dictionary-encoded (one copy)."""
    import pyarrow as pa

    n = len(columns["index"])
    arrays = {name: pa.array(values) for name, values in columns.items()}
    for name, text in labels.items():
        arrays[name] = pa.DictionaryArray.from_arrays(pa.array(np.zeros(n, dtype=np.int32)), pa.array([text]))
    return pa.table(arrays)


class _Lock:
    """A lock on a file in the output folder, released by the OS even on kill -9.

    A whole sweep holds the folder's lock exclusively; single-chunk jobs (``--chunk``, as
    a workflow engine runs them) share it and each holds its own chunk's lock exclusively.
    """

    def __init__(self, path: Path, shared: bool = False, what: str = "another sweep is writing into this folder"):
        self.path, self.shared, self.what = path, shared, what

    def __enter__(self):
        self.handle = open(self.path, "a")
        try:
            fcntl.flock(self.handle, (fcntl.LOCK_SH if self.shared else fcntl.LOCK_EX) | fcntl.LOCK_NB)
        except BlockingIOError:
            self.handle.close()
            raise SweepError(f"{self.path.parent}: {self.what}") from None
        return self

    def __exit__(self, *exc):
        fcntl.flock(self.handle, fcntl.LOCK_UN)
        self.handle.close()


def _progress(total: int, done: int):
    try:
        from tqdm import tqdm
    except ImportError:  # pragma: no cover - tqdm is a dependency
        return None
    return tqdm(total=total, initial=done, unit="coll", unit_scale=True, dynamic_ncols=True,
                disable=not sys.stderr.isatty(), desc="collisions")


def _claim(out: Path, spec: SweepSpec) -> None:
    """Record the sweep in ``out/sweep.json``, or refuse a folder that holds another sweep."""
    from .records import to_json, write_atomic

    record = out / "sweep.json"
    if record.exists():
        previous = json.loads(record.read_text())
        if previous.get("scene_hash") != spec.digest:
            raise SweepError(
                f"{out} holds sweep {previous.get('scene_hash')}, not this one ({spec.digest}): use another --out"
            )
    else:
        write_atomic(record, to_json({"scene_hash": spec.digest, "spec": spec.raw, "spinbounce_version": __version__}))


def run_sweep(spec: SweepSpec, out: Path, workers: int | None = None, log=print) -> Path:
    """Run every chunk that has no Parquet file yet; return the dataset folder."""
    out = Path(out)
    (out / "chunks").mkdir(parents=True, exist_ok=True)
    with _Lock(out / ".lock"):
        _claim(out, spec)
        todo = [c for c in spec.chunks() if not chunk_path(out, c[0], c[1]).exists()]
        total = spec.n * len(spec.groups)
        done = total - sum(stop - start for _, _, start, stop in todo)
        if done:
            log(f"resuming: {done} of {total} collisions already done")
        workers = max(1, min(workers or os.cpu_count() or 1, len(todo) or 1))
        bar = _progress(total, done)
        if workers == 1:  # no pool: one process start fewer, and plain tracebacks
            for c in todo:
                n, *_ = run_chunk(spec.raw, str(out), *c)
                if bar is not None:
                    bar.update(n)
        else:
            context = multiprocessing.get_context("spawn")
            with concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=context) as pool:
                futures = [pool.submit(run_chunk, spec.raw, str(out), *c) for c in todo]
                try:
                    for future in concurrent.futures.as_completed(futures):
                        n, *_ = future.result()
                        if bar is not None:
                            bar.update(n)
                except BaseException:
                    for f in futures:
                        f.cancel()
                    raise
        if bar is not None:
            bar.close()
    return out / "chunks"


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
    (out / "chunks").mkdir(parents=True, exist_ok=True)
    final = chunk_path(out, group, chunk)
    with _Lock(out / ".lock", shared=True, what="a whole sweep is writing into this folder"):
        with _Lock(out / "chunks" / f".{final.stem}.lock", what=f"chunk {k} is already being run"):
            _claim(out, spec)
            if final.exists():
                log(f"chunk {k} is already done: {final}")
            else:
                run_chunk(spec.raw, str(out), group, chunk, start, stop)
    return final


def chunk_table(spec: SweepSpec, out: Path | None = None) -> list[dict]:
    """Every chunk: its number k, model group, index within the group, row range and file."""
    rows = []
    for k, (group, chunk, start, stop) in enumerate(spec.chunks()):
        row = {"k": k, "group": group, "chunk": chunk, "start": start, "stop": stop,
               "path": str(chunk_path(Path("."), group, chunk))}
        if out is not None:
            row["done"] = chunk_path(Path(out), group, chunk).exists()
        rows.append(row)
    return rows


def read_results(path: Path) -> pd.DataFrame:
    """A sweep's rows, from its output folder or its ``chunks`` dataset folder."""
    path = Path(path)
    if (path / "chunks").is_dir():
        path = path / "chunks"
    files = sorted(path.glob("chunk-*.parquet")) if path.is_dir() else [path]
    if not files:
        raise SweepError(f"{path}: no chunk files")
    return pd.concat([pd.read_parquet(f) for f in files], ignore_index=True)
