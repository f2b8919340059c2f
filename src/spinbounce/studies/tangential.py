"""Becker, Schwager & Poeschel's tangential restitution curves (Phys. Rev. E 77, 011304, 2008):
LAMMPS, the exact solver and the rigid limits (:mod:`.tangential_limits`: convention, closed forms).

Only their abstract was available here (a constant e_n, the tangential coefficient depending
on the impact velocity), so their parameter sets are not reproduced; the sets below are chosen
in their spirit: the linear dashpot with a constant e_n, kt/kn at the magic 2/7 (Eq. 20), at the
paper's 1/10 and at 1/2, mu = 0.3, one set with normal and tangential damping. For each, beta
against psi = |g_t|/|v_n| (speed 1, no spin) comes from one batched LAMMPS run at the default
accuracy (library route), the exact Coulomb solver (:func:`~spinbounce.exact.choose.predict`)
and Walton's gross-slip line with the sticking plateau. Hookean contacts scale with |v_n|, so
beta depends on psi alone.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ..scenes.collision import Collision
from ..model.contact import ContactModel
from ..pipeline import run_scene
from ..exact import choose
from . import tangential_limits as limits
from .restitution import Curve
from .validation.materials import gamma_n_for_restitution_cut

__all__ = ["SETS", "ratios", "run_set", "solver_curve", "limit_deviations", "make_figure",
           "LAMMPS_POINTS", "SOLVER_POINTS", "MAX_REDUCED"]


#: e_n = 0.8 with the normal force kept compressive (Walton's branch needs int F_n = m (1 + e)|v_n|).
DAMPED_E = 0.8
SETS = (
    Curve("kt/kn = 2/7 (magic), e_n = 1", ContactModel(kt=20.0 / 7.0, mu=0.3)),
    Curve("kt/kn = 1/10 (Wang & Harrowell), e_n = 1", ContactModel(mu=0.3)),
    Curve("kt/kn = 1/2, e_n = 1", ContactModel(kt=5.0, mu=0.3)),
    Curve(f"kt/kn = 2/7, e_n = {DAMPED_E}, gamma_t = 0.3", ContactModel(
        kt=20.0 / 7.0, mu=0.3, gamma_n=gamma_n_for_restitution_cut(DAMPED_E, 1.0, 10.0), gamma_t=0.3,
        limit_damping=True)),
)
#: The reduced axis W/psi runs from near-grazing (W/psi -> 0, beta -> -1) to well past
#: every switch (-Omega <= 2): MAX_REDUCED shows the plateaus and their approach.
MIN_REDUCED, MAX_REDUCED = 0.05, 8.0
LAMMPS_POINTS, SOLVER_POINTS = 40, 400
#: The model's parameters each set's record holds.
MODEL_FIELDS = ("kn", "kt", "gamma_n", "gamma_t", "mu", "limit_damping", "alpha", "m", "r")


def ratios(model, points: int) -> np.ndarray:
    """psi on an even grid of the reduced ratio W/psi (the gross-slip branch is straight in it)."""
    return limits.walton_scale(model) / np.linspace(MIN_REDUCED, MAX_REDUCED, points)


def solver_curve(model, psi) -> np.ndarray:
    """beta from the exact Coulomb solver (exact.choose.predict)."""
    initial = limits.states_at(psi)
    return limits.beta(initial, choose.predict(model, initial))


def run_set(curve: Curve, run_dir: Path, points: int = LAMMPS_POINTS) -> dict:
    """One batched LAMMPS run over psi, the solver on the same states, and their deviations.

    ``state_deviation``: max |LAMMPS - solver| over the state's columns per unit speed (the
    default accuracy's measure, 1e-4); ``beta_deviation``: the same in beta, which divides the
    slip's error by g_t = psi/sqrt(1 + psi^2).
    """
    psi = ratios(curve.model, points)
    initial = limits.states_at(psi)
    scene = Collision(curve.model, v_n=initial[:, 0], v_t=initial[:, 1], omega=0.0)
    result = run_scene(scene, run_dir, atoms="library")
    final = result.table[["v_n_lammps", "v_t_lammps", "r_omega_lammps"]].to_numpy()
    predicted = choose.predict(curve.model, initial)
    beta_lammps, beta_solver = limits.beta(initial, final), limits.beta(initial, predicted)
    return {"label": curve.label, "model": curve.model, "psi": psi, "beta_lammps": beta_lammps,
            "beta_solver": beta_solver, "dt": result.scene.dt, "run": str(run_dir),
            "slip_deviation": np.abs(limits.slip_rate(final) - limits.slip_rate(predicted)),
            "state_deviation": float(np.abs(final - predicted).max()),
            "beta_deviation": float(np.abs(beta_lammps - beta_solver).max()),
            "theory_kind": choose.which(curve.model).kind}


def limit_deviations(model, psi: np.ndarray, beta_solver: np.ndarray) -> dict:
    """The solver against each closed form where that form is exact, or its limit's error.

    Gross slip: over psi >= psi_g (exact there; undamped sets), else at the largest psi.
    Plateau: over psi <= psi* at the magic ratio (exact), else the limit psi -> 0 at
    psi = 1e-4 with and without the first-order term (undamped), or alone (damped).
    """
    walton = limits.gross_slip(model, psi)
    onset = limits.gross_slip_onset(model)
    if onset is not None:
        slides = psi >= onset
        gross = {"where": f"psi >= psi_g = {onset:.6g} (exact there)",
                 "max_abs": float(np.abs(beta_solver - walton)[slides].max())}
    else:
        k = int(np.argmax(psi))
        gross = {"where": f"largest psi = {psi[k]:.6g} (no closed psi_g with damping)",
                 "max_abs": float(abs(beta_solver[k] - walton[k]))}
    stick = limits.plateau(model)
    slope = limits.plateau_slope(model)
    if limits.is_magic(model) and slope == 0.0:
        sticks = psi <= limits.switch_ratio(model)
        flat = {"where": "psi <= psi* (exact: the magic ratio sticks throughout)",
                "max_abs": float(np.abs(beta_solver[sticks] - stick).max())}
    else:
        small = 1e-4
        at_small = float(solver_curve(model, [small])[0])
        flat = {"where": f"limit psi -> 0, at psi = {small:g}", "max_abs": abs(at_small - stick)}
        if slope is not None:
            flat["max_abs_after_first_order_term"] = abs(at_small - stick - slope * small)
    return {"gross_slip": gross, "plateau": flat}


def _set_summary(run: dict) -> dict:
    model = run["model"]
    dense = ratios(model, SOLVER_POINTS)
    beta_dense = solver_curve(model, dense)
    return {**run, "psi_dense": dense, "beta_solver_dense": beta_dense,
            "walton_scale": limits.walton_scale(model), "plateau": limits.plateau(model),
            "switch_ratio": limits.switch_ratio(model), "gross_slip_onset": limits.gross_slip_onset(model),
            "plateau_slope": limits.plateau_slope(model), "Omega": model.Omega, "restitution": model.restitution,
            "limits": limit_deviations(model, dense, beta_dense)}


def _draw_curves(ax, sets: list[dict]) -> None:
    reduced = np.linspace(MIN_REDUCED, MAX_REDUCED, 200)
    ax.plot(reduced, -1.0 + reduced, "--", color="0.35", lw=1.0, zorder=3,
            label=r"gross slip (Walton): $\beta = -1 + \mu(1+e_n)(1+1/\alpha)|v_n|/|g_t|$")
    for k, s in enumerate(sets):
        colour, w = f"C{k}", s["walton_scale"]
        ax.plot(w / s["psi_dense"], s["beta_solver_dense"], "-", color=colour, lw=1.2)
        ax.plot(w / s["psi"], s["beta_lammps"], "o", color=colour, ms=3.5, mfc="none",
                label=f"{s['label']}: plateau {s['plateau']:.4f}, switch at psi* = {s['switch_ratio']:.4f}")
        ax.axhline(s["plateau"], color=colour, lw=0.7, ls=":")
        ax.plot([-s["Omega"]], [s["plateau"]], "v", color=colour, ms=8, mec="k", mew=0.6, zorder=4)
        if s["gross_slip_onset"] is not None:
            leave = w / s["gross_slip_onset"]
            ax.plot([leave], [-1.0 + leave], "^", color=colour, ms=7, mec="k", mew=0.6, zorder=4)
    ax.set(xlabel=r"reduced ratio $\mu(1+e_n)(1+1/\alpha)\,|v_n|/|g_t|$  ($g_t = v_t + r\omega$: contact point)",
           ylabel=r"tangential restitution $\beta = -g_t'/g_t$", xlim=(0.0, MAX_REDUCED), ylim=(-1.05, 1.2))
    arrow = {"arrowstyle": "->", "lw": 0.6}
    ax.annotate("sticking plateaus $\\beta = -(1+\\Omega)$ (dotted): exact at the magic 2/7 for\n"
                "$\\psi \\leq \\psi^*$, else reached as $\\psi \\to 0$, linearly in $\\psi/\\mu$",
                xy=(6.5, 0.283), xytext=(3.0, 0.36), fontsize=7, arrowprops=arrow)
    ax.annotate("$\\blacktriangledown$ switch: the gross-slip line meets the plateau at $\\psi^*$",
                xy=(2.0, 1.0), xytext=(2.45, 1.08), fontsize=7, arrowprops=arrow)
    ax.annotate("gross slip, exact for $\\psi \\geq \\psi_g$ (the contact slides throughout);\n"
                "$\\blacktriangle$: the exact curve leaves the line at $\\psi_g$ ($\\psi_g = \\psi^*$ only at 2/7)",
                xy=(0.45, -0.55), xytext=(0.75, -0.5), fontsize=7, arrowprops=arrow)
    ax.set_title("(a) lines: exact solver; circles: LAMMPS (default accuracy); dashed, dotted: rigid limits",
                 fontsize=8.5)
    ax.legend(fontsize=6.5, loc="lower right")


def _draw_deviations(ax, sets: list[dict]) -> None:
    for k, s in enumerate(sets):
        colour, w = f"C{k}", s["walton_scale"]
        ax.semilogy(w / s["psi"], np.maximum(s["slip_deviation"], 1e-17), "o-", color=colour, ms=3, lw=0.6,
                    mfc="none")
        off_line = np.abs(s["beta_solver_dense"] - limits.gross_slip(s["model"], s["psi_dense"]))
        ax.semilogy(w / s["psi_dense"], np.maximum(off_line, 1e-17), "--", color=colour, lw=0.8)
    ax.axhline(1e-4, color="k", lw=0.6)
    ax.text(0.1, 1.4e-4, "default accuracy 1e-4", fontsize=7)
    ax.set(xlabel=r"reduced ratio $\mu(1+e_n)(1+1/\alpha)\,|v_n|/|g_t|$", ylabel="deviation",
           xlim=(0.0, MAX_REDUCED), ylim=(1e-17, 10.0))
    ax.set_title("(b) circles: |LAMMPS - solver| in $g_t'$ ($|v| = 1$);\n"
                 "dashed: |solver - gross-slip line| in $\\beta$ (1e-16: slides throughout)",
                 fontsize=8.5)


def make_figure(out: Path, runs: Path) -> dict:
    """figures/tangential.png, .pdf, .json: beta against the velocity ratio for every set."""
    from ..figures.core import figure_files
    from ..outputs import check_outputs

    check_outputs(out, figure_files("tangential"))  # before its runs (spinbounce.outputs)
    import matplotlib.style

    from ..figures.core import STYLE, new_figure, save
    from ..records import software

    started = time.perf_counter()
    sets = [_set_summary(run_set(c, Path(runs) / f"set{k + 1}")) for k, c in enumerate(SETS)]
    with matplotlib.style.context(STYLE):
        fig, axes = new_figure(1, 2, figsize=(13.0, 5.2), gridspec_kw={"width_ratios": [1.5, 1.0]})
        _draw_curves(axes[0, 0], sets)
        _draw_deviations(axes[0, 1], sets)
        fig.suptitle("Coefficient of tangential restitution of a linear spring-dashpot with Coulomb friction "
                     "(Becker, Schwager & Poeschel 2008), sphere on a wall, mu = 0.3, alpha = 2/5, |v| = 1, "
                     "no spin", fontsize=9)
        metadata = {"figure": "tangential", **software(),
                    "reference": "Becker, Schwager & Poeschel, Phys. Rev. E 77, 011304 (2008)",
                    "parameters_source": "chosen in the paper's spirit: its own parameter sets were not available "
                                         "(abstract only)",
                    "convention": "beta = -g_t'/g_t, g_t = v_t + r omega; psi = |g_t|/|v_n|; reduced W/psi, "
                                  "W = mu (1 + e_n)(1 + 1/alpha)",
                    "lammps_points": LAMMPS_POINTS, "solver_points": SOLVER_POINTS,
                    "largest_state_deviation": max(s["state_deviation"] for s in sets),
                    "largest_beta_deviation": max(s["beta_deviation"] for s in sets),
                    "sets": [{**{k: v for k, v in s.items() if k != "model"},
                              "model": {f: getattr(s["model"], f) for f in MODEL_FIELDS}} for s in sets]}
        return save(fig, out, "tangential", metadata, started).metadata
