"""spinbounce frozen: a sphere held in contact at fixed height, against Eq. 10."""

from __future__ import annotations

import json
from pathlib import Path

from .options import (announce_cost, check_run_folder, count, force_flag, json_flag, model_from,
                      model_parser, number, out_folder)

HELP = "hold a sphere in contact at height z (v_n = 0) and compare v_t(t), omega(t) with Eq. 10"
COLUMNS = ["t", "v_t", "omega", "r_omega", "v_t_theory", "r_omega_theory"]
#: The time series a run writes into its folder.
SERIES = "frozen.csv"


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
                           "estimated error is below TOL (the CSV gets an 'estimate' column)")
    p.add_argument("--every", type=count, default=None, help="output every this many steps (default: ~2000 rows)")
    p.add_argument("--out", type=out_folder, default=None, metavar="DIR",
                   help=f"run folder: the deck, dump and log, the time series {SERIES} and its record "
                        "result.json (default: spinbounce-runs/frozen-<hash>)")
    force_flag(p)
    json_flag(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..scenes.frozen import Frozen
    from ..pipeline import run_series, series_record
    from ..records import run_folder
    from ..records import to_json, write_atomic

    check_run_folder(args.out, args.force)
    if args.tolerance is not None:
        return _run_to_tolerance(args)
    scene = Frozen(model_from(args), z=args.z, v_t=args.v_t, omega=args.omega, t_end=args.t_end,
                   dt=args.dt, every=args.every)
    announce_cost(scene.nsteps)
    run_dir = Path(args.out or run_folder(
        "frozen", {"model": scene.model.as_record(), "z": scene.z, "v_t": scene.v_t,
                   "omega": scene.omega, "nsteps": scene.nsteps, "dt": scene.dt, "every": scene.every}))
    result = run_series(scene, run_dir)
    out = run_dir / SERIES
    write_atomic(out, result.table[COLUMNS].to_csv(index=False, float_format="%.17g"))
    meta = series_record(result)
    meta["csv"] = str(out)
    meta_path = run_dir / "result.json"
    write_atomic(meta_path, to_json(meta))
    if args.json:
        print(json.dumps({"csv": str(out), "record": str(meta_path), "rows": len(result.table),
                          "max_abs_error": result.max_abs_error, "dt": scene.dt,
                          "deck": str(result.info.deck), "lammps_version": result.info.lammps_version},
                         indent=2))
        return 0
    print(f"frozen contact: z = {scene.z:g}, dt = {scene.dt:.6g}, {scene.nsteps} steps, "
          f"t_end = {scene.nsteps * scene.dt:.6g}")
    print(f"largest |LAMMPS - theory| in v_t and r*omega: {result.max_abs_error:.3e}")
    print(f"wrote {out} ({len(result.table)} rows) and {meta_path}")
    print(f"deck: {result.info.deck}\nLAMMPS {result.info.lammps_version}")
    return 0


def _run_to_tolerance(args) -> int:
    import numpy as np
    import pandas as pd
    from ..exact import choose
    from ..extrapolation import frozen_to_tolerance
    from ..records import run_folder
    from ..scenes.frozen import Frozen
    from ..records import software, to_json, write_atomic

    model = model_from(args)
    Frozen(model, z=args.z, v_t=args.v_t, omega=args.omega, t_end=args.t_end)  # validates before any run
    run_dir = Path(args.out or run_folder(
        "frozen", {"model": model.as_record(), "z": args.z, "v_t": args.v_t, "omega": args.omega,
                   "t_end": args.t_end, "tolerance": args.tolerance}))
    result = frozen_to_tolerance(model, args.z, args.v_t, args.omega, args.t_end, args.tolerance, run_dir,
                                 log=(lambda *_: None) if args.json else print)
    v_t_theory, rw_theory = choose.frozen(model, result.t, args.v_t, args.omega * model.r, args.z)
    table = pd.DataFrame({"t": result.t, "v_t": result.values[:, 0], "omega": result.values[:, 1] / model.r,
                          "r_omega": result.values[:, 1], "v_t_theory": v_t_theory, "r_omega_theory": rw_theory,
                          "estimate": result.estimate[:, 0]})
    error = float(max(np.abs(table["v_t"] - v_t_theory).max(), np.abs(table["r_omega"] - rw_theory).max()))
    out = run_dir / SERIES
    write_atomic(out, table.to_csv(index=False, float_format="%.17g"))
    meta = {"scene": "frozen", "model": model.as_record(), "z": args.z, "v_t": args.v_t,
            "omega": args.omega, "t_end": args.t_end, "tolerance": result.tolerance,
            "estimate": result.max_estimate, "max_abs_error": error, "steps": result.steps,
            "plain_steps_for_same_estimate": result.plain_steps_for(result.max_estimate),
            "levels": result.levels, **software(), "csv": str(out)}
    meta_path = run_dir / "tolerance.json"
    write_atomic(meta_path, to_json(meta))
    if args.json:
        print(json.dumps(meta, indent=2))
        return 0
    print(f"frozen contact to tolerance {result.tolerance:g}: {len(result.levels)} runs, {result.steps} LAMMPS "
          f"steps (one plain run would need ~{meta['plain_steps_for_same_estimate']:.0f})")
    print(f"estimated error {result.max_estimate:.2e}; largest |extrapolated - theory| {error:.2e}")
    print(f"wrote {out} ({len(table)} rows) and {meta_path}")
    return 0
