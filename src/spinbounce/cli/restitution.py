"""spinbounce restitution: restitution maps against the incidence angle, LAMMPS, theory and Kharaz's data."""

from __future__ import annotations

from .options import figure_options, make_with_runs, print_json

HELP = ("map normal and tangential restitution, rebound angle and spin against the incidence angle (Hooke, Hertz, "
        "with and without mu), with Kharaz's measured alumina data and the model fitted to it")


def register(sub) -> None:
    p = sub.add_parser(
        "restitution", help=HELP,
        description=(f"{HELP}. Each curve is one batched LAMMPS run beside the theory that applies. "
                     "Writes restitution.png, restitution.pdf and restitution.json."),
    )
    figure_options(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..records import json_ready
    from ..studies.restitution import make_figure

    meta = make_with_runs(make_figure, args.out, args.runs, "spinbounce-restitution-")
    fit = meta["kharaz_fit"]
    if args.json:
        curves = [{k: c[k] for k in ("label", "theory_kind", "max_abs_state_deviation")}
                  for c in meta["curves"]]
        return print_json(json_ready({"out": str(args.out), "files": meta["files"], "kharaz_fit": fit,
                                      "curves": curves}))
    for c in meta["curves"]:
        print(f"{c['label']:<60} ({c['theory_kind']}): largest |LAMMPS - theory| in the state "
              f"{c['max_abs_state_deviation']:.2e}")
    print(f"Kharaz et al. 2001 fitted (Hooke, e = {fit['e']}, limit_damping): kt/kn = {fit['kt_over_kn']:.4f}, "
          f"mu = {fit['mu']:.4f}, rms residual {fit['rms_residual']:.4f} over {fit['points']} points")
    print(f"wrote {args.out / meta['files']['png']}, {args.out / meta['files']['pdf']}, "
          f"{args.out / 'restitution.json'} ({meta['runtime_seconds']:.1f} s)")
    return 0
