"""spinbounce theory: what the theory that applies predicts, without running LAMMPS.

Parsing and printing only: the work is :func:`spinbounce.api.theory`.
"""

from __future__ import annotations

import math

from ..errors import SceneError
from .collide import print_pair_record
from .options import json_flag, model_parser, number, pair_parsers, print_json, state_cell, state_parser, values_of

HELP = ("print the theory that applies to a contact model: its scattering matrix (Eq. 18) and Omega, "
        "or, for a given state, the outcome")


def register(sub) -> None:
    parents = [model_parser(), state_parser(optional=True), *pair_parsers()]
    p = sub.add_parser("theory", parents=parents, help=HELP,
                       description=HELP + ". A state (--v-n, and --v-t, --omega, ...: they default to 0) asks for "
                                          "its outcome instead of the matrix.")
    p.add_argument("--romega", "--r-omega", dest="r_omega", type=number, default=None,
                   help="instead of --omega: r*omega(0)")
    json_flag(p)
    p.set_defaults(handler=run)


def _keywords(args) -> dict:
    """The API's keywords: the model, the scene and, if given, the state (--r-omega as omega)."""
    values = values_of(args)
    state = {name: values.pop(name) for name in ("v_n", "v_t", "omega", "v_s", "omega_s", "omega_n", "speed",
                                                 "angle_deg") if name in values}
    if args.r_omega is not None:
        if "omega" in state:
            raise SceneError("r_omega", args.r_omega, "give --omega or --r-omega, not both")
        state["omega"] = args.r_omega / values["r"]
    if state and not {"v_n", "speed", "angle_deg"} & state.keys():
        raise SceneError("v_n", None, "a state needs --vn (and --vt, --omega; they default to 0), or --speed and "
                                      "--angle-deg")
    return values | state


def run(args) -> int:
    import numpy as np

    from .. import api

    report = api.theory(**_keywords(args))
    if args.json:
        return print_json(report, default=lambda x: x.tolist())
    if "planar" in report:
        print_pair_record(report)
        return 0
    print(f"theory: {report['theory_name']}")
    if "theory" in report:
        names = list(report["initial"])
        print(f"{'':8}" + "".join(f"{n:>16}" for n in names))
        for label in ("initial", "theory"):
            print(f"{label:8}" + "".join(state_cell(report[label][n]) for n in names))
    elif report["matrix"] is None:
        print(f"no single scattering matrix: {report['why_no_matrix']}")
    elif report["theory_kind"] == "mindlin":
        _print_mindlin(report)
    elif report["theory_kind"] == "damped_nonlinear":
        print(f"Omega = {report['Omega']:.10g}, restitution = {report['restitution']:.10g}   "
              f"({report['Omega_depends_on']})")
        _print_matrix(report["matrix"])
    elif report["theory_kind"] == "pair planar":
        print(f"tau   = {report['tau']:.10g}   (pi sqrt(m*/kn), m* the reduced mass)")
        print(f"Omega = {report['Omega']:.10g}   (the wall's at alpha_eq = "
              f"{report['alpha_equivalent']:.10g})")
        print("scattering matrix of sphere a, (v_n, v_t, r*omega) before -> after:")
        for row in report["matrix"]:
            print("   ", "  ".join(f"{x:11.8f}" for x in row))
        print(f"model error: {report['model_error']}")
    else:
        damped = report["theory_kind"] == "damped"
        print(f"tau   = {report['tau']:.10g}   (contact time, Eq. 16; pi*sqrt(m/kn) = "
              f"{math.pi * math.sqrt(args.m / args.kn):.10g})")
        print(f"Q     = {report['Q']:.10g}   (Eq. 8)")
        print(f"Omega = {report['Omega']:.10g}   ({'exact damped' if damped else 'Eq. 18'})")
        if damped:
            print(f"        Eq. 18 undamped: {report['Omega_paper']:.10g}; paper's Eq. 22: "
                  f"{report['Omega_paper_damped']:.10g}")
        print("scattering matrix, (v_n, v_t, r*omega) before -> after:")
        with np.printoptions(precision=8, suppress=True, floatmode="fixed"):
            for row in report["matrix"]:
                print("   ", row)
        if damped:  # the magic ratio conserves energy only without dashpots
            print("energy: the dashpots dissipate it at every kt/kn (no energy-conserving ratio with damping)")
        else:
            print(f"energy-conserving ratio kt/kn = alpha/(1+alpha) = {report['magic_kt_over_kn']:.10g} "
                  "(Omega = -2)")
    return 0


def _print_mindlin(report: dict) -> None:
    print(f"Omega = {report['Omega']:.10g}   ({report['Omega_depends_on']}; lam = (1 + alpha)/alpha k_t/kn "
          f"= {report['lam']:.10g}, k_t = {report['k_t']:.10g})")
    print(f"energy: {report['energy']} (|Omega + 1| {'>' if report['energy'] == 'gained' else '<='} 1)")
    _print_matrix(report["matrix"])
    poisson = report.get("energy_conserving_poisson_ratio")
    print(f"energy conserved (searched up to k_t/kn = {report['energy_conserving_searched_to_k_t_over_kn']:.4g}):")
    for key, ratios in report["energy_conserving_k_t_over_kn"].items():
        line = f"{key} (energy conserved) at k_t/kn = {_numbers(ratios) or 'none found'}"
        if poisson is not None:
            line += f"; at Poisson's ratio {_numbers(poisson[key]) or 'none in (-1, 1/2]'}"
        print(line)


def _numbers(values) -> str:
    return ", ".join(f"{x:.10g}" for x in values)


def _print_matrix(matrix) -> None:
    import numpy as np

    print("scattering matrix, (v_n, v_t, r*omega) before -> after:")
    with np.printoptions(precision=8, suppress=True, floatmode="fixed"):
        for row in matrix:
            print("   ", row)
