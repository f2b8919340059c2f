"""States near a law's jump: where the first trial force of a damped displacement history on the
contact radius reaches the cap (:attr:`spinbounce.exact.wall_law.Law.first_touch_runaway`), the
outcome jumps and LAMMPS converges to it slowly; the wall and the pair scenes warn of them and probe
their step finer than their rules.
"""

from __future__ import annotations

import warnings

import numpy as np

from ..errors import PhysicsWarning
from ..exact.wall_law import Law

__all__ = ["NEAR_THE_JUMP", "BEYOND_REACH", "near_the_jump", "beyond_reach", "warn_near_the_jump"]

#: States up to this many times the jump get a probed step and a warning. At the fixed batch rule
#: LAMMPS erred above 1e-4 from 1.03 to 1.48 times it (tsuji, Hertz-Mindlin, mu = 0.5); a probed
#: single sphere met 1e-4 from 1.2 up, and 1.05 needed 3.2e8 steps.
NEAR_THE_JUMP = 2.0
#: Below this many times the jump no affordable step reaches the default accuracy: a probe leaves such
#: states out (they would hold every other state of a batch at the rule's step), and they are answered
#: at the step the others need, each row's error reported (a pair at 1.13 times it: 0.13 at 32 times the
#: rule's steps).
BEYOND_REACH = 1.2


def _ratio(model, initial: np.ndarray) -> np.ndarray | None:
    """Each state's first trial force over the cap, or None under a law without a jump."""
    law = Law.of(model)
    if not law.first_touch_runaway:
        return None
    slip = initial[:, 1] + initial[:, 2]
    if initial.shape[1] == 6:
        slip = np.hypot(slip, initial[:, 3] + initial[:, 4])
    return law.threshold_ratio(initial[:, 0], slip)


def near_the_jump(model, initial: np.ndarray) -> np.ndarray:
    """Per initial state (rows of (v_n, v_t, r omega[, v_s, r omega_s, r omega_n])), whether its
    first trial force is between 1 and NEAR_THE_JUMP times the cap, under a law that jumps there."""
    ratio = _ratio(model, initial)
    return np.zeros(len(initial), dtype=bool) if ratio is None else (ratio > 1.0) & (ratio < NEAR_THE_JUMP)


def beyond_reach(model, initial: np.ndarray) -> np.ndarray:
    """Per initial state, whether it lies between 1 and BEYOND_REACH times its law's jump, or grazes: its
    deepest overlap too small for double precision to resolve against r (checks.RESOLVABLE_OVERLAP_ULPS),
    so that its error is rounding's at any step and a finer one only stalls the slow sphere."""
    from ..checks import RESOLVABLE_OVERLAP_ULPS

    grazing = model.max_overlap(np.abs(initial[:, 0])) < RESOLVABLE_OVERLAP_ULPS * np.spacing(model.r)
    ratio = _ratio(model, initial)
    return grazing if ratio is None else grazing | ((ratio > 1.0) & (ratio < BEYOND_REACH))


def warn_near_the_jump(model, near: np.ndarray) -> None:
    """One PhysicsWarning naming how many states are near the jump, and what a run does with them."""
    rows = np.flatnonzero(near)
    if rows.size:
        warnings.warn(f"{rows.size} state(s) (the first: row {int(rows[0])}) put the first trial force, x_t |u'|, "
                      f"just above the cap mu |v_n| (below {NEAR_THE_JUMP:g} times it): with tangential = "
                      f"{model.tangential} and a tangential dashpot the friction then pushes along the slip from "
                      "first touch, the outcome jumps at 1 and LAMMPS converges to it slowly (docs: Hertz-Mindlin, "
                      "with a Coulomb cap): the step is probed and each row's error reported",
                      PhysicsWarning, stacklevel=4)
