"""spinbounce theory: what the theory that applies predicts, without running LAMMPS."""

from __future__ import annotations

import json
import math

from ..model.parameters import SceneError
from .options import json_flag, model_from, model_parser, number, scene_from, scene_parser

HELP = ("print the theory that applies to a contact model: its scattering matrix (Eq. 18) and Omega, "
        "or, for a given state, the outcome")
STATE_FLAGS = (("--vn", "v_n", "normal velocity v_n(0) (< 0)"), ("--vt", "v_t", "tangential velocity v_t(0)"),
               ("--omega", "omega", "angular velocity omega(0), anticlockwise positive"),
               ("--vs", "v_s", "3-D: second tangential velocity"), ("--omega-s", "omega_s", "3-D: spin along v_s"),
               ("--omega-n", "omega_n", "3-D: spin about the normal"))


def register(sub) -> None:
    p = sub.add_parser("theory", parents=[model_parser(), scene_parser()], help=HELP, description=HELP + ".")
    g = p.add_argument_group("a state (optional): print its outcome instead of the matrix")
    for flag, dest, text in STATE_FLAGS:
        g.add_argument(flag, dest=dest, type=number, default=None, help=text)
    p.add_argument("--romega", "--r-omega", dest="r_omega", type=number, default=None,
                   help="instead of --omega: r*omega(0)")
    json_flag(p)
    p.set_defaults(handler=run)


def _state(args, r: float) -> dict | None:
    given = {dest: getattr(args, dest) for _, dest, _ in STATE_FLAGS if getattr(args, dest) is not None}
    if args.r_omega is not None:
        if "omega" in given:
            raise SceneError("r_omega", args.r_omega, "give --omega or --r-omega, not both")
        given["omega"] = args.r_omega / r
    if not given:
        return None
    if "v_n" not in given:
        raise SceneError("v_n", None, "a state needs --vn (and --vt, --omega; they default to 0)")
    return given


def run(args) -> int:
    from ..exact import choose

    model = model_from(args)
    state = _state(args, model.r)
    b = scene_from(args)
    if b is not None:
        from .pair import pair_theory

        return pair_theory(args, model, b, state)
    if state is not None:
        return _outcome(args, model, state)
    choice = choose.which(model)
    if not choice.has_matrix:
        report = {"theory_kind": choice.kind, "theory_name": choice.name, "matrix": None,
                  "why_no_matrix": choice.no_matrix_reason}
        if args.json:
            print(json.dumps(report, indent=2))
        else:
            print(f"theory: {choice.name}\nno single scattering matrix: {choice.no_matrix_reason}")
        return 0
    return _matrix(args, model, choice)


def _matrix(args, model, choice) -> int:
    import numpy as np
    from .. import exact

    report = {
        "theory_kind": choice.kind, "theory_name": choice.name,
        "tau": model.tau, "Q": model.Q, "Omega": model.Omega, "restitution": model.restitution,
        "matrix": model.matrix().tolist(), "order": ["v_n", "v_t", "r_omega"],
        "Omega_paper": exact.Omega(model.kn, model.kt, model.alpha),
        "Omega_paper_damped": exact.Omega_paper_damped(model.m, model.kn, model.kt, model.alpha, model.gamma_t),
        "magic_kt_over_kn": exact.magic_kt_over_kn(model.alpha),
    }
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    damped = choice.kind == "damped"
    print(f"theory: {choice.name}")
    print(f"tau   = {model.tau:.10g}   (contact time, Eq. 16; pi*sqrt(m/kn) = {math.pi * math.sqrt(model.m / model.kn):.10g})")
    print(f"Q     = {model.Q:.10g}   (Eq. 8)")
    print(f"Omega = {model.Omega:.10g}   ({'exact damped' if damped else 'Eq. 18'})")
    if damped:
        print(f"        Eq. 18 undamped: {report['Omega_paper']:.10g}; paper's Eq. 22: {report['Omega_paper_damped']:.10g}")
    print("scattering matrix, (v_n, v_t, r*omega) before -> after:")
    with np.printoptions(precision=8, suppress=True, floatmode="fixed"):
        for row in model.matrix():
            print("   ", row)
    print(f"energy-conserving ratio kt/kn = alpha/(1+alpha) = {report['magic_kt_over_kn']:.10g} (Omega = -2)")
    return 0


def _outcome(args, model, state: dict) -> int:
    """The final state of one collision from the theory that applies (no LAMMPS run)."""
    from ..exact import choose

    initial, final = choose.outcome(model, **state)
    names = list(initial)
    choice = choose.which(model)
    report = {"theory_kind": choice.kind, "theory_name": choice.name, "initial": initial, "theory": final,
              "contact_time": float(model.contact_times(state["v_n"])[0])}
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    print(f"theory: {choice.name}")
    print(f"{'':8}" + "".join(f"{n:>16}" for n in names))
    for label in ("initial", "theory"):
        print(f"{label:8}" + "".join(f"{report[label][n]:>16.10f}" for n in names))
    return 0
