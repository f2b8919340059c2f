"""The gas figure: T_rot/T_tr of gases of frictional spheres against collisions per sphere, LAMMPS beside
the two-temperature theories, the steady ratio against kt/kn, and the energy's drift."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ..exact import kinetic
from ..records import software
from ..scenes.gas.parameters import SHOWN_GAS
from .core import STYLE, FigureRecord, new_figure, save

__all__ = ["make_gas", "CASES", "FIGURE_GAS"]

#: The figure's gases: packing, stiffness and size (each run's accuracy is in its record); kt/kn per case.
FIGURE_GAS = SHOWN_GAS
#: kt/kn of each case: the magic ratio alpha/(1 + alpha) of alpha = 2/5, and a soft and a stiff spring.
CASES = (2.0 / 7.0, 0.1, 0.6)
#: kt/kn where the steady-ratio curves are drawn.
CURVE = np.linspace(0.02, 1.0, 99)


def _run(ratio: float, gases: Path, log) -> dict:
    from ..scenes.gas.run import declared_gas

    report = declared_gas(gases, FIGURE_GAS, ratio, log)
    return {"kt_over_kn": ratio, "series": report.series, "record": report.record}


def _steady_curve() -> np.ndarray:
    """The matrix theory's steady ratio at each kt/kn of CURVE (undamped Hookean spheres, alpha = 2/5)."""
    from ..model.contact import ContactModel
    from ..scenes.gas.predict import matrix_averages

    out = []
    for ratio in CURVE:
        averages, _ = matrix_averages(ContactModel(kn=FIGURE_GAS["kn"], kt=ratio * FIGURE_GAS["kn"]))
        out.append(kinetic.steady_ratio(averages.matrices[0]))
    return np.array(out)


def _draw(cases: list[dict], curve: np.ndarray):
    fig, axes = new_figure(1, 3, figsize=(13.0, 4.2))
    ratio_ax, steady_ax, energy_ax = axes[0]
    for k, case in enumerate(cases):
        s, colour = case["series"], f"C{k}"
        label = f"kt/kn = {case['kt_over_kn']:.3g}"
        ratio_ax.plot(s["collisions"], s["ratio"], "o", color=colour, ms=2.5, mfc="none", label=f"LAMMPS, {label}")
        ratio_ax.plot(s["collisions"], s["ratio_pairs"], "-", color=colour, lw=1.0)
        ratio_ax.plot(s["collisions"], s["ratio_matrix"], "--", color=colour, lw=0.8)
        energy_ax.plot(s["collisions"], s["energy"] / s["energy"][0], "o", color=colour, ms=2.5, mfc="none")
        energy_ax.plot(s["collisions"], s["energy_pairs"] / s["energy_pairs"][0], "-", color=colour, lw=1.0)
        theory = case["record"]["theories"]
        steady_ax.plot(case["kt_over_kn"], case["record"]["lammps"]["late_ratio"], "o", color=colour, mfc="none")
        steady_ax.plot(case["kt_over_kn"], theory["pairs"]["steady_ratio"], "x", color=colour)
        if theory["pairs"]["steady_ratio_boltzmann"] is not None:
            steady_ax.plot(case["kt_over_kn"], theory["pairs"]["steady_ratio_boltzmann"], "+", color=colour, ms=9)
    steady_ax.plot(CURVE, curve, "-", color="0.3", lw=0.8, label="matrix theory")
    steady_ax.axvline(2.0 / 7.0, color="0.7", lw=0.5)
    ratio_ax.set(xlabel="collisions per sphere (LAMMPS's, from its open contacts)", ylabel="T_rot / T_tr",
                 title="(a) circles LAMMPS, lines pair-level theory, dashes matrix theory")
    steady_ax.set(xlabel="kt/kn", ylabel="steady T_rot / T_tr",
                  title="(b) circles LAMMPS (last quarter), x pair-level, + with the closure's error")
    energy_ax.set(xlabel="collisions per sphere", ylabel="kinetic energy / its start",
                  title="(c) circles LAMMPS, lines pair-level theory")
    ratio_ax.legend(fontsize=7, loc="lower right")
    steady_ax.legend(fontsize=7)
    g = FIGURE_GAS
    fig.suptitle(f"Gases of {g['spheres']} Hookean frictional spheres (alpha = 2/5), packing {g['packing']}, "
                 f"kn = {g['kn']:g}, from T_rot = 0", fontsize=9)
    return fig


def make_gas(out: Path, runs: Path, log=print, gases: Path | None = None) -> FigureRecord:
    """gas.png, .pdf and .json into ``out`` (LAMMPS runs in ``gases``, by default the gases' folder under
    ``runs``, where a gas finished there before is read back: :func:`spinbounce.scenes.gas.run.shared_gas`)."""
    import matplotlib.style

    from ..scenes.gas.run import GASES

    started = time.perf_counter()
    gases = Path(gases) if gases is not None else Path(runs) / GASES
    cases = [_run(ratio, gases, log) for ratio in CASES]
    curve = _steady_curve()
    with matplotlib.style.context(STYLE):
        fig = _draw(cases, curve)
        metadata = {"figure": "gas", "title": "T_rot/T_tr of gases of frictional spheres", "gas": FIGURE_GAS,
                    "theory": "spinbounce.exact.kinetic with L from the matrix, the exact pair references and "
                              "LAMMPS's isolated pairs, these two with the overlapping contacts "
                              "(spinbounce.scenes.gas.predict)",
                    "steady_ratio_curve": {"kt_over_kn": CURVE, "matrix": curve}, "software": software(),
                    "cases": [{"kt_over_kn": c["kt_over_kn"], "lammps": c["record"]["lammps"],
                               "theories": {n: {k: v for k, v in t.items() if k in ("max_ratio_difference",
                                                                                    "energy_drift", "steady_ratio",
                                                                                    "relaxation_collisions",
                                                                                    "steady_ratio_boltzmann",
                                                                                    "late_ratio")}
                                            for n, t in c["record"]["theories"].items()},
                               "overlaps": c["record"]["overlaps"], "closure": c["record"]["closure"],
                               "accuracy": c["record"]["accuracy"],
                               "dt": c["record"]["parameters"]["dt"],
                               "run": str(Path(c["record"]["csv"]).parent)} for c in cases]}
        return save(fig, out, "gas", metadata, started)
