"""spinbounce sweep: many collisions from a scene file or flags, into a Parquet dataset."""

from __future__ import annotations

import os
from pathlib import Path

import json

from ..sweeps import SweepError, chunk_table, load_spec, run_one_chunk, run_sweep, spec_from_dict

HELP = "run many collisions in parallel chunks (resumable) into a Parquet dataset"


def register(sub) -> None:
    p = sub.add_parser("sweep", help=HELP, description=HELP + ". Give a TOML scene file, or the flags below.")
    p.add_argument("scene", nargs="?", type=Path, help="TOML scene file (see spinbounce.sweeps for its keys)")
    p.add_argument("--out", type=Path, metavar="DIR", help="output folder (rerun to resume); required to run")
    p.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                   help="parallel worker processes (default: the machine's cores, %(default)s)")
    p.add_argument("--chunk", type=int, metavar="K",
                   help="run only chunk K (see --list-chunks), in this process; several such jobs may "
                        "share one --out (as a workflow engine runs them)")
    p.add_argument("--list-chunks", action="store_true",
                   help="print the chunks (K, group, chunk, start, stop, file) and exit without running")
    p.add_argument("--json", action="store_true", help="with --list-chunks: print JSON")
    g = p.add_argument_group("sweep from flags (instead of a scene file)")
    g.add_argument("--n", type=int, help="number of sampled collisions")
    g.add_argument("--seed", type=int, default=0)
    g.add_argument("--chunk-size", type=int, default=None)
    g.add_argument("--vn", type=float, nargs=2, metavar=("LOW", "HIGH"), help="default: -1.5 -0.1")
    g.add_argument("--vt", type=float, nargs=2, metavar=("LOW", "HIGH"), help="default: -2 2")
    g.add_argument("--speed", type=float, nargs=2, metavar=("LOW", "HIGH"), help="instead of --vn/--vt")
    g.add_argument("--angle-deg", type=float, nargs=2, metavar=("LOW", "HIGH"),
                   help="incidence angle from the wall's normal, degrees (with --speed)")
    g.add_argument("--r-omega", type=float, nargs=2, metavar=("LOW", "HIGH"), help="default: -2 2")
    g.add_argument("--omega", type=float, nargs=2, metavar=("LOW", "HIGH"), help="instead of --r-omega")
    g.add_argument("--kt-over-kn", type=float, nargs="+", help="one or more values (a grid)")
    g.add_argument("--alpha", type=float, nargs="+", help="one or more values (a grid)")
    g.add_argument("--dt", type=float, default=None)
    g.add_argument("--tolerance", type=float, default=None, metavar="TOL",
                   help="instead of --dt: extrapolate each chunk's runs until every row's estimated error is below TOL")
    p.set_defaults(handler=run)


def _from_flags(args) -> dict:
    if args.n is None:
        raise SystemExit("spinbounce sweep: give a scene file or --n")
    states = {"n": args.n}
    if args.speed or args.angle_deg:
        if args.vn or args.vt:
            raise SweepError("--speed/--angle-deg: give them or --vn/--vt, not both")
        states["speed"] = list(args.speed or (0.1, 1.5))
        states["angle_deg"] = list(args.angle_deg or (-60.0, 60.0))
    else:
        states["v_n"] = list(args.vn or (-1.5, -0.1))
        states["v_t"] = list(args.vt or (-2.0, 2.0))
    if args.omega:
        if args.r_omega:
            raise SweepError("--omega: give it or --r-omega, not both")
        states["omega"] = list(args.omega)
    else:
        states["r_omega"] = list(args.r_omega or (-2.0, 2.0))
    raw = {"seed": args.seed, "states": states}
    if args.tolerance is not None:
        raw["tolerance"] = args.tolerance
    if args.chunk_size is not None:
        raw["chunk_size"] = args.chunk_size
    model = {}
    if args.kt_over_kn:
        model["kt_over_kn"] = args.kt_over_kn
    if args.alpha:
        model["alpha"] = args.alpha
    if args.dt is not None:
        model["dt"] = args.dt
    if model:
        raw["model"] = model
    return raw


def run(args) -> int:
    spec = load_spec(args.scene) if args.scene else spec_from_dict(_from_flags(args))
    if args.list_chunks:
        table = chunk_table(spec, args.out)
        if args.json:
            print(json.dumps(table, indent=2))
        else:
            for row in table:
                print(" ".join(str(row[k]) for k in ("k", "group", "chunk", "start", "stop", "path")))
        return 0
    if args.out is None:
        raise SweepError("--out = None: an output folder is required to run a sweep")
    if args.chunk is not None:
        path = run_one_chunk(spec, args.out, args.chunk)
        print(f"chunk {args.chunk}: {path}")
        return 0
    total = spec.n * len(spec.groups)
    print(f"sweep {spec.digest}: {total} collisions in {len(spec.chunks())} chunks, "
          f"{len(spec.groups)} model group(s), {args.workers} worker(s)")
    dataset = run_sweep(spec, args.out, workers=args.workers)
    print(f"dataset: {dataset} (pandas.read_parquet of that folder)")
    return 0
