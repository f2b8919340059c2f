"""spinbounce fit: least-squares scattering matrices of a sweep, against the theory."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from ..fit import fit_groups, plot_groups
from ..sweeps import read_results

HELP = "fit the 3x3 scattering matrix (6x6 block matrix for a 3-D sweep) and Omega (Eq. 19) per model group"


def register(sub) -> None:
    p = sub.add_parser("fit", help=HELP, description=HELP + ".")
    p.add_argument("results", type=Path, help="a sweep's output folder (or its chunks/ dataset)")
    p.add_argument("--json", action="store_true", help="print machine-readable JSON instead of text")
    p.add_argument("--plot", type=_figure_path, metavar="PATH",
                   help="also draw Delta v_t and r Delta omega against the initial slip, per group "
                        "(Eq. 19), to PATH (.png or .pdf)")
    p.set_defaults(handler=run)


def _figure_path(text: str) -> Path:
    # Checked while parsing, so a typo fails before the dataset is read.
    path = Path(text)
    if path.suffix.lower() not in (".png", ".pdf"):
        raise argparse.ArgumentTypeError(f"{text!r}: the figure's name must end in .png or .pdf")
    return path


def run(args) -> int:
    rows = read_results(args.results)
    fits = fit_groups(rows)
    if args.plot:
        plot_groups(rows, args.plot)
    if args.json:
        print(json.dumps(fits, indent=2))
        return 0
    for f in fits:
        p = f["parameters"]
        print("group: " + ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in p.items()))
        print(f"  collisions {f['n']}; Omega = {f['omega']:.8f} +/- {f['omega_stderr']:.1e} "
              f"(theory {f['omega_theory']:.8f}, diff {f['omega_diff']:.2e})")
        with np.printoptions(precision=7, suppress=True, floatmode="fixed"):
            for fitted, theory in zip(np.array(f["matrix"]), np.array(f["matrix_theory"]), strict=True):
                print(f"  fit {fitted}   theory {theory}")
        print(f"  largest element difference {f['max_element_diff']:.2e}; residual rms "
              + " ".join(f"{x:.1e}" for x in f["residual_rms"])
              + f"; largest per-collision error {f['max_abs_error_vs_theory']:.1e}")
    return 0
