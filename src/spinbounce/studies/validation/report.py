"""The benchmarks' report: BENCHMARKS.md, benchmarks.json and benchmarks.png/pdf.

Everything here is drawn and written from the tables :func:`.run.run_benchmark`
returns; nothing is recomputed. matplotlib is imported only when the figure is drawn.
"""

from __future__ import annotations

import math
import tempfile
import time
from contextlib import nullcontext
from pathlib import Path

import numpy as np

from ...outputs import check_outputs, write_output
from ...records import json_ready, software
from .cases import select
from .quantities import QUANTITIES, quantity, restitution, walton
from .run import ACCEPTANCE, BenchmarkRun, run_benchmark

__all__ = ["make_benchmarks", "draw", "markdown", "record"]

#: One colour per series of a benchmark.
COLOURS = ("#d62728", "#1f77b4", "#2ca02c", "#9467bd")


def _draw_series(ax, run: BenchmarkRun, k: int, y: str) -> None:
    """Series ``k`` of a run on one panel: oracle line, LAMMPS circles, rigid-body dashes, data squares."""
    bench = run.benchmark
    series = bench.series[k]
    c = COLOURS[k % len(COLOURS)]
    many = len(bench.series) > 1
    s = run.table[run.table["series"] == series.label].sort_values("x")
    ok = s[s["oracle_ok"]]
    ax.plot(ok["x"], ok[f"{y}_oracle"], "-", color=c, lw=1.0, label=series.label if many else "oracle")
    ax.plot(s["x"], s[f"{y}_lammps"], "o", ms=2.8, mfc="none", color=c, label="LAMMPS" if k == 0 else None)
    # Walton's outcome on a dense grid of the benchmark's x quantity
    grid = np.linspace(np.nanmin(s["x"]), np.nanmax(s["x"]), 400)
    initial = np.array([bench.to_state(series.model, x) for x in grid]) * [1.0, 1.0, series.model.r]
    final, _ = walton(series.model, initial, restitution(series.model, initial), bench.beta0)
    ax.plot(quantity(bench.x, initial, initial, series.model), quantity(y, initial, final, series.model),
            "--", color=c, lw=0.9, alpha=0.8, label="rigid body" if k == 0 else None)
    m = run.measured
    pts = m[(m["series"] == series.label) & (m["quantity"] == y)] if len(m) else m
    if len(pts):
        first = not any(h.get_label() == "data" for h in ax.lines)
        ax.plot(pts["x"], pts["measured"], "s", ms=3.5, color=c if many else "k", label="data" if first else None)


def _dashpot(model) -> str:
    """The normal dashpot of a series' model: gamma_n (kg/s), or its damping model's prefactor of a^s."""
    s = model.damping_law.radius_power(model.normal_law)
    if not s:
        return f"gamma_n = {model.gamma_n:.6g} kg/s"
    return f"damping {model.damping}, dashpot gamma_n a^{s:g} with gamma_n = {model.gamma_n:.6g} (SI)"


def draw(runs: list[BenchmarkRun]):
    """One row per benchmark, one panel per plotted quantity against the benchmark's x."""
    from ...figures.core import new_figure

    ncols = max(len(r.benchmark.panels) for r in runs)
    fig, axes = new_figure(len(runs), ncols, figsize=(3.2 * ncols, 2.9 * len(runs)))
    for row, run in enumerate(runs):
        bench = run.benchmark
        for col, ax in enumerate(axes[row]):
            if col >= len(bench.panels):
                ax.set_axis_off()
                continue
            for k in range(len(bench.series)):
                _draw_series(ax, run, k, bench.panels[col])
            ax.set_xlabel(QUANTITIES[bench.x]["label"])
            ax.set_ylabel(QUANTITIES[bench.panels[col]]["label"])
            if col == 0:
                ax.set_title(bench.name, loc="left", fontweight="bold")
            if col == len(bench.panels) - 1:
                ax.legend(fontsize=6, loc="best", ncol=2 if len(bench.series) > 1 else 1)
    _fit_ylabels(fig)
    return fig


def _fit_ylabels(fig, smallest: float = 6.0) -> None:
    """Shrink each y-label longer than its axes is tall until it fits (not below ``smallest``
    points): the layout engine moves labels but cannot shorten them, so a long label would
    run past the figure's edge and be cut off."""
    fig.canvas.draw()  # lays the figure out: the axes' heights are known from here
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        label = ax.yaxis.label
        if not ax.get_visible() or not ax.axison or not label.get_text():
            continue
        room = ax.get_window_extent(renderer).height
        length = label.get_window_extent(renderer).height
        if length > room:
            label.set_fontsize(max(smallest, label.get_fontsize() * room / length))


def _fmt(x, spec=".2e") -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return format(x, spec)


def _hertz_mindlin_names() -> list[str]:
    """The benchmarks with a damped series whose springs both grow with the contact radius (Hertz's, Mindlin's)."""
    def damped_hertz_mindlin(m) -> bool:  # as the sentence that names them says: coeff_restitution, no gamma_t
        return (m.normal_law.contact_radius and m.tangential_law.contact_radius and m.gamma_n > 0.0
                and m.damping == "coeff_restitution" and m.gamma_t == 0.0)

    return [b.name for b in select(None) if any(damped_hertz_mindlin(s.model) for s in b.series)]


def _introduction(meta: dict) -> list[str]:
    return [
        "# Published sphere-wall benchmarks",
        "",
        f"Regenerated by `spinbounce benchmarks` (spinbounce {meta['spinbounce_version']}, LAMMPS "
        f"{meta['lammps_version']}, {meta['created']}); figure `benchmarks.png`, every number in `benchmarks.json`. "
        "Do not edit by hand.",
        "",
        "Each state is run in LAMMPS (one batch per contact model, at the benchmark's refined step and at twice "
        "that refinement), integrated by the Coulomb oracle (exact for the Hookean model), and set beside "
        "Walton's rigid-body law and, where they exist, measured or published points.",
        "",
        "**Normalisation.** Deviations are the largest over (v_n, v_t, r omega) of the absolute difference, divided "
        "by the impact speed U = sqrt(v_n^2 + (v_t + r omega)^2), the contact point's speed at first touch "
        f"(|v| for an oblique impact, the spin's surface speed for a spin drop). The bar for LAMMPS against the "
        f"oracle is {ACCEPTANCE:g} U.",
        "",
        "**Models.** Hookean normal and tangential springs with history, a Coulomb cap, normal damping set "
        "for the benchmark's restitution e with `limit_damping` (the normal force is never tensile, as in "
        "rigid-body theory: otherwise the cap mu |F_n| passes through zero at the tensile turn and sheds the "
        "spring's load), no tangential damping, a solid sphere (alpha = 2/5). chung-ooi-5 is undamped (e = 1): its normal "
        "force is never tensile, and `limit_damping` is left off there. "
        "The rigid-body column is Walton's law with beta0 = 0 (the contact point stops when the Coulomb bound "
        "is not reached); it is exact for this model in gross sliding when e = 1, and approached with damping. "
        f"The Hertz-Mindlin series ({', '.join(_hertz_mindlin_names())}) are LAMMPS's `hertz` with "
        "`damping coeff_restitution` (the normal force let pull) and `tangential mindlin` without a tangential "
        "dashpot, "
        "set beside the Coulomb oracle carried over to them (exact.oracle); their pull near the exit adds "
        "friction the rigid-body law does not have.",
        "",
        "## Summary",
    ]


def _summary(runs: list[BenchmarkRun]) -> list[str]:
    lines = [
        "",
        "| benchmark | states | refine (dt = default/refine) | max \\|LAMMPS - oracle\\|/U | at 2x refine | "
        f"below {ACCEPTANCE:g}? | oracle failures | max \\|oracle - rigid\\|/U, sliding | all states | "
        "model - measured (max abs) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for run in runs:
        s = run.summary()
        meas = "; ".join(f"{q}: {v['max_abs_model_minus_measured']:.3g}"
                         f"{' ' + v['unit'] if v['unit'] else ''}" for q, v in s["measured"].items()) or "no data"
        lines.append(
            f"| {s['benchmark']} | {s['states']} | {s['refine']} | {s['max_dev_lammps_oracle_rel']:.2e} | "
            f"{s['max_dev_lammps_oracle_rel_2f']:.2e} | {'yes' if s['passes'] else '**no**'} | "
            f"{s['oracle_failures']} | {_fmt(s['max_dev_oracle_rigid_rel_sliding'])} | "
            f"{s['max_dev_oracle_rigid_rel']:.2e} | {meas} |")
    failures = sum(r.summary()["oracle_failures"] for r in runs)
    if failures:
        lines += [
            "",
            f"**Oracle failures ({failures} states).** The oracle stops with 'more than 200 regime switches' for "
            "damped contacts that are still sliding when the normal force ends under `limit_damping`: its "
            "stick-test jumps there (the cap's rate drops to zero) and the switch is found a hair before the "
            "force's end, so it switches stick/slip at the same instant forever. These states have no oracle "
            "value; their LAMMPS result is checked against its own run at twice the refinement "
            "(column 'self'), and against the rigid-body law.",
        ]
    return lines


def _section(run: BenchmarkRun) -> list[str]:
    """A benchmark's sources, models, notes and largest deviation."""
    bench, s = run.benchmark, run.summary()
    lines = ["", f"## {bench.name}: {bench.title}", "", bench.citation, "", "Sources:", ""]
    lines += [f"- {what}: {src}" for what, src in bench.sources]
    lines += ["", f"Stiffness: {bench.stiffness}", "",
              f"Step: refine {bench.refine}; {bench.refine_why}."]
    for series in bench.series:
        mdl, v_n = series.model, series.states[0][0]
        spring = (f"kt = {mdl.kt:.6g} N/m" if not mdl.tangential_law.contact_radius
                  else f"tangential {mdl.tangential}, k_t = {mdl.tangential_law.stiffness(mdl):.6g} N/m^2")
        lines.append(f"Model ({series.label}): m = {mdl.m:.6g} kg, r = {mdl.r:g} m, {mdl.normal} kn = {mdl.kn:.6g} "
                     f"{'N/m^2' if mdl.normal_law.contact_radius else 'N/m'}, {spring}, {_dashpot(mdl)}, mu = {mdl.mu:g}, restitution {float(mdl.normal_law.restitutions(mdl, v_n)[0]):.6g}, "
                     f"limit_damping {mdl.limit_damping}, contact time "
                     f"{float(mdl.normal_law.force_times(mdl, v_n)[0]):.4g} s.")
    lines += [f"- {n}" for n in bench.notes]
    lines += [
        "",
        f"Largest \\|LAMMPS - oracle\\|/U: **{s['max_dev_lammps_oracle_rel']:.2e}** (state "
        f"{s['max_dev_lammps_oracle_state']}), {'below' if s['passes'] else '**above**'} the "
        f"{ACCEPTANCE:g} bar; at twice the refinement {s['max_dev_lammps_oracle_rel_2f']:.2e}.",
    ]
    return lines


def _states_table(run: BenchmarkRun) -> list[str]:
    """One row per state: the first panel's quantity, regimes and deviations."""
    bench = run.benchmark
    y = bench.panels[0]
    lines = [
        "",
        f"| series | state | {QUANTITIES[bench.x]['label']} | U (m/s) | rigid regime | oracle pattern | "
        f"{QUANTITIES[bench.panels[0]]['label']}: LAMMPS / oracle / rigid | \\|L - O\\|/U | at 2x | self "
        "\\|L - L(2x)\\|/U | \\|O - R\\|/U | first-touch stick estimate /U |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in run.table.to_dict(orient="records"):
        lines.append(
            f"| {r['series']} | {r['state']} | {r['x']:.4g} | {r['impact_speed']:.4g} | {r['regime_rigid']} | "
            f"{r['oracle_pattern']} | {r[f'{y}_lammps']:.5g} / {_fmt(r[f'{y}_oracle'], '.5g')} / "
            f"{r[f'{y}_rigid']:.5g} | {_fmt(r['dev_lammps_oracle_rel'])} | {_fmt(r['dev_lammps_oracle_rel_2f'])} | "
            f"{r['dev_lammps_self_rel']:.2e} | {_fmt(r['dev_oracle_rigid_rel'])} | "
            f"{_fmt(r['first_touch_stick_rel'])} |")
    return lines


def _measured_table(run: BenchmarkRun) -> list[str]:
    m = run.measured
    if not len(m):
        return []
    lines = ["", "Measured and published points, with the model (oracle) and the rigid-body law at the "
              "same digitised input:", "",
              "| series | quantity | x | measured | LAMMPS | model | rigid | model - measured | "
              "rigid - measured | rigid regime | source |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in m.to_dict(orient="records"):
        lines.append(
            f"| {r['series']} | {r['quantity']} | {r['x']:.4g} | {r['measured']:.4g} | {r['lammps']:.4g} | "
            f"{_fmt(r['model'], '.4g')} | {r['rigid']:.4g} | {_fmt(r['model_minus_measured'], '.3g')} | "
            f"{r['rigid_minus_measured']:.3g} | {r['regime_rigid']} | {r['source']} |")
    return lines


def markdown(runs: list[BenchmarkRun], meta: dict) -> str:
    """BENCHMARKS.md: how the benchmarks were run, a summary, each benchmark's tables."""
    lines = _introduction(meta) + _summary(runs)
    for run in runs:
        lines += _section(run) + _states_table(run) + _measured_table(run)
    lines += ["", "## Where the Hookean model departs from Hertz-Mindlin and the data", "", *DEPARTURES, ""]
    return "\n".join(lines)


DEPARTURES = [
    "- **Sliding regime** (rigid regime 'sliding'): every contact slides over the whole impact, the friction "
    "impulse is mu times the normal impulse whatever the force law, and the oracle, LAMMPS, the rigid-body law, "
    "Hertz-Mindlin references and the measurements agree. Without damping (chung-ooi-5) oracle and rigid body "
    "agree to round-off. With damping the cap starts at mu gamma_n |v_n| > 0, so the contact first sticks "
    "briefly and falls short of the rigid-body impulse; the column 'first-touch stick estimate' gives the "
    "size expected from that (c0^2/(2 kt |u'| alpha m) in r omega), and the oracle-rigid deviation in "
    "sliding tracks it: largest near the threshold and for strong damping (thornton-linear e = 0.25, "
    "whose normalised spin levels off near -4.7 where rigid theory and the digitised data give -5: a dashpot "
    "that already pushes at first touch, as a linear one does, costs that much friction impulse).",
    "- **Sticking regime**: rigid-body theory with beta0 = 0 stops the contact point; a compliant contact "
    "does not. The tangential spring stores energy and gives it back (the contact point's velocity can "
    "reverse), and micro-slip switches between sticking and sliding (oracle patterns stick-slip-stick-slip). "
    "The measured e_t dip to 0.6 and the negative contact rebound angles of chung-ooi-4 are this effect, "
    "which the Hookean model reproduces in kind; its size depends on kt/kn. Hertz-Mindlin has a stiffness "
    "that grows with the overlap and a tangential stiffness that softens with micro-slip (Mindlin-Deresiewicz), "
    "so at the same kt/kn ratio of tangent stiffnesses the Hookean contact's tangential oscillation has a "
    "different phase at separation: the model-measured differences are largest here.",
    "- **Near-normal incidence**: chung-ooi-4's measured e_t near 2 deg (0.79) and the centre rebound angle are "
    "sensitive to small tangential speeds; a linear contact with kt/kn near 0.86 keeps part of the slip "
    "energy in the spring and returns it, Hertz-Mindlin and the experiment return less.",
    "- **Restitution**: the benchmarks' e is matched exactly (limit_damping, gamma_n from bisection). "
    "A Hertzian dashpot gives a restitution that changes with impact speed; a linear one does not.",
]


def record(runs: list[BenchmarkRun], meta: dict) -> dict:
    """benchmarks.json: ``meta``, then per benchmark its definition, runs, summary and tables."""
    out = dict(meta)
    out["benchmarks"] = []
    for run in runs:
        b = run.benchmark
        out["benchmarks"].append({
            "name": b.name, "title": b.title, "citation": b.citation,
            "sources": [{"what": w, "source": s} for w, s in b.sources], "stiffness": b.stiffness,
            "refine": b.refine, "refine_why": b.refine_why, "beta0": b.beta0, "x": b.x, "panels": list(b.panels),
            "series": [{"label": s.label, "model": {k: getattr(s.model, k) for k in (
                "m", "r", "alpha", "kn", "kt", "gamma_n", "gamma_t", "mu", "limit_damping")}
                | {k: v for k, v in s.model.as_record().items() if k in ("normal", "tangential", "mindlin_kt")},
                "restitution": float(restitution(s.model, np.array(s.states))[0]),
                "tau": float(s.model.normal_law.force_times(s.model, s.states[0][0])[0])} for s in b.series],
            "runs": run.runs, "summary": run.summary(),
            "states": run.table.to_dict(orient="records"),
            "measured": run.measured.to_dict(orient="records") if len(run.measured) else [],
        })
    return json_ready(out)


def make_benchmarks(out: Path, only: list[str] | None = None, runs: Path | None = None,
                    log=print) -> tuple[list[BenchmarkRun], dict[str, Path]]:
    """Run the selected benchmarks and write BENCHMARKS.md, benchmarks.json, .png and .pdf into ``out``.

    LAMMPS's run folders go under ``runs`` if given (kept), else a temporary folder (removed).
    """
    import matplotlib.style

    from ...figures.core import STYLE, figure_files, save

    chosen = select(only)
    check_outputs(out, (*figure_files("benchmarks"), "BENCHMARKS.md"))
    started = time.perf_counter()
    with (nullcontext(runs) if runs is not None else
          tempfile.TemporaryDirectory(prefix="spinbounce-benchmarks-", ignore_cleanup_errors=True)) as root:
        results = [run_benchmark(b, Path(root), log=log) for b in chosen]
    meta = {
        "report": "benchmarks", **software(),
        "acceptance": ACCEPTANCE, "normalisation": "max over (v_n, v_t, r omega) of |difference| / "
        "sqrt(v_n^2 + (v_t + r omega)^2) at first touch",
        "benchmarks_run": [b.name for b in chosen], "markdown": "BENCHMARKS.md",
        "runs_kept_in": None if runs is None else str(runs),
    }
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    body = record(results, meta)
    with matplotlib.style.context(STYLE):
        fig = draw(results)
        saved = save(fig, out, "benchmarks", body, started)
    md = out / "BENCHMARKS.md"
    write_output(md, markdown(results, meta))
    return results, {"png": saved.png, "pdf": saved.pdf, "json": saved.json, "markdown": md}
