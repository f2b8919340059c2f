"""spinbounce benchmarks: published sphere-wall DEM benchmarks, LAMMPS against the oracle,
rigid-body theory and measured data."""

from __future__ import annotations

import argparse
import sys

from .options import out_folder, out_option

HELP = "run the published sphere-wall benchmarks (Chung & Ooi Tests 4-6, Thornton's linear law) and report"


def _names(text: str) -> list[str]:
    from ..studies.validation import BENCHMARKS

    names = [n.strip() for n in text.split(",") if n.strip()]
    unknown = [n for n in names if n not in BENCHMARKS]
    if not names or unknown:
        raise argparse.ArgumentTypeError(
            f"unknown benchmark {', '.join(unknown) or repr(text)}; choose from: {', '.join(BENCHMARKS)}")
    return names


def register(sub) -> None:
    p = sub.add_parser(
        "benchmarks", help=HELP,
        description=(f"{HELP}. Each benchmark's states run in LAMMPS at its refined step and at twice that "
                     "refinement, beside the Coulomb oracle, Walton's rigid-body law and digitised data. Writes "
                     "BENCHMARKS.md, benchmarks.json, benchmarks.png and benchmarks.pdf."),
    )
    out_option(p, "the report, the JSON record and the figure")
    p.add_argument("--only", type=_names, default=None, metavar="NAME,...",
                   help="run only these benchmarks (comma-separated): chung-ooi-4, chung-ooi-5, chung-ooi-6, "
                        "thornton-linear")
    p.add_argument("--runs", type=out_folder, default=None, metavar="DIR",
                   help="keep every LAMMPS run's folder here (default: a temporary folder, removed)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..studies.validation.report import make_benchmarks

    results, files = make_benchmarks(args.out, only=args.only, runs=args.runs, log=lambda s: print(s, file=sys.stderr))
    print(f"{'benchmark':<17}{'states':>7}{'refine':>7}{'LAMMPS-oracle':>15}{'at 2x':>10}{'<1e-4':>7}"
          f"{'oracle fails':>13}{'oracle-rigid (sliding)':>24}")
    for r in results:
        s = r.summary()
        sliding = s["max_dev_oracle_rigid_rel_sliding"]
        print(f"{s['benchmark']:<17}{s['states']:>7}{s['refine']:>7}{s['max_dev_lammps_oracle_rel']:>15.2e}"
              f"{s['max_dev_lammps_oracle_rel_2f']:>10.2e}{'yes' if s['passes'] else 'NO':>7}"
              f"{s['oracle_failures']:>13}{(format(sliding, '.2e') if sliding is not None else '-'):>24}")
        for q, v in s["measured"].items():
            unit = f" {v['unit']}" if v["unit"] else ""
            print(f"    {q}: {v['points']} points, max |model - measured| {v['max_abs_model_minus_measured']:.3g}{unit}"
                  f" (rigid body {v['max_abs_rigid_minus_measured']:.3g}{unit})")
    print("deviations: max over (v_n, v_t, r omega) of |difference| / sqrt(v_n^2 + (v_t + r omega)^2)")
    print(f"wrote {', '.join(str(p) for p in files.values())}")
    return 0 if all(r.summary()["passes"] for r in results) else 1
