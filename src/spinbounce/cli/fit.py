"""spinbounce fit: least-squares scattering matrices of a sweep, against the theory that applies."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from ..model import parameters
from .options import json_flag, optional_number, print_json

#: Parameters a group can be selected by: the model's and the scene's (wall or pair, sphere b's).
SELECTABLE = parameters.MODEL + parameters.SCENE
HELP = ("fit the 3x3 scattering matrix (6x6 for a 3-D sweep) and Omega (Eq. 19) per model group, where one "
        "matrix applies; otherwise report each group's per-collision deviation from its theory")


def register(sub) -> None:
    p = sub.add_parser("fit", help=HELP, description=HELP + ".")
    p.add_argument("results", type=Path, help="a sweep's output folder (or its chunks/ dataset)")
    json_flag(p)
    p.add_argument("--plot", type=_figure_path, metavar="PATH",
                   help="also draw Delta v_t and r Delta omega against the initial slip, per group "
                        "(Eq. 19), to PATH (.png or .pdf; a file there is kept unless --force)")
    p.add_argument("--force", action="store_true", help="replace the file --plot names if it exists")
    g = p.add_argument_group("select groups (any model parameter: fit only the groups with that value)")
    for parameter in SELECTABLE:
        kind = {"flag": _flag_value, "choice": str}.get(parameter.kind, optional_number)
        g.add_argument(*parameter.flags, dest=parameter.name, type=kind, default=argparse.SUPPRESS,
                       metavar="VALUE", help=f"{parameter.meaning} ({parameter.range_text()})")
    p.set_defaults(handler=run)


def _flag_value(text: str) -> bool:
    if text.lower() not in ("true", "false"):
        raise argparse.ArgumentTypeError(f"{text!r}: give true or false")
    return text.lower() == "true"


def _figure_path(text: str) -> Path:
    # Checked while parsing, so a typo fails before the dataset is read.
    path = Path(text)
    if path.suffix.lower() not in (".png", ".pdf"):
        raise argparse.ArgumentTypeError(f"{text!r}: the figure's name must end in .png or .pdf")
    return path


def run(args) -> int:
    import numpy as np

    from .. import api

    from ..records import check_new_file

    check_new_file(args.plot, args.force, "--plot", "--force")
    selection = {p.name: getattr(args, p.name) for p in SELECTABLE if hasattr(args, p.name)}
    fits = api.fit_groups(args.results, plot=args.plot, force=True, **selection)
    if args.plot:
        print(f"figure: {args.plot}")
    if args.json:
        return print_json(fits)
    for f in fits:
        p = f["parameters"]
        print("group: " + ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                                    for k, v in p.items()))
        print(f"  collisions {f['n']}; theory: {f['theory']}; {f['regime']}")
        size = "the pair's speed, both spheres" if p.get("scene") == "pair" else "the state's size"
        print(f"  per collision |LAMMPS - theory|: worst {f['worst_deviation']:.2e}, median "
              f"{f['median_deviation']:.2e} (over {size}: worst {f['worst_relative_deviation']:.2e})"
              + ("; rows " + ", ".join(f"{n} {s}" for s, n in f["status"].items()) if "status" in f else ""))
        if not f["has_matrix"]:
            continue
        print(f"  Omega = {f['Omega']:.8f} +/- {f['Omega_stderr']:.1e} "
              f"(theory {f['Omega_theory']:.8f}, diff {f['Omega_diff']:.2e})")
        # rounded, and + 0.0: no "-0"
        fitted, theory = (np.round(np.array(f[key]), 7) + 0.0 for key in ("matrix", "matrix_theory"))
        with np.printoptions(precision=7, suppress=True, floatmode="fixed"):
            for fitted_row, theory_row in zip(fitted, theory, strict=True):
                print(f"  fit {fitted_row}   theory {theory_row}")
        rms = " ".join(f"{x:.1e}" for x in f["residual_rms"])
        print(f"  largest element difference {f['max_element_diff']:.2e}; residual rms {rms}")
        if math.isnan(f["Omega"]):
            print("  (no tangential slip in this group: Omega cannot be fitted)")
    return 0
