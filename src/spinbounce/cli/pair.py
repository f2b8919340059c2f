"""spinbounce pair: two free spheres collide in LAMMPS, beside the exact reference and the planar theory."""

from __future__ import annotations

import json
from pathlib import Path

from .options import default_run_dir, json_flag

HELP = "collide two free spheres (pair granular) and compare with the exact reference and the planar theory"


def register(sub) -> None:
    p = sub.add_parser("pair", help=HELP, description=(
        f"{HELP}. The state is given at first touch: b's centre at the origin, a's at (r_a + r_b) NORMAL; "
        "vectors are LAMMPS's x y z, spins LAMMPS's angular velocities. No Coulomb cap. Errors are in units of "
        "the larger of |v_a - v_b| and the initial slip speed. --figure and --cost run the studies instead."))
    for side in "ab":
        p.add_argument(f"--m-{side}", type=float, default=1.0, help=f"mass of {side} (default %(default)s)")
        p.add_argument(f"--r-{side}", type=float, default=0.5, help=f"radius of {side} (default %(default)s)")
        p.add_argument(f"--alpha-{side}", type=float, default=0.4, help=f"I/(m r^2) of {side} (default %(default)s)")
    for name, default in (("normal", (0.0, 0.0, 1.0)), ("v-a", (1.0, 0.0, -1.0)), ("v-b", (0.0, 0.0, 0.0)),
                          ("w-a", (0.0, 0.0, 0.0)), ("w-b", (0.0, 0.0, 0.0))):
        p.add_argument(f"--{name}", type=float, nargs=3, default=default, metavar=("X", "Y", "Z"),
                       help=f"(default {' '.join(f'{x:g}' for x in default)})")
    for name, default in (("kn", 10.0), ("kt", 1.0), ("gamma-n", 0.0), ("gamma-t", 0.0)):
        p.add_argument(f"--{name}", type=float, default=default, help="(default %(default)s)")
    p.add_argument("--dt", type=float, default=None, help="timestep (default: pairs.scene.PAIR_STEPS_PER_HALF_PERIOD)")
    p.add_argument("--out", type=Path, default=None, metavar="DIR", help="run folder (default: spinbounce-runs/pair-*)")
    p.add_argument("--figure", type=Path, default=None, metavar="DIR",
                   help="write pair_validity.png/.pdf/.json into DIR instead")
    p.add_argument("--cost", type=int, default=None, metavar="N",
                   help="measure LAMMPS's cost per pair collision against the wall's, over N impacts, instead")
    json_flag(p)
    p.set_defaults(handler=run)


def _one_pair(args) -> int:
    from ..pairs import Pair, PairBatch, PairContact, Sphere, run_pairs

    pair = Pair(a=Sphere(args.m_a, args.r_a, args.alpha_a), b=Sphere(args.m_b, args.r_b, args.alpha_b),
                normal=args.normal, v_a=args.v_a, v_b=args.v_b, w_a=args.w_a, w_b=args.w_b)
    batch = PairBatch([pair], PairContact(args.kn, args.kt, args.gamma_n, args.gamma_t), args.dt)
    out = args.out or default_run_dir("pair", vars(args) | {"handler": None})
    row = run_pairs(batch, out).table.iloc[0]
    if args.json:
        print(json.dumps({k: (v.item() if hasattr(v, "item") else v) for k, v in row.items()}, indent=2))
        return 0
    print(f"dt = {batch.dt:.6g}, {batch.nsteps} steps; contact {row.contact_time:.6g} (planar tau {row.tau:.6g}); "
          f"line of centres turned {row.turn:.4g} rad (eps = {row.eps:.4g})")
    print(f"{'':8}{'LAMMPS':>14}{'exact':>14}{'planar':>14}")
    for side in "ab":
        for q in "vw":
            for axis in "xyz":
                name = f"{side}_{q}{axis}"
                print(f"{name:8}{row[name]:>14.8f}{row[name + '_exact']:>14.8f}{row[name + '_planar']:>14.8f}")
    print(f"LAMMPS vs exact: {row.lammps_error:.2e}; planar theory vs exact (model error): {row.planar_error:.2e}")
    print(f"run: {out}")
    return 0


def run(args) -> int:
    if args.figure is not None:
        from ..pairs.figure import make_pair_validity

        record = make_pair_validity(args.figure)
        print(f"wrote {record.png}, {record.pdf}, {record.json}")
        return 0
    if args.cost is not None:
        from ..pairs.studies import pair_to_wall_cost

        report = pair_to_wall_cost(args.cost)
        print(json.dumps(report, indent=2) if args.json else
              f"pair {report['pair_seconds_per_collision']:.3g} s, wall {report['wall_seconds_per_collision']:.3g} s "
              f"per collision: {report['pair_to_wall']:.1f}x ({report['pair_steps']} vs {report['wall_steps']} steps; "
              f"{report['pair_to_wall_per_step']:.2f}x per step); max errors {report['pair_max_error']:.1e} "
              f"and {report['wall_max_error']:.1e}")
        return 0
    return _one_pair(args)
