"""Run a pair batch through LAMMPS and set each pair beside its references.

Table: one row per pair, with the pair's geometry (eps, the centrifugal ratio, how far the
line of centres turned), and for every final quantity q of sphere a and b (``a_vx`` ...
``b_wz``, LAMMPS's frame, omega as LAMMPS's angular velocity) LAMMPS's value ``q``, the
exact reference ``q_exact`` (:mod:`spinbounce.exact.pair_exact`) and the planar theory's
``q_planar`` (:mod:`spinbounce.exact.pair`). The errors are the largest differences over
the velocities and r times the spins, in units of the pair's ``speed``
(:meth:`Pair.speed`): ``lammps_error`` (LAMMPS against the exact reference: the run's
accuracy) and ``planar_error`` (the planar theory against the exact reference: a model error).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ..lammps.dumps import read_dump
from ..lammps.runner import RunInfo, run_deck
from ..pipeline import ResultError, prepare_run_dir, provenance
from ..model.timestep import ACCURACY, StepChoice
from ..records import to_json, write_atomic
from ..exact import pair as planar
from .deck import PAIR_NO_CAP_MU, render_pairs
from .scene import PairBatch
from .stepping import tune_pairs

__all__ = ["PairResult", "run_pairs", "pair_table", "pair_states", "QUANTITIES"]

#: The final quantities of each sphere, in table order.
QUANTITIES = tuple(f"{side}_{q}{axis}" for side in "ab" for q in "vw" for axis in "xyz")


@dataclass(frozen=True)
class PairResult:
    batch: PairBatch
    table: pd.DataFrame
    info: RunInfo
    dump: Path
    #: Per pair, the atom ids of a and b in the dump (an (n, 2) array).
    ids: np.ndarray | None = None
    #: How dt was chosen (:func:`.stepping.tune_pairs`).
    step: StepChoice | None = None

    @property
    def max_lammps_error(self) -> float:
        return float(self.table["lammps_error"].max())

    @property
    def max_planar_error(self) -> float:
        return float(self.table["planar_error"].max())


def pair_states(batch: PairBatch, ids: np.ndarray, frames: pd.DataFrame, step: int) -> dict[str, np.ndarray]:
    """Both spheres' (n, 3) velocities ``a_v``, spins ``a_w`` (each pair's time scale undone:
    :attr:`PairBatch.time_scales`) and positions ``a_x`` ... ``b_x`` at ``step`` of the dump."""
    rows = frames[frames["step"] == step].set_index("id")
    scales = batch.time_scales[:, None]
    out = {}
    for column, side in ((0, "a"), (1, "b")):
        sphere = rows.loc[ids[:, column]]
        for q, lammps in (("v", "v"), ("w", "omega")):
            out[f"{side}_{q}"] = sphere[[f"{lammps}{axis}" for axis in "xyz"]].to_numpy() * scales
        out[f"{side}_x"] = sphere[["x", "y", "z"]].to_numpy()
    return out


def _final_states(batch: PairBatch, ids: np.ndarray, dump: Path) -> dict[str, np.ndarray]:
    frames = read_dump(dump)
    if sorted(frames["step"].unique()) != [0, batch.nsteps]:
        raise ResultError(f"{dump}: expected frames at steps 0 and {batch.nsteps}")
    if int((frames["step"] == batch.nsteps).sum()) != 2 * batch.n:
        raise ResultError(f"{dump}: {int((frames['step'] == batch.nsteps).sum())} of {2 * batch.n} spheres "
                          "at the end (lost atoms)")
    states = pair_states(batch, ids, frames, batch.nsteps)
    if not all(np.all(np.isfinite(v)) for v in states.values()):
        raise ResultError(f"{dump}: non-finite final states: the integration blew up")
    return _columns(states, "") | {"a_x": states["a_x"], "b_x": states["b_x"]}


def _columns(values: dict[str, np.ndarray], suffix: str) -> dict[str, np.ndarray]:
    """Split (n, 3) arrays keyed a_v, a_w, b_v, b_w into per-axis columns."""
    return {f"{key[:3]}{axis}{suffix}": values[key][:, i] for key in ("a_v", "a_w", "b_v", "b_w")
            for i, axis in enumerate("xyz")}


def _references(batch: PairBatch) -> tuple[dict, dict]:
    exact = {"a_v": np.array([o.v_a for o in batch.exact]), "b_v": np.array([o.v_b for o in batch.exact]),
             "a_w": np.array([o.w_a for o in batch.exact]), "b_w": np.array([o.w_b for o in batch.exact])}
    if batch.contact.mu is not None:  # the capped planar problem has no closed form: n held fixed, solved
        held = [batch.contact.solve(p, planar=True) for p in batch.pairs]
        return exact, {f"{side}_{q}": np.array([getattr(o, f"{q}_{side}") for o in held])
                       for side in "ab" for q in "vw"}
    vectors = {k: np.array([p.vectors()[k] for p in batch.pairs]) for k in ("n", "v_a", "v_b", "w_a", "w_b")}
    props = {k: np.array([p.properties()[k] for p in batch.pairs]) for k in batch.pairs[0].properties()}
    v_a, v_b, w_a, w_b = planar.predict(**vectors, **props, **batch.contact.law())
    return exact, {"a_v": v_a, "b_v": v_b, "a_w": w_a, "b_w": w_b}


def _error(table: pd.DataFrame, suffix: str, other: str, radii: dict) -> np.ndarray:
    """Largest |difference| over velocities and r * spins, in units of each pair's speed."""
    worst = np.zeros(len(table))
    for q in QUANTITIES:
        scale = radii[q[0]] if q[2] == "w" else 1.0
        worst = np.maximum(worst, np.abs(table[q + suffix] - table[q + other]).to_numpy() * scale)
    return worst / table["speed"].to_numpy()


def pair_table(batch: PairBatch, lammps: dict[str, np.ndarray] | None) -> pd.DataFrame:
    """The batch's table; without LAMMPS's final states, the references alone."""
    pairs = batch.pairs
    props = {k: np.array([p.properties()[k] for p in pairs]) for k in pairs[0].properties()}
    tau = planar.contact_time(props["m_a"], props["m_b"], batch.contact.kn, batch.contact.gamma_n)
    v_t, v_n = np.array([p.v_t for p in pairs]), np.array([p.v_n for p in pairs])
    columns = {"pair": np.arange(batch.n), **props, "v_n": v_n, "v_t": v_t,
               "speed": np.array([p.speed() for p in pairs]), "tau": tau,
               "contact_time": np.array([o.contact_time for o in batch.exact]),
               "eps": planar.line_turn(v_t, tau, props["r_a"], props["r_b"]),
               "centrifugal": planar.centrifugal_ratio(v_t, v_n, tau, props["r_a"], props["r_b"]),
               "turn": np.array([o.turn for o in batch.exact]), "time_scale": batch.time_scales}
    exact, theory = _references(batch)
    if lammps is not None:
        columns.update({q: lammps[q] for q in QUANTITIES})
    columns.update(_columns(exact, "_exact"))
    columns.update(_columns(theory, "_planar"))
    table = pd.DataFrame(columns)
    radii = {"a": table["r_a"].to_numpy(), "b": table["r_b"].to_numpy()}
    if lammps is not None:
        table["lammps_error"] = _error(table, "", "_exact", radii)
    table["planar_error"] = _error(table, "_planar", "_exact", radii)
    return table


def _probe_error(batch: PairBatch, out_dir: Path) -> float:
    """The step probe's measurement: a batch at a given step, its largest error against the reference."""
    return run_pairs(batch, out_dir, record=False).max_lammps_error


def run_pairs(batch: PairBatch, out_dir: Path, record: bool = True, target: float = ACCURACY,
              probe_pairs: tuple | None = None) -> PairResult:
    """Run every pair of ``batch`` in one LAMMPS run in ``out_dir``; compare with both references.

    A batch at the default step first gets the step ``target`` needs, probed on its own pairs
    (:func:`.stepping.tune_pairs`, in ``out_dir/probe``; ``probe_pairs``: what to probe with,
    if not its own). With ``record``, ``result.json``
    beside the deck holds the table, the step's choice and the provenance.
    """
    batch, step = tune_pairs(batch, Path(out_dir) / "probe", _probe_error, target, probe_pairs)
    rendered = render_pairs(batch)
    deck_path = prepare_run_dir(out_dir, rendered.deck)
    info = run_deck(deck_path)
    dump = deck_path.parent / rendered.deck.dump
    lammps = _final_states(batch, rendered.ids, dump)
    gap = np.linalg.norm(lammps["a_x"] - lammps["b_x"], axis=1) - np.array([p.radsum for p in batch.pairs])
    if np.any(gap <= 0.0):
        raise ResultError(f"{dump}: pair {int(np.argmin(gap))} still in contact after {batch.nsteps} steps")
    table = pair_table(batch, lammps)
    result = PairResult(batch, table, info, dump, rendered.ids, step)
    if record:
        cap = batch.contact.mu if batch.contact.mu is not None else f"none ({PAIR_NO_CAP_MU:g})"
        parameters = {"contact": batch.contact.law(), "dt": batch.dt, "nsteps": batch.nsteps, "mu": cap}
        out = {**provenance(info, "pairs", parameters), "step": step.record(),
               "max_lammps_error": result.max_lammps_error, "max_planar_error": result.max_planar_error,
               "pairs": table.to_dict(orient="records")}
        write_atomic(deck_path.parent / "result.json", to_json(out))
    return result
