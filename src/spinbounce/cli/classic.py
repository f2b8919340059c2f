"""spinbounce classic: what this build's classic wall does to your collisions, and the line you meant."""

from __future__ import annotations

from .options import (figure_options, make_with_runs, model_parser, model_values, number, print_json,
                      state_parser)

HELP = ("for your contact model: how this build's classic wall (fix wall/gran hooke/history) scatters "
        "against the paper's model, speed by speed, and the granular line that gives the paper's model")


def register(sub) -> None:
    p = sub.add_parser("classic", parents=[model_parser(), state_parser(three_d=False)], help=HELP,
                       description=HELP + ". The state's v_n is one of the table's speeds; --figure also "
                                          "draws classic.png/.pdf/.json, with LAMMPS's classic wall beside the theory.")
    p.add_argument("--speeds", type=number, nargs="+", default=None, metavar="V",
                   help="impact speeds |v_n| for the table (default: 1%%, 10%%, 30%%, 60%% and 90%% of the "
                        "tunnelling speed r sqrt(kn/m), and the state's own)")
    p.add_argument("--figure", action="store_true", help="also write the figure and its JSON record into --out")
    figure_options(p)
    p.set_defaults(handler=run)


def _speeds(args, model) -> list[float]:
    from ..model.parameters import SceneError
    from ..studies.classic_effect import table_speeds, tunnelling_speed

    if args.speeds is None:
        return table_speeds(model, args.v_n).tolist()
    limit = tunnelling_speed(model)
    for speed in args.speeds:
        if not 0.0 < speed < limit:
            raise SceneError("--speeds", speed, f"must be > 0 and below the tunnelling speed r sqrt(kn/m) = {limit:.6g}")
    return sorted(set(args.speeds))


def run(args) -> int:
    from ..model.contact import ContactModel
    from ..records import json_ready
    from ..studies.classic_effect import compare, fix_lines

    model = ContactModel(**model_values(args)).replace(wall="classic")
    rows = compare(model, _speeds(args, model), args.v_t, args.omega)
    lines = fix_lines(model)
    record = None
    if args.figure:
        from ..figures.classic import make_classic

        record = make_with_runs(lambda out, runs: make_classic(out, runs, model, args.v_t, args.omega), args.out,
                                args.runs, "spinbounce-classic-").metadata
    if args.json:
        return print_json(json_ready({"rows": rows, "fix_lines": lines,
                                      "figure": record and record["files"]}))
    print(f"state v_t = {args.v_t:g}, omega = {args.omega:g}; classic: this build's wall/gran hooke/history, "
          "paper: granular linear_history")
    print(f"{'|v_n|':>9s} {'Omega':>9s} {'Omega':>9s} {'v_t out':>9s} {'v_t out':>9s} {'r*w out':>9s} {'r*w out':>9s}"
          f" {'E gain':>10s} {'E gain':>10s}")
    print(f"{'':>9s} {'classic':>9s} {'paper':>9s} {'classic':>9s} {'paper':>9s} {'classic':>9s} {'paper':>9s}"
          f" {'classic':>10s} {'paper':>10s}")
    for row in rows:
        classic, meant = row["final_classic"], row["final_meant"]
        columns = (row["omega_classic"], row["omega_meant"], classic[1], meant[1], classic[2], meant[2])
        print(f"{row['v_n']:9.4g} " + " ".join(f"{round(x, 5) + 0.0:9.5f}" for x in columns)
              + f" {row['energy_gain_classic']:+10.2e} {row['energy_gain_meant']:+10.2e}")
    print(f"you run:   {lines['classic']}")
    print(f"you meant: {lines['granular']}")
    if record is not None:
        print(f"wrote {args.out / record['files']['png']}, {args.out / record['files']['pdf']}, "
              f"{args.out / 'classic.json'}")
    return 0
