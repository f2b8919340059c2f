"""spinbounce sweep: many collisions from a scene file or flags, into a Parquet dataset."""

from __future__ import annotations

import os
from pathlib import Path

from ..sweeps import load_spec, run_sweep, spec_from_dict

HELP = "run many collisions in parallel chunks (resumable) into a Parquet dataset"


def register(sub) -> None:
    p = sub.add_parser("sweep", help=HELP, description=HELP + ". Give a TOML scene file, or the flags below.")
    p.add_argument("scene", nargs="?", type=Path, help="TOML scene file (see spinbounce.sweeps for its keys)")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder (rerun to resume)")
    p.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                   help="parallel worker processes (default: the machine's cores, %(default)s)")
    g = p.add_argument_group("sweep from flags (instead of a scene file)")
    g.add_argument("--n", type=int, help="number of sampled collisions")
    g.add_argument("--seed", type=int, default=0)
    g.add_argument("--chunk-size", type=int, default=None)
    g.add_argument("--vn", type=float, nargs=2, metavar=("LOW", "HIGH"), default=(-1.5, -0.1))
    g.add_argument("--vt", type=float, nargs=2, metavar=("LOW", "HIGH"), default=(-2.0, 2.0))
    g.add_argument("--r-omega", type=float, nargs=2, metavar=("LOW", "HIGH"), default=(-2.0, 2.0))
    g.add_argument("--kt-over-kn", type=float, nargs="+", help="one or more values (a grid)")
    g.add_argument("--alpha", type=float, nargs="+", help="one or more values (a grid)")
    g.add_argument("--dt", type=float, default=None)
    p.set_defaults(handler=run)


def _from_flags(args) -> dict:
    if args.n is None:
        raise SystemExit("spinbounce sweep: give a scene file or --n")
    raw = {"seed": args.seed,
           "states": {"n": args.n, "v_n": list(args.vn), "v_t": list(args.vt), "r_omega": list(args.r_omega)}}
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
    total = spec.n * len(spec.groups)
    print(f"sweep {spec.digest}: {total} collisions in {len(spec.chunks())} chunks, "
          f"{len(spec.groups)} model group(s), {args.workers} worker(s)")
    dataset = run_sweep(spec, args.out, workers=args.workers)
    print(f"dataset: {dataset} (pandas.read_parquet of that folder)")
    return 0
