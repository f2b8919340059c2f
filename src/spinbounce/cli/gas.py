"""spinbounce gas: a gas of frictional spheres in LAMMPS, its two temperatures against kinetic theory."""

from __future__ import annotations

from .options import (_parent, check_run_folder, model_parser, model_values, note, number, print_json,
                      run_folder_flags, shown_path)

HELP = "run a gas of frictional spheres in LAMMPS: T_rot/T_tr and the energy against two-temperature kinetic theory"


def _ranks(text: str) -> int:
    import argparse

    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: give a whole number of MPI ranks >= 1") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r}: give a whole number of MPI ranks >= 1")
    return value


def register(sub) -> None:
    from ..scenes.gas import GAS

    p = sub.add_parser("gas", parents=[model_parser(), _parent("gas", GAS)], help=HELP, description=(
        f"{HELP}, with each collision's energy changes from the paper's matrix and from the project's pair outcomes "
        "(LAMMPS's own isolated pairs at the gas's step, and the exact references). Writes gas.csv and result.json."))
    p.add_argument("--kt-over-kn", dest="kt_over_kn", type=number, default=None, metavar="RATIO",
                   help="instead of --kt: the stiffness ratio kt/kn (2/7 = 0.2857...: the magic ratio of alpha = 2/5)")
    p.add_argument("--dt", type=number, default=None,
                   help="timestep (default: the mean contact time over 50, finer where a mode of the fastest "
                   "collisions needs it; at most 20 steps a half-period of the fastest mode)")
    p.add_argument("--ranks", type=_ranks, default=1,
                   help="MPI ranks: 1 runs LAMMPS in this process; K > 1 runs it under mpiexec -np K (default 1)")
    run_folder_flags(p, "run folder: the deck, data file, log, gas.csv and result.json (default: "
                        "spinbounce-runs/gas-<hash>); --force also runs a gas estimated beyond an hour")
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..api import gas
    from ..api import model as make_model
    from ..errors import SceneError
    from ..exact.kinetic import DILUTE
    from ..records import json_ready
    from ..scenes.gas import GAS
    from ..scenes.gas.closure import absent as closure_absent

    check_run_folder(args.out, args.force)
    values = model_values(args)
    if args.kt_over_kn is not None:
        if "kt" in getattr(args, "given_options", set()) or args.contact is not None:
            raise SceneError("kt_over_kn", args.kt_over_kn, "give the tangential spring once: --kt, --contact or "
                             "--kt-over-kn")
        if make_model(**values).normal_law.contact_radius:  # kn is then not a spring constant
            raise SceneError("kt_over_kn", args.kt_over_kn, f"is a ratio of Hookean springs; with normal = "
                             f"{values['normal']} kn is not a spring constant: give --kt")
        values["kt"] = args.kt_over_kn * values["kn"]
    report = gas(**{p.name: getattr(args, p.name) for p in GAS}, dt=args.dt, ranks=args.ranks, out=args.out,
                 force=args.force, log=None if args.json else note, **values)
    r = report.record
    if args.json:
        return print_json(json_ready({"series": report.series, "lammps": r["lammps"], "theories": r["theories"],
                           "overlaps": r["overlaps"], "closure": r["closure"], "closure_drift": r["closure_drift"],
                           "accuracy": r["accuracy"],
                           "no_matrix": r["no_matrix"], "csv": r["csv"],
                           "record": str(report.record_path), "parameters": r["parameters"],
                           "lammps_version": r["lammps_version"]}))
    s = r["lammps"]
    print(f"gas of {r['parameters']['spheres']} spheres: {s['collisions_per_sphere']:.3g} collisions per sphere "
          f"(counted to {100 * r['accuracy']['collisions_noise']:.1f}%), late T_rot/T_tr {s['late_ratio']:.4f}, "
          f"energy drift {_percent(s['energy_drift'])}")
    for name, t in r["theories"].items():
        print(f"  theory {name:<12} largest |ratio difference| {t['max_ratio_difference']:.4f}, steady ratio "
              f"{t['steady_ratio']:.4f}, energy drift {_percent(t['energy_drift']['theory'])}")
    print(f"  of the pair-level drift, the overlapping contacts' (a sphere meeting a third while it touches a second): "
          f"{_percent(r['overlaps']['energy_drift'])}")
    if r["closure_drift"]:
        d = r["closure_drift"]
        print(f"  the isolated pairs' drift by DSMC of the exact pairs (no closure) "
              f"{_percent(d['energy_drift_dsmc'])}, by the equations {_percent(d['energy_drift_equations'])}; "
              f"the pair-level drift with DSMC's {_percent(r['theories']['pairs']['energy_drift_boltzmann'])}")
    if r["closure"] is None:
        print(f"  no closure's error: {closure_absent(make_model(**values))}")
    elif r["closure"]["method"] != "DSMC":
        print(f"  the closure's error: {r['closure']['method']}")
    else:
        c = r["closure"]
        print(f"  beyond the two-temperature closure (DSMC of the planar rule): steady ratio "
              f"{c['steady_ratio_dsmc']:.4f} +/- {c['standard_error']:.4f} against its closed form's "
              f"{c['steady_ratio_closed_form']:.4f}; the pair-level steady ratio with it "
              f"{r['theories']['pairs']['steady_ratio_boltzmann']:.4f}")
    if r["no_matrix"]:
        print(f"  no matrix theory: {r['no_matrix']}")
    if not r["judged"]:
        print(f"  packing {r['parameters']['packing']:g} is above {DILUTE}: binary-collision theory is shown, not "
              "held to this gas")
    print(f"wrote {shown_path(report.csv)} and {shown_path(report.record_path)}")
    return 0


def _percent(fraction: float) -> str:
    """A drift as a signed percentage to 1e-3 points; one that rounds to zero is +0.000% (its sign, a rounding
    residue's, differs between machines)."""
    points = 100.0 * fraction
    return f"{points if round(points, 3) else 0.0:+.3f}%"
