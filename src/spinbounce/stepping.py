"""The step a scene needs for the default accuracy, measured where no rule can say: one probe
for every scene.

Without damping, cap or Hertz force the paper's contact converges at second order with a
known constant, and :mod:`spinbounce.model.timestep` sets its step a priori. Every other
wall model (damped: first order; a Coulomb cap: rough; a Hertzian wall at one speed; the
classic wall) and every pair batch is probed: a few of the scene's own rows run at a
coarse step and at half of it, against the exact reference that applies; the observed
order and constant give the step for :data:`SAFETY` times the target, kept mid-step. A
probe costs two or three short runs of at most :data:`PROBE_SPHERES` rows, and its result
goes into the run's record. Every row's own error is measured afterwards anyway (``error``
and ``status`` columns): the probe only chooses the step. Each scene tells the probe what
differs (:mod:`spinbounce.scenes`); a pair may fall back to its fine rule (:data:`FALLBACK`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np

from .errors import ResultError, SceneError
from .model.timestep import ACCURACY, SAFETY, StepChoice, mid_step_dt

__all__ = ["StepChoice", "tune", "reachable", "converge", "extrapolate", "expected_steps", "PROBE_SPHERES", "SAFETY",
           "FALLBACK", "FINEST_PROBED", "UNMEASURED"]

#: States a probe runs: the scene's own, every k-th of them beyond this many.
PROBE_SPHERES = 32
#: Errors below this are rounding: a probe that sees none keeps the rule's step.
ROUNDING = 1e-13
#: How often a probe whose run cannot see the contact's end is refined before giving up.
MAX_REFINEMENTS = 8
#: Checks of a chosen step on the probe (a rough convergence's extrapolation can miss), the
#: slack a check allows over SAFETY times the target, the slowest order assumed between two
#: points, and the largest refinement one extrapolation may ask for.
MAX_CHECKS = 4
CHECK_SLACK = 1.5
ORDER_FLOOR = 0.5
MAX_GROWTH = 64
#: An extrapolation past the scene's limit by at most this factor is checked with one run at the limit:
#: its floor on the order and SAFETY make it ask for more than the target needs (a pair that converges
#: as sqrt(dt) asked for 27M steps a contact against a limit of 25M, and 8M met 1e-4).
LIMIT_REACH = 4
#: The method recorded when a probe could not do better than the scene's fine rule.
FALLBACK = "the rule (the probe could not reach the target coarser, or within a run's steps)"
#: How much finer than the rule a probe's point must be to be kept instead of it (a point at a limit of the
#: rule's own steps differs from the rule only by its alignment mid-step).
FINER = 1.01
#: The method recorded when no probed row has a reference (LAMMPS has no dt -> 0 limit on any: status no_limit):
#: the probe's finer step is kept, its error unmeasured (NaN); rows that have one are checked, and probed again
#: where they err (:func:`spinbounce.pipeline.run_scene`).
UNMEASURED = "probe: no probed row has a reference (status no_limit), the finer probe's step kept, its error unmeasured"
#: The method recorded when the target was beyond the probe's reach and its best point finer than the rule.
FINEST_PROBED = "probe: its least error within a run's steps, finer than the rule (the target asked for more)"


def tune(scene, out: Path, run: Callable, probe_states=None, target: float = ACCURACY):
    """The scene at the step its accuracy needs (unchanged where the a priori rule holds),
    and how that step was chosen (:class:`StepChoice`).

    ``run(scene, folder)`` runs a probe scene and returns its rows' relative errors (inf
    where the run was too coarse to finish the contact; none where no row has a reference:
    :data:`UNMEASURED`); ``probe_states``: a scene of the
    same kind whose rows to probe with (a sweep's group: the same for every chunk, so every
    chunk of a group gets the same step), by default the scene's own.
    """
    if not scene.default_step or not scene.needs_probe():
        method = "given" if not scene.default_step else "second-order rule"
        return scene, StepChoice(scene.dt, method, target)
    source = probe_states or scene
    sample = source.rows(reachable(source)[:: max(1, math.ceil(source.n / PROBE_SPHERES))])
    t_contact = scene.probe_time(sample)
    coarse_steps = sample.first_probe_steps(t_contact)  # the probe states' rule: one per sweep group
    limit = scene.step_limit(t_contact)
    errors: list[float] = []
    points: list[tuple[int, float]] = []  # every probe's (steps, error), for a fallback
    unmeasured = False  # whether a probe had no row with a reference (``run`` gave no error)
    folders = itertools.count()

    def probe(steps: int) -> float:
        nonlocal unmeasured
        folder = Path(out) / f"probe-{next(folders)}"
        found = np.asarray(run(sample.at_step(mid_step_dt(t_contact, steps)), folder))
        unmeasured = unmeasured or not found.size
        errors.append(float(np.max(found)) if found.size else math.nan)
        points.append((steps, errors[-1]))
        return errors[-1]

    # a step too coarse to see the contact end (a slow exit: strong normal damping) counts as
    # an infinite error: refine until both probes finish
    for _ in range(MAX_REFINEMENTS):
        errors.clear()
        pair = [(coarse_steps, probe(coarse_steps)), (2 * coarse_steps, probe(2 * coarse_steps))]
        if unmeasured:  # nothing to measure an error against: no step is chosen from one
            tuned = scene.at_step(mid_step_dt(t_contact, 2 * coarse_steps))
            return tuned, StepChoice(tuned.dt, UNMEASURED, target, None, tuple(errors), None)
        if all(math.isfinite(e) for _, e in pair):
            break
        coarse_steps *= 2
    else:
        raise ResultError(f"no probe of this {scene.kind} scene finished its contact within {coarse_steps} steps "
                          "(a contact LAMMPS cannot resolve: give a dt of your own, each row's error reported)")
    try:
        steps, order, predicted = converge(*pair, target, probe, limit=limit)
        if steps > limit or predicted > target * SAFETY * CHECK_SLACK:  # the scene's fine rule, if it has one
            fine = scene.fallback()
            if fine is not None:
                return _fallback(scene, fine, t_contact, limit, points, StepChoice(fine.dt, FALLBACK, target, order,
                                                                                   tuple(errors), None))
        tuned = scene.at_step(mid_step_dt(t_contact, steps))
    except SceneError as exc:  # the step the target asks for is beyond what one run may take
        if exc.parameter != "dt":
            raise
        probes = ", ".join(f"{e:.2g}" for e in errors)
        raise SceneError("dt", "default", f"is probed for the accuracy {target:g}, and here (probe errors {probes}) "
                                          f"{exc.limit}: give dt to run at a step of your choice, each row's "
                                          "error reported") from None
    return tuned, StepChoice(tuned.dt, "probe", target, order, tuple(errors), predicted)


def _fallback(scene, fine, t_contact: float, limit: float, points: list[tuple[int, float]], choice: StepChoice):
    """The scene at its fine rule (``fine``, ``choice``), or at the probe's point of least error within ``limit``
    where that is finer than the rule: a probe cut short by the limit has measured better than the rule guesses."""
    within = [point for point in points if point[0] <= limit and math.isfinite(point[1])]
    if within:
        steps, error = min(within, key=lambda point: (point[1], -point[0]))
        if steps > FINER * t_contact / fine.dt:  # finer than the rule, not only by alignment mid-step
            best = scene.at_step(mid_step_dt(t_contact, steps))
            return best, replace(choice, dt=best.dt, method=FINEST_PROBED, predicted_error=error)
    return fine, choice


def reachable(scene) -> np.ndarray:
    """The rows a probe measures: all but those no affordable step brings to the target (a state just
    above its law's jump: :func:`spinbounce.scenes.jump.beyond_reach`), unless that is all of them."""
    reachable = np.flatnonzero(~scene.beyond_reach())
    return reachable if reachable.size else np.arange(scene.n)


def converge(coarse: tuple[int, float], fine: tuple[int, float], target: float, measure: Callable[[int], float],
             limit: float = math.inf) -> tuple[int, float | None, float]:
    """(steps, observed order, predicted error) for ``target`` from two probes (steps, error).

    Nothing to resolve (the finer probe at rounding): the coarse steps. Else the steps
    :func:`extrapolate` gives; a rough convergence (a cap's switches, a contact-radius spring)
    can miss, so ``measure(steps)`` checks the chosen step on the probe itself, going on from
    the last two points while it misses, at most MAX_CHECKS times and up to ``limit`` steps (a
    step asked for past it by at most LIMIT_REACH is measured at the limit); a step coarser than
    the finer probe that misses gives way to the finer probe's.
    """
    if fine[1] <= ROUNDING:
        return coarse[0], None, fine[1]
    steps, order = extrapolate(coarse, fine, target)
    predicted = fine[1] * (fine[0] / steps) ** order
    last, bound = fine, target * SAFETY * CHECK_SLACK
    for _ in range(MAX_CHECKS):
        if steps >= limit and steps <= LIMIT_REACH * limit and last[0] < limit:
            steps = int(limit)  # a close call: the limit itself is measured
        if steps == last[0] or steps > limit:
            break
        measured = measure(steps)
        if measured <= bound:
            return steps, order, measured
        if not math.isfinite(measured):  # that probe did not finish its contact: no trend to follow
            break
        if steps < last[0]:  # coarser than a point that met SAFETY * target (a rough convergence): that point
            return last[0], order, last[1]
        previous, last = last, (steps, measured)
        steps, order = extrapolate(previous, last, target)
        predicted = measured * (last[0] / steps) ** order
    return steps, order, predicted


def extrapolate(coarser: tuple[int, float], finer: tuple[int, float], target: float) -> tuple[int, float]:
    """Steps for SAFETY * target from two (steps, error) points: the observed order, held to
    [ORDER_FLOOR, 2], and at most MAX_GROWTH times the finer point's steps at once."""
    (n0, e0), (n1, e1) = coarser, finer
    order = min(2.0, max(ORDER_FLOOR, math.log(e0 / e1) / math.log(n1 / n0))) if e0 > e1 else ORDER_FLOOR
    steps = n1 * (e1 / (SAFETY * target)) ** (1.0 / order)
    return max(n1 // 2, min(MAX_GROWTH * n1, math.ceil(steps))), order


#: A priori bounds on what a probe chooses, for costs known before anything runs (cluster
#: jobs are sized before their probes): a damped contact's error is first order, about
#: DAMPED c T dt over a contact of length T with damping rate c (measured 0.13 to 0.29 in
#: studies/accuracy's default-step table); a cap with tangential but no normal damping also
#: errs at first touch, about CAPPED_FIRST_TOUCH mu (gamma_t/m) T dt (measured 2.8 at mu =
#: 10); Coulomb and Hertzian contacts refine the rule's step by about ROUGH (measured 1.0
#: to 1.3 for mu from 0.3 to 3, 1.6 for a Hertzian speed of its own, 1.0 for a time-scaled
#: batch of Hertzian speeds, with linear_history or mindlin).
DAMPED = 0.4
CAPPED_FIRST_TOUCH = 4.0
ROUGH = 1.5


def expected_steps(scene, target: float = ACCURACY) -> int:
    """About how many steps a wall collision ``scene`` takes once probed (an upper estimate)."""
    if not scene.default_step or not scene.needs_probe():
        return scene.nsteps
    m = scene.model
    t_contact = scene.probe_time(scene)
    rate = max(m.gamma_n / m.m, 2.0 * m.zeta)
    if m.mu is not None and m.gamma_n == 0.0:
        rate = max(rate, CAPPED_FIRST_TOUCH / DAMPED * m.mu * m.gamma_t / m.m)
    first_order = math.ceil(DAMPED * rate * t_contact**2 / (SAFETY * target))
    return max(math.ceil(ROUGH * scene.nsteps), first_order + scene.nsteps)
