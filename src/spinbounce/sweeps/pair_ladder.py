"""A pair sweep's default: two aligned runs of each chunk combined, instead of one run at a fine step.

LAMMPS's pair step is first order in dt where the line of centres turns, so one run needs ~1,400
steps per contact to reach 1e-4 at the default radii. In an aligned batch
(:attr:`spinbounce.scenes.pair.PairBatch.time_scales`: every contact ends mid-step) the error of
each pair's final state is smooth in its step, e(h) = c1 h + c2 h^2 + ..., so a run at N steps
per contact and one at 2N combine (Richardson, first order) into

    R = (r x(h2) - x(h1)) / (r - 1),   r = h1 / h2 (each pair's own step in its time: dt over its scale),

whose error is second order. Measured on 2,000 pairs of the paper's ranges (kt/kn = 0.1, default
radii): at N = 40 (55 + 108 steps) the largest error is 5.3e-5 of the pair's speed (median
1.9e-5), falling as 1/N^2 (1.4e-5 at N = 80); one plain run reaches 5.7e-5 at 1,381 steps.

A Coulomb cap keeps the expansion: LAMMPS's capped force is continuous in the state at a switch
between stick and slide (only its slope jumps), so a switch inside a step errs at second order and
the combination stays second order. Measured on 2,000 pairs (seed 4, kt/kn = 0.1, default radii),
the combination's largest error at N = 20, 40, 80, 160, 320: mu = 0.3: 4.7e-4, 1.2e-4, 2.8e-5,
6.8e-6, 1.9e-6; mu = 1: 1.7e-3, 4.2e-4, 1.0e-4, 2.5e-5, 6.1e-6; mu = 5: 5.4e-3, 1.8e-3, 5.2e-4,
1.3e-4, 3.2e-5 (a larger cap leaves the slide to the contact's last instants, where the normal force
vanishes: a larger constant, the same order), while the finer run alone is first order (2.1e-4 to
2.8e-4 at 640 steps). A capped sweep's probe takes N = 40 to 320 (163 to 1,214 LAMMPS steps a pair
for both runs, mu = 0.02 to 5), where one plain run needed 2,882 to 8,401.

It is taken where that was measured: Hooke's law without dashpots, with or without a cap (the damped
batches' time-scale classes leave no smooth expansion: measured 1.5e-3 and 5.4e-4 at N = 40 and 80
with gamma_n = gamma_t = 0.5), and free spheres (alpha = 2/5: rigid bodies are integrated by fix rigid,
where even one plain run misses 1e-4 on some pairs). Other laws keep the plain probe
(:func:`spinbounce.stepping.tune`).

N is probed: a sample of the group's states runs at N and 2N from :data:`START`, doubling until
the sample's largest error of R against the exact reference is below the target over
:data:`MARGIN`. Every row's error is measured against its exact reference afterwards, as for any
run: ``error`` and ``status`` say how far each combined row is from the truth.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from .. import checks
from ..lammps.decks import ALPHA_NVE_SPHERE
from ..errors import ContactHeld, SceneError
from ..model.timestep import ACCURACY, StepChoice
from ..pipeline import RunResult, run_scene
from ..scenes.pair.scene import PairBatch
from ..scenes.pair.table import QUANTITIES

__all__ = ["applies", "ladder_steps", "run_ladder", "Ladder", "START", "LONGEST", "MARGIN"]

#: The coarse run's steps per contact at the probe's start; the most it doubles to.
START, LONGEST = 40, 640
#: The probe's sample must reach the target over this: its rows are a sample of the chunk's.
MARGIN = 2.0
#: The probe's sample: every k-th of the group's states beyond this many.
SAMPLE = 256
#: A pair whose two runs' steps differ by less than this ratio is not combined (the finer run's state).
MIN_RATIO = 1.5


def applies(batch: PairBatch) -> bool:
    """Whether the batch's law and spheres are those the ladder was measured on (the module's text): a cap
    or none."""
    c, columns = batch.contact, batch.columns
    undamped = c.gamma_n == 0.0 and c.gamma_t == 0.0
    free = bool(np.all(columns["alpha_a"] == ALPHA_NVE_SPHERE) and np.all(columns["alpha_b"] == ALPHA_NVE_SPHERE))
    return c.batched and undamped and free


@dataclass(frozen=True)
class Ladder:
    """The combined run as any run's result (``result``: the finer run's scene, deck and dump, the
    combination's checked columns, both runs' LAMMPS seconds, how its steps were chosen), and its two
    runs (``coarse``, ``fine``)."""

    result: RunResult
    coarse: RunResult
    fine: RunResult

    @property
    def columns(self) -> dict:
        return self.result.columns

    @property
    def nsteps(self) -> int:
        """LAMMPS steps of both runs."""
        return self.coarse.scene.nsteps + self.fine.scene.nsteps


def _contact_time(batch: PairBatch) -> float:
    return float(np.median(batch.contact_times))


def run_ladder(batch: PairBatch, steps: int, folder: Path, target: float = ACCURACY,
               contact_time: float | None = None) -> Ladder:
    """``batch`` at ``steps`` and twice as many steps per ``contact_time`` (by default its pairs' median),
    aligned, combined and checked. A :class:`SceneError` if a rung's step is refused (too coarse)."""
    tau = _contact_time(batch) if contact_time is None else contact_time
    coarse, fine = (run_scene(PairBatch(batch.pairs, batch.contact, tau / n, aligned=True), Path(folder) / f"n{n}",
                              atoms="library", record=False) for n in (steps, 2 * steps))
    # each pair's step in its own time is dt over its time scale: r is their ratio, pair by pair. A contact
    # shorter than a step or two has r far from 2 (1 when both runs give it the same count): no expansion
    # to combine, so its row keeps the finer run's state, and its error says how far that is
    r = (coarse.scene.dt / coarse.scene.time_scales) / (fine.scene.dt / fine.scene.time_scales)
    usable = r > MIN_RATIO
    combined = {q: np.where(usable, (r * fine.columns[q] - coarse.columns[q]) / np.where(usable, r - 1.0, 1.0),
                            fine.columns[q]) for q in QUANTITIES}
    columns = {**fine.columns, **combined}  # the references are the finer run's; the checks are redone
    deviation = checks.add_row_checks(columns, fine.scene.row_states(columns), target)
    step = StepChoice(fine.scene.dt, f"extrapolated (2 runs, {steps} and {2 * steps} steps per contact; "
                                     "spinbounce.sweeps.pair_ladder)", target)
    info = replace(fine.info, loop_seconds=coarse.info.loop_seconds + fine.info.loop_seconds)
    result = RunResult(fine.scene, columns, info, fine.deck, fine.dump, tuple(checks.notes(columns["status"], target)),
                       step, deviation)
    return Ladder(result, coarse, fine)


def ladder_steps(sample: PairBatch, folder: Path, target: float = ACCURACY) -> tuple[int, float] | None:
    """(the coarse run's steps per contact, the contact time they divide: the median of ``sample``, the
    group's states) that bring every k-th row of the sample (at most :data:`SAMPLE`) below ``target`` /
    :data:`MARGIN`; None if none up to :data:`LONGEST` does. Every chunk of the group then runs at the same
    two steps, as one probed step serves a group."""
    tau = _contact_time(sample)
    rows = sample.rows(np.arange(0, sample.n, max(1, math.ceil(sample.n / SAMPLE))))
    steps = START
    while steps <= LONGEST:
        try:
            found = run_ladder(rows, steps, Path(folder) / f"probe-{steps}", target, tau)
        except ContactHeld:  # a state no step ends: refused as it is
            raise
        except SceneError:  # a rung too coarse for the stiffest mode (a large kt): finer
            found = None
        if found is not None and float(np.max(found.columns["error"])) <= target / MARGIN:
            return steps, tau
        steps *= 2
    return None
