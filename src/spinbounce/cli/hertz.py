"""spinbounce hertz: the energy-conserving kt of a Hertzian wall against v_n, measured in LAMMPS."""

from __future__ import annotations

from pathlib import Path

from .options import json_flag, note, number, out_folder, out_option, positive_count, print_json

HELP = "measure how the energy-conserving kt depends on v_n with a Hertzian normal force, and plot it"
#: The study's parameters as options: (flag, field of HertzParameters, metavar, help).
PARAMETERS = (("--v-min", "v_min", "V", "slowest |v_n|"), ("--v-max", "v_max", "V", "fastest |v_n|"),
              ("--points", "points", "N", "speeds on the log grid"),
              ("--v-ref", "v_ref", "V", "the speed at which the one-kt series conserves energy"),
              ("--kn", "kn", None, "Hertzian stiffness K, F = K sqrt(r) delta^1.5"),
              ("--mass", "m", "M", "sphere mass"), ("--radius", "r", "R", "sphere radius"),
              ("--alpha", "alpha", "A", "I/(m r^2)"))


def register(sub) -> None:
    from ..figures.hertz_parameters import HertzParameters

    d = HertzParameters()
    p = sub.add_parser(
        "hertz", help=HELP,
        description=(f"{HELP}: for each |v_n| on a log grid, LAMMPS's kt* (from a run at kt*/4) against the "
                     "closed form kt*/kn ~ |v_n|^(2/5), the energy lost at that kt*, and the energy lost at one "
                     "kt for every speed. Writes hertz.png, hertz.pdf, hertz.json and HERTZ.md."),
    )
    out_option(p, "the figure, its JSON record and HERTZ.md")
    p.add_argument("--runs", type=out_folder, default=None, metavar="DIR",
                   help="folder for the LAMMPS runs (default: OUT/runs/hertz)")
    for flag, field, metavar, text in PARAMETERS:
        p.add_argument(flag, dest=field, type=positive_count if field == "points" else number,
                       default=getattr(d, field), metavar=metavar, help=f"{text} (default %(default)s)")
    json_flag(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..figures.hertz import HertzParameters, make_hertz

    params = HertzParameters(**{field: getattr(args, field) for _, field, _, _ in PARAMETERS})
    record = make_hertz(args.out, params, runs=args.runs, log=note if args.json else print)
    meta = record.metadata
    summary = {key: meta[key] for key in ("max_relative_deviation", "slope_lammps", "max_abs_f_at_kt_star_lammps",
                                          "max_abs_f_fixed_deviation", "lammps_version", "runtime_seconds")}
    if args.json:
        return print_json({"out": str(args.out), "files": meta["files"], **summary})
    print(f"largest relative deviation of kt* from the closed form: {summary['max_relative_deviation']:.2e}; "
          f"slope {summary['slope_lammps']:.5f} (2/5); largest |f| at kt*: {summary['max_abs_f_at_kt_star_lammps']:.1e}")
    print(f"wrote {record.png}, {record.pdf}, {record.json}, {Path(args.out) / 'HERTZ.md'} "
          f"({summary['runtime_seconds']:.1f} s)")
    return 0
