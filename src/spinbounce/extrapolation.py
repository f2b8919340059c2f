"""Ask for an accuracy, not a timestep: Richardson extrapolation over a ladder of LAMMPS runs.

A collision run at dt = tau/(N + 1/2) (the contact's end mid-step) has an error that is a
smooth function of dt with no first-order term: e(dt) = c2 dt^2 + c4 dt^4 + ... (velocity
Verlet is symmetric). Two such runs at dt1 > dt2 combine into

    R = (r^2 x(dt2) - x(dt1)) / (r^2 - 1),   r = dt1/dt2,

whose error is fourth order. With damping LAMMPS's step is first order (its damping force
sees the half-step velocity), e = c1 dt + c2 dt^2 + ..., and R uses r^1 instead, leaving
second order. The frozen contact has no contact end; its error has the same expansions.

The ladder doubles the steps per half-period from a coarse start until two successive
extrapolations agree: their difference, divided by what the known order of the
extrapolation predicts (2^q - 1) and multiplied by a margin of 4, is the reported error
estimate. The estimate is trusted only once the differences shrink from one level to the
next. Measured at the paper's defaults with a tolerance of 1e-6: runs at 20, 40 and 80
steps per half-period, 146 LAMMPS steps in all, give an estimate of 7.9e-7 and a true
error of 2.0e-7, where one plain run needs ~3,000 steps for the same error.

The ladder starts at :data:`START_STEPS`, not at the default step (174 steps per contact at the
paper's defaults, chosen for one plain run to reach ACCURACY): it only needs its rungs in the
asymptotic regime. A damped wall collision's default is this ladder (:func:`default_tolerance`).

Where the error has no smooth expansion in dt (:func:`smooth_in_dt`), extrapolation gains
nothing: the tolerance is met by measurement instead (:func:`measured_to_tolerance`), the
step probed against the exact theory of what LAMMPS integrates (:func:`spinbounce.stepping.tune`
with the tolerance as its target, as the default step is for the default accuracy).

The convergence study (:mod:`spinbounce.studies.accuracy`) climbs the same rungs
(:func:`contact_steps`, :func:`collision_rung_dt`, :func:`frozen_rung_dt`) and measures the
raw orders that :func:`raw_orders` assumes here.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import checks
from .scenes.collision import Collision, STATE_ARGS
from .model.contact import ContactModel
from .scenes.frozen import Frozen
from .errors import SceneError
from .model.timestep import ACCURACY, mid_step_dt, refine_mid_step

__all__ = ["Extrapolated", "collide_to_tolerance", "frozen_to_tolerance", "collision_frame", "check_tolerance",
           "contact_steps", "collision_rung_dt", "frozen_rung_dt", "raw_orders", "MIN_TOLERANCE",
           "MIN_MEASURED_TOLERANCE", "smooth_in_dt", "measured_to_tolerance", "default_tolerance",
           "extrapolate_collision"]

#: Below this, double-precision rounding in LAMMPS's O(1) velocities (amplified ~2x by
#: the extrapolation) is as large as the request: no ladder can certify it.
MIN_TOLERANCE = 1e-12
#: Steps per half-period of the fastest mode at the ladder's first rung: the ladder's own,
#: not the default step's. At w dt = pi/20 the next term of the error's expansion is a few
#: percent of the leading one (the accuracy study's local orders from n = 32 on are within
#: 0.01 of 2 undamped, within 0.11 of 1 damped), which is all Richardson extrapolation needs;
#: it is also the coarsest step that ContactModel.check_dt accepts without a warning.
START_STEPS = 20
#: Safety factor on the asymptotic error estimate of an extrapolation.
MARGIN = 4.0
MAX_LEVELS = 9


@dataclass
class Extrapolated:
    """A result obtained to a requested tolerance.

    ``values``: the extrapolated outputs (collision: (n, 3) final (v_n, v_t, r omega);
    frozen: (T, 2) v_t and r omega at the common output times ``t``); ``estimate``: the
    error estimate of each value (the largest over its row: one per sphere, or per output
    time); ``levels``: what each LAMMPS run was and cost.
    """

    values: np.ndarray
    estimate: np.ndarray
    tolerance: float
    order: int  # the order of the raw runs (2 undamped, 1 damped; 0: measured against the exact theory)
    levels: list[dict] = field(default_factory=list)
    t: np.ndarray | None = None
    finest: object = None  # a collision ladder's finest run (pipeline.RunResult: its raw LAMMPS rows)

    @property
    def max_estimate(self) -> float:
        return float(np.max(self.estimate))

    def relative_estimate(self, initial) -> float:
        """The largest row estimate over its initial state's size (the default step's measure)."""
        return float(np.max(self.estimate.max(axis=-1) / np.linalg.norm(initial, axis=-1)))

    @property
    def how(self) -> str:
        """How the values and their estimates were obtained."""
        return "measured against the exact theory" if self.order == 0 else "extrapolated to dt = 0"

    @property
    def steps(self) -> int:
        return int(sum(level["nsteps"] for level in self.levels))

    def plain_steps_for(self, error: float) -> float:
        """LAMMPS steps one plain run would need for ``error``, from the measured error of
        the finest raw run (its distance from the extrapolation) and the raw order; a measured
        result is itself one plain run."""
        finest = self.levels[-1]
        if self.order == 0:
            return float(finest["nsteps"])
        return finest["nsteps"] * (finest["error_vs_extrapolation"] / error) ** (1.0 / self.order)


def check_tolerance(tolerance: float) -> float:
    try:
        tol = float(tolerance)
    except (TypeError, ValueError):
        raise SceneError("tolerance", tolerance, "must be a number") from None
    if not math.isfinite(tol) or tol < MIN_TOLERANCE:
        raise SceneError("tolerance", tolerance,
                         f"must be >= {MIN_TOLERANCE:g}: below it double-precision rounding is as large as the request")
    if tol >= 1.0:
        raise SceneError("tolerance", tolerance, "must be below 1: the velocities themselves are of order 1")
    return tol


def contact_steps(model: ContactModel, per_half_period: float) -> int:
    """Whole steps in a Hookean contact time that resolve its fastest mode with
    ``per_half_period`` steps per half-period: the N of tau/(N + 1/2)."""
    return math.ceil(per_half_period * model.fastest_rate(frozen=False) * model.tau / math.pi - 1e-9)


def collision_rung_dt(model: ContactModel, per_half_period: float) -> float:
    """The mid-step collision dt at ``per_half_period`` steps per half-period."""
    return mid_step_dt(model.tau, contact_steps(model, per_half_period))


def frozen_rung_dt(model: ContactModel, per_half_period: float, t_end: float,
                   overlap: float | None = None) -> float:
    """The frozen step at ``per_half_period`` steps per half-period, snapped to a whole number
    of steps in ``t_end``, held at ``overlap`` (a Mindlin spring needs it). With kt = gamma_t = 0
    nothing evolves: 100 steps."""
    rate = model.fastest_rate(frozen=True, overlap=overlap)
    dt = math.pi / rate / per_half_period if rate > 0.0 else t_end / 100
    return t_end / math.ceil(t_end / dt - 1e-9)


def raw_orders(model: ContactModel, columns: int = 3, frozen: bool = False) -> np.ndarray:
    """The order in dt of a plain mid-step run's error, per output column.

    Collision (v_n, then the tangential columns): v_n is first order only with normal
    damping; the tangential columns with either dashpot, whose force LAMMPS evaluates with
    the half-step velocity. Frozen (v_t, r omega): first order with gamma_t, else second.
    """
    damped = model.gamma_t > 0.0 or model.gamma_n > 0.0
    if frozen:
        return np.full(columns, 1 if model.gamma_t > 0.0 else 2)
    return np.array([1 if model.gamma_n > 0.0 else 2] + [1 if damped else 2] * (columns - 1))


def _eliminate(values: list[np.ndarray], dts: list[float], power: int, depth: int) -> list[np.ndarray]:
    """Neville's scheme: extrapolate the runs to dt = 0 with a polynomial in dt^power.

    Column j of the table has removed the error terms of orders power, 2 power, ...,
    j power; returns column ``depth``, one entry per level from ``depth`` on (the last
    the most accurate).
    """
    column = dict(enumerate(values))
    for j in range(1, depth + 1):
        column = {i: column[i] + (column[i] - column[i - 1]) / ((dts[i - j] / dts[i]) ** power - 1.0)
                  for i in range(j, len(values))}
    return [column[i] for i in range(depth, len(values))]


#: Raw order -> (expansion in dt^power, terms removed, order left).
_SCHEMES = {2: (2, 1, 4), 1: (1, 2, 3)}


def _extrapolate(values: list[np.ndarray], dts: list[float], p: np.ndarray):
    """The best extrapolation of the runs so far and each value's raw estimate (the gap of
    the last two extrapolations over what the order left predicts, times MARGIN); None
    while some column has too few levels for its scheme."""
    best = np.empty_like(values[-1])
    per_value = np.empty_like(values[-1])
    for raw_order, (power, depth, left) in _SCHEMES.items():
        columns = p == raw_order
        if not columns.any():
            continue
        tops = _eliminate([v[..., columns] for v in values], dts, power, depth)
        if len(tops) < 2:
            return None
        best[..., columns] = tops[-1]
        per_value[..., columns] = MARGIN * np.abs(tops[-1] - tops[-2]) / (2.0**left - 1.0)
    return best, per_value


def _ladder(run_level, tolerance: float, p: np.ndarray, log, scale=1.0) -> tuple[np.ndarray, np.ndarray, list[dict]]:
    """Run levels k = 0, 1, ... until the extrapolations agree to ``tolerance`` (each row's estimate
    over its ``scale``: 1, or the size of its initial state).

    ``p``: the order of the raw error of each output column (broadcast over rows): 2 for
    an even expansion (remove dt^2: what is left is fourth order), 1 for a damped run
    (remove dt and dt^2: third order). The reported estimate of a row is the largest over
    its columns."""
    p = np.asarray(p)
    values, levels, gaps = [], [], []
    eps = np.finfo(float).eps
    for k in range(MAX_LEVELS):
        value, info = run_level(k)  # the outputs, and what the run was (its dt among them)
        values.append(value)
        levels.append(info)
        extrapolated = _extrapolate(values, [level["dt"] for level in levels], p)
        if extrapolated is None:
            continue
        best, per_value = extrapolated
        # rounding: each of the finest run's steps may add an ulp of the velocities
        floor = MARGIN * info["nsteps"] * eps * max(1.0, float(np.abs(value).max()))
        estimate = np.maximum(np.broadcast_to(per_value.max(axis=-1, keepdims=True), per_value.shape), floor)
        gaps.append(float(np.max(estimate.max(axis=-1) / scale)))
        shrinking = len(gaps) < 2 or gaps[-1] < gaps[-2]
        log(f"  level {k}: {info['nsteps']} steps, estimated error {gaps[-1]:.2e}"
            + ("" if shrinking else " (not yet converging)"))
        if shrinking and gaps[-1] <= tolerance:
            for level, raw in zip(levels, values, strict=True):
                level["error_vs_extrapolation"] = float(np.abs(raw - best).max())
            return best, estimate, levels
    from .pipeline import ResultError

    raise ResultError(
        f"tolerance = {tolerance:g} not reached in {MAX_LEVELS} levels "
        f"(finest: {levels[-1]['nsteps']} steps, last estimate {gaps[-1]:.2g}): ask for a looser tolerance"
    )


def smooth_in_dt(model: ContactModel) -> bool:
    """Whether a collision's error has a smooth expansion in dt, so that extrapolation works: not
    with a finite cap (its stick-slip switches leave kinks anywhere inside a step), nor for the
    classic wall (measured: at tolerance 1e-6 the ladder's estimate was 1.0e-6 where the error was
    2.1e-6; its spring kt sqrt(r delta) has an infinite slope at contact), nor for a Mindlin spring
    k_t sqrt(r delta), or a dashpot on the contact radius, for the same reason."""
    return (model.mu is None and model.style.smooth_in_dt and not model.tangential_law.contact_radius
            and not model.normal_law.integrated(model))


def default_tolerance(model: ContactModel) -> float | None:
    """The accuracy a damped wall collision's default step is extrapolated to (ACCURACY), or None where
    the default is one run at the step the rule or a probe chooses.

    A dashpot makes LAMMPS's step first order (its force sees the half-step velocity): one run that
    reaches ACCURACY takes ~18 times the undamped steps (3,247 against 174 at gamma_t = 1); the ladder's
    first four runs, 20 to 160 steps per half-period (~300 steps in all), extrapolate to dt = 0 with an
    estimate far below ACCURACY. Only where the error is smooth in dt (:func:`smooth_in_dt`)."""
    return ACCURACY if (model.gamma_n > 0.0 or model.gamma_t > 0.0) and smooth_in_dt(model) else None


#: The exact theories the measured route checks against (exact.coulomb, exact.classic) are solved
#: to ~1e-9 of the speed: a tolerance below ten times that cannot be told apart.
MIN_MEASURED_TOLERANCE = 1e-8


def collide_to_tolerance(model: ContactModel, v_n, v_t, omega, tolerance: float, out_dir: Path,
                         log=lambda *_: None, relative: bool = False, **out_of_plane) -> tuple[Extrapolated, Collision]:
    """Collisions (one sphere or many, as in :class:`Collision`) to a requested accuracy (``relative``:
    of each row's initial state's size, as the default accuracy; else absolute).

    ``out_of_plane``: Collision's 3-D arguments (v_s, omega_s, omega_n), if any. Each
    level's run lives in ``out_dir/level-K``. Returns the extrapolated final states with
    their estimates, and the finest level's scene (for its initial states and theory)."""
    from .pipeline import run_scene

    tol = check_tolerance(tolerance)
    # a force on the contact radius: each sphere's contact ends somewhere inside a step that moves with dt
    if not smooth_in_dt(model) or model.normal_law.contact_radius:
        return measured_to_tolerance(model, v_n, v_t, omega, tol, out_dir, log, **out_of_plane)
    unknown = set(out_of_plane) - set(STATE_ARGS[3:])
    if unknown:
        raise TypeError(f"collide_to_tolerance: unknown argument(s) {', '.join(sorted(unknown))}")
    out_dir = Path(out_dir)
    scenes: list[Collision] = []
    runs: list = []

    def scene_at(k: int) -> Collision:
        dt = collision_rung_dt(model, START_STEPS * 2**k)
        return Collision(model, v_n=v_n, v_t=v_t, omega=omega, dt=dt, **out_of_plane)

    for first in range(5):  # near the tunnelling speed a coarse step's overshoot alone tunnels: start finer
        try:
            names = scene_at(first).state_names
            break
        except SceneError as exc:
            if not exc.parameter.startswith("v_n") or "at dt" not in exc.limit or first >= 4:
                raise

    def run_level(k: int):
        scene = scene_at(first + k)
        result = run_scene(scene, out_dir / f"level-{k}", atoms="library")
        scenes.append(scene)
        runs.append(result)
        final = result.table[[f"{s}_lammps" for s in names]].to_numpy()
        return final, {"level": k, "dt": scene.dt, "nsteps": scene.nsteps,
                       "run": str(out_dir / f"level-{k}"), "deck": str(result.info.deck),
                       "loop_seconds": result.info.loop_seconds, "lammps_seconds": result.info.wall_seconds}

    p = raw_orders(model, len(names))
    scale = np.linalg.norm(scene_at(first).initial, axis=1) if relative else 1.0
    values, estimate, levels = _ladder(run_level, tol, p, log, scale)
    return Extrapolated(values, estimate, tol, int(p.min()), levels, finest=runs[-1]), scenes[-1]


def extrapolate_collision(scene: Collision, tolerance: float, out_dir: Path, log=lambda *_: None,
                          relative: bool = False) -> tuple[Extrapolated, Collision]:
    """:func:`collide_to_tolerance` of a scene's spheres (its model and initial states, not its step)."""
    out_of_plane = {name: getattr(scene, name) for name in STATE_ARGS[3:]} if scene.is_3d else {}
    return collide_to_tolerance(scene.model, scene.v_n, scene.v_t, scene.omega, tolerance, out_dir, log, relative,
                                **out_of_plane)


def measured_to_tolerance(model: ContactModel, v_n, v_t, omega, tolerance: float, out_dir: Path,
                          log=lambda *_: None, **out_of_plane) -> tuple[Extrapolated, Collision]:
    """Collisions to ``tolerance`` where extrapolation cannot serve: one run at the step a probe
    against the exact theory chooses for the tolerance; each row's estimate is its measured
    |LAMMPS - theory| (the largest over its columns), and every row must be within it."""
    from .pipeline import ResultError, run_scene

    if tolerance < MIN_MEASURED_TOLERANCE:
        raise SceneError("tolerance", tolerance, f"must be >= {MIN_MEASURED_TOLERANCE:g} for this model: its error is "
                                                 "measured against an exact theory solved to ~1e-9")
    scene = Collision(model, v_n=v_n, v_t=v_t, omega=omega, **out_of_plane)
    folder, levels = Path(out_dir) / "measured", []
    for refinement in range(MAX_LEVELS):
        result = run_scene(scene, folder / f"run-{refinement}", atoms="library", target=tolerance)
        final = result.table[[f"{s}_lammps" for s in result.scene.state_names]].to_numpy()
        distance = np.abs(final - result.scene.predicted()).max(axis=1, keepdims=True)
        log(f"  run at {result.scene.nsteps} steps: largest |LAMMPS - theory| {distance.max():.2e}")
        levels.append({"level": refinement, "dt": result.scene.dt, "nsteps": result.scene.nsteps,
                       "run": str(folder / f"run-{refinement}"), "loop_seconds": result.info.loop_seconds,
                       "error_vs_theory": float(distance.max())})
        if distance.max() <= tolerance:
            break
        # the probe's states missed a harder row: twice the steps, the contact's end kept mid-step
        t_end = float(np.max(model.contact_times(scene.v_n)))
        scene = dataclasses.replace(scene, dt=refine_mid_step(t_end, result.scene.dt, 2))
    else:
        raise ResultError(f"tolerance = {tolerance:g} not reached: |LAMMPS - theory| = {distance.max():.2g} at "
                          f"dt = {result.scene.dt:.4g}; give a smaller dt or a looser tolerance")
    estimate = np.broadcast_to(distance, final.shape).copy()
    return Extrapolated(final, estimate, tolerance, 0, levels, finest=result), result.scene


def frozen_to_tolerance(model: ContactModel, z: float, v_t: float, omega: float, t_end: float,
                        tolerance: float, out_dir: Path, samples: int = 500,
                        log=lambda *_: None) -> Extrapolated:
    """A frozen contact's v_t(t), r omega(t) to a requested accuracy, at common output times.

    Level k halves dt and doubles the dump interval, so every level samples the same times
    exactly (dt is divided by a power of two).
    """
    from .pipeline import run_series

    tol = check_tolerance(tolerance)
    out_dir = Path(out_dir)
    dt0 = frozen_rung_dt(model, START_STEPS, t_end, model.r - z)
    every0 = max(1, round(t_end / dt0) // samples)
    p = raw_orders(model, 2, frozen=True)
    times: list[np.ndarray] = []

    def run_level(k: int):
        scene = Frozen(model, z=z, v_t=v_t, omega=omega, t_end=t_end, dt=dt0 / 2**k, every=every0 * 2**k)
        result = run_series(scene, out_dir / f"level-{k}")
        table = result.table
        if times and not np.array_equal(table["t"].to_numpy(), times[0]):
            raise RuntimeError("frozen levels do not share their output times")
        times.append(table["t"].to_numpy())
        return (table[["v_t", "r_omega"]].to_numpy(),
                {"level": k, "dt": scene.dt, "nsteps": scene.nsteps, "run": str(out_dir / f"level-{k}"),
                 "loop_seconds": result.info.loop_seconds})

    values, estimate, levels = _ladder(run_level, tol, p, log)
    return Extrapolated(values, estimate, tol, int(p.min()), levels, t=times[0])


def collision_frame(result: Extrapolated, scene: Collision, target: float = ACCURACY):
    """The extrapolated final states beside the theory, one row per sphere, checked as a run's rows are
    (:func:`spinbounce.checks.add_row_checks` against ``target``: error, energy, status): a DataFrame."""
    import pandas as pd

    theory = scene.predicted()
    out = {f"{s}_initial": scene.initial[:, k] for k, s in enumerate(scene.state_names)}
    for k, s in enumerate(scene.state_names):
        out[f"{s}_lammps"] = result.values[:, k]
        out[f"{s}_estimate"] = result.estimate[:, k]
        out[f"{s}_theory"] = theory[:, k]
        out[f"{s}_error"] = result.values[:, k] - theory[:, k]
    checks.add_row_checks(out, scene.row_states(out), target)
    return pd.DataFrame(out)
