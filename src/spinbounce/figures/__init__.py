"""The paper's Figs. 2-7, regenerated from LAMMPS runs and the theory.

Each figure is ``figN_data(out, runs) -> FigureData``, which runs its scenes (into ``runs``,
default OUT/runs/figN) and builds tables, and ``draw_figN(data)``, which draws from them only;
:func:`figure_function` joins them into ``figN(out, runs=None) -> FigureRecord``, which writes
``figN.png``, ``figN.pdf`` and ``figN.json`` (the metadata: parameters, steps, versions
and the largest deviation between LAMMPS and the exact theory) into ``out``.

Importing this package loads neither matplotlib nor LAMMPS; they load when a figure is made.
"""

from __future__ import annotations

import functools
import importlib
from collections.abc import Callable
from pathlib import Path

__all__ = ["FIGURES", "FigureNameError", "check_names", "figure_function", "make_figures"]

#: name -> (module, what the figure shows). The order is the paper's.
FIGURES: dict[str, tuple[str, str]] = {
    "fig2": ("frozen", "frozen contact: v_t(t) and omega(t), LAMMPS against Eq. 10"),
    "fig3": ("frozen", "frozen trajectories in the (r omega, v_t) plane, end points Eq. 12, slope Eq. 13"),
    "fig4": ("collisions", "Delta v_t and r Delta omega against u'(0), LAMMPS against Eq. 19"),
    "fig5": ("collisions", "bounce trajectories: rough sphere (Eq. 20), rolling (Eq. 23), frictionless"),
    "fig6": ("collisions", "dissipation f against u'(0): kt/kn = 1/10, 2/7 and the rolling limit"),
    "fig7": ("frozen", "damped frozen contact: LAMMPS against the exact solution and Eq. 22"),
}


class FigureNameError(ValueError):
    """A figure name that is not one of :data:`FIGURES`."""


def check_names(names) -> list[str]:
    """The names, in the paper's order and without repeats; raise on an unknown one."""
    names = list(names)
    bad = [n for n in names if n not in FIGURES]
    if bad:
        raise FigureNameError(
            f"unknown figure {', '.join(repr(b) for b in bad)} (choose from {', '.join(FIGURES)})"
        )
    return [n for n in FIGURES if n in names]


def figure_function(name: str) -> Callable:
    """``figN(out, runs=None) -> FigureRecord``, making figure ``name`` (its module imported on first use)."""
    from .core import make

    (name,) = check_names([name])
    module = importlib.import_module(f".{FIGURES[name][0]}", __name__)
    return functools.partial(make, getattr(module, f"{name}_data"), getattr(module, f"draw_{name}"), name)


def make_figures(out: Path, only: list[str] | None = None, log=print, runs: Path | None = None) -> list[dict]:
    """Make the figures ``only`` (default: all) into ``out``; return their metadata records.

    LAMMPS runs go to ``runs``/figN (default OUT/runs/figN) and are kept: each run folder
    holds its deck, log and result, so every number in a figure can be traced and rerun.
    A figure whose largest deviation from the exact theory is not below 1e-4, or whose
    runs fail their checks, raises (pipeline.ResultError) rather than being drawn.
    """
    from ..outputs import check_outputs
    from .core import figure_files

    out = Path(out)
    names = check_names(FIGURES if only is None else only)
    check_outputs(out, [file for name in names for file in figure_files(name)])  # before any figure runs
    records = []
    for name in names:
        record = figure_function(name)(out, None if runs is None else Path(runs) / name)
        meta = record.metadata
        line = (f"{name}: {record.png.name}, {record.pdf.name}, {record.json.name}; largest |LAMMPS - exact| "
                f"{meta['max_deviation_exact']:.2e}")
        if "max_deviation_eq22" in meta:
            line += f", |LAMMPS - Eq. 22| {meta['max_deviation_eq22']:.2e}"
        log(f"{line} ({meta['runtime_seconds']:.1f} s)")
        records.append(meta)
    return records
