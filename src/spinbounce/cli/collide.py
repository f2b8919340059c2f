"""spinbounce collide: one LAMMPS collision against Eq. 18."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

from ..pipeline import run_collision
from ..model.scenes import Collision
from .options import default_run_dir, json_flag, model_from, model_parser

HELP = "bounce one sphere off the wall in LAMMPS and compare with the scattering matrix (Eq. 18)"


def register(sub) -> None:
    p = sub.add_parser("collide", parents=[model_parser()], help=HELP, description=HELP + ".")
    g = p.add_argument_group("initial state")
    g.add_argument("--vn", type=float, required=True, help="normal velocity v_n(0) (< 0: towards the wall)")
    g.add_argument("--vt", type=float, required=True, help="tangential velocity v_t(0)")
    g.add_argument("--omega", type=float, required=True, help="angular velocity omega(0), anticlockwise positive")
    step = p.add_mutually_exclusive_group()
    step.add_argument("--dt", type=float, default=None,
                      help="timestep (default: tau/(N + 1/2), N = 250 steps per half-period of the fastest mode)")
    step.add_argument("--tolerance", type=float, default=None, metavar="TOL",
                      help="ask for an accuracy instead: runs at doubling resolutions, extrapolated to dt = 0 "
                           "until the estimated error is below TOL (reported with the result)")
    p.add_argument("--out", type=Path, default=None, metavar="DIR",
                   help="run folder for the deck, dump, log and result.json (default: spinbounce-runs/collide-<hash>)")
    json_flag(p)
    p.set_defaults(handler=run)


def _state(table, suffix: str, r: float) -> dict:
    row = table.iloc[0]
    return {
        "vn": float(row[f"vn_{suffix}"]),
        "vt": float(row[f"vt_{suffix}"]),
        "omega": float(row[f"r_omega_{suffix}"]) / r,
        "r_omega": float(row[f"r_omega_{suffix}"]),
    }


def run(args) -> int:
    if args.tolerance is not None:
        return _run_to_tolerance(args)
    scene = Collision(model_from(args), v_n=args.vn, v_t=args.vt, omega=args.omega, dt=args.dt)
    out = args.out or default_run_dir(
        "collide", {"model": dataclasses.asdict(scene.model), "vn": args.vn, "vt": args.vt,
                    "omega": args.omega, "dt": scene.dt}
    )
    result = run_collision(scene, out)
    r = scene.model.r
    t = result.table
    report = {
        "initial": _state(t, "0", r),
        "final": _state(t, "final", r),
        "theory": _state(t, "theory", r),
        "error": _state(t, "error", r),
        "dt": scene.dt,
        "nsteps": scene.nsteps,
        "tau": scene.model.tau,
        "Omega": scene.model.Omega,
        "deck": str(result.info.deck),
        "dump": str(result.dump),
        "lammps_version": result.info.lammps_version,
        "warnings": list(result.warnings),
    }
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    print(f"collision: dt = {scene.dt:.6g} ({scene.nsteps} steps, tau = {scene.model.tau:.6g}), "
          f"Omega = {scene.model.Omega:.8g}")
    _print_states(report, label_width=8)
    for w in result.warnings:
        print(f"warning: {w}")
    print(f"deck: {report['deck']}\ndump: {report['dump']}\nLAMMPS {report['lammps_version']}")
    return 0


def _print_states(report: dict, label_width: int) -> None:
    """The initial, LAMMPS, theory and error rows of a collision report, in (v_n, v_t, r*omega)."""
    print(f"{'':{label_width}}{'v_n':>16}{'v_t':>16}{'r*omega':>16}")
    for label, key in (("initial", "initial"), ("LAMMPS", "final"), ("theory", "theory"), ("error", "error")):
        fmt = "{:>16.3e}" if key == "error" else "{:>16.10f}"
        print(f"{label:{label_width}}" + "".join(fmt.format(report[key][k]) for k in ("vn", "vt", "r_omega")))


def _run_to_tolerance(args) -> int:
    from ..studies.tolerance import collide_to_tolerance, collision_frame

    model = model_from(args)
    out = args.out or default_run_dir(
        "collide", {"model": dataclasses.asdict(model), "vn": args.vn, "vt": args.vt, "omega": args.omega,
                    "tolerance": args.tolerance})
    result, scene = collide_to_tolerance(model, args.vn, args.vt, args.omega, args.tolerance, out,
                                         log=(lambda *_: None) if args.json else print)
    row = collision_frame(result, scene).iloc[0]
    r = model.r
    keys = ("vn", "vt", "r_omega")
    report = {
        "initial": {k: float(row[f"{k}_0"]) for k in keys},
        "final": {k: float(row[f"{k}_final"]) for k in keys},
        "estimate": result.max_estimate,
        "theory": {k: float(row[f"{k}_theory"]) for k in keys},
        "error": {k: float(row[f"{k}_error"]) for k in keys},
        "tolerance": result.tolerance,
        "steps": result.steps,
        "plain_steps_for_same_estimate": result.plain_steps_for(result.max_estimate),
        "levels": result.levels,
        "Omega": model.Omega,
    }
    report["final"]["omega"] = report["final"]["r_omega"] / r
    out_json = Path(out) / "tolerance.json"
    from ..records import to_json, write_atomic
    from ..lammps.runner import lammps_version

    report["lammps_version"] = lammps_version()
    write_atomic(out_json, to_json(report))
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    print(f"collision to tolerance {result.tolerance:g}: {len(result.levels)} runs, {result.steps} LAMMPS steps "
          f"(one plain run would need ~{report['plain_steps_for_same_estimate']:.0f} for the same error)")
    _print_states(report, label_width=10)
    print(f"estimated error {result.max_estimate:.2e} (extrapolated to dt = 0 from the runs in {out})")
    print(f"record: {out_json}")
    return 0
