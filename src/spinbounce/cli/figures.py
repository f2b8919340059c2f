"""spinbounce figures: the paper's Figs. 2-7 from LAMMPS runs, with a JSON record each."""

from __future__ import annotations

import argparse

from .options import json_flag, note, out_folder, out_option, print_json

HELP = "regenerate the paper's Figs. 2-7 (PNG, PDF and a JSON record each) from LAMMPS runs"


def figure_names(text: str) -> list[str]:
    """argparse type for --only: one name or a comma-separated list, each one of FIGURES."""
    from ..figures import FIGURES, FigureNameError, check_names

    names = [part.strip() for part in text.split(",") if part.strip()]
    if not names:
        raise argparse.ArgumentTypeError(f"no figure named in {text!r} (choose from {', '.join(FIGURES)})")
    try:
        return check_names(names)
    except FigureNameError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def register(sub) -> None:
    from ..figures import FIGURES

    listing = "; ".join(f"{name}: {what}" for name, (_, what) in FIGURES.items())
    p = sub.add_parser("figures", help=HELP, description=f"{HELP}. Figures: {listing}.")
    p.add_argument("--only", action="append", type=figure_names, default=None, metavar="FIG[,FIG...]",
                   help=f"make only these figures (repeat or separate by commas; from {', '.join(FIGURES)})")
    out_option(p, "figN.png, figN.pdf and figN.json")
    p.add_argument("--runs", type=out_folder, default=None, metavar="DIR",
                   help="folder for the LAMMPS runs, one subfolder per figure (default: OUT/runs)")
    json_flag(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..figures import check_names, make_figures

    only = None if args.only is None else check_names(name for group in args.only for name in group)
    records = make_figures(args.out, only=only, log=note if args.json else print, runs=args.runs)
    if args.json:
        summary = [
            {key: m.get(key) for key in ("figure", "files", "max_deviation_exact", "max_deviation_eq22", "dt",
                                         "lammps_version", "spinbounce_version", "runtime_seconds")}
            for m in records
        ]
        return print_json({"out": str(args.out), "figures": summary})
    total = sum(m["runtime_seconds"] for m in records)
    print(f"{len(records)} figure(s) in {args.out} ({total:.1f} s); LAMMPS {records[0]['lammps_version']}")
    return 0
