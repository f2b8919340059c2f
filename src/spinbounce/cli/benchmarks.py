"""spinbounce benchmarks: published sphere-wall DEM benchmarks, LAMMPS against the oracle,
rigid-body theory and measured data."""

from __future__ import annotations

from .options import json_flag, name_list, note, out_folder, out_option, print_json

HELP = ("run the published sphere-wall benchmarks (Chung & Ooi Tests 4-6, Thornton's linear and Hertzian laws) and "
        "report")


def _benchmark_names() -> list[str]:
    from ..studies.validation import BENCHMARKS

    return list(BENCHMARKS)


def register(sub) -> None:
    p = sub.add_parser(
        "benchmarks", help=HELP,
        description=(f"{HELP}. Each benchmark's states run in LAMMPS at its refined step and at twice that "
                     "refinement, beside the Coulomb oracle, Walton's rigid-body law and digitised data. Writes "
                     "BENCHMARKS.md, benchmarks.json, benchmarks.png and benchmarks.pdf."),
    )
    out_option(p, "the report, the JSON record and the figure")
    p.add_argument("--only", type=name_list("benchmark", _benchmark_names), default=None, metavar="NAME,...",
                   help="run only these benchmarks (comma-separated): chung-ooi-4, chung-ooi-5, chung-ooi-6, "
                        "thornton-linear, thornton-hertz-mindlin")
    p.add_argument("--runs", type=out_folder, default=None, metavar="DIR",
                   help="keep every LAMMPS run's folder here (default: a temporary folder, removed)")
    p.add_argument("--pairs", action="store_true",
                   help="run the published sphere-sphere benchmarks instead (Chung & Ooi tests 1, 7, 8; "
                        "studies/validation/pair_cases.py): pair_benchmarks.json")
    json_flag(p)
    p.set_defaults(handler=run)


def _pairs(out, as_json: bool) -> int:
    """The sphere-sphere benchmarks: each in one LAMMPS batch, beside the published value, the
    exact reference and the planar theory."""
    import tempfile
    from pathlib import Path

    from ..outputs import check_replaceable, write_output
    from ..records import software, to_json
    from ..studies.validation.pair_cases import PAIR_BENCHMARKS, run_pair_benchmark

    check_replaceable(Path(out) / "pair_benchmarks.json")
    with tempfile.TemporaryDirectory() as scratch:
        records = [run_pair_benchmark(bench, Path(scratch)) for bench in PAIR_BENCHMARKS.values()]
    Path(out).mkdir(parents=True, exist_ok=True)
    path = write_output(Path(out) / "pair_benchmarks.json", to_json({"benchmarks": records, **software()}))
    if as_json:
        return print_json(records, default=float)
    for r in records:
        print(f"{r['name']:<22} {'agrees' if r['agrees'] else 'DISAGREES'}: {r['published']}; {r['quantity']} "
              f"within {r['lammps_vs_published']:.1e} (bound {r['tolerance']:.1e}); LAMMPS vs exact "
              f"{r['lammps_vs_exact']:.1e}, planar vs exact {r['planar_vs_exact']:.1e}")
    print(f"wrote {path}")
    return 0 if all(r["agrees"] for r in records) else 1


def run(args) -> int:
    from ..studies.validation.report import make_benchmarks

    if args.pairs:
        return _pairs(args.out, args.json)

    results, files = make_benchmarks(args.out, only=args.only, runs=args.runs, log=note)
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
