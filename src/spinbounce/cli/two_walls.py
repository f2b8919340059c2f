"""spinbounce two-walls: a sphere bouncing between two parallel walls, LAMMPS against the matrices."""

from __future__ import annotations

from .options import figure_options, make_with_runs, print_json

HELP = "bounce a sphere many times between two parallel walls in LAMMPS, against the product of the matrices"


def register(sub) -> None:
    p = sub.add_parser(
        "two-walls", help=HELP,
        description=(f"{HELP} (the top wall's conjugated by the mirror z -> -z) or, with a finite mu, the exact "
                     "stick-slip solution bounce by bounce: the paper's model, the magic kt/kn = 2/7, a damped and a capped "
                     "contact. Writes two_walls.png, two_walls.pdf and two_walls.json."),
    )
    figure_options(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..records import json_ready
    from ..figures.two_walls import make_figure

    meta = make_with_runs(make_figure, args.out, args.runs, "spinbounce-two-walls-")
    summary = [{"case": c["label"], "theory": c["theory"], "max_abs_deviation": c["max_abs_deviation"],
                "final_state_lammps": c["lammps_path"][-1]} for c in meta["cases"]]
    if args.json:
        return print_json(json_ready({"out": str(args.out), "files": meta["files"], "cases": summary}))
    for s in summary:
        final = ", ".join(f"{x:.3g}" for x in s["final_state_lammps"])
        print(f"{s['case']:<40} ({s['theory']}): largest |LAMMPS - theory| {s['max_abs_deviation']:.2e} over "
              f"{meta['bounces']} bounces; last state ({final})")
    print(f"wrote {args.out / meta['files']['png']}, {args.out / meta['files']['pdf']}, {args.out / 'two_walls.json'} "
          f"({meta['runtime_seconds']:.1f} s)")
    return 0
