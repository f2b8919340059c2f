"""Options shared by several commands, declared once."""

from __future__ import annotations

import argparse
import hashlib
import json
from pathlib import Path

from ..model.scenes import ContactModel

_DEFAULTS = ContactModel()


def model_parser() -> argparse.ArgumentParser:
    """The contact-model options (paper's defaults), as a parent parser."""
    p = argparse.ArgumentParser(add_help=False)
    g = p.add_argument_group("contact model (defaults: the paper's)")
    g.add_argument("--mass", type=float, default=_DEFAULTS.m, metavar="M", help="sphere mass m (default %(default)s)")
    g.add_argument("--radius", type=float, default=_DEFAULTS.r, metavar="R", help="sphere radius r (default %(default)s)")
    g.add_argument("--alpha", type=float, default=_DEFAULTS.alpha, metavar="A",
                   help="I/(m r^2), in (0, 1] (default %(default)s, a solid sphere)")
    g.add_argument("--kn", type=float, default=_DEFAULTS.kn, help="normal spring constant (default %(default)s)")
    g.add_argument("--kt", type=float, default=_DEFAULTS.kt, help="tangential spring constant (default %(default)s)")
    g.add_argument("--gamma-n", type=float, default=_DEFAULTS.gamma_n, metavar="G",
                   help="normal viscous damping (default %(default)s)")
    g.add_argument("--gamma-t", type=float, default=_DEFAULTS.gamma_t, metavar="G",
                   help="tangential viscous damping (default %(default)s)")
    g.add_argument("--mu", type=float, default=None,
                   help="Coulomb friction coefficient; omit for the paper's model (no Coulomb limit)")
    g.add_argument("--limit-damping", action="store_true",
                   help="never let the normal force pull (LAMMPS's limit_damping): with gamma_n > 0 the "
                        "contact then ends when the dashpot would start to pull")
    return p


def model_from(args: argparse.Namespace) -> ContactModel:
    return ContactModel(
        m=args.mass, r=args.radius, alpha=args.alpha, kn=args.kn, kt=args.kt,
        gamma_n=args.gamma_n, gamma_t=args.gamma_t, mu=args.mu, limit_damping=args.limit_damping,
    )


def json_flag(p: argparse.ArgumentParser) -> None:
    p.add_argument("--json", action="store_true", help="print machine-readable JSON instead of text")


def default_run_dir(kind: str, parameters: dict) -> Path:
    """``spinbounce-runs/<kind>-<hash of the parameters>`` under the current folder."""
    digest = hashlib.sha256(json.dumps(parameters, sort_keys=True).encode()).hexdigest()[:10]
    return Path("spinbounce-runs") / f"{kind}-{digest}"
