"""Runs over dt: each case's ladder of steps, its error against theory, steps and seconds.

A level is n steps per half-period of the case's fastest contact mode. The collision's
step comes from the rungs shared with :mod:`spinbounce.studies.tolerance` (the mid-step
rule itself lives in :mod:`spinbounce.model.timestep`); the other forms are the study's own
contrasts: the end on a step boundary, and one dt for spheres that end at their own times.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from ...model.scenes import (
    COLLISION_STEPS_PER_HALF_PERIOD,
    FROZEN_STEPS_PER_HALF_PERIOD,
    HERTZ_STEPS_PER_HALF_PERIOD,
    STATE_ARGS,
    Collision,
    ContactModel,
    Frozen,
)
from ...model.timestep import mid_step_dt, steps_through
from ...pipeline import run_collision, run_frozen
from ..tolerance import collision_rung_dt, contact_steps, frozen_rung_dt
from .cases import ANY, EDGE, FROZEN, FROZEN_T_END, FROZEN_Z, MID, Case

__all__ = ["FULL_LADDER", "QUICK_LADDER", "ladder", "collision_dt", "frozen_dt", "default_resolution",
           "run_collision_level", "run_frozen_level", "run_case", "warm_up", "steps_of_dt"]

#: Steps per half-period of the fastest mode along the full ladder, and the quick one.
FULL_LADDER = tuple(2**k for k in range(5, 17))  # 32 .. 65536
QUICK_LADDER = (64, 128, 256, 512, 1024)
#: The scenes' own resolution of each kind of case: the ladder adds it as a level.
_DEFAULT_RESOLUTION = {"collision": COLLISION_STEPS_PER_HALF_PERIOD, "frozen": FROZEN_STEPS_PER_HALF_PERIOD,
                       "hertz": HERTZ_STEPS_PER_HALF_PERIOD}


def ladder(quick: bool = False) -> tuple[int, ...]:
    return QUICK_LADDER if quick else FULL_LADDER


def default_resolution(case: Case) -> int:
    return _DEFAULT_RESOLUTION["hertz" if case.model.normal == "hertz" else case.kind]


def _speed(states) -> float:
    return float(np.max(np.abs(np.asarray(states, dtype=float)[:, 0])))


def collision_dt(model: ContactModel, n: float, form: str, speed: float | None = None) -> float:
    """The collision step for ``n`` steps per half-period of the fastest mode, in ``form``.

    Hookean: the mid-step rung (for n = COLLISION_STEPS_PER_HALF_PERIOD the scenes' default
    dt) or its end on a step, tau/M. ``ANY``: pi/(n w) for a Hertzian wall, whose fastest
    mode w depends on the fastest |v_n|, ``speed`` (for n = HERTZ_STEPS_PER_HALF_PERIOD the
    scenes' default). A Hertzian mid-step dt is one speed's own: :func:`_hertz_mid_dt`.
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
    """The frozen rung (snapped to whole steps in t_end; the scenes' default for n =
    FROZEN_STEPS_PER_HALF_PERIOD)."""
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


def collision_scene(case: Case, dt: float, states=None) -> Collision:
    """The case's collision (or ``states``, in the case's columns) at step ``dt``."""
    s = np.asarray(case.states if states is None else states, dtype=float)
    r = case.model.r
    # spins are stored as r omega (STATE_3D); Collision takes the angular velocities
    columns = {name: s[:, k] / (r if name.startswith("omega") else 1.0) for k, name in enumerate(STATE_ARGS)
               if k < s.shape[1]}
    return Collision(case.model, dt=dt, **columns)


def run_collision_level(case: Case, dt: float, folder: Path, states=None, repeats: int = 1):
    """One batch at ``dt``: (row, final states). The row holds the largest error of each
    state column against the case's theory, the LAMMPS steps and the seconds."""
    scene = collision_scene(case, dt, states)
    result, wall = _timed(lambda: run_collision(scene, folder, atoms="library", record=False), repeats)
    t = result.table
    row = {"dt": scene.dt, "lammps_steps": scene.nsteps, "spheres": scene.n,
           "loop_seconds": result.info.loop_seconds, "lammps_seconds": result.info.wall_seconds,
           "wall_seconds": wall}
    for s in scene.state_names:
        row[f"error_{s}"] = float(np.max(np.abs(t[f"{s}_error"])))
    return row, t[[f"{s}_final" for s in scene.state_names]].to_numpy()


def _run_hertz_mid(case: Case, n: float, folder: Path, repeats: int) -> dict:
    """Each Hertzian speed alone at its own mid-step dt; the row takes the largest errors,
    the longest run's dt and steps, and the seconds of all the runs together."""
    states = np.asarray(case.states, dtype=float)
    speed = _speed(states)
    rows = []
    for k, v_n in enumerate(np.unique(states[:, 0])):
        dt = _hertz_mid_dt(case.model, n, float(v_n), speed)
        row, _ = run_collision_level(case, dt, folder / f"speed-{k}", states[states[:, 0] == v_n], repeats)
        rows.append(row)
    longest = max(rows, key=lambda r: r["lammps_steps"])
    out = {"dt": longest["dt"], "lammps_steps": longest["lammps_steps"]}
    for key in ("spheres", "loop_seconds", "lammps_seconds", "wall_seconds"):
        out[key] = sum(r[key] for r in rows)
    for key in (k for k in rows[0] if k.startswith("error_")):
        out[key] = max(r[key] for r in rows)
    return out


def run_frozen_level(case: Case, dt: float, folder: Path, repeats: int = 1) -> dict:
    ((_, v_t, r_omega),) = case.states
    scene = Frozen(case.model, z=FROZEN_Z, v_t=v_t, omega=r_omega / case.model.r, t_end=FROZEN_T_END, dt=dt)
    result, wall = _timed(lambda: run_frozen(scene, folder), repeats)
    t = result.table
    return {"dt": scene.dt, "lammps_steps": scene.nsteps, "spheres": 1,
            "loop_seconds": result.info.loop_seconds, "lammps_seconds": result.info.wall_seconds,
            "wall_seconds": wall, "error_vn": 0.0,  # held: v_n = 0 exactly
            "error_vt": float(np.max(np.abs(t["vt"] - t["vt_theory"]))),
            "error_r_omega": float(np.max(np.abs(t["r_omega"] - t["r_omega_theory"])))}


def run_level(case: Case, n: float, form: str, folder: Path, repeats: int = 1) -> dict:
    """One level of ``case`` in ``form`` at ``n`` steps per half-period: its row."""
    if form == FROZEN:
        return run_frozen_level(case, frozen_dt(case.model, n), folder, repeats)
    if case.model.normal == "hertz" and form == MID:
        return _run_hertz_mid(case, n, folder, repeats)
    dt = collision_dt(case.model, n, form, speed=_speed(case.states))
    row, _ = run_collision_level(case, dt, folder, repeats=repeats)
    return row


def warm_up(all_cases: list[Case], root: Path) -> None:
    """One short run of each scene kind, normal law and integrator, untimed: the first run in
    a process also pays for compiling its deck template and loading LAMMPS's styles."""
    seen = set()
    for case in all_cases:
        key = (case.kind, case.model.normal, case.model.alpha != ContactModel().alpha)
        if key not in seen:
            seen.add(key)
            run_level(case, 32, case.forms[0], root / "warm-up" / case.name)


def _levels(case: Case, steps: tuple[int, ...]) -> list[tuple[int, bool]]:
    """(n, at the scene's default resolution) for the ladder plus that resolution."""
    default = default_resolution(case)
    levels = {n: n == default for n in steps}
    levels[default] = True
    return sorted(levels.items())


def run_case(case: Case, steps: tuple[int, ...], root: Path, log, repeats: int = 1) -> list[dict]:
    """Every form and level of ``case``: one row per run."""
    rows = []
    for form in case.forms:
        for n, is_default in _levels(case, steps):
            folder = root / case.name / form.replace(" ", "-") / f"n{n:06d}"
            row = run_level(case, n, form, folder, repeats)
            row.update(case=case.name, label=case.label, kind=case.kind, form=form, steps_per_half_period=n,
                       default_dt=is_default, in_ladder=n in steps, theory=case.theory)
            row["error"] = max(row[f"error_{s}"] for s in case.state_names)
            rows.append(row)
    ends = [r for r in rows if r["in_ladder"] and r["steps_per_half_period"] in (steps[0], steps[-1])]
    log(f"  {case.name:<14}" + "  ".join(f"{r['form']} n={r['steps_per_half_period']}: {r['error']:.2e}"
                                         for r in ends))
    return rows
