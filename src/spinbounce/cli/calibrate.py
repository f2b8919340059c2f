"""spinbounce calibrate: from a bounce's restitutions and contact time to LAMMPS parameters."""

from __future__ import annotations

from ..laws import TANGENTIAL
from ..model.parameters import by_name
from ..errors import SceneError
from .options import json_flag, make_with_runs, number, optional_number, out_folder, print_json

HELP = ("turn targets (normal restitution e, tangential restitution beta or Omega, mu, contact time) into "
        "LAMMPS wall/gran and pair granular parameters, and check them in LAMMPS")


def register(sub) -> None:
    p = sub.add_parser(
        "calibrate", help=HELP,
        description=(f"{HELP}. Inverts the exact linear theory (docs/theory.md, 'Calibration'): kn and gamma_n from "
                     "e and the contact time, kt (gamma_t held, default 0) or gamma_t (--kt-over-kn held) from the "
                     "tangential restitution of the contact point, beta = -u'(out)/u'(in) = -(1 + Omega), which a "
                     "sticking collision obeys. Unreachable targets are refused with the reachable range. Then runs "
                     "one LAMMPS bounce with the parameters and prints what it achieved."),
    )
    t = p.add_argument_group("targets")
    t.add_argument("--e", type=number, required=True, help="normal restitution, in (0, 1]")
    t.add_argument("--contact-time", type=number, default=None, metavar="T",
                   help="how long the sphere overlaps the wall (time units); the linear model's (required there)")
    tangential = t.add_mutually_exclusive_group()
    tangential.add_argument("--beta", type=number, help="tangential restitution of the contact point, in [-1, 1]")
    tangential.add_argument("--Omega", type=number, help="Eq. 18's Omega, in [-2, 0] (beta = -(1 + Omega))")
    t.add_argument("--mu", type=optional_number, default=None, help="friction coefficient (default: none, no cap)")
    s = p.add_argument_group("sphere and what is held")
    for name in ("m", "r", "alpha"):
        parameter = by_name(name)
        s.add_argument(*parameter.flags, dest=name, type=number, default=parameter.default,
                       help=f"{parameter.meaning} (default %(default)s)")
    s.add_argument("--limit-damping", action="store_true", help="never let the normal force pull (LAMMPS's keyword)")
    held = s.add_mutually_exclusive_group()
    held.add_argument("--gamma-t", type=number, default=None, help="hold the tangential damping (default 0), solve kt")
    held.add_argument("--kt-over-kn", type=number, default=None, help="hold kt/kn, solve gamma_t")
    hm = p.add_argument_group("Hertz-Mindlin instead of the linear model (hertz/material, damping coeff_restitution: "
                              "e_n = e at every speed; beta sets nu's NULL stiffness, or k_t with --poisson-ratio)")
    hm.add_argument("--tangential", choices=[k for k in TANGENTIAL if TANGENTIAL[k].contact_radius
                                             and not TANGENTIAL[k].classic_cap], default=None,
                    help="the Mindlin variant: calibrate Hertz-Mindlin")
    for name in ("youngs_modulus", "poisson_ratio", "x_t"):
        parameter = by_name(name)
        hm.add_argument(*parameter.flags, dest=name, type=number, default=None, help=parameter.meaning)
    p.add_argument("--no-run", action="store_true", help="print the parameters only; do not run LAMMPS")
    p.add_argument("--runs", type=out_folder, default=None, metavar="DIR",
                   help="keep the LAMMPS run here (default: a temporary folder, removed)")
    json_flag(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..studies.calibrate import Targets, calibrate, fix_line, measure, pair_lines

    if args.tangential is not None:
        return _run_mindlin(args)
    for name in ("contact_time", "youngs_modulus", "poisson_ratio", "x_t"):
        given = getattr(args, name)
        if (name == "contact_time") == (given is None):
            raise SceneError(name, given, "is the linear model's: required there" if name == "contact_time"
                             else "is Hertz-Mindlin's: give --tangential too")
    if args.beta is None and args.Omega is None:
        raise SceneError("beta", None, "the linear model needs a tangential target: --beta or --Omega")
    beta = args.beta if args.beta is not None else -(1.0 + args.Omega)
    gamma_t = None if args.kt_over_kn is not None else (args.gamma_t or 0.0)
    calibration = calibrate(Targets(e=args.e, contact_time=args.contact_time, beta=beta, mu=args.mu, m=args.m,
                                    r=args.r, alpha=args.alpha, limit_damping=args.limit_damping,
                                    gamma_t=gamma_t, kt_over_kn=args.kt_over_kn))
    model = calibration.model
    report = {"targets": {"e": args.e, "beta": calibration.targets.beta, "contact_time": args.contact_time,
                          "mu": args.mu},
              "parameters": {k: getattr(model, k) for k in ("m", "r", "alpha", "kn", "kt", "gamma_n", "gamma_t", "mu",
                                                            "limit_damping")},
              "fix_wall_gran": fix_line(model), "pair_granular": list(pair_lines(model)),
              "theory": calibration.achieved_theory()}
    if not args.no_run:
        report["lammps"] = make_with_runs(lambda _, runs: measure([calibration], runs)[0], None, args.runs,
                                          "spinbounce-calibrate-")
        if args.runs is None:  # its deck went with the temporary folder
            report["lammps"]["deck"] = None
    if args.json:
        return print_json(report)
    print("parameters: " + ", ".join(f"{k} = {v!r}" for k, v in report["parameters"].items()))
    print(f"wall (z = 0):\n  {report['fix_wall_gran']}")
    print("two equal spheres (kn, gamma_n, kt, gamma_t halved: reduced mass m/2):\n  "
          + "\n  ".join(report["pair_granular"]))
    print(f"{'':<14}{'target':>14}{'theory':>14}" + ("" if args.no_run else f"{'LAMMPS':>14}"))
    for label, key in (("e", "e"), ("beta", "beta"), ("contact time", "contact_time")):
        line = f"{label:<14}{report['targets'][key]:>14.8g}{report['theory'][key]:>14.8g}"
        print(line + ("" if args.no_run else f"{report['lammps'][key]:>14.8g}"))
    if args.mu is not None and not args.no_run:
        print("(LAMMPS's beta from a sticking bounce: slip u'(0) = 1e-3 mu |v_n|)")
    return 0


def _run_mindlin(args) -> int:
    """Hertz-Mindlin: e_n = e, beta through nu or k_t; then one LAMMPS bounce at the default step."""
    from ..lammps.decks import fix_line
    from ..studies.calibrate_mindlin import MindlinTargets, achieved, calibrate_mindlin, measure_mindlin

    if args.contact_time is not None:
        raise SceneError("contact_time", args.contact_time, "is set by the material and the speed with "
                                                            "Hertz-Mindlin: give --youngs-modulus instead")
    beta = args.beta if args.beta is not None or args.Omega is None else -(1.0 + args.Omega)
    targets = MindlinTargets(e=args.e, beta=beta, youngs_modulus=args.youngs_modulus or 1.0e4,
                             poisson_ratio=args.poisson_ratio, tangential=args.tangential, x_t=args.x_t, m=args.m,
                             r=args.r, alpha=args.alpha)
    model = calibrate_mindlin(targets)
    names = ("m", "r", "alpha", "youngs_modulus", "poisson_ratio", "e_n", "x_t", "mindlin_kt", "kn")
    report = {"targets": {"e": args.e, "beta": beta}, "parameters": {k: getattr(model, k) for k in names},
              "fix_wall_gran": fix_line(model), "theory": achieved(model)}
    if not args.no_run:
        report["lammps"] = make_with_runs(lambda _, runs: measure_mindlin(model, runs), None, args.runs,
                                          "spinbounce-calibrate-")
    if args.json:
        return print_json(report)
    print("parameters: " + ", ".join(f"{k} = {v!r}" for k, v in report["parameters"].items()))
    print(f"wall (z = 0):\n  {report['fix_wall_gran']}")
    print(f"{'':<14}{'target':>14}{'theory':>14}" + ("" if args.no_run else f"{'LAMMPS':>14}"))
    for key in ("e", "beta"):
        target = report["targets"][key]
        line = f"{key:<14}{'-' if target is None else format(target, '.8g'):>14}{report['theory'][key]:>14.8g}"
        print(line + ("" if args.no_run else f"{report['lammps'][key]:>14.8g}"))
    print("(the same at every impact speed: the contact is self-similar)")
    return 0
