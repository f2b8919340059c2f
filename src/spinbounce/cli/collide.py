"""spinbounce collide: one LAMMPS collision against the theory that applies."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

from .options import (announce_cost, check_run_folder, default_run_dir, force_flag, json_flag, model_from, model_parser,
                      number, scene_from, scene_parser, state_from, state_parser)

if TYPE_CHECKING:
    from ..scenes.collision import Collision

HELP = "bounce one sphere off the wall in LAMMPS and compare it with the theory that applies"
SUFFIXES = {"initial": "initial", "lammps": "lammps", "theory": "theory", "error": "error"}
LABELS = {"v_n": "v_n", "v_t": "v_t", "r_omega": "r*omega", "v_s": "v_s", "r_omega_s": "r*omega_s",
          "r_omega_n": "r*omega_n"}


def register(sub) -> None:
    p = sub.add_parser("collide", parents=[model_parser(), state_parser(), scene_parser()], help=HELP,
                       description=HELP + " (--scene pair: a free sphere b at rest instead of the wall).")
    step = p.add_mutually_exclusive_group()
    step.add_argument("--dt", type=number, default=None,
                      help="timestep (default: the accuracy rule's step, model/timestep.py, with the contact's "
                           "end mid-step; damped, Coulomb-capped and Hertzian scenes measure theirs with a short "
                           "probe, stepping.py)")
    step.add_argument("--tolerance", type=number, default=None, metavar="TOL",
                      help="ask for an accuracy instead: runs at doubling resolutions, extrapolated to dt = 0 "
                           "until the estimated error is below TOL (reported with the result)")
    p.add_argument("--out", type=Path, default=None, metavar="DIR",
                   help="run folder for the deck, dump, log and result.json (default: spinbounce-runs/collide-<hash>)")
    force_flag(p)
    json_flag(p)
    p.set_defaults(handler=run)


def _states(names, row, suffix: str, r: float) -> dict:
    """A state by column name, each spin also as an angular velocity (r_omega -> omega)."""
    state = {name: float(row[f"{name}_{suffix}"]) for name in names}
    state.update({name[2:]: state[name] / r for name in names if name.startswith("r_")})
    return state


def _contact_time(scene: Collision) -> float:
    import numpy as np

    return float(np.max(scene.model.contact_times(scene.v_n)))


def run(args) -> int:
    import numpy as np
    from ..exact import choose
    from ..scenes.collision import Collision
    from ..pipeline import run_scene
    from ..stepping import expected_steps

    check_run_folder(args.out, args.force)
    state = state_from(args)
    b = scene_from(args)
    if b is not None:
        from .pair import pair_collide

        return pair_collide(args, model_from(args), b, state)
    if args.tolerance is not None:
        return _run_to_tolerance(args, state)
    scene = Collision(model_from(args), dt=args.dt, **state)
    announce_cost(expected_steps(scene), scene.n)
    out = args.out or default_run_dir("collide", {"model": scene.model.as_record(), **state, "dt": scene.dt})
    result = run_scene(scene, out)
    scene = result.scene  # at the step its accuracy needed
    row = result.table.iloc[0]
    names = scene.state_names
    choice = choose.which(scene.model)
    omega = float(choose.omega_per_sphere(scene.model, scene.v_n)[0])
    report = {
        **{key: _states(names, row, suffix, scene.model.r) for key, suffix in SUFFIXES.items()},
        "theory_kind": choice.kind, "theory_name": choice.name,
        "dt": scene.dt, "nsteps": scene.nsteps, "contact_time": _contact_time(scene),
        "step": result.step.record(), "error_estimate": float(row["error"]), "status": row["status"],
        "Omega": None if np.isnan(omega) else omega,
        "deck": str(result.info.deck), "dump": str(result.dump), "lammps_version": result.info.lammps_version,
        "warnings": list(result.warnings),
    }
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    omega_text = f"Omega = {omega:.8g}" if report["Omega"] is not None else "no single Omega"
    print(f"collision: dt = {scene.dt:.6g} ({scene.nsteps} steps, contact time {report['contact_time']:.6g}); "
          f"theory: {choice.name}; {omega_text}")
    _print_states(report, names, label_width=8)
    print(f"accuracy: |LAMMPS - theory| / |initial state| = {row['error']:.2e} "
          f"(target {result.step.target:g}; step: {result.step.method}); status {row['status']}")
    for w in result.warnings:
        print(f"warning: {w}")
    print(f"deck: {report['deck']}\ndump: {report['dump']}\nLAMMPS {report['lammps_version']}")
    return 0


def _print_states(report: dict, names, label_width: int) -> None:
    """The initial, LAMMPS, theory and error rows of a collision report."""
    print(f"{'':{label_width}}" + "".join(f"{LABELS[n]:>16}" for n in names))
    for label, key in (("initial", "initial"), ("LAMMPS", "lammps"), ("theory", "theory"), ("error", "error")):
        fmt = "{:>16.3e}" if key == "error" else "{:>16.10f}"
        print(f"{label:{label_width}}" + "".join(fmt.format(report[key][n]) for n in names))


def _run_to_tolerance(args, state: dict) -> int:
    from ..exact import choose
    from ..extrapolation import collide_to_tolerance, collision_frame
    from ..records import software, to_json, write_atomic

    model = model_from(args)
    out = args.out or default_run_dir("collide", {"model": model.as_record(), **state,
                                                  "tolerance": args.tolerance})
    out_of_plane = {k: v for k, v in state.items() if k in ("v_s", "omega_s", "omega_n") and v}
    result, scene = collide_to_tolerance(model, state["v_n"], state["v_t"], state["omega"], args.tolerance, out,
                                         log=(lambda *_: None) if args.json else print, **out_of_plane)
    row = collision_frame(result, scene).iloc[0]
    names = scene.state_names
    report = {
        **{key: _states(names, row, suffix, model.r) for key, suffix in SUFFIXES.items()},
        "estimate": result.max_estimate,
        "theory_kind": choose.which(model).kind,
        "tolerance": result.tolerance, "steps": result.steps,
        "plain_steps_for_same_estimate": result.plain_steps_for(result.max_estimate),
        "levels": result.levels, "Omega": model.Omega, **software(),
    }
    out_json = Path(out) / "tolerance.json"
    write_atomic(out_json, to_json(report))
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    print(f"collision to tolerance {result.tolerance:g}: {len(result.levels)} runs, {result.steps} LAMMPS steps "
          f"(one plain run would need ~{report['plain_steps_for_same_estimate']:.0f} for the same error)")
    _print_states(report, names, label_width=10)
    print(f"estimated error {result.max_estimate:.2e} ({result.how} from the runs in {out})")
    print(f"record: {out_json}")
    return 0
