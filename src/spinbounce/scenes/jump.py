"""States LAMMPS converges to slowly from its first step: where the first trial force of a damped
displacement history on the contact radius exceeds the cap (:attr:`spinbounce.exact.wall_law.Law.first_touch_on_cap`).
Near a law's jump (dashpots slower than the spring: :attr:`~spinbounce.exact.wall_law.Law.first_touch_runaway`) the
outcome jumps and some states no affordable step reaches; with dashpots that grow as the spring every state
above the cap converges as sqrt(dt). The wall and the pair scenes warn of them and probe their step finer than
their rules.
"""

from __future__ import annotations

import warnings

import numpy as np

from ..errors import PhysicsWarning
from ..exact.wall_law import Law

__all__ = ["NEAR_THE_JUMP", "BEYOND_REACH", "near_the_jump", "slow_start", "beyond_reach", "warn_slow_start"]

#: States up to this many times the jump get a probed step and a warning. At the fixed batch rule
#: LAMMPS erred above 1e-4 from 1.03 to 1.48 times it (tsuji, Hertz-Mindlin, mu = 0.5); a probed
#: single sphere met 1e-4 from 1.2 up, and 1.05 needed 3.2e8 steps.
NEAR_THE_JUMP = 2.0
#: Below this many times the jump no affordable step reaches the default accuracy: a probe leaves such
#: states out (they would hold every other state of a batch at the rule's step), and they are answered
#: at the step the others need, each row's error reported (a pair at 1.13 times it: 0.13 at 32 times the
#: rule's steps).
BEYOND_REACH = 1.2


def _ratio(initial: np.ndarray, law: Law) -> np.ndarray | None:
    """Each state's first trial force over the cap, or None under a law that never starts on its cap
    (:attr:`.wall_law.Law.first_touch_on_cap`)."""
    if not law.first_touch_on_cap:
        return None
    slip = initial[:, 1] + initial[:, 2]
    if initial.shape[1] == 6:
        slip = np.hypot(slip, initial[:, 3] + initial[:, 4])
    return law.threshold_ratio(initial[:, 0], slip)


def near_the_jump(model, initial: np.ndarray) -> np.ndarray:
    """Per initial state (rows of (v_n, v_t, r omega[, v_s, r omega_s, r omega_n])), whether its
    first trial force is between 1 and NEAR_THE_JUMP times the cap, under a law that jumps there."""
    return slow_start(model, initial) & Law.of(model).first_touch_runaway


def slow_start(model, initial: np.ndarray) -> np.ndarray:
    """Per initial state, whether LAMMPS converges to it slowly from its first step: near its law's jump
    (:func:`near_the_jump`), or above the cap at any ratio under a law whose dashpots grow as its spring
    (no jump, but LAMMPS's first step sets the history on the cap and it converges as sqrt(dt) from there:
    :attr:`.wall_law.Law.first_touch_on_cap`). Such states are warned of and probed finer."""
    law = Law.of(model)
    ratio = _ratio(initial, law)
    if ratio is None:
        return np.zeros(len(initial), dtype=bool)
    return (ratio > 1.0) & (ratio < (NEAR_THE_JUMP if law.first_touch_runaway else np.inf))


def beyond_reach(model, initial: np.ndarray) -> np.ndarray:
    """Per initial state, whether it lies between 1 and BEYOND_REACH times its law's jump, or grazes: its
    deepest overlap too small for double precision to resolve against r (checks.RESOLVABLE_OVERLAP_ULPS),
    so that its error is rounding's at any step and a finer one only stalls the slow sphere."""
    from ..checks import RESOLVABLE_OVERLAP_ULPS

    grazing = model.max_overlap(np.abs(initial[:, 0])) < RESOLVABLE_OVERLAP_ULPS * np.spacing(model.r)
    law = Law.of(model)
    ratio = _ratio(initial, law) if law.first_touch_runaway else None
    return grazing if ratio is None else grazing | ((ratio > 1.0) & (ratio < BEYOND_REACH))


def warn_slow_start(model, slow: np.ndarray, probed: bool = True) -> None:
    """One PhysicsWarning naming how many states LAMMPS converges to slowly (:func:`slow_start`), why,
    and what a run does with them (``probed``: whether the scene probes its step)."""
    rows = np.flatnonzero(slow)
    if not rows.size:
        return
    first = f"{rows.size} state(s) (the first: row {int(rows[0])}) put the first trial force, x_t |u'|, "
    law = Law.of(model)  # a pair's wall may carry no cap: the law's powers say which kind of start
    if law.spring_power > law.damping_power:
        why = (f"just above the cap mu |v_n| (below {NEAR_THE_JUMP:g} times it): with tangential = {model.tangential} "
               "and a tangential dashpot the friction then pushes along the slip from first touch, the outcome "
               "jumps at 1 and LAMMPS converges to it slowly")
    else:
        why = (f"above the cap mu |v_n|: with tangential = {model.tangential} and dashpots that grow as its spring "
               f"(damping = {model.damping}) LAMMPS's first step sets the history on the cap and converges from "
               "there as sqrt(dt)")
    does = ("the step is probed and each row's error reported" if probed else "this batch of several speeds keeps "
            "its rule's step, each row's error reported (a finer one: --tolerance, or a dt of your own)")
    warnings.warn(first + why + " (docs: Hertz-Mindlin, with a Coulomb cap): " + does, PhysicsWarning, stacklevel=4)
