"""figures/mindlin: what the paper's Omega becomes with LAMMPS's Mindlin tangential springs.

With the Hertzian force and no cap, a Mindlin bounce keeps the form of Eq. 18 with an Omega that
depends on lam = (1 + alpha)/alpha k_t/kn only, not on the impact speed (spinbounce.exact.mindlin).
Left: Omega against Poisson's ratio for LAMMPS's NULL stiffness (k_t/kn = 3 (1 - nu)/(2 - nu),
a solid sphere), one curve per variant; the points are LAMMPS at two impact speeds a factor 7.5
apart. Right: Omega against k_t/kn for an explicit k_t; where |Omega + 1| > 1 the bounce gains
energy (shaded for ``mindlin``, whose Omega ``mindlin/force`` shares), and Omega = -2 at k_t/kn =
alpha/(1 + alpha), the paper's magic ratio; the points are LAMMPS at one speed.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ..exact import choose, mindlin
from ..model.contact import ContactModel
from ..pipeline import run_scene
from ..records import software
from ..scenes.collision import Collision
from .core import ACCEPTANCE, STYLE, FigureRecord, new_figure, save

__all__ = ["compute", "draw", "make_mindlin", "VARIANTS"]

VARIANTS = tuple(mindlin.VARIANTS)
#: The material (E sets only the time and length scales: Omega does not depend on it).
YOUNGS_MODULUS = 1.0e4
#: Poisson's ratios with LAMMPS points, and the two impact speeds run at each.
POISSON_POINTS = (-0.8, -0.4, 0.0, 0.25, 0.45)
SPEEDS = (0.2, 1.5)
#: k_t/kn with LAMMPS points (mindlin_kt = this times kn), at the first speed; kn of the Hertzian force.
RATIO_POINTS = (0.1, 2.0 / 7.0, 0.357142857142857, 3.0 / 7.0, 1.0, 1.6)
KN = 1.0e4
#: The state every LAMMPS point starts from (v_t, r omega): Omega is read from the slip ratio.
V_T, R_OMEGA = 1.0, -0.3


def _lammps_omega(model: ContactModel, speed: float, folder: Path) -> dict:
    """LAMMPS's Omega of one bounce at the default step, from its slip ratio, and its error."""
    row = run_scene(Collision(model, v_n=-speed, v_t=V_T, omega=R_OMEGA / model.r), folder, record=False).table.iloc[0]
    ratio = (row["v_t_lammps"] + row["r_omega_lammps"]) / (V_T + R_OMEGA)
    return {"omega": float(ratio - 1.0), "error": float(row["error"]), "dt": float(row["dt"]) if "dt" in row else None}


def _material(variant: str, nu: float) -> ContactModel:
    return ContactModel(normal="hertz/material", youngs_modulus=YOUNGS_MODULUS, poisson_ratio=nu, tangential=variant)


def _stiffness(variant: str, ratio: float) -> ContactModel:
    return ContactModel(normal="hertz", kn=KN, tangential=variant, mindlin_kt=ratio * KN)


def compute(runs: Path) -> dict:
    """The curves (exact) and the points (LAMMPS), per variant."""
    runs = Path(runs)
    nu_grid = np.linspace(-0.98, 0.5, 75)
    ratio_grid = np.linspace(0.02, 2.0, 100)
    alpha = ContactModel().alpha
    out = {"alpha": alpha, "poisson_ratio": nu_grid.tolist(), "k_t_over_kn": ratio_grid.tolist(), "variants": {}}
    for variant in VARIANTS:
        key = mindlin.VARIANTS[variant]
        lams = mindlin.speed_free_lam(mindlin.wall_stiffness_ratio(nu_grid), 1.0, alpha)
        points = [{"poisson_ratio": nu, "v_n": -v,
                   **_lammps_omega(_material(variant, nu), v, runs / variant.replace("/", "_") / f"nu{nu:+.2f}_v{v:g}")}
                  for nu in POISSON_POINTS for v in SPEEDS]
        ratio_points = [{"k_t_over_kn": q, "v_n": -SPEEDS[0],
                         **_lammps_omega(_stiffness(variant, q), SPEEDS[0],
                                         runs / variant.replace("/", "_") / f"ratio{q:.4f}")} for q in RATIO_POINTS]
        for point in (*points, *ratio_points):
            model = _material(variant, point["poisson_ratio"]) if "poisson_ratio" in point \
                else _stiffness(variant, point["k_t_over_kn"])
            point["omega_exact"] = float(choose.omega_per_sphere(model, point["v_n"])[0])
        out["variants"][variant] = {
            "omega_of_poisson_ratio": (mindlin.Omega(lams, 0.0, key, 1.5)).tolist(),
            "omega_of_k_t_over_kn": mindlin.Omega(mindlin.speed_free_lam(ratio_grid, 1.0, alpha), 0.0, key,
                                                  1.5).tolist(),
            "lammps_poisson": points, "lammps_k_t_over_kn": ratio_points}
    deviations = [abs(p["omega"] - p["omega_exact"]) for v in out["variants"].values()
                  for p in (*v["lammps_poisson"], *v["lammps_k_t_over_kn"])]
    errors = [p["error"] for v in out["variants"].values() for p in (*v["lammps_poisson"], *v["lammps_k_t_over_kn"])]
    out["largest_row_error"] = float(max(errors))
    out["largest_omega_deviation"] = float(max(deviations))
    if out["largest_row_error"] > ACCEPTANCE:
        raise AssertionError(f"a LAMMPS point is {out['largest_row_error']:.2g} from the reference (> {ACCEPTANCE:g})")
    return out


def draw(data: dict):
    import matplotlib.style

    with matplotlib.style.context(STYLE):
        fig, axes = new_figure(1, 2, figsize=(10.0, 3.9))
        nu_ax, ratio_ax = axes[0]
        ratios = np.asarray(data["k_t_over_kn"])
        for variant, curves in data["variants"].items():
            # a force history without a rescale has the displacement one's Omega at every lam: dashed,
            # over the displacement one's wider line
            key = mindlin.VARIANTS[variant]
            style = {} if key.rescale else {"linestyle": "--"} if key.force else {"linewidth": 2.5}
            line, = nu_ax.plot(data["poisson_ratio"], curves["omega_of_poisson_ratio"], label=variant, **style)
            for marker, speed in zip("os", SPEEDS):
                points = [p for p in curves["lammps_poisson"] if abs(p["v_n"]) == speed]
                nu_ax.plot([p["poisson_ratio"] for p in points], [p["omega"] for p in points], marker,
                           color=line.get_color(), ms=4 if marker == "o" else 7, mfc="none" if marker == "s" else None)
            ratio_ax.plot(ratios, curves["omega_of_k_t_over_kn"], color=line.get_color(), label=variant, **style)
            ratio_ax.plot([p["k_t_over_kn"] for p in curves["lammps_k_t_over_kn"]],
                          [p["omega"] for p in curves["lammps_k_t_over_kn"]], "o", color=line.get_color(), ms=4)
        plain = next(v for v in VARIANTS if not any(mindlin.VARIANTS[v]))  # displacement, no rescale
        gain = np.abs(np.asarray(data["variants"][plain]["omega_of_k_t_over_kn"]) + 1.0) > 1.0
        ratio_ax.fill_between(ratios, -2.2, 0.2, where=gain, color="0.85", zorder=0,
                              label="energy gained (mindlin, mindlin/force)")
        magic = data["alpha"] / (1.0 + data["alpha"])
        ratio_ax.axvline(magic, color="0.5", linestyle="--", linewidth=0.8, label="alpha/(1+alpha)")
        for ax in (nu_ax, ratio_ax):
            ax.axhline(-2.0, color="0.7", linewidth=0.6, zorder=0)
        nu_ax.set(xlabel="Poisson's ratio nu (NULL stiffness 8 G*)", ylabel="Omega (the same at every v_n)",
                  title=f"dots: LAMMPS at |v_n| = {SPEEDS[0]:g}, squares: at {SPEEDS[1]:g}")
        ratio_ax.set(xlabel="k_t/kn (Hertzian force, explicit k_t)", ylabel="Omega", ylim=(-2.2, 0.2),
                     title=f"dots: LAMMPS at |v_n| = {SPEEDS[0]:g}")
        nu_ax.legend(fontsize=7)
        ratio_ax.legend(fontsize=7, loc="lower right")
    return fig


def make_mindlin(out: Path, runs: Path) -> FigureRecord:
    """Compute, draw and save mindlin.{png,pdf,json} into ``out`` (LAMMPS runs in ``runs``)."""
    started = time.perf_counter()
    data = compute(runs)
    metadata = {"figure": "mindlin", "title": "Omega of LAMMPS's Mindlin tangential springs, Hertzian wall",
                "theory": "spinbounce.exact.mindlin (Eq. 18 with a speed-free Omega(lam), lam = (1 + alpha)/alpha "
                          "k_t/kn)", "software": software(), **data}
    return save(draw(data), out, "mindlin", metadata, started)
