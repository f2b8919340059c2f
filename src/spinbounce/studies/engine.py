"""What a user waits for, beside what LAMMPS itself takes (``spinbounce bench``, ``bench --quick``).

* :func:`scene_sweeps`: one sweep per scene a user runs (the wall, damped, Hertzian and
  Hertz-Mindlin walls, two free spheres, a Coulomb-capped pair), each end to end on one worker,
  with the bare engine's seconds on the same decks and states in the same run
  (:func:`spinbounce.lammps.runner.engine_clock`: LAMMPS's instance, the deck's commands and the
  atoms in and out, nothing of spinbounce between), each scene's time per collision over the
  wall's and its mean LAMMPS steps a collision (a pair row run again finer counts all its runs);
* :func:`sweep_against_engine`: the frictionless sweep as a user runs it (``spinbounce sweep`` in a
  process of its own, start-up included) against the bare engine running the same chunks' decks;
* :func:`help_seconds`: ``spinbounce --help`` and ``spinbounce collide --help`` in a fresh process;
* :func:`damped_steps`: the damped wall's default against the undamped one, in LAMMPS steps;
* :func:`reference_rates`: the compiled exact pair references, pairs per second on a sweep's states.

These are measurements on a shared machine: each ratio is taken between runs made side by side.
"""

from __future__ import annotations

import math
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .speed import MODELS, PLANE, _sweep_process, _timed, chunk_deck, core_line

__all__ = ["SCENES", "scene_sweeps", "sweep_against_engine", "help_seconds", "damped_steps", "reference_rates",
           "measure_waits", "wait_lines", "ENGINE_SWEEP"]

#: Frictionless collisions the sweep is set beside the bare engine over (full bench, ``--quick``).
ENGINE_SWEEP = (800_000, 200_000)

#: name: (model, states, collisions in the full bench, collisions in ``bench --quick``). A pair
#: sweep's fixed costs (its step's probe) need ~20,000 pairs to amortise, the capped pair's too.
SCENES = {
    "wall": ({}, PLANE, 100_000, 20_000),
    "damped wall": ({"gamma_t": 1.0}, PLANE, 100_000, 20_000),
    "Hertzian wall": ({"normal": "hertz"}, {**PLANE, "v_n": [-0.8, -0.1]}, 100_000, 20_000),
    "Hertz-Mindlin wall": (*MODELS["Hertz-Mindlin"], 100_000, 20_000),
    "pair": ({"scene": "pair"}, PLANE, 20_000, 20_000),
    "capped pair": ({"scene": "pair", "mu": 0.3}, PLANE, 20_000, 20_000),
}


def _user_spec(n: int, model: dict, states: dict, seed: int):
    """The sweep a user's ``spinbounce sweep`` builds: its own chunks (the wall's 25,000 spheres, or as
    many as a pair's references allow)."""
    from ..sweeps import spec_from_dict

    return spec_from_dict({"seed": seed, **({"model": model} if model else {}), "states": {"n": n, **states}})


def _scene_sweep(name: str, n: int, seed: int, root: Path) -> dict:
    from ..lammps.runner import engine_clock
    from ..sweeps import read_results, run_sweep

    model, states, *_ = SCENES[name]
    folder = root / name.replace(" ", "-")
    with engine_clock() as clock:
        wall = _timed(lambda: run_sweep(_user_spec(n, model, states, seed), folder, workers=1, log=lambda *_: None))
    rows = read_results(folder)
    return {"scene": name, "collisions": n, "wall_seconds": wall, "engine_seconds": clock.seconds,
            "lammps_runs": clock.runs, "collisions_per_second": n / wall,
            "engine_collisions_per_second": n / clock.seconds, "outside_engine_share": 1.0 - clock.seconds / wall,
            "steps_per_collision": round(float(rows["nsteps"].mean())), "max_error": float(rows["error"].max())}


def scene_sweeps(quick: bool = False, seed: int = 0, n: int | None = None) -> list[dict]:
    """Each of :data:`SCENES` swept end to end on one worker (``n`` collisions each, or the table's),
    beside the bare engine's seconds; with each one's time per collision over the wall's (``over_wall``)."""
    root = Path(tempfile.mkdtemp(prefix="spinbounce-bench-scenes-"))
    try:
        # untimed: the first sweep of a kind in a process also loads LAMMPS, the table code and (pairs) the compiled
        # references, which no ratio should carry (reference_rates reports what that load costs a process)
        for name in ("wall", "pair", "capped pair"):
            _scene_sweep(name, min(n or 200, 200), seed, root / "warm-up" / name.replace(" ", "-"))
        out = [_scene_sweep(name, n or (spec[3] if quick else spec[2]), seed, root) for name, spec in SCENES.items()]
    finally:
        shutil.rmtree(root, ignore_errors=True)
    wall = out[0]["wall_seconds"] / out[0]["collisions"]
    for entry in out:
        entry["over_wall"] = entry["wall_seconds"] / entry["collisions"] / wall
    return out


def sweep_against_engine(n: int, seed: int = 0, repeats: int = 1) -> dict:
    """The frictionless ``spinbounce sweep --n N --workers 1`` (a process, as a user runs it) and the
    bare engine running the same chunks' decks on the same states: the engine's wall seconds over
    LAMMPS's runs alone (its decks written and its spheres prepared beforehand, untimed). Each the
    fastest of ``repeats``, the two in turn (the machine is shared: a run is slowed, never sped up); and the
    sweep's start-up, a sweep of one collision (the fastest of ``repeats``), which a short sweep pays in full."""
    from ..lammps.decks import prepare_run_dir
    from ..lammps.runner import run_deck

    spec = _user_spec(n, *MODELS["frictionless"], seed)
    sweep = engine = math.inf
    with tempfile.TemporaryDirectory(prefix="spinbounce-bench-engine-") as folder:
        decks = []  # written once: each repeat runs the same decks again in their folders
        for group, chunk, start, stop in spec.chunks():
            deck = chunk_deck(spec, group, start, stop, "library")
            decks.append((prepare_run_dir(Path(folder) / f"engine-{chunk}", deck), deck.atoms))
        for repeat in range(repeats):
            sweep = min(sweep, _sweep_process("--n", n, "--seed", seed, "--workers", 1,
                                              "--out", Path(folder) / f"sweep-{repeat}"))
            engine = min(engine, sum(_timed(lambda: run_deck(path, atoms=atoms)) for path, atoms in decks))
        start = min(_sweep_process("--n", 1, "--seed", seed, "--workers", 1, "--out", Path(folder) / f"one-{repeat}")
                    for repeat in range(repeats))
    return {"collisions": n, "sweep_seconds": sweep, "engine_seconds": engine, "sweep_per_second": n / sweep,
            "engine_per_second": n / engine, "sweep_over_engine": engine / sweep, "repeats": repeats,
            "start_seconds": start}


def at_count(seconds: float, start: float, n: int, count: int) -> float:
    """A sweep of ``n`` collisions that took ``seconds``, ``start`` of them its start-up, carried to ``count``
    collisions: the start-up once, the rest in proportion (its chunks are alike)."""
    return start + (seconds - start) * count / n


def _carried(n: int, seconds: float, start: float) -> bool:
    """Whether a sweep of ``n`` collisions is carried to the full bench's count: the quick bench's own count only
    (a sweep hardly longer than its start-up would carry its noise thousands of times)."""
    return n == ENGINE_SWEEP[1] and seconds > start


def _at_full(f: dict) -> str:
    """The quick frictionless line's reading at the full bench's count (the target's), from its start-up."""
    full = ENGINE_SWEEP[0]
    if not _carried(f["collisions"], f["sweep_seconds"], f["start_seconds"]):
        return ""
    share = f["engine_seconds"] * full / f["collisions"] / at_count(f["sweep_seconds"], f["start_seconds"],
                                                                     f["collisions"], full)
    return (f"; its start-up {f['start_seconds']:.2f} s (a sweep of one collision), paid once over the target's "
            f"{full:,}: {share:.0%} (bench measures it)")


def help_seconds(repeats: int = 3) -> dict:
    """The fastest of ``repeats`` runs of ``spinbounce --help`` and ``spinbounce collide --help``, each a
    fresh process (what a user waits for before anything is asked)."""
    out = {}
    for label, args in (("--help", ["--help"]), ("collide --help", ["collide", "--help"])):
        times = []
        for _ in range(repeats):
            started = time.perf_counter()
            subprocess.run([sys.executable, "-m", "spinbounce", *args], check=True, capture_output=True)
            times.append(time.perf_counter() - started)
        out[label] = min(times)
    return out


def damped_steps() -> dict:
    """LAMMPS steps of the damped wall's default (the accuracy study's ``damped_t`` case, gamma_t = 1)
    against the undamped one (``defaults``), both at the default accuracy, with the errors reached."""
    from .accuracy import default_step_table

    table = default_step_table(["defaults", "damped_t"]).set_index("case")
    undamped, damped = table.loc["defaults"], table.loc["damped_t"]
    return {"undamped_steps": int(undamped["steps_per_collision"]), "damped_steps": int(damped["steps_per_collision"]),
            "ratio": damped["steps_per_collision"] / undamped["steps_per_collision"],
            "damped_method": damped["step_method"], "damped_error": float(damped["error_reached"]),
            "damped_estimate": float(damped["estimate"]), "target": float(damped["target"])}


#: A fresh process that solves one pair in compiled code: what it costs beyond starting spinbounce's modules.
_FIRST_PAIR = ("import numpy as np; from spinbounce.exact import pair_batch; pair_batch.solve(n=[[0, 0, 1.0]], "
               "v_a=[[0.1, 0, -1.0]], v_b=[[0, 0, 0.0]], w_a=[[0, 0, 0.0]], w_b=[[0, 0, 0.0]], m_a=1.0, r_a=0.5, "
               "alpha_a=0.4, m_b=1.0, r_b=0.5, alpha_b=0.4, kn=1e4, kt=2e3)")


def _load_seconds(repeats: int = 3) -> float:
    """Seconds a process spends loading the compiled references (numba and its cached code) before its first
    pair: the fastest of ``repeats`` fresh processes that solve one pair, less the fastest that import spinbounce."""
    def fastest(code: str) -> float:
        times = []
        for _ in range(repeats):
            started = time.perf_counter()
            done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
            if done.returncode:
                raise RuntimeError(f"bench: a process loading the pair references failed: {done.stderr.strip()}")
            times.append(time.perf_counter() - started)
        return min(times)

    return max(0.0, fastest(_FIRST_PAIR) - fastest("import spinbounce.exact"))


def reference_rates(n: int = 20_000, seed: int = 0, mu: float = 0.3, repeats: int = 3) -> dict:
    """Pairs per second of the compiled exact pair references on one core, uncapped and with a cap ``mu``,
    on the pair sweep's own ``n`` states (the default spheres; their compiled code loaded beforehand), and
    what loading that code costs a process (:func:`_load_seconds`, the fastest of ``repeats``)."""
    import numpy as np

    from ..exact import pair_batch, pair_capped_batch
    from ..scenes.pair.kind import pair_contact, pairs_from_states

    spec = _user_spec(n, {"scene": "pair"}, PLANE, seed)
    model, _ = spec.model(0)
    b = spec.sphere_b(0)
    rows = [p.vectors() | p.properties() for p in pairs_from_states(model, b, spec.initial_states(0))]
    columns = {k: np.array([row[k] for row in rows]) for k in rows[0]}
    law = pair_contact(model, b).law()
    out = {"pairs": len(rows), "mu": mu, "load_seconds": _load_seconds(repeats)}
    for name, solve, cap in (("uncapped", pair_batch.solve, {}), ("capped", pair_capped_batch.solve, {"mu": mu})):
        solve(**{k: v[:2] for k, v in columns.items()}, **law, **cap)  # untimed: loads the compiled code
        out[f"{name}_per_second"] = len(rows) / _timed(lambda: solve(**columns, **law, **cap))  # noqa: B023
    return out


#: The sections of LAMMPS's timing breakdown that a gas deck and its bare self spend alike (the forces, the
#: neighbour lists, communication and the loop's rest), and those that measuring adds to (its fixes compute and
#: write their samples at the step's end, which LAMMPS times under Modify, the contacts' own neighbour list
#: included; Output holds the thermo lines, alike in both). One pair of runs reads to about +-2%.
_ALIKE, _MEASURING = ("Pair", "Neigh", "Comm", "Other"), ("Modify", "Output")


def measuring_share(bare: dict, measured: dict) -> float:
    """What a gas deck's measuring costs beside its bare self, from one run of each (their timing breakdowns,
    :func:`..lammps.runner.section_times`): the measured run's Modify and Output less the bare run's, the
    latter scaled by how much faster or slower the machine ran the sections both spend alike; over the
    measured run's time less that cost. The machine's drift between two runs (10% here) would hide a cost of a
    few percent in their loop times; it moves the shared sections as much, and is taken out."""
    drift = sum(measured[k] for k in _ALIKE) / sum(bare[k] for k in _ALIKE)
    cost = sum(measured.get(k, 0.0) for k in _MEASURING) - drift * sum(bare.get(k, 0.0) for k in _MEASURING)
    return cost / (sum(measured.values()) - cost)


def gas_rates(quick: bool = False, repeats: int = 3, spheres: int | None = None) -> dict:
    """A magic-ratio gas's deck (packing 0.05, kn = 1e4) run in this process with and without what it measures
    (the kinetic energies, the open contacts), alternately, ``repeats`` times each: LAMMPS's
    sphere-steps a second on one core over the measured run (the settling before it, alike in both, left out),
    the fastest of the runs, and what measuring costs beside the bare deck (:func:`measuring_share`, the median
    over the pairs of runs). ``spheres``: the gas's size (default 5,000 quick, 20,000 in full)."""
    from ..lammps.decks import prepare_run_dir
    from ..lammps.runner import loop_times, run_deck, section_times
    from ..scenes.gas import collisions
    from ..scenes.gas.deck import render_gas
    from ..model.contact import ContactModel
    from ..scenes.gas.scene import Gas

    m = ContactModel(kn=1e4, kt=1e4 * 2.0 / 7.0)
    spheres = spheres or (5000 if quick else 20000)
    scene = Gas(m, collisions.mean_contact_time(m, 1.0, collisions.draws(2000, 1)), spheres=spheres,
                collisions=4.0 if quick else 8.0, samples=20)
    seconds = {"bare": math.inf, "measured": math.inf}
    shares = []
    with tempfile.TemporaryDirectory() as root:
        for _ in range(repeats):
            sections = {}
            for name in seconds:
                deck = render_gas(scene, measure=name == "measured")
                info = run_deck(prepare_run_dir(Path(root) / name, deck, durable=False))
                seconds[name] = min(seconds[name], loop_times(info.log)[-1])  # the measured run, not the settling
                sections[name] = section_times(info.log)[-1]
            shares.append(measuring_share(sections["bare"], sections["measured"]))
    sphere_steps = scene.spheres * scene.nsteps
    return {"spheres": scene.spheres, "steps": scene.nsteps,
            "sphere_steps_per_second": sphere_steps / seconds["measured"],
            "bare_sphere_steps_per_second": sphere_steps / seconds["bare"],
            "measuring_share": float(statistics.median(shares)), "measuring_shares": shares,
            "loop_share": seconds["measured"] / seconds["bare"] - 1.0}


def measure_waits(quick: bool = False, seed: int = 0, workers: int = 2, n: int | None = None) -> dict:
    """Everything :func:`wait_lines` prints: each scene's sweep beside the engine, the frictionless sweep
    against the bare engine, ``workers`` workers against one, the help's start-up, the damped steps and the
    gas deck beside its bare self. ``n`` collisions for every sweep (and as many spheres for the gas, 1,000
    to 20,000), or the counts of :data:`SCENES` and :data:`ENGINE_SWEEP`."""
    from .speed import parallel_efficiency

    scenes = scene_sweeps(quick, seed, n)
    references = reference_rates(n or SCENES["pair"][3 if quick else 2], seed, repeats=1 if quick else 3)
    gas = gas_rates(quick, repeats=1 if quick else 3,
                    spheres=None if n is None else min(max(n, 1000), 20000))  # a given count sizes it too
    n = n or (ENGINE_SWEEP[1] if quick else ENGINE_SWEEP[0])
    frictionless = sweep_against_engine(n, seed, repeats=1 if quick else 2)
    return {"quick": quick, "scenes": scenes, "references": references, "frictionless": frictionless,
            "cores": parallel_efficiency(n=n, workers=workers, seed=seed, repeats=1 if quick else 3),
            "help_seconds": help_seconds(),
            "damped": damped_steps(), "gas": gas}


def _cores_at_full(c: dict, start: float) -> str:
    """The quick two-worker line's reading at the full bench's count, each run's start-up paid once: the one
    worker's ``start`` (the workers' own start, each loading LAMMPS, is left in the part carried: an estimate
    that reads low)."""
    full, n, walls = ENGINE_SWEEP[0], c["collisions"], c["wall_seconds"]
    if not all(_carried(n, walls[k], start) for k in ("one", "all")):
        return ""
    one, every = (at_count(walls[k], start, n, full) for k in ("one", "all"))
    return (f"; the {c['workers']} workers over {full:,}, one worker's start-up paid once (an estimate): "
            f"{one / (c['workers'] * every):.0%}")


def wait_lines(report: dict) -> list[str]:
    """:func:`measure_waits`' report as printed lines, each ratio beside its target (issue 27's)."""
    lines = [f"{'sweep, one worker':<20}{'collisions':>11}{'coll/s':>10}{'engine coll/s':>15}{'outside LAMMPS':>16}"
             f"{'time/coll vs wall':>19}{'steps':>7}{'max error':>11}"]
    for s in report["scenes"]:
        lines.append(f"{s['scene']:<20}{s['collisions']:>11}{s['collisions_per_second']:>10.0f}"
                     f"{s['engine_collisions_per_second']:>15.0f}{s['outside_engine_share']:>16.0%}"
                     f"{s['over_wall']:>18.2f}x{s['steps_per_collision']:>7}{s['max_error']:>11.2e}")
    by_name = {s["scene"]: s for s in report["scenes"]}
    lines.append(f"pair / wall per collision: {by_name['pair']['over_wall']:.1f}x (target 8x); capped pair / wall: "
                 f"{by_name['capped pair']['over_wall']:.0f}x (target 16x)")
    r = report["references"]
    lines.append(f"exact pair references, one core, the pair sweep's {r['pairs']:,} states: "
                 f"{r['uncapped_per_second']:,.0f} pairs/s uncapped (target 100,000), {r['capped_per_second']:,.0f}/s "
                 f"with mu = {r['mu']:g} (target 20,000); loading them costs a process {r['load_seconds']:.2f} s "
                 "once (untimed in the sweeps above, as LAMMPS's own load)")
    f = report["frictionless"]
    best = "" if f.get("repeats", 1) == 1 else f"; the fastest of {f['repeats']}, each"
    lines.append(f"frictionless sweep of {f['collisions']:,} (a process, start-up included{best}): "
                 f"{f['sweep_per_second']:,.0f}/s; the bare engine on the same chunks: "
                 f"{f['engine_per_second']:,.0f}/s: {f['sweep_over_engine']:.0%} of it (target 85%){_at_full(f)}")
    c = report["cores"]
    lines.append(core_line(c) + _cores_at_full(c, f["start_seconds"]))
    h = report["help_seconds"]
    lines.append("start-up: " + ", ".join(f"spinbounce {k} {v:.2f} s" for k, v in h.items()) + " (target 0.5 s)")
    d = report["damped"]
    lines.append(f"damped wall (gamma_t = 1) at the default accuracy: {d['damped_steps']} steps against "
                 f"{d['undamped_steps']} undamped: {d['ratio']:.2f}x (target 3x; {d['damped_method']}, error "
                 f"{d['damped_error']:.1e}, estimate {d['damped_estimate']:.1e}, target {d['target']:g})")
    g = report["gas"]
    pairs = len(g["measuring_shares"])
    runs = "one pair of runs" if pairs == 1 else f"the median of {pairs} pairs of runs"
    lines.append(f"gas of {g['spheres']:,} spheres, {g['steps']:,} steps: {g['sphere_steps_per_second']:.3g} "
                 f"sphere-steps/s on one core, the bare deck {g['bare_sphere_steps_per_second']:.3g}/s: measuring "
                 f"costs {g['measuring_share']:.1%} (target 10%; LAMMPS's own timings of what it adds, {runs}; "
                 f"their loop times differ by {g['loop_share']:+.1%}, the machine's drift included)")
    return lines
