"""spinbounce frozen: a sphere held in contact at fixed height, against Eq. 10."""

from __future__ import annotations

from .options import (check_run_folder, count, model_parser, model_values, note, number, print_json,
                      run_folder_flags, shown_path)

HELP = "hold a sphere in contact at height z (v_n = 0) and compare v_t(t), omega(t) with Eq. 10"


def register(sub) -> None:
    p = sub.add_parser("frozen", parents=[model_parser()], help=HELP, description=HELP + ".")
    g = p.add_argument_group("scene")
    g.add_argument("--z", type=number, required=True, help="height of the centre, 0 < z < r")
    g.add_argument("--vt", "--v-t", dest="v_t", type=number, required=True, help="tangential velocity v_t(0)")
    g.add_argument("--omega", type=number, required=True, help="angular velocity omega(0), anticlockwise positive")
    g.add_argument("--t-end", type=number, required=True, help="duration")
    step = p.add_mutually_exclusive_group()
    step.add_argument("--dt", type=number, default=None,
                      help="timestep (default: 1000 steps per half-period of the slip oscillation)")
    step.add_argument("--tolerance", type=number, default=None, metavar="TOL",
                      help="ask for an accuracy instead: runs at halving dt, extrapolated to dt = 0 until the "
                           "estimated error is below TOL (with --mu: until the error measured against the capped "
                           "theory is; the CSV gets an 'estimate' column)")
    p.add_argument("--every", type=count, default=None, help="output every this many steps (default: ~2000 rows)")
    run_folder_flags(p, "run folder: the deck, dump and log, the time series frozen.csv and its record "
                        "result.json (default: spinbounce-runs/frozen-<hash>)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from .. import api

    check_run_folder(args.out, args.force)
    # --out was checked above, naming the command's flags: the API is told to go ahead
    report = api.frozen(args.z, args.v_t, args.omega, args.t_end, dt=args.dt, every=args.every, tolerance=args.tolerance,
                        out=args.out, force=True, **model_values(args),
                        log=None if args.json else (print if args.tolerance is not None else note))
    r = report.record
    laddered = "levels" in r  # to a tolerance: asked for, or the default accuracy measured (a classic cap)
    if args.json:
        return print_json(r if laddered else
                          {"csv": r["csv"], "record": str(report.record_path), "rows": r["rows"],
                           "max_abs_error": r["max_abs_error"], "dt": r["parameters"]["dt"],
                           "deck": r["deck"], "lammps_version": r["lammps_version"]})
    if laddered:
        print(f"frozen contact to tolerance {r['tolerance']:g}: {len(r['levels'])} runs, {r['steps']} LAMMPS "
              f"steps (one plain run would need ~{r['plain_steps_for_same_estimate']:.0f})")
        if "method" in r:  # measured, not extrapolated (a capped contact)
            print(f"error {r['estimate']:.2e} ({r['method']})")
        else:
            print(f"estimated error {r['estimate']:.2e}; largest |extrapolated - theory| {r['max_abs_error']:.2e}")
    else:
        q = r["parameters"]
        print(f"frozen contact: z = {q['z']:g}, dt = {q['dt']:.6g}, {q['nsteps']} steps, t_end = {q['t_end']:.6g}")
        print(f"largest |LAMMPS - theory| in v_t and r*omega: {r['max_abs_error']:.3e}")
    print(f"wrote {shown_path(report.csv)} ({r['rows']} rows) and {shown_path(report.record_path)}")
    if not laddered:
        print(f"deck: {shown_path(r['deck'])}\nLAMMPS {r['lammps_version']}")
    return 0
