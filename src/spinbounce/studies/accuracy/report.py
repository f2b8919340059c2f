"""The study's outputs: accuracy.png/.pdf (error against steps and seconds), accuracy.json
(every run) and ACCURACY.md (orders, steps per target, the default step, costs, and why), each written
atomically through :mod:`spinbounce.records` (the figures through figures.core.save)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from ...model.contact import ContactModel
from ...outputs import write_output
from ...records import json_ready
from .cases import ANY, EDGE, FROZEN_T_END, MECHANISMS, MID
from .orders import ERROR_FLOOR, FIT_LEVELS, TARGETS
from .study import Study

__all__ = ["draw", "markdown", "write_study", "EXTRA_CURVES"]

#: Curves drawn besides each case's first form: the end on a step where it is first order
#: (defaults) or third (magic, head-on), and the Hertzian wall's one dt for all spheres.
EXTRA_CURVES = {("defaults", EDGE), ("magic", EDGE), ("head_on", EDGE), ("hertz", ANY)}
_LINESTYLE = {EDGE: "--", ANY: "-."}


def _records(frame: pd.DataFrame) -> list[dict]:
    return [json_ready(r) for r in frame.to_dict(orient="records")]


def _curve(table: pd.DataFrame, name: str, form: str) -> pd.DataFrame:
    return table[(table["case"] == name) & (table["form"] == form) & table["in_ladder"]
                 & (table["error"] > ERROR_FLOOR)]


def _under_the_first(study: Study) -> list[str]:
    """Names of the cases whose main curve lies on the first case's (the same v_n error sets
    both): the first case is drawn wide and underneath so that it stays visible."""
    first = study.cases[0]
    base = _curve(study.table, first.name, MID)
    same = []
    for c in study.cases[1:]:
        rows = _curve(study.table, c.name, MID)
        if (c.kind == first.kind and np.array_equal(rows["lammps_steps"], base["lammps_steps"])
                and np.allclose(rows["error"], base["error"], rtol=1e-6, atol=0.0)):
            same.append(c.name)
    return same


def fitted_seconds(rows: pd.DataFrame) -> np.ndarray:
    """A curve's LAMMPS seconds smoothed: the least-squares line start-up + steps x per-step cost
    through its measured (steps, seconds), each coefficient kept >= 0. Single timings of runs of
    milliseconds scatter by tens of per cent on a shared machine; the line keeps what they say."""
    steps, seconds = rows["lammps_steps"].to_numpy(float), rows["lammps_seconds"].to_numpy(float)
    slope, start = np.polyfit(steps, seconds, 1) if len(steps) > 1 else (0.0, float(seconds.mean()))
    slope = max(float(slope), 0.0)
    start = max(float(np.mean(seconds - slope * steps)), 0.0) if start < 0.0 or slope == 0.0 else float(start)
    return start + slope * steps


def draw(study: Study):
    """Error against LAMMPS steps and against LAMMPS's seconds: one curve per case in its first
    form, plus the EXTRA_CURVES; the legend gives each curve's observed order. Call inside
    ``matplotlib.style.context(STYLE)``."""
    import matplotlib

    from ...figures.core import new_figure

    fig, axes = new_figure(1, 2, figsize=(11.5, 6.6), sharey=True)
    ax_steps, ax_wall = axes[0]
    colours = list(matplotlib.colormaps["tab20"].colors)
    markers = "osD^v<>phH*Xd8P"
    orders = {(r["case"], r["form"]): r["observed_order"] for r in study.summary.to_dict(orient="records")}
    same = _under_the_first(study)
    for k, case in enumerate(study.cases):
        for form in case.forms:
            main = form == case.forms[0]
            if not main and (case.name, form) not in EXTRA_CURVES:
                continue
            rows = _curve(study.table, case.name, form)
            label = f"{case.label}{'' if main else ', ' + form}: order {orders[(case.name, form)]:.2f}"
            colour = colours[k % len(colours)]
            style = {"color": colour, "marker": markers[k % len(markers)], "markersize": 3.5,
                     "linestyle": "-" if main else _LINESTYLE[form], "linewidth": 1.3 if main else 1.0,
                     "markerfacecolor": colour if main else "none"}
            if k == 0 and main and same:
                label += f" (wide; under {', '.join(same)})"
                style.update(linewidth=5.0, alpha=0.35, zorder=1, markersize=0)
            ax_steps.loglog(rows["lammps_steps"], rows["error"], label=label, **style)
            ax_wall.loglog(fitted_seconds(rows), rows["error"], **style)
            # the run at the scenes' default step: a star on its curve (if the form has one)
            t = study.table
            star = t[(t["case"] == case.name) & (t["form"] == form) & t["default_dt"]]
            ax_steps.loglog(star["lammps_steps"], star["error"], linestyle="none", marker="*", markersize=10,
                            color=colour, markeredgecolor="black", markeredgewidth=0.6, zorder=5)
    for target in TARGETS:
        for ax in (ax_steps, ax_wall):
            ax.axhline(target, color="0.8", linewidth=0.7, zorder=0)
    ax_steps.set_xlabel("LAMMPS steps per run")
    ax_steps.set_ylabel("largest |LAMMPS $-$ theory|")
    # LAMMPS's own seconds: the run's wall seconds also hold the theory (the oracle's take ~0.5 s)
    ax_wall.set_xlabel("LAMMPS seconds per run (start-up + steps x cost, fitted per curve)")
    ax_steps.set_ylim(ERROR_FLOOR / 2, 0.3)
    ax_steps.set_title("error against steps (dashed: the end on a step; star: the default step)")
    ax_wall.set_title("error against LAMMPS's wall time (start-up dominates below ~10$^4$ steps)")
    handles, labels = ax_steps.get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=7.5)
    return fig


def _fmt_steps(steps: float, extrapolated: bool) -> str:
    if not math.isfinite(steps):
        return "n/a"
    text = f"{steps:.1e}".replace("e+0", "e") if steps >= 1e5 else f"{math.ceil(steps):,}"
    return f"{text}*" if extrapolated else text


def _fmt_order(order) -> str:
    return "-" if order is None or not math.isfinite(order) else f"{order:.2f}"


def _cell(text: str) -> str:
    """Text for a markdown table cell: a bare | would end the cell."""
    return text.replace("|", r"\|")


def _order_table(study: Study) -> list[str]:
    lines = [
        ("| case | form | observed order (v_n; tangential) | expected | error at the default step "
         "| steps for 1e-4 | 1e-6 | 1e-8 |"),
        "|---|---|---|---|---|---|---|---|",
    ]
    labels = {c.name: c.label for c in study.cases}
    rough = {(c.name, form) for c in study.cases for form in c.rough}
    for r in study.summary.to_dict(orient="records"):
        cells = [
            _cell(labels[r["case"]]), r["form"],
            f"{'~' if (r['case'], r['form']) in rough else ''}**{_fmt_order(r['observed_order'])}** "
            f"({_fmt_order(r['order_v_n'])}; {_fmt_order(r['order_tangential'])})",
            f"{r['expected_order']:g}",
            "-" if not math.isfinite(r["error_at_default_dt"]) else f"{r['error_at_default_dt']:.2e}",
            *(_fmt_steps(r[f"steps_{t:.0e}"], r[f"extrapolated_{t:.0e}"]) for t in TARGETS),
        ]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def _intro(study: Study) -> list[str]:
    meta = study.metadata
    steps = meta["parameters"]["ladder_steps_per_half_period"]
    return [
        "# Speed against accuracy",
        "",
        (f"Regenerated by `spinbounce accuracy{' --quick' if meta['quick'] else ''}` "
         f"(spinbounce {meta['spinbounce_version']}, LAMMPS {meta['lammps_version']}, {meta['created']}); "
         "figure `accuracy.png`, every run in `accuracy.json`."),
        "",
        (f"Each case runs a ladder of n = {steps[0]} to {steps[-1]} steps per half-period of its fastest "
         "contact mode. Error: the largest |LAMMPS - theory| over the case's states and state columns "
         "(frozen: over the whole time series), against each case's own theory: Eq. 18 (its exact damped "
         "form, its 6x6 block form in 3-D, its Omega(v_n) for a Hertzian wall), Eq. 10 for frozen contacts, "
         "the Coulomb oracle for a finite mu. Forms: the contact's end in the middle of a step "
         "(dt = tau/(M + 1/2), the form of every default step but a Hertzian batch's), on a step boundary "
         "(dt = tau/M), or, for the Hertzian wall, "
         "wherever one dt for every speed puts it (its mid-step form runs each speed at its own dt). "
         f"Observed order: the slope of log error against log dt over the {FIT_LEVELS} finest levels with an "
         f"error above {ERROR_FLOOR:g}; in brackets the same for v_n alone and for the tangential columns. "
         "Steps for a target: interpolated on the measured log-log curve, or (marked *) extrapolated along "
         "the fitted line beyond the measured range. Steps are per run: a collision's whole contact, a "
         f"frozen contact's {FROZEN_T_END:g} time units."),
        "",
    ]


def _default_section(study: Study) -> list[str]:
    """The default step of every case: what chose it, its steps, the error it reached."""
    meta = study.metadata["parameters"]
    lines = [
        "## The default step",
        "",
        ("What the scenes run when no dt is given: the step follows from a target accuracy, "
         f"{meta['accuracy']:g} of the size of the initial state |(v_n, v_t, r omega, ...)| "
         f"({meta['frozen_accuracy']:g} for a frozen contact without damping), chosen for {meta['safety']:g} "
         "of it: by the a priori second-order rule for the paper's linear contact, by a probe at two "
         "resolutions against the exact theory for damped, capped and single-speed Hertzian contacts, by a "
         "fixed resolution for a Hertzian batch of several speeds (which no dt can end mid-step). Error "
         "reached: the largest |LAMMPS - theory| over the case's states, over the size of each state (the "
         "target's measure); absolute: the same undivided (the ladder's measure). Steps: one run, a "
         f"collision's whole contact or a frozen contact's {FROZEN_T_END:g} time units."),
        "",
        "| case | form | chosen by | n per half-period | LAMMPS steps | error reached | target | absolute error |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in study.defaults.to_dict(orient="records"):
        flag = "" if r["within_target"] else " (over)"
        lines.append(f"| {_cell(r['label'])} | {r['form']} | {r['step_method']} | {r['steps_per_half_period']:.1f} "
                     f"| {r['steps_per_collision']:,} | {r['error_reached']:.2e}{flag} | {r['target']:g} "
                     f"| {r['absolute_error']:.2e} |")
    return lines + [""]


def _cost_section(study: Study) -> list[str]:
    lines = [
        "## Cost at the paper's defaults",
        "",
        ("Runs at the default step, then at the steps the table gives for each target (mid-step end), "
         "measured again: the error reached over the 8 corners of the sweep's box (absolute; in brackets over "
         "the size of the state); one collision alone (the worst corner at the default step, in a LAMMPS "
         "instance of its own, start-up included); and one collision's share of a batch of "
         f"{study.metadata['parameters']['cost_batch_spheres']} states drawn from the box. Wall seconds on "
         "one core of a shared machine; LAMMPS's own loop time in brackets."),
        "",
        ("| step | target | LAMMPS steps | n per half-period | error reached | one collision alone, s "
         "| per collision in a batch, s |"),
        "|---|---|---|---|---|---|---|",
    ]
    for c in study.costs:
        lines.append(
            f"| {c['step']} | {c['target']:.0e}{'*' if c['extrapolated'] else ''} | {c['lammps_steps']:,} | "
            f"{c['steps_per_half_period']:.1f} | {c['error_reached']:.2e} ({c['relative_error_reached']:.2e}) | "
            f"{c['single_wall_seconds']:.2g} ({c['single_loop_seconds']:.2g}) | "
            f"{c['per_collision_wall_seconds']:.2g} ({c['per_collision_loop_seconds']:.2g}) |")
    default = study.costs[0]
    model = ContactModel()
    over_kick = 1.5 * (model.kn / model.m) * default["dt"] ** 2 / 8.0
    lines += ["", (f"The default step's target is relative to the size of the state, the other rows' absolute. Its "
                   f"largest error is the normal over-kick at |v_n| = 1.5: 1.5 (w_n dt)^2/8 = {over_kick:.2e} at "
                   f"its dt = {default['dt']:.4g}, measured {default['error_reached']:.2e}."), ""]
    return lines


def markdown(study: Study) -> str:
    """ACCURACY.md: the orders and steps per case and form, the default step of each case,
    the costs at the paper's defaults, and what limits each order."""
    lines = _intro(study) + _order_table(study) + [
        "",
        ("Frozen contacts have one form (no contact end) and hold v_n = 0. ~: an error that is not a smooth "
         "series in dt (it jumps with where a stick-slip switch or a contact's end falls inside a step), so "
         "its local orders swing and the fitted order is approximate."),
        ""]
    lines += _default_section(study) + _cost_section(study)
    lines += [
        "## What limits the order",
        "",
        "Mechanisms:",
        "",
        *(f"- **{name}**: {text}." for name, text in MECHANISMS.items()),
        "",
        "Per case:",
        "",
        *(f"- **{case.label}** ({case.why}; against {case.theory}): {case.limit}." for case in study.cases),
        "",
        ("Why a few states per case: without a Coulomb cap the Hookean contact is linear and its end does "
         "not depend on the state, so LAMMPS's map, like the exact one, is linear in the state; the "
         "error's largest value over the sweep's box sits at one of its corners, and grazing, head-on and "
         "high-spin incidence probe single columns of that linear error."),
        "",
    ]
    return "\n".join(lines)


def write_study(study: Study, out: Path) -> dict[str, Path]:
    """Write accuracy.png, accuracy.pdf, accuracy.json and ACCURACY.md into ``out``, each atomically."""
    import matplotlib.style

    from ...figures.core import STYLE, save

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    record = {**study.metadata, "cases": [c.record() for c in study.cases],
              "summary": _records(study.summary), "default_steps": _records(study.defaults),
              "default_costs": json_ready(study.costs), "runs_table": _records(study.table),
              "markdown": "ACCURACY.md"}
    with matplotlib.style.context(STYLE):
        fig = draw(study)
        saved = save(fig, out, "accuracy", json_ready(record))
    md = out / "ACCURACY.md"
    write_output(md, markdown(study))
    return {"png": saved.png, "pdf": saved.pdf, "json": saved.json, "markdown": md}
