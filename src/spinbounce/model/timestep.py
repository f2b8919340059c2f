"""The timestep rule, in one place: where a collision's end falls inside a step.

LAMMPS's velocity-Verlet step cuts the contact force off somewhere inside the step in
which the overlap closes. With ``dt = t_end/(N + 1/2)`` the end falls in the middle of a
step, where the error of that cut cancels to first order and the collision's error is
second order in dt (LAMMPS_FACTS section 10: on a step boundary it is first order and
about ten times larger at the default resolution). Every run of a collision that has one
contact time (Hookean normal force) takes its step from here; a Hertzian wall, whose
spheres each end at their own time, cannot be aligned and converges at first order.
"""

from __future__ import annotations

import math

__all__ = ["mid_step_dt", "align_mid_step", "refine_mid_step", "steps_through", "steps_per_contact"]

#: Guards the rounding of t_end/dt so that an exact multiple is not pushed one step further.
_ROUNDING = 1e-9


def mid_step_dt(t_end: float, steps: int) -> float:
    """The step that puts ``t_end`` in the middle of step ``steps + 1``: t_end/(steps + 1/2)."""
    if steps < 0:
        raise ValueError(f"steps = {steps}: must be >= 0")
    return t_end / (steps + 0.5)


def steps_per_contact(t_end: float, dt: float) -> int:
    """Whole steps before the contact ends at a mid-step dt (the N of t_end/(N + 1/2))."""
    return max(0, math.ceil(t_end / dt - 0.5 - _ROUNDING))


def align_mid_step(t_end: float, dt_max: float) -> float:
    """The largest mid-step dt (:func:`mid_step_dt`) no larger than ``dt_max``."""
    return mid_step_dt(t_end, steps_per_contact(t_end, dt_max))


def refine_mid_step(t_end: float, dt: float, factor: int) -> float:
    """A mid-step dt about ``factor`` times finer than the mid-step ``dt``, still mid-step.

    Dividing a mid-step dt by an integer would move the end onto a step boundary for an
    even factor; this keeps it in the middle (N -> factor N).
    """
    if factor < 1 or factor != int(factor):
        raise ValueError(f"factor = {factor!r}: must be a whole number >= 1")
    return mid_step_dt(t_end, int(factor) * steps_per_contact(t_end, dt))


def steps_through(t_end: float, dt: float) -> int:
    """Steps that carry a run past ``t_end``: the step in which it falls, and one more for rounding."""
    return math.floor(t_end / dt) + 2
