"""spinbounce accuracy: the error against the exact theory as dt shrinks, and what it costs."""

from __future__ import annotations

from .options import json_flag, note, out_folder, out_option

HELP = "measure how LAMMPS's error against the exact theory falls with dt, and its cost in steps and seconds"


def register(sub) -> None:
    p = sub.add_parser(
        "accuracy", help=HELP,
        description=(f"{HELP}: a dt ladder for collisions and frozen contacts across representative parameters "
                     "(damping, 3-D spin, a Hertzian wall, a Coulomb cap against the oracle), with the observed "
                     "order of convergence and the steps needed for 1e-4, 1e-6 and 1e-8, and each case's default step "
                     "(the steps per collision it chooses and the error it reaches). "
                     "Writes accuracy.png, accuracy.pdf, accuracy.json and ACCURACY.md."),
    )
    out_option(p, "the figure, the JSON record and ACCURACY.md")
    p.add_argument("--quick", action="store_true",
                   help="five levels (n = 64 .. 1024 steps per half-period) and a small cost batch: seconds, "
                        "for checks; the orders hold, the steps for 1e-8 are extrapolated")
    p.add_argument("--runs", type=out_folder, default=None, metavar="DIR",
                   help="keep every LAMMPS run's folder here (default: a temporary folder, removed)")
    json_flag(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..records import json_ready, to_json
    from ..studies.accuracy import TARGETS, make_accuracy

    study, files = make_accuracy(args.out, quick=args.quick, runs=args.runs, log=note if args.json else print)
    s = study.summary
    if args.json:
        rows = s[["case", "form", "observed_order", "expected_order", "error_at_default_dt",
                  *(f"steps_{t:.0e}" for t in TARGETS)]]
        report = {"files": files, "summary": rows.to_dict(orient="records"),
                  "default_steps": study.defaults.to_dict(orient="records"),
                  "default_costs": study.costs, "study_seconds": study.metadata["study_seconds"]}
        print(to_json(json_ready(report)), end="")
        return 0
    print(f"{'case':<15}{'form':<15}{'order':>7}{'expected':>9}{'err@default':>13}"
          + "".join(f"{'steps ' + format(t, '.0e'):>14}" for t in TARGETS))
    for r in s.to_dict(orient="records"):
        steps = "".join(
            f"{(format(r[f'steps_{t:.0e}'], '.3g') + ('*' if r[f'extrapolated_{t:.0e}'] else '')):>14}"
            for t in TARGETS)
        print(f"{r['case']:<15}{r['form']:<15}{r['observed_order']:>7.2f}{r['expected_order']:>9g}"
              f"{r['error_at_default_dt']:>13.2e}{steps}")
    print("* extrapolated beyond the measured range; err@default: none where no default step takes the form")
    print(f"{'default step':<15}{'form':<15}{'chosen by':<28}{'steps':>9}{'error':>11}{'target':>9}")
    for r in study.defaults.to_dict(orient="records"):
        print(f"{r['case']:<15}{r['form']:<15}{r['step_method']:<28}{r['steps_per_collision']:>9}"
              f"{r['error_reached']:>11.2e}{r['target']:>9g}"
              + ("" if r["within_target"] else "  over the target"))
    print("error: the largest |LAMMPS - theory| over the size of the initial state")
    for c in study.costs:
        print(f"defaults, {c['step']} ({c['target']:.0e}): {c['lammps_steps']} steps, error {c['error_reached']:.2e}; "
              f"one collision alone {c['single_wall_seconds']:.3g} s, in a batch "
              f"{c['per_collision_wall_seconds']:.3g} s each")
    print(f"wrote {', '.join(str(p) for p in files.values())} ({study.metadata['study_seconds']:.0f} s)")
    return 0
