"""The timestep rule, in one place: how fine a step the accuracy asks for, and where a
collision's end falls inside it.

**How fine.** Accuracy is the largest |LAMMPS - theory| over the state columns, divided
by the size of the initial state |(v_n, v_t, r omega, ...)|; the default target is
:data:`ACCURACY`. Without damping, LAMMPS's step is second order: a mode of frequency w
resolved with N steps per half-period (w dt = pi/N) over a contact of length T errs by
about ``SECOND_ORDER (w dt)^2 max(1, w T/pi)`` (the phase error of each half-period
adds up). The constant was measured at the paper's defaults (1.16e-4 at N = 100, order
2.0: tools of studies/accuracy) with a margin. Damping, a Coulomb cap, a Hertzian force
and the classic wall make the error first order or rough; their step is measured per scene
by a probe (:mod:`spinbounce.stepping`), which starts from this rule's step.

**Where the end falls.** With ``dt = t_end/(N + 1/2)`` the contact ends mid-step, where the
error of LAMMPS's cutting the force off within the step cancels to first order (LAMMPS_FACTS
section 10; docs/explanation/numerics.md). Every collision with one contact time (Hookean)
takes its step from here; a batch of Hertzian speeds too, each sphere time-scaled to the
longest contact (scenes.collision); with a dashpot its spheres end at their own times: first order.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

__all__ = ["mid_step_dt", "align_mid_step", "refine_mid_step", "steps_to", "steps_through",
           "steps_per_contact", "ACCURACY", "SECOND_ORDER", "SAFETY", "FROZEN_ACCURACY", "MAX_STEPS",
           "second_order_dt", "mode_rate", "check_steps", "estimate_seconds", "duration_text", "StepChoice",
           "cost_notice", "ANNOUNCE_SECONDS", "MAX_CORE_HOURS"]

#: Guards the rounding of t_end/dt so that an exact multiple is not pushed one step further.
_ROUNDING = 1e-9
#: The default accuracy: largest deviation from the theory over the size of the initial state.
ACCURACY = 1e-4
#: Second-order error constant (see the module's docstring): measured 0.118 at the paper's defaults.
SECOND_ORDER = 0.15
#: Steps are chosen for this fraction of the target: the states a rule or probe did not see,
#: and its constant, have room (measured at the paper's defaults: 4e-5 where 1e-4 is asked).
SAFETY = 0.5
#: The frozen contact keeps its acceptance of 1e-5 over 10 time units (one sphere: cheap).
FROZEN_ACCURACY = 1e-5
#: The most steps one run may take: LAMMPS counts steps in a 32-bit integer for `run`, and at
#: about 2e7 sphere-steps a second on one core this is already an hour for 100 spheres.
MAX_STEPS = 100_000_000
#: Fewer steps per half-period than this is a caricature of the contact, whatever the target:
#: the rule never goes coarser, and a given dt that coarse is refused (ContactModel.check_dt).
MIN_STEPS_PER_HALF_PERIOD = 20


@dataclass(frozen=True)
class StepChoice:
    """How a collision's step was chosen: the rule, a given dt, or a probe (its measurements)."""

    dt: float
    method: str
    target: float
    observed_order: float | None = None
    probe_errors: tuple[float, ...] = ()
    predicted_error: float | None = None

    def record(self) -> dict:
        return asdict(self)


def mode_rate(w: float, c: float) -> float:
    """The fastest rate (1/time) of x'' + c x' + w^2 x = 0: w, or an overdamped mode's fast decay."""
    half = 0.5 * c
    return w if half < w else half + math.sqrt(half * half - w * w)


def second_order_dt(modes, t_contact: float, target: float = ACCURACY) -> float:
    """The largest dt whose second-order error estimate stays within ``target``.

    ``modes``: (w, c) pairs of the contact's linear modes (frequency, damping rate); the
    fastest rate of each (w, or the fast decay of an overdamped mode) must be resolved.
    """
    dts = []
    for w, c in modes:
        rate = mode_rate(w, c)
        if rate <= 0.0:
            continue
        periods = max(1.0, rate * t_contact / math.pi)
        wdt = min(math.sqrt(SAFETY * target / (SECOND_ORDER * periods)), math.pi / MIN_STEPS_PER_HALF_PERIOD)
        dts.append(wdt / rate)
    return min(dts) if dts else t_contact / MIN_STEPS_PER_HALF_PERIOD


#: LAMMPS's cost on one core for this contact: a fixed cost per step (one sphere: 2.5 million
#: steps in 2.7 s), and each sphere's (200,000 collisions x 252 steps in 8.4 s).
SECONDS_PER_STEP = 1e-6
SPHERE_STEP_SECONDS = 1.7e-7


def estimate_seconds(steps: int, spheres: int = 1) -> float:
    """About how long LAMMPS takes for ``steps`` steps of ``spheres`` spheres on one core."""
    return steps * (SECONDS_PER_STEP + spheres * SPHERE_STEP_SECONDS)


def duration_text(seconds: float) -> str:
    return f"{seconds:.3g} s" if seconds < 3600 else f"{seconds / 3600:.3g} core-hours"


def check_steps(steps: float, parameter: str, value, why: str, spheres: int = 1) -> int:
    """Refuse a run of more than :data:`MAX_STEPS` steps, naming the parameter, why and the cost.
    ``steps`` may be a float (t_end/dt), even infinite: a dt of 5e-324 overflows any count."""
    from .parameters import SceneError

    if not steps <= MAX_STEPS:  # NaN too: a count no float arithmetic could make
        cost = f" (about {duration_text(estimate_seconds(steps, spheres))} on one core)" if math.isfinite(steps) else ""
        raise SceneError(parameter, value, f"needs {steps:.3g} steps ({why}), more than the limit of "
                                           f"{MAX_STEPS:.0e} for one run{cost}")
    return int(steps)


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


def steps_to(t_end: float, dt: float) -> float:
    """Whole steps that reach ``t_end`` (an exact multiple is not pushed one step further; inf when
    t_end/dt overflows a float: :func:`check_steps` refuses it)."""
    ratio = t_end / dt if dt > 0.0 else math.inf  # a step that underflowed to zero counts no run either
    return math.ceil(ratio - _ROUNDING) if math.isfinite(ratio) else math.inf


def steps_through(t_end: float, dt: float) -> int:
    """Steps that carry a run past ``t_end``: the step in which it falls, and one more for rounding
    (infinite when t_end/dt overflows a float: :func:`check_steps` refuses it)."""
    ratio = t_end / dt
    return math.floor(ratio) + 2 if math.isfinite(ratio) else math.inf


#: A run expected to take longer than this says so before it starts.
ANNOUNCE_SECONDS = 60.0
#: The most a sweep may be estimated to take on one core before it must be forced: a longer one
#: belongs on a cluster, as chunks run by the workflow (workflows/Snakefile).
MAX_CORE_HOURS = 1.0


def cost_notice(steps: int, spheres: int = 1) -> str | None:
    """What to tell the user before a run of ``steps`` steps of ``spheres`` spheres starts, if it
    is expected to take longer than :data:`ANNOUNCE_SECONDS`."""
    seconds = estimate_seconds(steps, spheres)
    if seconds <= ANNOUNCE_SECONDS:
        return None
    return f"estimated {duration_text(seconds)} on one core ({steps:.3g} steps of {spheres} sphere(s)); Ctrl-C stops it"
