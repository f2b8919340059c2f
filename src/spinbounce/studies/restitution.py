"""Restitution maps: what a bounce does against the incidence angle, from LAMMPS and theory.

For spheres of speed |v| = 1 at incidence theta, no initial spin: e_n, e_t (Kharaz's), the
centre's rebound angle and the rebound spin r omega'/|v| (docs/theory.md, section 6), for a Hookean
and a Hertzian wall, each without and with a Coulomb cap. Each curve is one batched LAMMPS run
(library route) beside :func:`~spinbounce.exact.choose.predict`. Kharaz, Gorham & Salman's (2001)
alumina sphere on an aluminium-alloy plate, as digitised in other DEM codes
(:data:`~spinbounce.studies.validation.digitised.KHARAZ_2001`), is drawn with its source, with
the Hookean model fitted to it; the model runs in the paper's units and the data keep theirs.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..scenes.collision import Collision
from ..model.contact import ContactModel
from ..pipeline import run_scene
from ..exact import choose
from .validation.digitised import KHARAZ_2001
from .validation.materials import gamma_n_for_restitution_cut

__all__ = ["Curve", "QUANTITY_LABELS", "CURVES", "angles", "quantities", "run_curve", "fit_kharaz",
           "kharaz_points", "kharaz_residuals", "kharaz_model", "make_figure", "KHARAZ_SPEED", "KHARAZ_RADIUS", "KHARAZ_E"]

#: Kharaz's impact speed (m/s) and sphere radius (m): Chung & Ooi Test 4 (validation/cases.py).
KHARAZ_SPEED, KHARAZ_RADIUS = 3.9, 2.5e-3
#: Kharaz's normal restitution, as the benchmark gives it (not among the digitised points).
KHARAZ_E = 0.98
QUANTITY_LABELS = {
    "e_n": r"normal restitution $e_n = -v_n'/v_n$",
    "e_t": r"tangential restitution $e_t = v_t'/v_t$",
    "rebound_centre": r"rebound angle $\arctan(v_t'/v_n')$ (deg)",
    "spin": r"rebound spin $r\omega'/|v|$",
}


@dataclass(frozen=True)
class Curve:
    label: str
    model: ContactModel


#: The four maps: Hooke and Hertz (K = 40: its tunnelling speed is 2, twice |v|), the paper's
#: kt = 1, each without and with a Coulomb cap mu = 0.3.
CURVES = (
    Curve("Hooke, no cap (Eq. 18)", ContactModel()),
    Curve("Hooke, mu = 0.3", ContactModel(mu=0.3)),
    Curve("Hertz, no cap", ContactModel(normal="hertz", kn=40.0)),
    Curve("Hertz, mu = 0.3", ContactModel(normal="hertz", kn=40.0, mu=0.3)),
)


def angles(points: int = 44, low: float = 2.0, high: float = 88.0) -> np.ndarray:
    """Incidence angles (deg); grazing and normal incidence are left out (v_n or v_t -> 0)."""
    return np.linspace(low, high, points)


def quantities(initial: np.ndarray, final: np.ndarray) -> dict[str, np.ndarray]:
    """The four maps' values for (n, 3) initial and final states (v_n, v_t, r omega)."""
    speed = np.hypot(initial[:, 0], initial[:, 1])
    return {"e_n": -final[:, 0] / initial[:, 0], "e_t": final[:, 1] / initial[:, 1],
            "rebound_centre": np.degrees(np.arctan2(final[:, 1], final[:, 0])), "spin": final[:, 2] / speed}


def _states(theta_deg: np.ndarray) -> np.ndarray:
    t = np.radians(theta_deg)
    return np.column_stack([-np.cos(t), np.sin(t), np.zeros_like(t)])


def run_curve(curve: Curve, theta_deg: np.ndarray, run_dir: Path) -> dict:
    """One batched LAMMPS run over the angles and the theory beside it."""
    initial = _states(theta_deg)
    scene = Collision(curve.model, v_n=initial[:, 0], v_t=initial[:, 1], omega=0.0)
    result = run_scene(scene, run_dir, atoms="library")
    final = result.table[["v_n_lammps", "v_t_lammps", "r_omega_lammps"]].to_numpy()
    predicted = choose.predict(curve.model, initial)
    return {"label": curve.label, "theta": theta_deg, "lammps": quantities(initial, final),
            "theory": quantities(initial, predicted), "theory_kind": choose.which(curve.model).kind,
            "dt": result.scene.dt, "run": str(run_dir), "max_abs_state_deviation": float(np.abs(final - predicted).max())}


def kharaz_points() -> dict[str, dict]:
    """Kharaz's e_t, rebound spin (as r omega'/|v|) and centre rebound angle, with their sources."""
    out = {}
    for measured in KHARAZ_2001:
        scale = KHARAZ_RADIUS / KHARAZ_SPEED if measured.quantity == "omega_out" else 1.0
        name = {"omega_out": "spin"}.get(measured.quantity, measured.quantity)
        if name in QUANTITY_LABELS:
            out[name] = {"theta": np.array(measured.x), "values": np.array(measured.values) * scale,
                         "source": measured.source, "label": measured.label}
    return out


def kharaz_model(kt_over_kn: float, mu: float) -> ContactModel:
    """The Hookean spring-dashpot of Chung & Ooi's Test 4 in the paper's units: e = 0.98 with the
    normal force kept compressive (limit_damping), alpha = 2/5; kt/kn and mu free."""
    m, kn = 1.0, 10.0
    return ContactModel(m=m, r=0.5, kn=kn, kt=kt_over_kn * kn, gamma_n=gamma_n_for_restitution_cut(KHARAZ_E, m, kn),
                        mu=mu, limit_damping=True)


#: Starting points (kt/kn, mu) of the fit: the squared residual has a local minimum on each
#: branch of Omega's cosine (measured: from (0.2, 0.2) the fit stops at kt/kn = 0.097, from
#: (1.5, 0.1) at 1.89, both with three to four times the residual of the best one).
FIT_STARTS = ((0.1, 0.1), (0.4, 0.1), (0.86, 0.092), (1.5, 0.1))


def kharaz_residuals(kt_over_kn: float, mu: float) -> np.ndarray:
    """Theory minus Kharaz's points for :func:`kharaz_model`: e_t and the spin r omega'/|v| as they
    are, the rebound angle in radians, so each is of order one (theory: the Coulomb oracle)."""
    model = kharaz_model(kt_over_kn, mu)
    out = []
    for name, points in kharaz_points().items():
        initial = _states(points["theta"])
        got = quantities(initial, choose.predict(model, initial))[name]
        scale = math.pi / 180.0 if name == "rebound_centre" else 1.0
        out.append((got - points["values"]) * scale)
    return np.concatenate(out)


def fit_kharaz(starts=FIT_STARTS) -> dict:
    """(kt/kn, mu) of :func:`kharaz_model` that fit Kharaz's points best: least squares on
    :func:`kharaz_residuals` (every digitised point weighs the same) from each start, the best kept."""
    from scipy.optimize import least_squares

    fits = [least_squares(lambda p: kharaz_residuals(*p), start, bounds=([0.01, 0.01], [2.0, 1.0]),
                          x_scale=[0.1, 0.01], xtol=1e-6)
            for start in starts]
    fit = min(fits, key=lambda f: f.cost)
    return {"kt_over_kn": float(fit.x[0]), "mu": float(fit.x[1]), "e": KHARAZ_E, "limit_damping": True,
            "alpha": 0.4, "rms_residual": float(np.sqrt(np.mean(fit.fun**2))), "points": int(fit.fun.size),
            "local_minima": [{"kt_over_kn": float(f.x[0]), "mu": float(f.x[1]),
                              "rms_residual": float(np.sqrt(np.mean(f.fun**2)))} for f in fits],
            "weights": "e_t and r omega'/|v| as they are, rebound angle in radians; every point the same"}


def make_figure(out: Path, runs: Path, points: int = 44) -> dict:
    """figures/restitution.png, .pdf, .json: the four maps, Kharaz's data and the fitted model."""
    from ..figures.core import figure_files
    from ..outputs import check_outputs

    check_outputs(out, figure_files("restitution"))  # before its runs (spinbounce.outputs)
    import matplotlib.style

    from ..figures.core import STYLE, new_figure, save
    from ..records import software

    started = time.perf_counter()
    theta = angles(points)
    fit = fit_kharaz()
    curves = [*CURVES, Curve(f"Hooke fitted to Kharaz: kt/kn = {fit['kt_over_kn']:.3f}, mu = {fit['mu']:.4f}, "
                             f"e = {KHARAZ_E}", kharaz_model(fit["kt_over_kn"], fit["mu"]))]
    results = [run_curve(c, theta, Path(runs) / f"curve{k + 1}") for k, c in enumerate(curves)]
    data = kharaz_points()
    with matplotlib.style.context(STYLE):
        fig, axes = new_figure(2, 2, figsize=(11.0, 8.0))
        for ax, name in zip(axes.ravel(), QUANTITY_LABELS, strict=True):
            for k, res in enumerate(results):
                ax.plot(res["theta"], res["theory"][name], "-", color=f"C{k}", lw=1.0)
                ax.plot(res["theta"][::3], res["lammps"][name][::3], "o", color=f"C{k}", ms=3.5, mfc="none",
                        label=res["label"])
            if name in data:
                ax.plot(data[name]["theta"], data[name]["values"], "k*", ms=7,
                        label=f"{data[name]['label']}, measured")
            ax.set(xlabel=r"incidence angle $\theta$ (deg, from the normal)", ylabel=QUANTITY_LABELS[name])
        axes[0, 0].legend(fontsize=6.5, loc="center right")
        for ax in axes.ravel()[1:]:
            stars = [(h, lab) for h, lab in zip(*ax.get_legend_handles_labels(), strict=True) if "measured" in lab]
            ax.legend(*zip(*stars, strict=True), fontsize=6.5, loc="upper left")
        fig.suptitle("Restitution maps, |v| = 1, no initial spin: lines theory (Eq. 18, Hertz, Coulomb oracle), "
                     "circles LAMMPS, stars Kharaz et al. 2001 (alumina on Al alloy, 3.9 m/s)", fontsize=8.5)
        metadata = {"figure": "restitution", **software(), "kharaz_fit": fit,
                    "kharaz_sources": {k: v["source"] for k, v in data.items()},
                    "curves": [{**{k: v for k, v in r.items() if k not in ("lammps", "theory", "theta")},
                                "model": {f: getattr(c.model, f) for f in ("normal", "kn", "kt", "gamma_n", "mu",
                                                                           "limit_damping")},
                                "theta_deg": r["theta"], "lammps": r["lammps"], "theory": r["theory"]}
                               for r, c in zip(results, curves, strict=True)]}
        return save(fig, out, "restitution", metadata, started).metadata
