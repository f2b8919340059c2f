"""A pair scene's collisions as a sweep chunk: the wall's columns, and both spheres' final states.

Sphere a's columns are the wall sweep's (:func:`spinbounce.scenes.collision.table.collision_table`):
``{s}_initial`` (requested), ``{s}_lammps_initial`` (LAMMPS's first frame), ``{s}_lammps`` (LAMMPS),
``{s}_theory`` (the exact reference, :mod:`spinbounce.exact.pair_exact`: what LAMMPS
integrates, to 1e-9), ``{s}_error`` (final - theory), the spins as angular velocities
beside them, and ``z_*`` (a's centre above b's). Added for the pair: both spheres' final
states in LAMMPS's frame (``a_vx`` ... ``b_wz``, :data:`.run.QUANTITIES`) with their exact
(``*_theory``) and planar (``*_planar``) values; a's state by the planar theory
(``{s}_planar``); the geometry (``eps``, ``centrifugal``, ``turn``, ``contact_time``) and
``planar_error``, the planar theory's model error (never mixed into ``error``); and
``step_method``, how the chunk's step was chosen (:func:`spinbounce.stepping.tune`: a probe
of the group's pairs, the fine rule, or a given dt).

Row checks are the pipeline's (:mod:`spinbounce.checks`), over both spheres: ``error`` is
the largest |LAMMPS - exact| over both spheres' velocities and r times spins, over the
pair's speed (:meth:`~spinbounce.scenes.pair.Pair.speed`); ``energy_gain`` and
``energy_excess`` are the two spheres' kinetic energy; ``status`` as the wall's.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..exact.choose import PLANE_COLUMNS, SPACE_COLUMNS
from ..model.contact import ContactModel
from ..pipeline import run_scene
from ..scenes.pair.kind import pair_contact, pairs_from_states, wall_frame
from ..scenes.pair.scene import PairBatch, Sphere
from ..scenes.collision.table import SPINS
from ..scenes.pair.table import QUANTITIES, pair_frames, pair_states
from ..errors import ContactHeld, SceneError
from .pair_ladder import LONGEST, applies, ladder_steps, run_ladder

__all__ = ["pair_chunk"]


def _a_columns(names, when: str, v: np.ndarray, w: np.ndarray, r: float, height: np.ndarray) -> dict:
    """a's state columns ``{s}_{when}`` (and its spins as angular velocities) from (n, 3) v and w."""
    state = wall_frame(v, w, r)
    out = {}
    for k, name in enumerate(names):
        out[f"{name}_{when}"] = state[:, k]
        if name in SPINS:
            out[f"{SPINS[name]}_{when}"] = state[:, k] / r
    out[f"z_{when}"] = height
    return out


#: Rows a chunk's runs leave beyond the accuracy run again, alone, finer (their contacts have a large error
#: constant: a kt/kn of 0.5 leaves about 1 row in 80 so): a combined chunk's at doubling steps per contact up to
#: FINEST, a plain run's at a quarter of its step (aligned as it was), at most PLAIN_REFINEMENTS times (its error is
#: first order), but not a row beyond any affordable step's reach (a state just above its law's jump: it is flagged
#: as it is), and within REFINE_BUDGET: all the runs again may take at most that share of the chunk's own LAMMPS
#: pair-steps (a chunk left mostly beyond the accuracy has the wrong step for its group, and says so in its rows).
#: Each row's ``nsteps`` then counts its own runs too, and ``step_method`` says what it ended at (its ``dt`` stays
#: the group's, by which a fit groups its rows). A step the user gave is not refined.
FINEST = 16 * LONGEST
PLAIN_REFINEMENTS = 3
REFINE_BUDGET = 1.0


def _ladder(given: PairBatch, probe: PairBatch | None, run_dir: Path):
    """The chunk's two runs combined at the group's probed steps (:mod:`.pair_ladder`) and those steps, or None
    where the probe found none, or the chunk's stiffest pair refuses them: then the plain probe runs."""
    chosen = ladder_steps(probe or given, run_dir / "ladder-probe")
    if chosen is None:
        return None
    try:
        return run_ladder(given, chosen[0], run_dir, contact_time=chosen[1]), chosen
    except ContactHeld:  # a state no step ends: refused as it is
        raise
    except SceneError:
        return None


def pair_chunk(model: ContactModel, b: Sphere, states: np.ndarray, dt: float | None, run_dir: Path,
               probe_states: np.ndarray | None = None) -> tuple[dict, float, np.ndarray, float]:
    """Run a chunk's pairs in one LAMMPS run; (columns, the group's dt, each row's steps, LAMMPS loop seconds).

    ``states``: (n, 3) or (n, 6) rows of (v_n, v_t, omega[, v_s, omega_s, omega_n]), as a
    wall sweep's chunk gets them (angular velocities); ``probe_states``: the group's states
    a default step is probed with (the same for every chunk: one step per group), by
    default the chunk's own. At the default step, rows beyond the accuracy run again (:data:`FINEST`).
    """
    names = SPACE_COLUMNS if states.shape[1] == 6 else PLANE_COLUMNS
    pairs = pairs_from_states(model, b, states)
    contact = pair_contact(model, b)
    probe = None if probe_states is None else PairBatch(tuple(pairs_from_states(model, b, probe_states)), contact)
    given = PairBatch(pairs, contact, dt, rule_reach=1)  # rows beyond the accuracy run again below
    folder = Path(run_dir)
    ladder = _ladder(given, probe, folder) if dt is None and applies(given) else None
    if ladder is None:  # one probed run
        run = run_scene(given, run_dir, atoms="library", record=False, probe_states=probe)
        columns, nsteps = _columns(run, pairs, names), np.full(len(pairs), run.scene.nsteps)

        def plain(rows, level):
            finer = run.scene.dt / 4**level
            again = run_scene(rows.at_step(finer), folder / f"refine-{level}", atoms="library", record=False)
            return again, again.scene.nsteps, f"run again alone at dt = {finer:.6g} (the chunk's step left it " \
                                              f"beyond the accuracy)"

        levels = PLAIN_REFINEMENTS if dt is None else 0
        return columns, run.scene.dt, nsteps, run.info.loop_seconds + _refine(
            given, columns, nsteps, plain, lambda level: run.scene.nsteps * 4**level, levels, names)
    # two aligned runs combined (sweeps.pair_ladder; the final states are the combination's)
    (combined, (steps, tau)), n = ladder, len(pairs)
    columns, nsteps = _columns(combined.result, pairs, names), np.full(n, combined.nsteps)

    def finer_ladder(rows, level):
        again = run_ladder(rows, steps * 2**level, folder / f"refine-{level}", contact_time=tau)
        return again.result, again.nsteps, again.result.step.method

    levels = int(np.log2(FINEST // steps)) if steps <= FINEST else 0
    return columns, combined.result.scene.dt, nsteps, combined.result.info.loop_seconds + _refine(
        given, columns, nsteps, finer_ladder, lambda level: combined.nsteps * 2**level, levels, names)


def _refine(given: PairBatch, columns: dict, nsteps, again, cost, levels: int, names) -> float:
    """Run the rows of ``columns`` beyond the accuracy (but beyond no affordable step's reach) again,
    ``again(rows, level)`` (its run, its steps and what it ran at; ``cost(level)``: about its steps a row) at level
    1 to ``levels`` until each reaches it, within :data:`REFINE_BUDGET`; each row's columns, steps (its runs, all
    counted) and ``step_method`` replaced in place (its ``dt`` stays the group's: a fit groups rows by it);
    LAMMPS's loop seconds."""
    loop, bad = 0.0, np.flatnonzero(columns["status"] == "inaccurate")
    if bad.size:  # writable copies (a table's columns may be views of read-only buffers), words of any length
        columns.update({k: np.array(v, dtype=object if v.dtype.kind == "U" else v.dtype) for k, v in columns.items()})
        bad = bad[~given.beyond_reach()[bad]]
    budget = REFINE_BUDGET * float(np.sum(nsteps))  # pair-steps the runs again may take, all together
    for level in range(1, levels + 1):
        if not bad.size:
            break
        budget -= cost(level) * bad.size
        if budget < 0.0:  # too many rows to run again: the chunk's own answer stands, its rows flagged
            break
        rows = given.rows(bad)
        try:
            run, steps, method = again(rows, level)
        except ContactHeld:  # a state no step ends: refused as it is
            raise
        except SceneError:  # a step this fine is refused (its run too long): the rows stay as they are, flagged
            break
        for key, value in _columns(run, rows.pairs, names).items():
            columns[key][bad] = value
        columns["step_method"][bad] = method
        nsteps[bad] += steps
        loop += run.info.loop_seconds
        bad = bad[columns["status"][bad] == "inaccurate"]
    return loop


def _columns(run, pairs, names) -> dict:
    """A run's columns of sphere a (the wall sweep's), both spheres' states and references, geometry and
    checks (the module's text)."""
    a = pairs[0].a
    table, batch = run.table, run.scene
    requested = wall_frame(np.array([p.v_a for p in pairs]), np.array([p.w_a for p in pairs]), a.r)
    columns = {f"{name}_initial": requested[:, k] for k, name in enumerate(names)}
    columns.update({f"{SPINS[name]}_initial": columns[f"{name}_initial"] / a.r for name in names if name in SPINS})
    frames = pair_frames(run.info, run.deck, run.info.deck.parent, batch.nsteps)
    for when, step in (("lammps_initial", 0), ("lammps", batch.nsteps)):  # a's height above b, and its state
        state = pair_states(batch, run.deck.ids, frames, step)
        height = state["a_x"][:, 2] - state["b_x"][:, 2]
        if when == "lammps":  # LAMMPS's final state as the run reports it (a ladder's: the combination)
            state = {q: table[[f"a_{q[-1]}{x}" for x in "xyz"]].to_numpy() for q in ("a_v", "a_w")}
        columns.update(_a_columns(names, when, state["a_v"], state["a_w"], a.r, height))
    for suffix, when in (("_theory", "theory"), ("_planar", "planar")):
        v, w = (table[[f"a_{q}{x}{suffix}" for x in "xyz"]].to_numpy() for q in "vw")
        reference = _a_columns(names, when, v, w, a.r, columns["z_lammps"])
        columns.update({k: value for k, value in reference.items() if not k.startswith("z_")})
    for name in names + tuple(SPINS[n] for n in names if n in SPINS):
        columns[f"{name}_error"] = columns[f"{name}_lammps"] - columns[f"{name}_theory"]
    for key in ("eps", "centrifugal", "turn", "contact_time", "planar_error", "error", "energy_gain", "energy_excess",
                "status", "time_scale"):
        columns[key] = table[key].to_numpy()
    columns.update({q + suffix: table[q + suffix].to_numpy() for q in QUANTITIES
                    for suffix in ("", "_theory", "_planar")})
    columns["step_method"] = np.full(len(pairs), run.step.method, dtype=object)
    return columns
