"""spinbounce bench: collisions per second (one lmp process / one instance / batched), and
what each model, the exact solver, the cores, the cluster jobs and two spheres cost."""

from __future__ import annotations

import argparse
import math

from pathlib import Path

from ..model.parameters import SceneError
from .options import count, out_file, out_folder, positive_count, worker_count

HELP = "measure collisions/s of one lmp process per collision, one in-process instance, and a batched sweep"

LABELS = {"a_lmp_process": "(a) one lmp process each", "b_in_process": "(b) one instance each",
          "c_batched": "(c) batched sweep"}


def register(sub) -> None:
    from ..studies.speed import SPEED_DEFAULTS

    p = sub.add_parser("bench", help=HELP, description=HELP + ", side by side on the same states and dt.")
    for name, method in (("lmp", "a"), ("inprocess", "b"), ("batched", "c")):
        p.add_argument(f"--n-{name}", type=positive_count, default=SPEED_DEFAULTS[f"n_{name}"], metavar="N",
                       help=f"collisions for ({method}) (default %(default)s)")
    p.add_argument("--workers", type=worker_count, default=1,
                   help="worker processes for (c); rates are reported per core (default %(default)s)")
    p.add_argument("--chunk-size", type=positive_count, default=None, help="spheres per LAMMPS run in (c) (default: the sweep's)")
    p.add_argument("--n-needs", type=positive_count, default=1000, metavar="N",
                   help="spheres for the contact-only vs free-flight-and-dump comparison (default %(default)s)")
    p.add_argument("--seed", type=count, default=0, help="random seed of the states (default %(default)s)")
    p.add_argument("--out", type=out_file, default=Path("bench.json"), metavar="FILE",
                   help="JSON report (default %(default)s; a file there is kept unless --force)")
    p.add_argument("--force", action="store_true", help="replace the file --out names if it exists")
    p.add_argument("--keep-runs", type=out_folder, metavar="DIR", help="keep every run's folder here")
    p.add_argument("--n-models", type=positive_count, default=100_000, metavar="N",
                   help="collisions per model sweep (frictionless, mu 2-D and 3-D, Hertz, Hertz-Mindlin) "
                        "(default %(default)s)")
    p.add_argument("--n-pairs", type=pair_count, default=200, metavar="N",
                   help=f"impacts LAMMPS's pair-to-wall cost is measured over (1 to {MAX_PAIR_IMPACTS}; "
                        "default %(default)s)")
    p.add_argument("--n-scenes", type=positive_count, default=None, metavar="N",
                   help="collisions of each scene's sweep and of the frictionless sweeps set beside the bare "
                        "engine and across workers (default: 20,000 to 100,000 a scene and 800,000 frictionless; "
                        "with --quick 20,000 a scene and 200,000 frictionless)")
    p.add_argument("--quick", action="store_true",
                   help="only what a user waits for, at small counts (under a minute): each scene's sweep beside "
                        "the bare engine, the frictionless sweep against it, two workers, start-up, damped steps")
    p.set_defaults(handler=run)


#: The most impacts --n-pairs measures over: the cost per collision is steady to a few percent
#: from a few hundred, and each impact is a Python object before LAMMPS starts.
MAX_PAIR_IMPACTS = 100_000


def pair_count(text: str) -> int:
    """argparse type of --n-pairs: a whole number of impacts in [1, MAX_PAIR_IMPACTS]."""
    value = positive_count(text)
    if value > MAX_PAIR_IMPACTS:
        raise argparse.ArgumentTypeError(f"{text!r}: must be at most {MAX_PAIR_IMPACTS} (the cost per "
                                         "collision is steady to a few percent from a few hundred impacts)")
    return value


def run(args) -> int:
    from ..records import check_new_file, to_json, write_atomic, software
    from ..studies.engine import measure_waits, wait_lines
    from ..studies.speed import measure_speed

    check_new_file(args.out, args.force, "--out", "--force")  # before minutes of measuring
    if args.quick:
        waits = measure_waits(quick=True, seed=args.seed, workers=max(2, args.workers), n=args.n_scenes)
        print("\n".join(wait_lines(waits)))
        write_atomic(args.out, to_json({"waits": waits, **software()}))
        print(f"report: {args.out}")
        return 0

    reused = max(args.n_lmp, args.n_inprocess, args.n_needs)
    if reused > args.n_batched:
        raise SceneError("--n-batched", args.n_batched, f"must be at least --n-lmp, --n-inprocess and --n-needs "
                                                        f"({reused}): they reuse its states")
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
    report["models"] = _print_models(args.n_models, args.seed, args.n_pairs)
    report["waits"] = measure_waits(seed=args.seed, workers=max(2, args.workers), n=args.n_scenes)
    print("what a user waits for, beside the bare engine:\n" + "\n".join(wait_lines(report["waits"])))
    write_atomic(args.out, to_json(report))
    print(f"report: {args.out}")
    return 0


def _print_models(n: int, seed: int, n_pairs: int) -> dict:
    """Per model: a sweep's cost beside the frictionless one's, the solvers, the cores, the
    cluster jobs' estimates, the default step's accuracy and the pair-to-wall ratio."""
    from ..studies.pairs import cost_lines, pair_to_wall_cost
    from ..studies.accuracy import default_step_table
    from ..studies.solver_speed import measure_throughput
    from ..studies.speed import chunk_jobs, core_line, measure_models, parallel_efficiency
    from ..workers import cores as usable_cores

    models = measure_models(n=n, seed=seed)["models"]
    print(f"{'sweep (one core)':<18}{'collisions':>11}{'coll/s':>10}{'time/coll vs frictionless':>27}"
          f"{'theory':>8}{'checks':>8}{'steps':>8}{'max error':>11}")
    for m in models:
        print(f"{m['model']:<18}{m['collisions']:>11}{m['collisions_per_second']:>10.0f}"
              f"{m['time_per_collision_over_frictionless']:>26.2f}x{m['theory_seconds'] / m['wall_seconds']:>8.1%}"
              f"{m['checks_share']:>8.1%}{m['steps_per_collision']:>8}{m['max_error']:>11.2e}")
        if "time_per_collision_over_hooke_at_its_ratio" in m:
            print(f"{'':<18}Hertz-Mindlin per collision: {m['time_per_collision_over_hooke_at_its_ratio']:.2f}x the "
                  "Hookean sweep at its k_t/kn (the same accuracy)")
    solvers = {"2-D": measure_throughput(n=100_000), "3-D": measure_throughput(n=100_000, three_d=True)}
    print("exact Coulomb solver alone: " + ", ".join(f"{k} {v:,.0f} collisions/s" for k, v in solvers.items()))
    cores = parallel_efficiency(n=n, workers=usable_cores(), seed=seed)
    print("frictionless sweep, " + core_line(cores))
    jobs = chunk_jobs(n=min(n, 20_000), seed=seed)
    for j in jobs:
        print(f"chunk job ({j['model']}, {j['collisions']} collisions): estimated {j['estimated_seconds']:.2f} s, "
              f"measured {j['measured_seconds']:.2f} s ({j['estimated_over_measured']:.2f}x)")
    steps = default_step_table()
    print("default step, per case: steps per collision, the error reached (target in brackets) and an "
          "extrapolation's own estimate")
    for row in steps[steps["kind"] != "frozen"].itertuples():
        estimate = "" if math.isnan(row.estimate) else f" estimate {row.estimate:.2e}"
        print(f"  {row.case:<28}{row.step_method:<22}{row.steps_per_collision:>9}{row.error_reached:>11.2e} "
              f"({row.target:g}){estimate}")
    pairs = pair_to_wall_cost(n_pairs)
    print("\n".join(cost_lines(pairs)))
    return {"sweeps": models, "solver_collisions_per_second": solvers, "cores": cores, "chunk_jobs": jobs,
            "default_steps": steps.to_dict(orient="records"), "pairs": pairs}
