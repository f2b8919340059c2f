"""A pair scene's collisions as a sweep chunk: the wall's columns, and both spheres' final states.

Sphere a's columns are the wall sweep's (:func:`spinbounce.compare.collision_table`):
``{s}_0`` (requested), ``{s}_lammps_0`` (LAMMPS's first frame), ``{s}_final`` (LAMMPS),
``{s}_theory`` (the exact reference, :mod:`spinbounce.exact.pair_exact`: what LAMMPS
integrates, to 1e-9), ``{s}_error`` (final - theory), the spins as angular velocities
beside them, and ``z_*`` (a's centre above b's). Added for the pair: both spheres' final
states in LAMMPS's frame (``a_vx`` ... ``b_wz``, :data:`.run.QUANTITIES`) with their exact
(``*_exact``) and planar (``*_planar``) values; a's state by the planar theory
(``{s}_planar``); the geometry (``eps``, ``centrifugal``, ``turn``, ``contact_time``) and
``planar_error``, the planar theory's model error (never mixed into ``error``); and
``step_method``, how the chunk's step was chosen (:func:`.stepping.tune_pairs`: a probe of
the chunk's own pairs, the fine rule, or a given dt).

Row checks, as the wall's (:mod:`spinbounce.checks`) but over both spheres: ``error`` is the
largest |LAMMPS - exact| over both spheres' velocities and r times spins, over the pair's
speed (:meth:`.Pair.speed`); ``energy_gain`` and ``energy_excess`` are the two spheres'
kinetic energy; ``status`` grazing / energy_gained / inaccurate / ok.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..checks import RESOLVABLE_OVERLAP_ULPS
from ..compare import STATE, STATE_3D
from ..lammps.dumps import read_dump
from ..model.contact import ContactModel
from ..model.timestep import ACCURACY
from ..exact import linear
from ..exact import pair as planar
from .kind import pair_contact, pairs_from_states, wall_frame
from .run import QUANTITIES, pair_states, run_pairs
from .scene import PairBatch, Sphere

__all__ = ["pair_chunk"]

#: Each wall state column's angular velocity column (compare._SPINS).
_SPINS = {"r_omega": "omega", "r_omega_s": "omega_s", "r_omega_n": "omega_n"}


def _a_columns(names, when: str, v: np.ndarray, w: np.ndarray, r: float, height: np.ndarray) -> dict:
    """a's state columns ``{s}_{when}`` (and its spins as angular velocities) from (n, 3) v and w."""
    state = wall_frame(v, w, r)
    out = {}
    for k, name in enumerate(names):
        out[f"{name}_{when}"] = state[:, k]
        if name in _SPINS:
            out[f"{_SPINS[name]}_{when}"] = state[:, k] / r
    out[f"z_{when}"] = height
    return out


def _frame(batch: PairBatch, frames, ids: np.ndarray, step: int) -> dict:
    """a's v and w, and a's height above b, at ``step`` of the dump."""
    state = pair_states(batch, ids, frames, step)
    return {"v": state["a_v"], "w": state["a_w"], "height": state["a_x"][:, 2] - state["b_x"][:, 2]}


def _energy(spheres: list) -> np.ndarray:
    """Both spheres' kinetic energy; ``spheres``: (Sphere, (n, 3) v, (n, 3) w) for a and b."""
    return sum(0.5 * s.m * (v**2).sum(axis=1) + 0.5 * s.inertia * (w**2).sum(axis=1) for s, v, w in spheres)


def _energy_allowance(spheres: list, delta: np.ndarray) -> np.ndarray:
    """The most the two spheres' energy can move when each velocity and r * spin errs by ``delta``:
    |d(x^2/2)| <= |x| delta + delta^2/2 per component, weighted by m (velocities) and alpha m (r w)."""
    bound = 0.0
    for s, v, w in spheres:
        bound = bound + s.m * (np.abs(v).sum(axis=1) * delta + 1.5 * delta**2)
        bound = bound + s.alpha * s.m * (np.abs(s.r * w).sum(axis=1) * delta + 1.5 * delta**2)
    return bound


def _spheres(table, a: Sphere, b: Sphere, suffix: str) -> list:
    return [(sphere, *(table[[f"{side}_{q}{x}{suffix}" for x in "xyz"]].to_numpy() for q in "vw"))
            for side, sphere in (("a", a), ("b", b))]


def _row_checks(columns: dict, table, pairs, model: ContactModel) -> None:
    a, b = pairs[0].a, pairs[0].b
    e0 = _energy([(a, np.array([p.v_a for p in pairs]), np.array([p.w_a for p in pairs])),
                  (b, np.array([p.v_b for p in pairs]), np.array([p.w_b for p in pairs]))])
    exact = _spheres(table, a, b, "_exact")
    e1, e_exact = _energy(_spheres(table, a, b, "")), _energy(exact)
    error = table["lammps_error"].to_numpy()
    columns["energy_gain"] = (e1 - e0) / e0
    columns["error"] = error
    columns["energy_excess"] = (e1 - e_exact) / e0
    status = np.full(len(error), "ok", dtype=object)
    status[error > ACCURACY] = "inaccurate"
    allowance = _energy_allowance(exact, np.maximum(error, ACCURACY) * table["speed"].to_numpy())
    status[e1 - e_exact > allowance] = "energy_gained"
    m_star = planar.reduced_mass(a.m, b.m)
    overlap = np.asarray(linear.max_overlap(table["v_n"].to_numpy(), m_star, model.kn, model.gamma_n), dtype=float)
    status[overlap < RESOLVABLE_OVERLAP_ULPS * np.spacing(a.r + b.r)] = "grazing"
    columns["status"] = status


def pair_chunk(model: ContactModel, b: Sphere, states: np.ndarray, dt: float | None, run_dir: Path,
               probe_states: np.ndarray | None = None) -> tuple[dict, float, int, float]:
    """Run a chunk's pairs in one LAMMPS run; (columns, dt, steps, LAMMPS loop seconds).

    ``states``: (n, 3) or (n, 6) rows of (v_n, v_t, omega[, v_s, omega_s, omega_n]), as a
    wall sweep's chunk gets them (angular velocities); ``probe_states``: the group's states
    a default step is probed with (the same for every chunk: one step per group), by
    default the chunk's own.
    """
    names = STATE_3D if states.shape[1] == 6 else STATE
    pairs = pairs_from_states(model, b, states)
    a = pairs[0].a
    probe = None if probe_states is None else tuple(pairs_from_states(model, b, probe_states))
    result = run_pairs(PairBatch(pairs, pair_contact(model), dt), run_dir, record=False, probe_pairs=probe)
    table = result.table
    requested = wall_frame(np.array([p.v_a for p in pairs]), np.array([p.w_a for p in pairs]), a.r)
    columns = {f"{name}_0": requested[:, k] for k, name in enumerate(names)}
    columns.update({f"{_SPINS[name]}_0": columns[f"{name}_0"] / a.r for name in names if name in _SPINS})
    frames = read_dump(result.dump)
    for when, step in (("lammps_0", 0), ("final", result.batch.nsteps)):
        state = _frame(result.batch, frames, result.ids, step)
        columns.update(_a_columns(names, when, state["v"], state["w"], a.r, state["height"]))
    for suffix, when in (("_exact", "theory"), ("_planar", "planar")):
        v, w = (table[[f"a_{q}{x}{suffix}" for x in "xyz"]].to_numpy() for q in "vw")
        reference = _a_columns(names, when, v, w, a.r, columns["z_final"])
        columns.update({k: value for k, value in reference.items() if not k.startswith("z_")})
    for name in names + tuple(_SPINS[n] for n in names if n in _SPINS):
        columns[f"{name}_error"] = columns[f"{name}_final"] - columns[f"{name}_theory"]
    _row_checks(columns, table, pairs, model)
    for key in ("eps", "centrifugal", "turn", "contact_time", "planar_error"):
        columns[key] = table[key].to_numpy()
    columns.update({q + suffix: table[q + suffix].to_numpy() for q in QUANTITIES for suffix in ("", "_exact", "_planar")})
    columns["step_method"] = np.full(len(pairs), result.step.method, dtype=object)
    return columns, result.batch.dt, result.batch.nsteps, result.info.loop_seconds
