"""spinbounce frozen: a sphere held in contact at fixed height, against Eq. 10."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

from ..pipeline import frozen_metadata, run_frozen, to_json, write_atomic
from ..scenes import Frozen
from .options import default_run_dir, json_flag, model_from, model_parser

HELP = "hold a sphere in contact at height z (v_n = 0) and compare v_t(t), omega(t) with Eq. 10"
COLUMNS = ["t", "vt", "omega", "r_omega", "vt_theory", "r_omega_theory"]


def register(sub) -> None:
    p = sub.add_parser("frozen", parents=[model_parser()], help=HELP, description=HELP + ".")
    g = p.add_argument_group("scene")
    g.add_argument("--z", type=float, required=True, help="height of the centre, 0 < z < r")
    g.add_argument("--vt", type=float, required=True, help="tangential velocity v_t(0)")
    g.add_argument("--omega", type=float, required=True, help="angular velocity omega(0), anticlockwise positive")
    g.add_argument("--t-end", type=float, required=True, help="duration")
    p.add_argument("--dt", type=float, default=None,
                   help="timestep (default: 1000 steps per half-period of the slip oscillation)")
    p.add_argument("--every", type=int, default=None, help="output every this many steps (default: ~2000 rows)")
    p.add_argument("--out", type=Path, required=True, metavar="FILE.csv",
                   help="time series to write; its provenance goes to FILE.meta.json beside it")
    p.add_argument("--run-dir", type=Path, default=None, metavar="DIR",
                   help="folder for the deck, dump and log (default: spinbounce-runs/frozen-<hash>)")
    json_flag(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    scene = Frozen(model_from(args), z=args.z, v_t=args.vt, omega=args.omega, t_end=args.t_end,
                   dt=args.dt, every=args.every)
    run_dir = args.run_dir or default_run_dir(
        "frozen", {"model": dataclasses.asdict(scene.model), "z": scene.z, "vt": scene.v_t,
                   "omega": scene.omega, "nsteps": scene.nsteps, "dt": scene.dt, "every": scene.every}
    )
    result = run_frozen(scene, run_dir)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(out, result.table[COLUMNS].to_csv(index=False, float_format="%.17g"))
    meta = frozen_metadata(result)
    meta["csv"] = str(out)
    meta_path = out.with_suffix(".meta.json")
    write_atomic(meta_path, to_json(meta))
    if args.json:
        print(json.dumps({"csv": str(out), "meta": str(meta_path), "rows": len(result.table),
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
