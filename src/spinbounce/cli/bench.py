"""spinbounce bench: collisions per second, one lmp process / one instance / batched."""

from __future__ import annotations

from pathlib import Path

from ..studies.speed import SPEED_DEFAULTS, measure_speed
from ..records import to_json, write_atomic

HELP = "measure collisions/s of one lmp process per collision, one in-process instance, and a batched sweep"

LABELS = {"a_lmp_process": "(a) one lmp process each", "b_in_process": "(b) one instance each",
          "c_batched": "(c) batched sweep"}


def register(sub) -> None:
    p = sub.add_parser("bench", help=HELP, description=HELP + ", side by side on the same states and dt.")
    p.add_argument("--n-lmp", type=int, default=SPEED_DEFAULTS["n_lmp"], metavar="N",
                   help="collisions for (a) (default %(default)s)")
    p.add_argument("--n-inprocess", type=int, default=SPEED_DEFAULTS["n_inprocess"], metavar="N",
                   help="collisions for (b) (default %(default)s)")
    p.add_argument("--n-batched", type=int, default=SPEED_DEFAULTS["n_batched"], metavar="N",
                   help="collisions for (c) (default %(default)s)")
    p.add_argument("--workers", type=int, default=1,
                   help="worker processes for (c); rates are reported per core (default %(default)s)")
    p.add_argument("--chunk-size", type=int, default=None, help="spheres per LAMMPS run in (c) (default: the sweep's)")
    p.add_argument("--n-needs", type=int, default=1000, metavar="N",
                   help="spheres for the contact-only vs free-flight-and-dump comparison (default %(default)s)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--out", type=Path, default=Path("bench.json"), metavar="FILE",
                   help="JSON report (default %(default)s)")
    p.add_argument("--keep-runs", type=Path, metavar="DIR", help="keep every run's folder here")
    p.set_defaults(handler=run)


def run(args) -> int:
    report = measure_speed(n_lmp=args.n_lmp, n_inprocess=args.n_inprocess, n_batched=args.n_batched,
                       workers=args.workers, seed=args.seed, chunk_size=args.chunk_size, keep=args.keep_runs,
                       n_needs=args.n_needs)
    print(f"dt = {report['parameters']['dt']:.6g}, LAMMPS {report['lammps_version']}, "
          f"{report['machine']['cpus']} cpus")
    print(f"{'method':<27}{'collisions':>11}{'coll/s/core':>13}{'outside loop':>14}{'max error':>11}")
    for key, label in LABELS.items():
        m = report["methods"][key]
        print(f"{label:<27}{m['collisions']:>11}{m['collisions_per_second_per_core']:>13.1f}"
              f"{m['outside_loop_share']:>13.1%}{m['max_abs_error']:>12.2e}")
    r = report["ratios"]
    print(f"batched / lmp process: {r['batched_over_lmp_process']:.0f}x; "
          f"batched / in-process instance: {r['batched_over_in_process']:.1f}x")
    d = report["scene_needs"]
    print(f"contact only vs free flight before/after and a dump every step ({d['collisions']} spheres): "
          f"{d['contact_only']['wall_seconds']:.2f} s vs {d['free_flight_and_dump_every_step']['wall_seconds']:.2f} s, "
          f"{d['ratio']:.1f}x")
    write_atomic(args.out, to_json(report))
    print(f"report: {args.out}")
    return 0
