"""spinbounce tangential: the coefficient of tangential restitution against the velocity ratio
(Becker, Schwager & Poeschel 2008), LAMMPS, the exact solver and the rigid limits."""

from __future__ import annotations

from .options import figure_options, make_with_runs, print_json

HELP = ("tangential restitution beta = -g_t'/g_t against |g_t|/|v_n| with Coulomb friction (Becker et al. 2008): "
        "LAMMPS, the exact solver, Walton's gross-slip line and the sticking plateau")
#: Not figures/: the repository's committed outputs change only when asked with --out figures.


def register(sub) -> None:
    p = sub.add_parser(
        "tangential", help=HELP,
        description=(f"{HELP}. Each parameter set is one batched LAMMPS run at the default accuracy beside the "
                     "theory. Writes tangential.png, tangential.pdf and tangential.json."),
    )
    figure_options(p)
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..records import json_ready
    from ..studies.tangential import make_figure

    meta = make_with_runs(make_figure, args.out, args.runs, "spinbounce-tangential-")
    summary = [{"set": s["label"], "dt": s["dt"], "plateau": s["plateau"], "switch_ratio": s["switch_ratio"],
                "state_deviation": s["state_deviation"], "beta_deviation": s["beta_deviation"],
                "solver_vs_gross_slip": s["limits"]["gross_slip"]["max_abs"],
                "solver_vs_plateau": s["limits"]["plateau"]["max_abs"],
                "plateau_where": s["limits"]["plateau"]["where"]}
               for s in meta["sets"]]
    if args.json:
        return print_json(json_ready({"out": str(args.out), "files": meta["files"], "sets": summary}))
    for s in summary:
        print(f"{s['set']}: plateau {s['plateau']:.4f}, switch psi* = {s['switch_ratio']:.4f}; "
              f"|LAMMPS - solver| {s['state_deviation']:.1e} (state), {s['beta_deviation']:.1e} (beta); "
              f"|solver - gross slip| {s['solver_vs_gross_slip']:.1e}; |solver - plateau| "
              f"{s['solver_vs_plateau']:.1e} ({s['plateau_where']})")
    print(f"wrote {args.out / meta['files']['png']}, {args.out / meta['files']['pdf']}, "
          f"{args.out / 'tangential.json'} ({meta['runtime_seconds']:.1f} s)")
    return 0
