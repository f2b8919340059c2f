"""A pair batch's table: each pair's final states beside its references.

One row per pair, with the pair's geometry (the relative normal velocity ``v_n_relative`` and
tangential speed ``v_t_relative`` at first touch, eps, the centrifugal ratio, how far the line
of centres turned), and for every final quantity q of sphere a and b (``a_vx`` ... ``b_wz``,
LAMMPS's frame, omega as LAMMPS's angular velocity) LAMMPS's value ``q``, the exact
reference ``q_theory`` (:mod:`spinbounce.exact.pair_exact`) and the planar theory's
``q_planar`` (:mod:`spinbounce.exact.pair`). ``planar_error`` is the planar theory's
largest difference from the exact reference over the velocities and r times the spins, in
units of the pair's ``speed`` (:meth:`Pair.speed`): a model error. LAMMPS's own error
against the exact reference is the row checks' ``error`` (:mod:`spinbounce.checks`), in
the same units.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from ...errors import ResultError
from ...exact import choose
from ...exact import pair as planar
from ...lammps.dumps import finite_frames, read_dump
from .deck import QUANTITIES
from .pairs import speeds

if TYPE_CHECKING:
    from ...lammps.decks import Deck

__all__ = ["pair_table", "pair_states", "pair_frames", "read_pairs", "QUANTITIES"]


def pair_states(batch, ids: np.ndarray, frames: pd.DataFrame, step: int) -> dict[str, np.ndarray]:
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


def _columns(values: dict[str, np.ndarray], suffix: str) -> dict[str, np.ndarray]:
    """Split (n, 3) arrays keyed a_v, a_w, b_v, b_w into per-axis columns."""
    return {f"{key[:3]}{axis}{suffix}": values[key][:, i] for key in ("a_v", "a_w", "b_v", "b_w")
            for i, axis in enumerate("xyz")}


def _outcomes(outcomes) -> dict[str, np.ndarray]:
    """(n, 3) arrays a_v, a_w, b_v, b_w of the pairs' outcomes."""
    return {f"{side}_{q}": np.array([getattr(o, f"{q}_{side}") for o in outcomes])
            for side in "ab" for q in "vw"}


def _held(batch, props: dict) -> dict[str, np.ndarray]:
    """Each pair's outcome with its line of centres held (``props``: the spheres' columns, as :func:`pair_table`
    has them): its equivalent wall's (:func:`.pair.from_wall`) where
    that wall's theory is the exact stick-slip solver (Hooke's law and a cap: measured within 1.2e-12 of the
    speed of the held pair reference, tests/test_pairs_capped.py, at a fraction of its cost), else the pair
    reference held (:meth:`.PairContact.solve_all`)."""
    walls = [(wall.replace(mu=batch.contact.mu), index) for wall, index in batch.wall_groups]
    if not all(choose.which(wall).kind == "coulomb" for wall, _ in walls):
        return _outcomes(batch.held)
    c = batch.columns
    out = {k: np.empty((batch.n, 3)) for k in ("a_v", "b_v", "a_w", "b_w")}
    for wall, index in walls:
        vectors = [c[k][index] for k in ("normal", "v_a", "v_b", "w_a", "w_b")]
        spheres = {k: v[index] for k, v in props.items()}
        final = choose.predict(wall, planar.wall_states(*vectors, spheres["r_a"], spheres["r_b"]))
        for key, value in zip(("a_v", "b_v", "a_w", "b_w"), planar.from_wall(*vectors, **spheres, final=final),
                              strict=True):
            out[key][index] = value
    return out


def pair_table(batch, lammps: dict[str, np.ndarray] | None) -> pd.DataFrame:
    """The batch's table; without LAMMPS's final states, the references alone."""
    c = batch.columns
    props = {f"{k}_{side}": c[f"{k}_{side}"] for side in "ab" for k in ("m", "r", "alpha")}
    # the contact time: the planar theory's (Hookean, the force let pull), or each pair's own where it
    # depends on the speed or limit_damping cuts the force
    closed = not batch.contact.on_contact_radius and batch.contact.tensile
    tau = (planar.contact_time(props["m_a"], props["m_b"], batch.contact.kn, batch.contact.gamma_n) if closed
           else np.array([o.contact_time for o in batch.exact]))
    v = c["v_a"] - c["v_b"]
    v_n = np.einsum("mi,mi->m", v, c["normal"])
    v_t = np.linalg.norm(v - v_n[:, None] * c["normal"], axis=1)
    columns = {"pair": np.arange(batch.n), **props, "v_n_relative": v_n, "v_t_relative": v_t,
               "speed": speeds(c), "tau": tau,
               "contact_time": np.array([o.contact_time for o in batch.exact]),
               "eps": planar.line_turn(v_t, tau, props["r_a"], props["r_b"]),
               "centrifugal": planar.centrifugal_ratio(v_t, v_n, tau, props["r_a"], props["r_b"]),
               "turn": np.array([o.turn for o in batch.exact]), "time_scale": batch.time_scales}
    if batch.contact.mu is not None or not closed:  # no closed form: n held fixed, solved
        theory = _held(batch, props)
    else:
        vectors = {"n": c["normal"]} | {k: c[k] for k in ("v_a", "v_b", "w_a", "w_b")}
        predicted = planar.predict(**vectors, **props, **batch.contact.law())
        theory = dict(zip(("a_v", "b_v", "a_w", "b_w"), predicted))
    if lammps is not None:
        columns.update({q: lammps[q] for q in QUANTITIES})
    columns.update(_columns(_outcomes(batch.exact), "_theory"))
    columns.update(_columns(theory, "_planar"))
    table = pd.DataFrame(columns)
    # the planar theory's largest |difference| from the exact reference over velocities and r * spins,
    # in units of each pair's speed
    worst = np.zeros(len(table))
    for q in QUANTITIES:
        scale = props[f"r_{q[0]}"] if q[2] == "w" else 1.0
        worst = np.maximum(worst, np.abs(table[q + "_planar"] - table[q + "_theory"]).to_numpy() * scale)
    table["planar_error"] = worst / table["speed"].to_numpy()
    return table


def _frame(state: dict, step: int) -> pd.DataFrame:
    """The spheres (not the rigid bodies' centre points: every third atom type) of a state read from
    LAMMPS's memory, as a dump's frame."""
    spheres = state["type"] % 3 != 0
    columns = {"step": np.full(int(spheres.sum()), step, dtype=np.int64), "id": state["id"][spheres].astype(np.int64)}
    for name, axes in (("x", ("x", "y", "z")), ("v", ("vx", "vy", "vz")), ("omega", ("omegax", "omegay", "omegaz"))):
        columns.update({axis: state[name][spheres, k] for k, axis in enumerate(axes)})
    return pd.DataFrame(columns)


def pair_frames(info, deck: Deck, folder: Path, nsteps: int) -> pd.DataFrame:
    """The spheres' frames at steps 0 and ``nsteps``, finite: from LAMMPS's memory (a library-route run,
    :func:`.deck.render_pairs`) or from the run's dump."""
    if deck.dump is None:
        where = Path(folder) / deck.name
        return finite_frames(pd.concat([_frame(info.initial, 0), _frame(info.final, nsteps)], ignore_index=True), where)
    dump = Path(folder) / deck.dump
    return finite_frames(read_dump(dump), dump)


def read_pairs(batch, deck: Deck, folder: Path, info=None) -> dict:
    """The run's checked table columns: every pair's spheres there, finite, and apart at the end."""
    frames = pair_frames(info, deck, folder, batch.nsteps)
    dump = Path(folder) / (deck.dump or deck.name)
    if sorted(frames["step"].unique()) != [0, batch.nsteps]:
        raise ResultError(f"{dump}: expected frames at steps 0 and {batch.nsteps}")
    at_end = int((frames["step"] == batch.nsteps).sum())
    if at_end != 2 * batch.n:
        raise ResultError(f"{dump}: {at_end} of {2 * batch.n} spheres at the end (lost atoms)")
    states = pair_states(batch, deck.ids, frames, batch.nsteps)
    gap = np.linalg.norm(states["a_x"] - states["b_x"], axis=1) - (batch.columns["r_a"] + batch.columns["r_b"])
    if np.any(gap <= 0.0):
        raise ResultError(f"{dump}: pair {int(np.argmin(gap))} still touches after {batch.nsteps} steps: the contact "
                          "had not finished")
    return {k: v.to_numpy() for k, v in pair_table(batch, _columns(states, "")).items()}
