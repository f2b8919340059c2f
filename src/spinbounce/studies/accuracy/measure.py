"""Runs over dt: each case's ladder of steps, its error against theory, steps and seconds.

A level is n steps per half-period of the case's fastest contact mode. The collision's
step comes from the rungs shared with :mod:`spinbounce.extrapolation` (the mid-step
rule itself lives in :mod:`spinbounce.model.timestep`); the other forms are the study's own
contrasts: the end on a step boundary, and one dt for spheres that end at their own times.
Beside the ladder, each case runs once at the step the scenes choose by default
(:func:`run_default`): no constant resolution, but the one their accuracy target asks for.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from ...scenes.collision import Collision, STATE_ARGS
from ...model.contact import ContactModel
from ...scenes.frozen import Frozen
from ...checks import STATUSES
from ...model.timestep import ACCURACY, FROZEN_ACCURACY, mid_step_dt, steps_through
from ...pipeline import run_scene, run_series
from ...extrapolation import (collision_frame, collision_rung_dt, contact_steps, default_tolerance,
                              extrapolate_collision, frozen_rung_dt)
from .cases import ANY, EDGE, FROZEN, FROZEN_T_END, FROZEN_Z, MID, Case

__all__ = ["FULL_LADDER", "QUICK_LADDER", "DEFAULT_FORMS", "ladder", "collision_dt", "frozen_dt", "run_default",
           "default_target", "labelled_row", "run_collision_level", "run_frozen_level", "run_case", "warm_up",
           "steps_of_dt"]

#: Steps per half-period of the fastest mode along the full ladder, and the quick one.
FULL_LADDER = tuple(2**k for k in range(5, 17))  # 32 .. 65536
QUICK_LADDER = (64, 128, 256, 512, 1024)
#: The forms a scene's default step can take: its end mid-step (every Hookean contact, and a
#: Hertzian wall at one speed), one dt for several Hertzian speeds (time-scaled, every end
#: mid-step in deck time; with a dashpot the fixed rule), a frozen contact. No default puts
#: the end on a step boundary: that form is the study's contrast only.
DEFAULT_FORMS = (MID, ANY, FROZEN)


def ladder(quick: bool = False) -> tuple[int, ...]:
    return QUICK_LADDER if quick else FULL_LADDER


def collision_dt(model: ContactModel, n: float, form: str, speed: float | None = None) -> float:
    """The collision step for ``n`` steps per half-period of the fastest mode, in ``form``.

    Hookean: the mid-step rung or its end on a step, tau/M. ``ANY``: pi/(n w) for a Hertzian
    wall, whose fastest mode w depends on the fastest |v_n|, ``speed`` (for n =
    HERTZ_STEPS_PER_HALF_PERIOD the default of a damped Hertzian batch of several speeds). A
    Hertzian mid-step dt is one speed's own: :func:`_hertz_mid_dt`. A given dt runs every
    sphere at it (no time scale).
    """
    if form == MID:
        return collision_rung_dt(model, n)
    if form == EDGE:
        return model.tau / contact_steps(model, n)
    if form == ANY:
        return math.pi / model.fastest_rate(frozen=False, speed=speed) / n
    raise ValueError(f"form = {form!r}: a collision runs in form {MID!r}, {EDGE!r} or {ANY!r}")


def _hertz_mid_dt(model: ContactModel, n: float, v_n: float, speed: float) -> float:
    """The mid-step dt of one Hertzian speed: its own contact time over M + 1/2 steps, M
    resolving the case's fastest mode (at ``speed``) with ``n`` steps per half-period."""
    t_end = float(model.contact_times(v_n)[0])
    rate = model.fastest_rate(frozen=False, speed=speed)
    return mid_step_dt(t_end, math.ceil(n * rate * t_end / math.pi - 1e-9))


def frozen_dt(model: ContactModel, n: float, t_end: float = FROZEN_T_END) -> float:
    """The frozen rung (snapped to whole steps in t_end)."""
    return frozen_rung_dt(model, n, t_end)


def steps_of_dt(case: Case):
    """LAMMPS steps of a run of ``case`` at step dt (the scenes' own counts)."""
    if case.kind == "frozen":
        return lambda dt: math.ceil(FROZEN_T_END / dt - 1e-9)
    t_end = float(np.max(case.model.contact_times([s[0] for s in case.states])))
    return lambda dt: steps_through(t_end, dt)


def _timed(run, repeats: int):
    """``run()`` ``repeats`` times: the result of the fastest repeat and its wall seconds.

    The fastest of a few repeats is the run's cost with the least interference from the
    other processes on a shared machine. The repeats must agree exactly: LAMMPS on one
    rank is deterministic, and a difference would mean a run depends on something else.
    """
    best, best_wall = None, math.inf
    for _ in range(repeats):
        started = time.perf_counter()
        result = run()
        wall = time.perf_counter() - started
        if best is not None and not best.table.equals(result.table):
            raise RuntimeError(f"{result.info.deck}: a repeated run gave a different result")
        if wall < best_wall:
            best, best_wall = result, wall
    return best, best_wall


def collision_scene(case: Case, dt: float | None, states=None) -> Collision:
    """The case's collision (or ``states``, in the case's columns) at step ``dt`` (None: the
    scenes' default, which a run may still tune: :func:`spinbounce.stepping.tune`)."""
    s = np.asarray(case.states if states is None else states, dtype=float)
    r = case.model.r
    # spins are stored as r omega (STATE_3D); Collision takes the angular velocities
    columns = {name: s[:, k] / (r if name.startswith("omega") else 1.0) for k, name in enumerate(STATE_ARGS)
               if k < s.shape[1]}
    return Collision(case.model, dt=dt, **columns)


def run_collision_level(case: Case, dt: float | None, folder: Path, states=None, repeats: int = 1):
    """One batch at ``dt`` (None: the default step): (row, final states). The row holds the
    largest error of each state column against the case's theory, the largest error relative
    to the state's size (the default step's measure, checks.add_row_checks), how the step was
    chosen, the step LAMMPS ran at, its steps and the seconds. A damped case's default is the ladder's
    runs extrapolated to dt = 0 (:func:`_run_extrapolated`)."""
    if dt is None and default_tolerance(case.model) is not None:
        return _run_extrapolated(collision_scene(case, None, states), folder)
    result, wall = _timed(lambda: run_scene(collision_scene(case, dt, states), folder, atoms="library",
                                                record=False), repeats)
    ran, t = result.scene, result.table
    row = {"dt": ran.dt, "lammps_steps": ran.nsteps, "resolution": ran.steps_per_half_period, "spheres": ran.n,
           "step_method": result.step.method, "relative_error": float(t["error"].max()),
           "worst_status": min(t["status"], key=STATUSES.index), "loop_seconds": result.info.loop_seconds,
           "lammps_seconds": result.info.wall_seconds, "wall_seconds": wall}
    for s in ran.state_names:
        row[f"error_{s}"] = float(np.max(np.abs(t[f"{s}_error"])))
    return row, t[[f"{s}_lammps" for s in ran.state_names]].to_numpy()


def _run_extrapolated(scene: Collision, folder: Path):
    """(row, final states) of ``scene``'s default: its ladder extrapolated to ACCURACY; ``lammps_steps``:
    all runs' together, ``estimate``: the extrapolation's error estimate over the state's size (as
    ``relative_error``), beside the measured errors."""
    target = default_tolerance(scene.model)
    started = time.perf_counter()
    result, finest = extrapolate_collision(scene, target, folder, relative=True)
    wall = time.perf_counter() - started
    columns = collision_frame(result, finest, target)
    loop = sum(level["loop_seconds"] for level in result.levels)
    row = {"dt": finest.dt, "lammps_steps": result.steps, "resolution": finest.steps_per_half_period,
           "spheres": finest.n, "step_method": f"extrapolated ({len(result.levels)} runs)",
           "relative_error": float(np.max(columns["error"])),
           "worst_status": min(columns["status"], key=STATUSES.index), "loop_seconds": loop,
           "lammps_seconds": sum(level["lammps_seconds"] for level in result.levels), "wall_seconds": wall,
           "estimate": result.relative_estimate(finest.initial)}
    for s in finest.state_names:
        row[f"error_{s}"] = float(np.max(np.abs(columns[f"{s}_error"])))
    return row, result.values


def _run_hertz_mid(case: Case, dt_of_speed, folder: Path, repeats: int) -> dict:
    """Each Hertzian speed alone at ``dt_of_speed(v_n)`` (None: that scene's default). The row
    takes the largest errors, the coarsest resolution, the longest run's dt and steps, and the
    seconds of all the runs together."""
    states = np.asarray(case.states, dtype=float)
    rows = []
    for k, v_n in enumerate(np.unique(states[:, 0])):
        row, _ = run_collision_level(case, dt_of_speed(float(v_n)), folder / f"speed-{k}",
                                     states[states[:, 0] == v_n], repeats)
        rows.append(row)
    longest = max(rows, key=lambda r: r["lammps_steps"])
    out = {"dt": longest["dt"], "lammps_steps": longest["lammps_steps"],
           "resolution": min(r["resolution"] for r in rows),
           "step_method": ", ".join(sorted({r["step_method"] for r in rows})),
           "worst_status": min((r["worst_status"] for r in rows), key=STATUSES.index)}
    for key in ("spheres", "loop_seconds", "lammps_seconds", "wall_seconds"):
        out[key] = sum(r[key] for r in rows)
    for key in (k for k in rows[0] if k.startswith("error_") or k == "relative_error"):
        out[key] = max(r[key] for r in rows)
    return out


def run_frozen_level(case: Case, dt: float | None, folder: Path, repeats: int = 1) -> dict:
    """The frozen contact at ``dt`` (None: the scene's default): its row, as a collision's."""
    ((_, v_t, r_omega),) = case.states
    scene = Frozen(case.model, z=FROZEN_Z, v_t=v_t, omega=r_omega / case.model.r, t_end=FROZEN_T_END, dt=dt)
    result, wall = _timed(lambda: run_series(scene, folder), repeats)
    t = result.table
    errors = {"error_v_n": 0.0,  # held: v_n = 0 exactly
              "error_v_t": float(np.max(np.abs(t["v_t"] - t["v_t_theory"]))),
              "error_r_omega": float(np.max(np.abs(t["r_omega"] - t["r_omega_theory"])))}
    return {"dt": scene.dt, "lammps_steps": scene.nsteps, "resolution": scene.steps_per_half_period,
            "spheres": 1, "step_method": "frozen rule" if dt is None else "given",
            "relative_error": max(errors.values()) / math.hypot(v_t, r_omega), "worst_status": "ok",
            "loop_seconds": result.info.loop_seconds, "lammps_seconds": result.info.wall_seconds,
            "wall_seconds": wall, **errors}


def run_level(case: Case, n: float | None, form: str, folder: Path, repeats: int = 1) -> dict:
    """One level of ``case`` in ``form`` at ``n`` steps per half-period (None: the scenes'
    default step: the a priori rule, the probe (a Hertzian batch: time-scaled), a damped
    Hertzian batch's fixed resolution, or the frozen rule; pipeline.run_scene tunes a default
    step): its row."""
    if form == FROZEN:
        return run_frozen_level(case, None if n is None else frozen_dt(case.model, n), folder, repeats)
    speed = float(np.max(np.abs(np.asarray(case.states, dtype=float)[:, 0])))  # the fastest |v_n|
    if case.model.normal_law.contact_radius and form == MID:  # each speed is a scene of its own
        def dt_of_speed(v_n):
            return None if n is None else _hertz_mid_dt(case.model, n, v_n, speed)

        return _run_hertz_mid(case, dt_of_speed, folder, repeats)
    dt = None if n is None else collision_dt(case.model, n, form, speed=speed)
    return run_collision_level(case, dt, folder, repeats=repeats)[0]


def default_target(case: Case) -> float:
    """The accuracy the scenes' default step aims at for ``case`` (model.timestep): ACCURACY for
    a collision; for a frozen contact FROZEN_ACCURACY, but with gamma_t its first-order dashpot
    lag is held to ACCURACY only (Frozen.default_dt), so that is all the default promises."""
    if case.kind == "frozen" and case.model.gamma_t == 0.0:
        return FROZEN_ACCURACY
    return ACCURACY


def run_default(case: Case, form: str, folder: Path, repeats: int = 1) -> dict:
    """``case`` in ``form`` at the step the scenes choose by default: its row, with the target
    that step aims at."""
    if form not in DEFAULT_FORMS:
        raise ValueError(f"form = {form!r}: no default step takes it (only {', '.join(DEFAULT_FORMS)})")
    return {**run_level(case, None, form, folder, repeats), "target": default_target(case)}


def warm_up(all_cases: list[Case], root: Path) -> None:
    """One short run of each scene kind, normal law and integrator, untimed: the first run in
    a process also pays for compiling its deck template and loading LAMMPS's styles."""
    seen = set()
    for case in all_cases:
        key = (case.kind, case.model.normal, case.model.alpha != ContactModel().alpha)
        if key not in seen:
            seen.add(key)
            run_level(case, 32, case.forms[0], root / "warm-up" / case.name)


def labelled_row(row: dict, case: Case, form: str, n: float | None = None) -> dict:
    """``row`` with its case, form and level (``n`` steps per half-period of the ladder; None: a
    run at the default step, whose level is its resolution), and its largest error."""
    row.update(case=case.name, label=case.label, kind=case.kind, form=form,
               steps_per_half_period=row["resolution"] if n is None else n, default_dt=n is None,
               in_ladder=n is not None, theory=case.theory)
    row["error"] = max(row[f"error_{s}"] for s in case.state_names)
    return row


def run_case(case: Case, steps: tuple[int, ...], root: Path, log, repeats: int = 1) -> list[dict]:
    """Every form and level of ``case``, and each form a default step takes: one row per run."""
    rows = []
    for form in case.forms:
        folder = root / case.name / form.replace(" ", "-")
        for n in steps:
            rows.append(labelled_row(run_level(case, n, form, folder / f"n{n:06d}", repeats), case, form, n))
        if form in DEFAULT_FORMS:
            rows.append(labelled_row(run_default(case, form, folder / "default", repeats), case, form))
    ends = [r for r in rows if r["in_ladder"] and r["steps_per_half_period"] in (steps[0], steps[-1])]
    defaults = [r for r in rows if r["default_dt"]]
    log(f"  {case.name:<14}" + "  ".join(f"{r['form']} n={r['steps_per_half_period']}: {r['error']:.2e}"
                                         for r in ends)
        + "".join(f"  default ({r['form']}): {r['lammps_steps']} steps, {r['relative_error']:.2e} of the state"
                  for r in defaults))
    return rows
