"""spinbounce collide (and its alias pair): one LAMMPS collision against the theory that applies.

Parsing and printing only: the work is :func:`spinbounce.api.collide`.
"""

from __future__ import annotations

from .options import (check_run_folder, model_parser, note, number, pair_parsers, print_json, run_folder_flags,
                      shown_path, state_cell, state_parser, values_of)

HELP = "bounce one sphere off the wall (or a second free sphere: --scene pair) in LAMMPS against the theory"
PAIR_HELP = "collide sphere a with a free sphere b in LAMMPS (pair granular): collide --scene pair"


def _label(name: str) -> str:
    """A state column as printed: r times a spin reads r*omega."""
    return name.replace("r_omega", "r*omega")


def register(sub) -> None:
    _parser(sub, "collide", HELP, HELP + ". --scene pair: sphere b (--m-b, --r-b, --alpha-b; at rest unless its "
                                        "state is given, --v-n-b ... --omega-n-b) instead of the wall.")
    _parser(sub, "pair", PAIR_HELP,
            PAIR_HELP + ": the same options, --scene pair by default. Sphere a is the model's (--m, --r, "
                        "--alpha), b's state is in a's frame and sign.")


def _parser(sub, name: str, help_: str, description: str) -> None:
    p = sub.add_parser(name, parents=[model_parser(), state_parser(), *pair_parsers()], help=help_,
                       description=description)
    if name == "pair":  # the alias: a pair unless told otherwise
        p.set_defaults(scene="pair")
    step = p.add_mutually_exclusive_group()
    step.add_argument("--dt", type=number, default=None,
                      help="timestep (default: the accuracy rule's step, model/timestep.py, with the contact's "
                           "end mid-step; a damped wall collision runs four steps extrapolated to dt = 0 instead, "
                           "extrapolation.py; Coulomb-capped, Hertzian and pair scenes measure theirs with a "
                           "short probe, stepping.py)")
    step.add_argument("--tolerance", type=number, default=None, metavar="TOL",
                      help="ask for an accuracy instead: runs at doubling resolutions, extrapolated to dt = 0 "
                           "until the estimated error is below TOL (reported with the result; the wall only)")
    run_folder_flags(p, "run folder for the deck, dump, log and result.json (default: "
                        "spinbounce-runs/<kind>-<hash>)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from .. import api
    from ..errors import SceneError
    from ..records import json_ready

    if args.command == "pair" and args.scene != "pair":
        raise SceneError("--scene", args.scene, "pair is collide --scene pair: for the wall, use collide")
    check_run_folder(args.out, args.force)
    # --out was checked above, naming the command's flags: the API is told to go ahead
    report = api.collide(**values_of(args), dt=args.dt, tolerance=args.tolerance, out=args.out, force=True,
                         log=None if args.json else (print if args.tolerance is not None else note))
    record = report.record if isinstance(report, api.ToleranceReport) else report.record()
    if args.json:  # with the parameters it ran (the state given, the model and scene as they were read)
        return print_json(record | {"parameters": json_ready(values_of(args))})
    if isinstance(report, api.PairReport):
        print_pair_record(record)
    elif isinstance(report, api.ToleranceReport):
        print(f"collision to tolerance {record['tolerance']:g}: {len(record['levels'])} runs, "
              f"{record['steps']} LAMMPS steps (one plain run would need "
              f"~{record['plain_steps_for_same_estimate']:.0f} for the same error)")
        _print_states(record, list(report.table.index), label_width=10)
        print(f"estimated error {record['estimate']:.2e} ({report.how} from the runs in "
              f"{report.path.parent})")
        print(f"record: {shown_path(report.path)}")
    else:
        omega_text = f"Omega = {report.Omega:.8g}" if report.Omega is not None else "no single Omega"
        print(f"collision: dt = {report.dt:.6g} ({report.nsteps} steps, contact time "
              f"{report.contact_time:.6g}); theory: {report.theory_name}; {omega_text}")
        _print_states(record, list(report.table.index), label_width=8)
        estimate = f", estimated {report.step['estimate']:.2e}" if "estimate" in report.step else ""
        print(f"accuracy: max |LAMMPS - theory| / |initial state| = {report.error:.2e} "
              f"(target {report.step['target']:g}; step: {report.step['method']}{estimate}); status {report.status}")
        for w in report.warnings:
            print(f"warning: {w}")
        dump = "none (its states passed in memory)" if report.dump is None else shown_path(report.dump)
        print(f"deck: {shown_path(report.deck)}\ndump: {dump}\nLAMMPS {report.lammps_version}")
    return 0


def _print_states(record: dict, names, label_width: int) -> None:
    """The initial, LAMMPS, theory and error rows of a collision report."""
    print(f"{'':{label_width}}" + "".join(f"{_label(n):>16}" for n in names))
    for label in ("initial", "LAMMPS", "theory", "error"):
        cell = "{:>16.3e}".format if label == "error" else state_cell
        print(f"{label:{label_width}}" + "".join(cell(record[label.lower()][n]) for n in names))


def print_pair_record(record: dict) -> None:
    """A pair's report: both spheres' states (b's with _b) initially, as LAMMPS ended them (when it
    ran), by the exact reference (theory) and by the planar theory."""
    ran = "lammps" in record
    print(f"contact {record['contact_time']:.6g} (planar tau {record['tau']:.6g}); line of centres turned "
          f"{record['turn']:.4g} rad (eps = {record['eps']:.4g}, centrifugal ratio {record['centrifugal']:.4g})"
          + (f"; dt = {record['dt']:.6g}, {record['nsteps']} steps" if ran else ""))
    columns = [c for c in ("initial", "lammps", "theory", "error", "planar") if c in record]
    print(f"{'':12}" + "".join(f"{'LAMMPS' if c == 'lammps' else c:>14}" for c in columns))
    for name in (n for n in record["theory"] if n.startswith(("v_", "r_"))):
        cells = (f"{record[c][name]:>14.3e}" if c == "error" else f"{record[c][name]:>14.8f}" for c in columns)
        print(f"{_label(name):12}" + "".join(cells))
    print((f"accuracy: max |LAMMPS - theory| / the pair's speed = {record['error_estimate']:.2e} "
           f"(theory: the exact reference; status {record['status']}); " if ran else "")
          + f"planar theory vs exact (model error): {record['planar_error']:.2e}")
    if ran:
        for w in record["warnings"]:
            print(f"warning: {w}")
        print(f"run: {record['run_dir']}")
