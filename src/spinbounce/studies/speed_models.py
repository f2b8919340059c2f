"""What each model costs in a sweep, measured side by side in one run (``spinbounce bench``).

For each model (the paper's, Coulomb friction in the plane and in 3-D, the Hertzian wall)
one sweep of the same sampled states runs on one core. Its wall time is split into LAMMPS
(the rest) and the theory columns (:func:`spinbounce.exact.choose.predict` timed again on
the same states); the share of the row checks (:mod:`spinbounce.checks`) and of the step
probes is reported, and the cost estimate that sizes cluster jobs
(:mod:`spinbounce.sweeps.cost`) stands beside the measured time. Ratios to the paper's
sweep carry the result: the machine is shared, so absolute rates drift.
"""

from __future__ import annotations

import shutil
import tempfile
import time
from pathlib import Path

from .. import checks
from ..fitting import model_of_group
from ..model import parameters
from ..scenes.collision import STATE_3D
from ..scenes.collision.scene import row_states
from ..exact import choose

__all__ = ["MODELS", "measure_models", "parallel_efficiency", "chunk_jobs"]

#: The models a sweep is measured for, with the states each samples.
PLANE = {"v_n": [-1.5, -0.1], "v_t": [-2.0, 2.0], "r_omega": [-2.0, 2.0]}
SPACE = {**PLANE, "v_s": [-2.0, 2.0], "r_omega_s": [-2.0, 2.0], "r_omega_n": [-2.0, 2.0]}
MODELS = {
    "frictionless": ({}, PLANE),
    "mu = 0.3 (2-D)": ({"mu": 0.3}, PLANE),
    "mu = 0.3 (3-D)": ({"mu": 0.3}, SPACE),
    "Hertz": ({"normal": "hertz"}, {**PLANE, "v_n": [-0.8, -0.1]}),
}


def _spec(n: int, model: dict, states: dict, seed: int):
    from ..sweeps import spec_from_dict

    raw = {"seed": seed, "chunk_size": n, "states": {"n": n, **states}}
    if model:
        raw["model"] = model
    return spec_from_dict(raw)


def _timed(action) -> float:
    started = time.perf_counter()
    action()
    return time.perf_counter() - started


def _theory_and_checks_seconds(rows) -> tuple[float, float]:
    """The sweep's theory columns and its row checks, timed again on its own rows."""
    names = [s for s in STATE_3D if f"{s}_initial" in rows]
    model = model_of_group({p.column: rows[p.column].iloc[0] for p in parameters.MODEL})
    initial = rows[[f"{s}_initial" for s in names]].to_numpy()
    columns = {c: rows[c].to_numpy() for c in rows.columns}
    return (_timed(lambda: choose.predict(model, initial)),
            _timed(lambda: checks.add_row_checks(columns, row_states(model, names, columns))))


def _one(name: str, n: int, seed: int, root: Path) -> dict:
    from ..sweeps import read_results, run_sweep
    from ..sweeps.cost import chunk_cost

    model, states = MODELS[name]
    spec = _spec(n, model, states, seed)
    started = time.perf_counter()
    run_sweep(spec, root / name.replace(" ", "_"), workers=1, log=lambda *_: None)
    wall = time.perf_counter() - started
    rows = read_results(root / name.replace(" ", "_"))
    theory, checking = _theory_and_checks_seconds(rows)
    return {"model": name, "collisions": n, "wall_seconds": wall, "theory_seconds": theory,
            "lammps_and_rest_seconds": wall - theory, "checks_seconds": checking,
            "steps_per_collision": int(rows["nsteps"].iloc[0]), "max_error": float(rows["error"].max()),
            "collisions_per_second": n / wall, "estimated_seconds": chunk_cost(spec, 0, n).seconds}


def measure_models(n: int = 100_000, n_hertz: int = 1_000, seed: int = 0, keep: Path | None = None,
                   log=lambda *_: None) -> dict:
    """Each model's sweep on one core; ratios of time per collision to the frictionless one."""
    root = Path(keep) if keep else Path(tempfile.mkdtemp(prefix="spinbounce-bench-models-"))
    try:
        out = []
        for name in MODELS:
            log(f"  sweep: {name}")
            out.append(_one(name, n_hertz if name == "Hertz" else n, seed, root))
    finally:
        if keep is None:
            shutil.rmtree(root, ignore_errors=True)
    base = out[0]["wall_seconds"] / out[0]["collisions"]
    for entry in out:
        entry["time_per_collision_over_frictionless"] = entry["wall_seconds"] / entry["collisions"] / base
        entry["checks_share"] = entry["checks_seconds"] / entry["wall_seconds"]
        entry["measured_over_estimated"] = entry["wall_seconds"] / entry["estimated_seconds"]
    return {"models": out}


def parallel_efficiency(n: int = 100_000, workers: int = 2, seed: int = 0) -> dict:
    """Collisions per second per core of a frictionless ``spinbounce sweep`` (a process of its
    own, as a user runs it) at one worker and at ``workers``, one chunk per worker; and the
    share of the wider run that is not the chunks' own work (start-up, import, pool)."""
    import subprocess
    import sys

    rates, walls = {}, {}
    with tempfile.TemporaryDirectory(prefix="spinbounce-bench-cores-") as folder:
        for count in (1, workers):
            argv = [sys.executable, "-m", "spinbounce.cli", "sweep", "--n", str(n), "--seed", str(seed),
                    "--chunk-size", str(max(1, -(-n // count))), "--workers", str(count),
                    "--out", str(Path(folder) / f"w{count}")]
            started = time.perf_counter()
            subprocess.run(argv, check=True, capture_output=True)
            walls[count] = time.perf_counter() - started
            rates[count] = n / walls[count] / count
    return {"workers": workers, "per_core_at_one": rates[1], "per_core_at_all": rates[workers],
            "efficiency": rates[workers] / rates[1], "wall_seconds": walls}


def chunk_jobs(n: int = 20_000, seed: int = 0) -> list[dict]:
    """A frictionless and a finite-mu chunk run as the cluster runs them (``spinbounce sweep
    SCENE --chunk 0`` in a process of its own), beside the estimate that sizes their jobs."""
    import subprocess
    import sys

    from ..sweeps.cost import chunk_cost

    out = []
    with tempfile.TemporaryDirectory(prefix="spinbounce-bench-jobs-") as folder:
        for name in ("frictionless", "mu = 0.3 (2-D)"):
            model, states = MODELS[name]
            spec = _spec(n, model, states, seed)
            scene = Path(folder) / f"{len(out)}.toml"
            scene.write_text(_toml(spec.raw))
            started = time.perf_counter()
            subprocess.run([sys.executable, "-m", "spinbounce.cli", "sweep", str(scene), "--chunk", "0",
                            "--out", str(Path(folder) / f"out{len(out)}")], check=True, capture_output=True)
            measured = time.perf_counter() - started
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
