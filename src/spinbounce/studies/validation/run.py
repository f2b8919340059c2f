"""Running a benchmark: every series in one LAMMPS batch at a refined step, and once at
twice that refinement for a convergence estimate, tabulated beside the Coulomb oracle
(:mod:`spinbounce.exact.oracle`, exact for the Hookean model), Walton's rigid-body law
and the measured points.

Deviations are the largest over (v_n, v_t, r omega), relative to the impact speed
(:func:`.quantities.impact_speed`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ...scenes.collision import Collision, STATE
from ...model.contact import ContactModel
from ...model.timestep import refine_mid_step
from ...pipeline import run_scene
from ...exact import choose, oracle
from .cases import Benchmark, Series
from .quantities import QUANTITIES, first_touch_stick, impact_speed, quantity, restitution, walton

__all__ = ["ACCEPTANCE", "BenchmarkRun", "refined_dt", "run_benchmark"]

#: Largest |LAMMPS - oracle| allowed, as a fraction of the impact speed (:func:`impact_speed`).
ACCEPTANCE = 1e-4
#: The final states tabulated per state: LAMMPS at the benchmark's refinement and at twice
#: it, the oracle, the rigid-body law (columns named <component>_<final>).
FINALS = ("lammps", "lammps_2f", "oracle", "rigid")


def refined_dt(model: ContactModel, refine: int, speed: float = 1.0) -> float:
    """The scene's default step at |v_n| = ``speed`` made ``refine`` times finer, the contact's end
    kept mid-step (:func:`spinbounce.model.timestep.refine_mid_step`; a Hookean contact's step
    and end do not depend on the speed)."""
    default = Collision(model, v_n=-speed, v_t=0.0, omega=0.0).dt
    return refine_mid_step(_force_time(model, speed), default, refine)


def _force_time(model: ContactModel, speed: float) -> float:
    """How long the contact force lasts at |v_n| = ``speed`` (the Hookean tau at any speed)."""
    return float(model.normal_law.force_times(model, -speed)[0])


@dataclass(frozen=True)
class _OracleBatch(Collision):
    """A collision batch whose theory columns are oracle finals computed once beforehand
    (NaN where the oracle failed), so the two refinements share one oracle pass."""

    oracle_final: tuple = ()

    def predicted(self) -> np.ndarray:
        return np.asarray(self.oracle_final, dtype=float).reshape(self.n, 3)


@dataclass(frozen=True)
class BenchmarkRun:
    """A benchmark's results: one row per state (:attr:`table`), measured comparisons,
    and the runs' provenance."""

    benchmark: Benchmark
    table: pd.DataFrame
    measured: pd.DataFrame
    runs: list[dict]

    def _measured_summary(self) -> dict:
        """Per quantity (and series, when several have data): points, the model's and the rigid body's
        largest distance from the measured values."""
        m = self.measured
        if not len(m):
            return {}
        several = m["series"].nunique() > 1 or m.groupby("quantity")["data"].nunique().max() > 1
        return {_measured_key(q, f"{label}: {data}" if several else label, several): {
                    "points": int(len(g)),
                    "max_abs_model_minus_measured": float(g["model_minus_measured"].abs().max()),
                    "max_abs_rigid_minus_measured": float(g["rigid_minus_measured"].abs().max()),
                    "unit": QUANTITIES[q]["unit"]}
                for (label, q, data), g in m.groupby(["series", "quantity", "data"], sort=False)}

    def summary(self) -> dict:
        t = self.table
        ok = t[t["oracle_ok"]]
        worst = ok.loc[ok["dev_lammps_oracle_rel"].idxmax()]
        sliding = ok[ok["regime_rigid"] == "sliding"]
        return {
            "benchmark": self.benchmark.name,
            "states": int(len(t)),
            "oracle_failures": int((~t["oracle_ok"]).sum()),
            "max_dev_lammps_oracle_rel": float(worst["dev_lammps_oracle_rel"]),
            "max_dev_lammps_oracle_state": str(worst["state"]),
            "max_dev_lammps_oracle_rel_2f": float(ok["dev_lammps_oracle_rel_2f"].max()),
            "max_dev_lammps_self_rel": float(ok["dev_lammps_self_rel"].max()),
            "passes": bool(worst["dev_lammps_oracle_rel"] < ACCEPTANCE),
            "max_dev_oracle_rigid_rel": float(ok["dev_oracle_rigid_rel"].max()),
            "max_dev_oracle_rigid_rel_sliding": (float(sliding["dev_oracle_rigid_rel"].max())
                                                 if len(sliding) else None),
            "refine": self.benchmark.refine,
            "measured": self._measured_summary(),
        }


def _measured_key(quantity_name: str, series: str, several: bool) -> str:
    return f"{quantity_name} ({series})" if several else quantity_name


def _oracle(model: ContactModel, states) -> tuple[np.ndarray, list[str], list[str]]:
    """Oracle finals (v_n, v_t, r omega), contact patterns and errors, state by state: the Coulomb
    oracle for the Hookean or Hertzian spring on the slip history, else the theory that applies
    (:func:`spinbounce.exact.choose.predict`: a Mindlin contact's, capped or not)."""
    if choose.which(model).kind != "coulomb":
        initial = np.array([(v_n, v_t, model.r * w) for v_n, v_t, w in states])
        return choose.predict(model, initial), [choose.which(model).kind] * len(states), [""] * len(states)
    rows = []
    for v_n, v_t, omega in states:
        try:
            got = oracle.bounce(model, v_n, v_t, omega)
        except RuntimeError as exc:  # recorded and reported, never hidden
            rows.append(([np.nan] * 3, "failed", str(exc)))
        else:
            rows.append((got.final[:3], got.pattern, ""))
    return np.array([r[0] for r in rows]), [r[1] for r in rows], [r[2] for r in rows]


def _run_lammps(model, states, oracle_final, refine: int, folder: Path) -> tuple[np.ndarray, dict]:
    s = np.asarray(states, dtype=float)
    speed = float(np.max(np.abs(s[:, 0])))
    scene = _OracleBatch(model, v_n=s[:, 0], v_t=s[:, 1], omega=s[:, 2], dt=refined_dt(model, refine, speed),
                         oracle_final=tuple(np.asarray(oracle_final).ravel()))
    result = run_scene(scene, folder, atoms="library", record=True)
    final = result.table[[f"{c}_lammps" for c in STATE]].to_numpy(dtype=float)
    run = {"refine": refine, "dt": scene.dt, "nsteps": scene.nsteps, "tau": _force_time(model, speed),
           "run_dir": str(folder),
           "lammps_wall_seconds": result.info.wall_seconds, "warnings": list(result.warnings)}
    return final, run


def _series_table(bench: Benchmark, series: Series, labels, initial, finals: dict, notes: dict) -> pd.DataFrame:
    """One row per state: inputs, ``notes`` (per-state columns: regime, oracle pattern and error),
    deviations, and every final (:data:`FINALS` -> (n, 3)) and plotted quantity."""
    model = series.model
    lammps, lammps2, oracle_final, rigid = (finals[k] for k in FINALS)
    speed = impact_speed(initial)
    dev = np.abs(lammps - oracle_final).max(axis=1) / speed
    table = {
        "series": series.label, "state": labels, "v_n": initial[:, 0], "v_t": initial[:, 1],
        "omega": initial[:, 2] / model.r, "impact_speed": speed, "x": quantity(bench.x, initial, initial, model),
        **notes, "oracle_ok": ~np.isnan(oracle_final).any(axis=1),
        "dev_lammps_oracle_rel": dev, "dev_lammps_oracle_abs": dev * speed,
        "dev_lammps_oracle_rel_2f": np.abs(lammps2 - oracle_final).max(axis=1) / speed,
        "dev_lammps_self_rel": np.abs(lammps - lammps2).max(axis=1) / speed,
        "dev_oracle_rigid_rel": np.abs(oracle_final - rigid).max(axis=1) / speed,
        "first_touch_stick_rel": first_touch_stick(model, initial) / speed,
    }
    for name in FINALS:
        for c, component in enumerate(STATE):
            table[f"{component}_{name}"] = finals[name][:, c]
        for q in bench.panels:
            table[f"{q}_{name}"] = quantity(q, initial, finals[name], model)
    return pd.DataFrame(table)


def _measured_rows(series: Series, frame: pd.DataFrame, origin) -> list[dict]:
    """Each measured point beside LAMMPS, the model (oracle) and the rigid body at its own input."""
    rows = []
    for idx, p, j in origin:
        row = frame.iloc[idx]
        model_value, rigid_value = row[f"{p.quantity}_oracle"], row[f"{p.quantity}_rigid"]
        rows.append({
            "series": series.label, "quantity": p.quantity, "data": p.label, "x": p.x[j], "measured": p.values[j],
            "lammps": row[f"{p.quantity}_lammps"], "model": model_value, "rigid": rigid_value,
            "model_minus_measured": model_value - p.values[j], "rigid_minus_measured": rigid_value - p.values[j],
            "regime_rigid": row["regime_rigid"], "oracle_pattern": row["oracle_pattern"], "source": p.source,
        })
    return rows


def run_benchmark(bench: Benchmark, root: Path, refine: int | None = None, log=print) -> BenchmarkRun:
    """Run every series of ``bench`` at ``refine`` (default: the benchmark's) and twice that.

    Rows: the benchmark's grid states, then one per measured point at its digitised input.
    """
    refine = bench.refine if refine is None else refine
    tables, measured_rows, runs = [], [], []
    for k, series in enumerate(bench.series):
        model = series.model
        # origin: (row, Measured, point index) of each measured point's own state
        states = [tuple(s) for s in series.states]
        labels = [f"grid {i + 1}" for i in range(len(states))]
        origin = []
        for p in series.measured:
            for j, x in enumerate(p.x):
                origin.append((len(states), p, j))
                states.append(tuple(bench.to_state(model, x)))
                labels.append(f"{p.quantity} @ {x:.4g}")
        initial = np.array([(v_n, v_t, model.r * w) for v_n, v_t, w in states])
        oracle_final, patterns, errors = _oracle(model, states)
        rigid, regimes = walton(model, initial, restitution(model, initial), bench.beta0)
        finals = {"oracle": oracle_final, "rigid": rigid}
        folder = Path(root) / bench.name / f"series_{k}"
        for name, factor in (("lammps", refine), ("lammps_2f", 2 * refine)):
            finals[name], run = _run_lammps(model, states, oracle_final, factor, folder / f"refine_{factor}")
            runs.append({"series": series.label, **run})
        notes = {"regime_rigid": regimes, "oracle_pattern": patterns, "oracle_error": errors}
        frame = _series_table(bench, series, labels, initial, finals, notes)
        log(f"{bench.name} [{series.label}]: {len(states)} states, refine {refine} and {2 * refine}: "
            f"max |LAMMPS - oracle|/U = {np.nanmax(frame['dev_lammps_oracle_rel']):.3g}, "
            f"{np.nanmax(frame['dev_lammps_oracle_rel_2f']):.3g}")
        tables.append(frame)
        measured_rows += _measured_rows(series, frame, origin)
    return BenchmarkRun(bench, pd.concat(tables, ignore_index=True), pd.DataFrame(measured_rows), runs)
