"""spinbounce theory: tau, Q, Omega and the scattering matrix of a contact model."""

from __future__ import annotations

import json
import math

import numpy as np

from .. import theory
from .options import json_flag, model_from, model_parser

HELP = "print tau (Eq. 16), Q (Eq. 8), Omega (Eq. 18) and the 3x3 scattering matrix"


def register(sub) -> None:
    p = sub.add_parser("theory", parents=[model_parser()], help=HELP, description=HELP + ".")
    json_flag(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    model = model_from(args)
    report = {
        "tau": model.tau,
        "Q": model.Q,
        "omega": model.Omega,
        "matrix": model.matrix().tolist(),
        "restitution": model.restitution,
        "omega_paper": theory.Omega(model.kn, model.kt, model.alpha),
        "omega_paper_damped": theory.Omega_paper_damped(model.m, model.kn, model.kt, model.alpha, model.gamma_t),
        "magic_kt_over_kn": theory.magic_kt_over_kn(model.alpha),
        "order": ["v_n", "v_t", "r_omega"],
    }
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    damped = model.gamma_t > 0 or model.gamma_n > 0
    print(f"tau   = {model.tau:.10g}   (contact time, Eq. 16; pi*sqrt(m/kn) = {math.pi * math.sqrt(model.m / model.kn):.10g})")
    print(f"Q     = {model.Q:.10g}   (Eq. 8)")
    print(f"Omega = {model.Omega:.10g}   ({'exact damped' if damped else 'Eq. 18'})")
    if damped:
        print(f"        Eq. 18 undamped: {report['omega_paper']:.10g}; paper's Eq. 22: {report['omega_paper_damped']:.10g}")
    print("scattering matrix, (v_n, v_t, r*omega) before -> after:")
    with np.printoptions(precision=8, suppress=True, floatmode="fixed"):
        for row in model.matrix():
            print("   ", row)
    print(f"energy-conserving ratio kt/kn = alpha/(1+alpha) = {report['magic_kt_over_kn']:.10g} (Omega = -2)")
    return 0
