"""Figs. 2, 3 and 7: the frozen contact (Section 3, and its damped form in Section 5).

The sphere is held at z = 0.1 (overlap 0.4) with v_n = 0; only the slip evolves.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from .. import exact
from ..model.contact import ContactModel
from .core import (
    FROZEN_Z,
    FigureData,
    base_metadata,
    default_runs,
    finish_metadata,
    frozen_run,
    new_figure,
)

__all__ = [
    "FIG3_VT0",
    "FIG7_GAMMA_T",
    "draw_fig2",
    "draw_fig3",
    "draw_fig7",
    "fig2_data",
    "fig3_data",
    "fig7_data",
]

#: Fig. 3: r*omega(0) = -0.5 for every trajectory; v_t(0) = 0.5 is the rolling state (a point).
FIG3_R_OMEGA0 = -0.5
FIG3_VT0 = (-1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0)
#: Fig. 3 runs a little over one slip period 2 pi/sqrt(Q) = 3.36 (paper defaults), so
#: every trajectory reaches its far end (Eq. 12) and comes back.
FIG3_T_END = 4.0
#: Fig. 7: under-damped, near-critical (critical gamma_t = 2 sqrt(kt m alpha/(1+alpha)) = 1.07)
#: and over-damped tangential friction; the paper does not give its three values.
FIG7_GAMMA_T = (0.2, 1.0, 5.0)
FIG7_T_END = 10.0
FIG2_T_END = 10.0


def _frozen_table(tuned, model: ContactModel) -> pd.DataFrame:
    t = tuned.result.table[["t", "v_t", "omega", "r_omega", "v_t_theory", "r_omega_theory"]].copy()
    t["omega_theory"] = t["r_omega_theory"] / model.r
    return t


def _parameters(model: ContactModel, **scene) -> dict:
    return {"model": model.as_record(), "z": FROZEN_Z, **scene}


def fig2_data(out: Path, runs: Path | None = None) -> FigureData:
    """v_t(t) and omega(t) at z = 0.1 from v_t(0) = 1, omega(0) = 0, against Eq. 10."""
    runs = default_runs(out, runs, "fig2")
    model = ContactModel()
    tuned = frozen_run(model, 1.0, 0.0, FIG2_T_END, runs / "vt1_omega0", "fig2")
    table = _frozen_table(tuned, model)
    vbar, rwbar = exact.frozen_means(1.0, 0.0, model.alpha)
    meta = base_metadata("fig2", "Frozen contact: v_t(t) and omega(t), LAMMPS against Eq. 10",
                         "Fig. 2; Eqs. 8-11")
    meta["parameters"] = _parameters(model, v_t0=1.0, omega0=0.0, t_end=float(table["t"].iloc[-1]))
    meta["means_eq11"] = {"v_t": vbar, "omega": rwbar / model.r}
    finish_metadata(meta, [{"series": "v_t(0)=1, omega(0)=0", "tuned": tuned}], out)
    return FigureData({"series": table, "means": pd.DataFrame({"v_t": [vbar], "omega": [rwbar / model.r]})}, meta)


def draw_fig2(data: FigureData):
    t = data.tables["series"]
    means = data.tables["means"].iloc[0]
    fig, axes = new_figure()
    ax = axes[0, 0]
    for col, colour, label in (("v_t", "C0", r"$v_t$"), ("omega", "C1", r"$\omega$")):
        ax.plot(t["t"], t[f"{col}_theory"], color=colour, lw=2.6, alpha=0.45, label=f"{label}, Eq. 10")
        ax.plot(t["t"], t[col], color=colour, ls="--", lw=1.2, label=f"{label}, LAMMPS")
        ax.axhline(means[col], color=colour, ls=":", lw=0.8)
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel(r"$t$")
    ax.set_ylabel(r"$v_t,\ \omega$")
    ax.set_xlim(t["t"].iloc[0], t["t"].iloc[-1])
    ax.legend(ncols=4, loc="lower center", bbox_to_anchor=(0.5, 1.0), columnspacing=1.2,
              title=r"$z = 0.1$, $v_t(0) = 1$, $\omega(0) = 0$; dotted: rolling means (Eq. 11)",
              title_fontsize=8.5)
    return fig


def fig3_data(out: Path, runs: Path | None = None) -> FigureData:
    """Frozen trajectories in the (r omega, v_t) plane for r omega(0) = -0.5 (Eqs. 11-13)."""
    runs = default_runs(out, runs, "fig3")
    model = ContactModel()
    omega0 = FIG3_R_OMEGA0 / model.r
    paths, ends, records = [], [], []
    for vt0 in FIG3_VT0:
        tuned = frozen_run(model, vt0, omega0, FIG3_T_END, runs / f"vt{vt0:+g}", f"fig3 v_t(0) = {vt0:g}")
        t = _frozen_table(tuned, model)
        t.insert(0, "vt0", vt0)
        paths.append(t)
        vt_m, rw_m = exact.frozen_extremes(vt0, FIG3_R_OMEGA0, model.alpha)
        vbar, rwbar = exact.frozen_means(vt0, FIG3_R_OMEGA0, model.alpha)
        if vt0 + FIG3_R_OMEGA0 != 0.0:  # else the rolling state: a point
            # the slope d v_t / d(r omega) that LAMMPS's points lie on (Eq. 13 says alpha)
            slope = float(np.polyfit(t["r_omega"], t["v_t"], 1)[0])
            # LAMMPS's far end: the point farthest from the start, against Eq. 12
            far = int(np.argmax(np.hypot(t["v_t"] - vt0, t["r_omega"] - FIG3_R_OMEGA0)))
            end_dev = float(max(abs(t["v_t"].iloc[far] - vt_m), abs(t["r_omega"].iloc[far] - rw_m)))
        else:
            slope, end_dev = float("nan"), 0.0
        ends.append({"vt0": vt0, "r_omega0": FIG3_R_OMEGA0, "vt_m": vt_m, "r_omega_m": rw_m,
                     "vt_mean": vbar, "r_omega_mean": rwbar, "slope_lammps": slope})
        records.append({"series": f"v_t(0)={vt0:g}", "tuned": tuned, "v_t0": vt0,
                        "slope_lammps": None if np.isnan(slope) else slope,
                        "far_end_minus_eq12": end_dev})
    meta = base_metadata("fig3", "Frozen-contact trajectories in the (r omega, v_t) plane, r omega(0) = -0.5",
                         "Fig. 3; Eqs. 10-13")
    meta["parameters"] = _parameters(model, r_omega0=FIG3_R_OMEGA0, v_t0=list(FIG3_VT0), t_end=FIG3_T_END)
    slopes = [e["slope_lammps"] for e in ends if not np.isnan(e["slope_lammps"])]
    meta["slope_eq13"] = exact.frozen_slope(model.alpha)
    meta["max_slope_deviation"] = float(max(abs(s - model.alpha) for s in slopes))
    meta["notes"] = [
        "axes: r*omega horizontal, v_t vertical, so that Eq. 13's slope d v_t/d(r omega) = alpha is the drawn slope",
        ("far_end_minus_eq12 compares the dumped point farthest from the start with Eq. 12; "
        "it includes the dump's sampling in time"),
        f"v_t(0) = {-FIG3_R_OMEGA0:g} is the rolling state: no slip, the trajectory is a point",
    ]
    finish_metadata(meta, records, out)
    return FigureData({"paths": pd.concat(paths, ignore_index=True), "ends": pd.DataFrame(ends)}, meta)


def draw_fig3(data: FigureData):
    import matplotlib as mpl
    from matplotlib.lines import Line2D

    paths, ends = data.tables["paths"], data.tables["ends"]
    alpha = data.metadata["slope_eq13"]
    fig, axes = new_figure(figsize=(7.4, 4.6))
    ax = axes[0, 0]
    colours = mpl.colormaps["viridis"](np.linspace(0.0, 0.9, len(ends)))
    lim = np.array([ends[["r_omega0", "r_omega_m"]].min().min(), ends[["r_omega0", "r_omega_m"]].max().max()])
    ax.plot(lim, -lim, color="0.55", ls=":", lw=1.0, label="rolling:\n" r"$v_t + r\omega = 0$ (Eq. 11)")
    for colour, (_, e) in zip(colours, ends.iterrows(), strict=True):
        p = paths[paths["vt0"] == e["vt0"]]
        ax.plot([e["r_omega0"], e["r_omega_m"]], [e["vt0"], e["vt_m"]], color=colour, lw=3.0, alpha=0.35)
        step = max(1, len(p) // 60)  # dots, not a dashed line: the trajectory runs back over itself
        ax.plot(p["r_omega"].iloc[::step], p["v_t"].iloc[::step], ".", color=colour, ms=3.5,
                label=rf"$v_t(0) = {e['vt0']:g}$")
        ax.plot(e["r_omega0"], e["vt0"], "o", color=colour)
        ax.plot(e["r_omega_m"], e["vt_m"], "s", mfc="none", mec=colour, ms=7)
        ax.plot(e["r_omega_mean"], e["vt_mean"], "x", color=colour, ms=5)
    ax.set_xlabel(r"$r\omega$")
    ax.set_ylabel(r"$v_t$")
    fig.legend(loc="outside right upper", fontsize=8, markerscale=2,
               title=r"$r\omega(0) = -0.5$", title_fontsize=8)
    keys = [
        Line2D([], [], color="0.3", marker=".", ls="none", label="LAMMPS"),
        Line2D([], [], color="0.3", lw=3.0, alpha=0.35, label="Eq. 10,\n" rf"slope $\alpha = {alpha:g}$ (Eq. 13)"),
        Line2D([], [], color="0.3", marker="o", ls="none", label="start"),
        Line2D([], [], color="0.3", marker="s", mfc="none", ms=7, ls="none", label="far end (Eq. 12)"),
        Line2D([], [], color="0.3", marker="x", ls="none", label="mean (Eq. 11)"),
    ]
    fig.legend(handles=keys, loc="outside right lower", fontsize=8)
    return fig


def fig7_data(out: Path, runs: Path | None = None) -> FigureData:
    """Damped frozen contact, v_t(0) = 1, omega(0) = 1, three gamma_t: LAMMPS against the
    exact damped solution and against the paper's recipe (Eq. 22: cos times exp(-gamma_t t/m))."""
    runs = default_runs(out, runs, "fig7")
    tables, records = [], []
    for gamma_t in FIG7_GAMMA_T:
        model = ContactModel(gamma_t=gamma_t)
        tuned = frozen_run(model, 1.0, 1.0, FIG7_T_END, runs / f"gamma_t{gamma_t:g}", f"fig7 gamma_t = {gamma_t:g}")
        t = _frozen_table(tuned, model)
        vt22, rw22 = exact.frozen_velocities_paper_damped(
            t["t"].to_numpy(), 1.0, model.r * 1.0, model.kt, model.m, model.alpha, gamma_t)
        t["v_t_eq22"], t["omega_eq22"] = vt22, rw22 / model.r
        t.insert(0, "gamma_t", gamma_t)
        tables.append(t)
        dev22 = {"v_t": float(np.abs(t["v_t"] - t["v_t_eq22"]).max()),
                 "omega": float(np.abs(t["omega"] - t["omega_eq22"]).max()),
                 "r_omega": float(np.abs(t["r_omega"] - rw22).max())}
        records.append({"series": f"gamma_t={gamma_t:g}", "tuned": tuned, "gamma_t": gamma_t,
                        "zeta": model.zeta, "max_deviation_eq22": max(dev22.values()),
                        "deviations_eq22": dev22})
    model = ContactModel()
    vbar, rwbar = exact.frozen_means(1.0, model.r, model.alpha)
    meta = base_metadata("fig7", "Damped frozen contact: v_t(t) and omega(t) for three gamma_t",
                         "Fig. 7; Eqs. 10, 11, 22 and the exact damped solution")
    meta["parameters"] = _parameters(model, v_t0=1.0, omega0=1.0, t_end=FIG7_T_END, gamma_t=list(FIG7_GAMMA_T))
    meta["means_eq11"] = {"v_t": vbar, "omega": rwbar / model.r}
    meta["notes"] = [
        ("exact: u'' + 2 zeta u' + Q u = 0 with zeta = gamma_t (1 + alpha)/(2 alpha m); the paper's recipe "
        "(Eq. 22) multiplies cos(t sqrt(Q)) by exp(-gamma_t t/m): another decay rate, no frequency shift, "
        "no sine term"),
        ("LAMMPS's damped step is first order in dt: the step of each run is chosen from a pilot run "
        "(see runs[*].dt_choice)"),
    ]
    finish_metadata(meta, records, out)
    worst22 = max(records, key=lambda r: r["max_deviation_eq22"])
    meta["max_deviation_eq22"] = worst22["max_deviation_eq22"]
    meta["max_deviation_eq22_series"] = worst22["series"]
    means = pd.DataFrame({"v_t": [vbar], "omega": [rwbar / model.r]})
    return FigureData({"series": pd.concat(tables, ignore_index=True), "means": means}, meta)


def draw_fig7(data: FigureData):
    t, means = data.tables["series"], data.tables["means"].iloc[0]
    fig, axes = new_figure(2, 1, figsize=(6.4, 6.6), sharex=True)
    colours = ("C0", "C1", "C3")
    for ax, col, label, tag in ((axes[0, 0], "v_t", r"$v_t$", "a"), (axes[1, 0], "omega", r"$\omega$", "b")):
        for colour, gamma_t in zip(colours, FIG7_GAMMA_T, strict=True):
            s = t[t["gamma_t"] == gamma_t]
            ax.plot(s["t"], s[f"{col}_theory"], color=colour, lw=2.6, alpha=0.45)
            ax.plot(s["t"], s[col], color=colour, ls="--", lw=1.2, label=rf"$\gamma_t = {gamma_t:g}$")
            ax.plot(s["t"], s[f"{col}_eq22"], color=colour, ls=":", lw=1.0)
        ax.axhline(means[col], color="k", lw=0.6, ls="-.")
        ax.set_ylabel(label)
        ax.text(0.015, 0.04, f"{tag})", transform=ax.transAxes, va="bottom")
    axes[1, 0].set_xlabel(r"$t$")
    axes[1, 0].set_xlim(t["t"].min(), t["t"].max())
    axes[0, 0].legend(loc="upper right", title="dashed: LAMMPS", title_fontsize=8)
    axes[1, 0].text(0.99, 0.04, "wide: exact damped solution; dotted: Eq. 22 recipe;\n"
                    r"dash-dot: rolling means (Eq. 11); $z = 0.1$, $v_t(0) = \omega(0) = 1$",
                    transform=axes[1, 0].transAxes, ha="right", va="bottom", fontsize=8)
    return fig
