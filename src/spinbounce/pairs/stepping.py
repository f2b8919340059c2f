"""The step a pair batch needs for the default accuracy, probed on its own pairs as the wall's.

A pair batch's default is the fine rule (:data:`.scene.PAIR_STEPS_PER_HALF_PERIOD`), set for
the hardest pairs. :func:`tune_pairs` measures instead, with the wall's rules
(:mod:`spinbounce.stepping`: :data:`SAFETY`, the order floor, the checks of a chosen step):
a few of the batch's own pairs run at :data:`START_STEPS` steps per contact and at twice
that, against the exact reference (:mod:`spinbounce.exact.pair_exact`); the observed order
and constant give the steps for SAFETY times the target. Every probed and chosen batch is aligned
(:attr:`.scene.PairBatch.time_scales`): each undamped pair runs at its own time scale so that
its contact ends in the middle of a step, where two first-order errors cancel
(:attr:`.scene.PairBatch.lead`), and pairs whose line of centres barely turns converge at
second order (a damped batch's pairs share a few time scales, :attr:`.scene.PairBatch.scale_classes`,
and end within about 1/64 of a step of mid-step). LAMMPS's projection on a turning line of
centres leaves a first-order error. The probe sees what is left. A batch whose
probe cannot reach the target below the fine rule's steps keeps the fine rule. Every
row's own error is measured afterwards anyway.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..model.timestep import ACCURACY, SAFETY, StepChoice, mid_step_dt, steps_per_contact
from ..stepping import CHECK_SLACK, PROBE_SPHERES, converge
from .scene import PairBatch

__all__ = ["tune_pairs", "START_STEPS", "FALLBACK"]

#: The probe's coarser run: steps per contact (the wall's rule takes 174 at its defaults).
START_STEPS = 100
#: The method recorded when the probe could not do better than the fine rule.
FALLBACK = "fine rule (probe could not reach the target coarser)"


def tune_pairs(batch: PairBatch, out: Path, measure: Callable[[PairBatch, Path], float],
               target: float = ACCURACY, probe_pairs: tuple | None = None) -> tuple[PairBatch, StepChoice]:
    """The batch at the step its accuracy needs, and how that step was chosen.

    ``probe_pairs``: the pairs to probe with (a sweep's group: the same for every chunk, so
    every chunk of a group gets the same step), by default every k-th of the batch's own, at
    most :data:`PROBE_SPHERES`. A batch with a given dt is returned as it is (``given``).
    ``measure(batch, folder)`` runs a batch at its given step and returns its largest error
    against the exact reference (the runner's, handed in: the runner calls this module).
    """
    if not batch.default_step:
        return batch, StepChoice(batch.dt, "given", target)
    source = tuple(probe_pairs or batch.pairs)
    pairs = source[:: max(1, math.ceil(len(source) / PROBE_SPHERES))]
    t_contact = float(np.median([o.contact_time for o in PairBatch(pairs, batch.contact).exact]))
    cap = steps_per_contact(t_contact, batch.dt)
    errors: list[float] = []

    def probe(steps: int) -> float:
        sample = PairBatch(pairs, batch.contact, mid_step_dt(t_contact, steps), aligned=True)
        errors.append(measure(sample, Path(out) / f"probe-{len(errors)}"))
        return errors[-1]

    coarse = (START_STEPS, probe(START_STEPS))
    steps, order, predicted = converge(coarse, (2 * START_STEPS, probe(2 * START_STEPS)), target, probe, limit=cap)
    if steps >= cap or predicted > target * SAFETY * CHECK_SLACK:
        fine = PairBatch(batch.pairs, batch.contact, batch.dt, aligned=True)
        return fine, StepChoice(fine.dt, FALLBACK, target, order, tuple(errors), None)
    tuned = PairBatch(batch.pairs, batch.contact, mid_step_dt(t_contact, steps), aligned=True)
    return tuned, StepChoice(tuned.dt, "probe", target, order, tuple(errors), predicted)
