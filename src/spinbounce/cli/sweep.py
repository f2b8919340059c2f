"""spinbounce sweep: many collisions from a scene file or flags, into a Parquet dataset.

A scene file is the whole sweep (beside one, only the run flags apply); from flags, every
sweepable model parameter takes one value or several.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..model import parameters
from ..model.timestep import MAX_CORE_HOURS
from ..errors import SweepError
from ..workers import cores
from .options import count, number, print_json, sweep_model_flags, worker_count

HELP = "run many collisions in parallel chunks (resumable) into a Parquet dataset"
#: State ranges from flags: (dest, flags, default range or None, help); the speed's and angle's
#: defaults hold when either is given.
STATE_RANGES = (
    ("v_n", ("--vn", "--v-n"), (-1.5, -0.1), "range of v_n (default: -1.5 -0.1)"),
    ("v_t", ("--vt", "--v-t"), (-2.0, 2.0), "range of v_t (default: -2 2)"),
    ("speed", ("--speed",), (0.1, 1.5), "instead of --vn/--vt: range of the impact speed"),
    ("angle_deg", ("--angle-deg",), (-60.0, 60.0),
     "incidence angle from the wall's normal, degrees (with --speed)"),
    ("r_omega", ("--r-omega",), (-2.0, 2.0), "range of r*omega (default: -2 2)"),
    ("omega", ("--omega",), None, "instead of --r-omega: range of omega"),
    ("v_s", ("--vs", "--v-s"), None, "3-D: range of v_s (give all three 3-D ranges)"),
    ("r_omega_s", ("--r-omega-s",), None, "3-D: range of r*omega_s (or --omega-s)"),
    ("omega_s", ("--omega-s",), None, "3-D: range of omega_s"),
    ("r_omega_n", ("--r-omega-n",), None, "3-D: range of r*omega_n (or --omega-n)"),
    ("omega_n", ("--omega-n",), None, "3-D: range of omega_n"),
)
SCENE_FLAGS = ("n", "seed", "chunk_size", "dt", "tolerance", "kt_over_kn",
               *(p.name for p in parameters.MODEL if p.sweepable), *(p.name for p in parameters.SCENE),
               *(dest for dest, *_ in STATE_RANGES))


def register(sub) -> None:
    p = sub.add_parser("sweep", help=HELP, description=HELP + ". Give a TOML scene file, or the flags below.")
    p.add_argument("scene_file", nargs="?", type=Path, metavar="scene", help="TOML scene file (its keys: spinbounce.sweeps.spec)")
    p.add_argument("--out", type=Path, metavar="DIR", help="output folder (rerun to resume); required to run")
    p.add_argument("--workers", type=worker_count, default=None,
                   help="parallel worker processes, >= 1 and at most the cores available (default: all of them)")
    p.add_argument("--chunk", type=count, metavar="K",
                   help="run only chunk K (see --list-chunks), in this process; several such jobs may "
                        "share one --out (as a workflow engine runs them)")
    p.add_argument("--list-chunks", action="store_true",
                   help="print the chunks (K, group, chunk, start, stop, file) and exit without running")
    p.add_argument("--json", action="store_true", help="with --list-chunks: print JSON")
    p.add_argument("--force", action="store_true",
                   help=f"run a sweep estimated at more than {MAX_CORE_HOURS:g} core-hour(s) on this machine anyway")
    p.add_argument("--strict", action="store_true",
                   help="exit with status 1 if any row is not 'ok' (grazing, no_limit, energy_gained or inaccurate)")
    g = p.add_argument_group("states, from flags (instead of a scene file)")
    g.add_argument("--n", type=count, default=None, help="number of sampled collisions")
    g.add_argument("--seed", type=count, default=None, help="random seed (default 0)")
    g.add_argument("--chunk-size", type=count, default=None, help="spheres per LAMMPS run (default: at most 25000, and at most what is estimated to run "
                        "in 5 minutes on one core)")
    for dest, flags, _, text in STATE_RANGES:
        g.add_argument(*flags, dest=dest, type=number, nargs=2, metavar=("LOW", "HIGH"), default=None, help=text)
    step = g.add_mutually_exclusive_group()
    step.add_argument("--dt", type=number, default=None, help="timestep (default: the timestep rule)")
    step.add_argument("--tolerance", type=number, default=None, metavar="TOL",
                      help="instead of --dt: extrapolate each chunk's runs until every row's estimated error is below TOL")
    sweep_model_flags(p)
    group = p.add_argument_group("scene, from flags: sphere a (the model's m, r, alpha) against a free sphere b "
                                 "at rest instead of the wall")
    for parameter in parameters.SCENE:
        if parameter.kind == "choice":
            group.add_argument(*parameter.flags, dest=parameter.name, choices=parameter.choices, default=None,
                               help=f"{parameter.meaning} (default {parameter.default})")
        else:
            group.add_argument(*parameter.flags, dest=parameter.name, type=number, nargs="+", default=None,
                               metavar=parameter.name.upper(),
                               help=f"{parameter.meaning}; {parameter.range_text()} (default {parameter.default})")
    for parameter in parameters.STATE_B:  # declared, so refused here with the reason rather than unknown
        group.add_argument(*parameter.flags, dest=parameter.name, type=_b_state_refused, nargs="+", default=None,
                           metavar=parameter.name.upper(), help=argparse.SUPPRESS)
    p.set_defaults(handler=run)


def _b_state_refused(text: str):
    """argparse type of sphere b's state in a sweep: refused, with the reason."""
    raise argparse.ArgumentTypeError(f"{text!r}: a sweep samples sphere a's state with b at rest (the planar matrix "
                                     "and the fit assume it); give b's state to one collision: collide --scene pair")


def _states_from_flags(args) -> dict:
    given = {dest: list(getattr(args, dest)) for dest, *_ in STATE_RANGES if getattr(args, dest) is not None}
    by_speed = bool({"speed", "angle_deg"} & given.keys())
    if by_speed and {"v_n", "v_t"} & given.keys():
        raise SweepError("--speed/--angle-deg: give them or --vn/--vt, not both")
    if {"omega", "r_omega"} <= given.keys():
        raise SweepError("--omega: give it or --r-omega, not both")
    pair = ("speed", "angle_deg") if by_speed else ("v_n", "v_t")
    defaults = {dest: list(default) for dest, _, default, _ in STATE_RANGES if dest in pair}
    states = {"n": args.n, **defaults, **given}
    if "omega" not in states:
        states.setdefault("r_omega", [-2.0, 2.0])
    return states


def spec_from_flags(args) -> dict:
    """The scene-file content that the flags describe (the same keys, the same checks)."""
    if args.n is None:
        raise SweepError("--n = None: give a scene file or the number of collisions --n")
    raw = {"seed": args.seed or 0, "states": _states_from_flags(args)}
    for key in ("tolerance", "chunk_size"):
        if getattr(args, key) is not None:
            raw[key] = getattr(args, key)
    model = {}
    for key in [p.name for p in parameters.MODEL if p.sweepable] + ["kt_over_kn"]:
        values = getattr(args, key)
        if values == [] and key == "limit_damping":  # the flag alone
            values = [True]
        if values is not None:
            model[key] = [v if v is not None else "none" for v in values]
    for parameter in parameters.SCENE:
        if getattr(args, parameter.name) is not None:
            model[parameter.name] = getattr(args, parameter.name)
    if args.dt is not None:
        model["dt"] = args.dt
    if getattr(args, "contact", None) is not None:
        model["contact"] = args.contact
    if model:
        raw["model"] = model
    return raw


def run(args) -> int:
    from .. import api
    from ..records import lammps_version
    from ..sweeps import chunk_table, load_spec, run_one_chunk, spec_from_dict

    if args.scene_file is not None:
        given = [name for name in SCENE_FLAGS if getattr(args, name, None) is not None]
        if given:
            flags = ", ".join("--" + name.replace("_", "-") for name in given)
            raise SweepError(f"{flags}: a scene file is the whole sweep; put these in {args.scene_file} instead "
                             "(beside a scene file only --out, --workers, --chunk, --list-chunks, --force and --json apply)")
        spec = load_spec(args.scene_file)
    else:
        spec = spec_from_dict(spec_from_flags(args))
    if args.list_chunks:
        table = chunk_table(spec, args.out)
        if args.json:
            return print_json(table)
        for row in table:
            print(" ".join(str(row[k]) for k in ("k", "group", "chunk", "start", "stop", "path")))
        return 0
    if args.out is None:
        raise SweepError("--out = None: an output folder is required to run a sweep")
    if args.chunk is not None:
        path = run_one_chunk(spec, args.out, args.chunk)
        print(f"chunk {args.chunk}: {path}")
        return 0
    try:
        report = api.run_sweep(spec, args.out, workers=args.workers or cores(), force=args.force,
                               log=None if args.json else print,
                               size_name="states.n" if args.scene_file is not None else "--n")
    except KeyboardInterrupt:
        print(f"spinbounce sweep: interrupted; the finished chunks in {args.out} are kept: rerun the same "
              "command to resume", file=sys.stderr)
        raise SystemExit(130) from None
    counts = report.counts
    bad = {name: n for name, n in counts.items() if name != "ok" and n}
    if args.json:
        print_json({"dataset": str(report.dataset), "scene": report.scene, "collisions": report.collisions,
                    "estimated_seconds": report.estimated_seconds, "counts": counts, "scene_hash": report.scene_hash,
                    "lammps_version": lammps_version()})
        return 1 if bad and args.strict else 0
    print(f"dataset: {report.dataset} (pandas.read_parquet of that folder)")
    size = ("the pair's speed, over both spheres (theory: the exact reference; planar_error: the planar theory's "
            "model error)" if report.scene == "pair" else "its state's size")
    print(f"rows: {counts['ok']} ok" + "".join(f", {n} {name}" for name, n in bad.items())
          + f" (column 'status'; 'error' holds each row's |LAMMPS - theory| over {size})")
    return 1 if bad and args.strict else 0
