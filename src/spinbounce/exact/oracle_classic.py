"""The cap of this build's ``linear_history_classic`` in the wall's oracle, in 3-D and for any law.

Its spring is k a^q on a displacement history h (q = 1: the contact radius a = sqrt(r delta)). When
the trial force A = k a^q h + gamma_t u' passes the cap C = mu |F_n|, LAMMPS sets the force to C along
A (s, its unit) and the history to the elastic part of that force divided by k alone, not by k a^q:
h = (C s - gamma_t u')/k. The next step's trial force is then

    A+ = f C s + (1 - f) gamma_t u',   f = a^q,

a finite jump in continuous time, not the rescale of the other laws. With f < 1 (a contact radius
below one length unit, as every contact of a sphere of radius 0.5 and unit speed):

* |A+| < C: the contact sticks again from A+ at once (a sawtooth: each time A reaches the cap it drops
  to about f of it);
* |A+| >= C, which needs gamma_t |u'| >= C: every step is capped and each one turns s towards u' by a
  fixed fraction (s_next is along f C s + (1 - f) gamma_t u'), so in continuous time s is the slip's unit
  at once, and the contact slides with F_t = -C s for as long as gamma_t |u'| >= C. u'' is then along
  s, so s stays put. At the slide's end the contact sticks from A+, just inside the cap.

Teeth can start from zero size: where a slide ends (its margin closes), where the cap restarts from
zero at a tensile turn, and at first touch where the spring outgrows a Hertzian cap (both ~ t^1.5). Each
tooth is then a fixed factor longer than the one before (a Zeno point), and their phase after it is set
by how the first one is cut: here by the reference's own cuts (the slide held on by NEAR_ONE of its
scale, the floor of a switch, the start FIRST_TOUCH after first touch), in LAMMPS by the step. Where the
teeth grow large quickly that phase carries into the outcome, which then has no dt -> 0 limit (measured:
a Hertzian viscoelastic contact whose slide ends at 1e-3 of its contact time gave r omega = -0.438,
-0.425, -0.439, -0.499 and -0.333 at dt = 1e-5 to 3.9e-8, in LAMMPS and in a replica of its steps
alike; an undamped Hertzian one erred 4e-4 to 7e-3 at halving steps). A contact with a tooth shorter
than ZENO of its contact time (:func:`tooth`) is solved again with every cut moved by a factor up to
ten (:func:`check_limit`), and refused if its outcome moves by more than LIMIT_SPREAD, the 1e-6 of the
state a reference is held to against converged LAMMPS. A contact radius of one length unit or more is
refused (:func:`check_radius`): there |A+| >= C whatever the slip does and s moves away from u'
(``exact.classic`` covers it in the plane,
with Hooke's force).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import NoLimit, NoMatrix
from .oracle_forces import A as _A
from .oracle_forces import V as _V
from .oracle_forces import W as _W

__all__ = ["reset", "slides", "is_zeno", "note_cap", "after_cap", "after_slide", "tooth", "slide_margin", "bounce",
           "reaches_one", "check_radius", "check_limit", "NEAR_ONE", "MAX_SWITCHES"]

#: The slide is held on by this fraction of its scale C + gamma_t |u'| (the teeth's Zeno point).
NEAR_ONE = 1.0e-10
#: Where the cuts are moved to (factors), and how far the outcome may move with them (of the state's
#: size): the bar a reference is held to against converged LAMMPS (its own accuracy elsewhere is ~1e-9).
CUTS = (2.2, 4.7, 10.0)
LIMIT_SPREAD = 1.0e-6
#: A tooth shorter than this fraction of the contact time marks a Zeno point (teeth from zero size).
ZENO = 1.0e-6
#: The sawtooth can take many teeth: more regime switches than this in one contact are refused.
MAX_SWITCHES = 20000


def factors(forces, y) -> tuple[float, float]:
    """(f = a^q, gamma_t a^s) at state y: the spring's radius factor and the tangential dashpot."""
    law = forces.law
    return forces.radius_power(y, law.spring_power)[0], law.c_t * forces.radius_power(y, law.damping_power)[0]


def reset(f: float, cap: float, s, drag):
    """The trial force after a capped step (a vector or a number): A+ = f C s + (1 - f) gamma_t u', the force
    C s with its history divided by k alone (f = a^q; f = 1 is the plain cap); ``drag``: gamma_t u'."""
    return f * cap * s + (1.0 - f) * drag


def slides(after, cap: float, drag) -> bool:
    """Whether the contact slides after a capped step: A+ stays on the cap and a dashpot holds it there."""
    return bool(np.linalg.norm(after) >= cap and np.any(drag))


def is_zeno(now: float, last: float, tau: float) -> bool:
    """Whether a tooth reached the cap within ZENO of the contact time ``tau`` of the last cap or slide's end."""
    return now - last < ZENO * tau


def note_cap(contact, tooth: bool) -> None:
    """Note a cap reached (``tooth``) or a slide's end at ``contact.now``: ``contact.zeno`` set at a Zeno point."""
    contact.zeno = contact.zeno or tooth and is_zeno(contact.now, contact.last_cap, contact.tau)
    contact.last_cap = contact.now


def after_cap(forces, y, cap: float) -> str:
    """The regime once the trial force y[A] is capped at ``cap``; puts y[A] to the next trial force A+
    (sticking) or to the slide's unit s = u'/|u'| (sliding)."""
    f, dashpot = factors(forces, y)
    slip = y[_V] + y[_W]
    size = math.hypot(*y[_A])
    after = reset(f, cap, y[_A] / size if size > 0.0 else np.zeros(2), dashpot * slip)
    if not slides(after, cap, dashpot * slip):
        y[_A] = after
        return "stick"
    y[_A] = slip / math.hypot(*slip)
    return "slip"


def slide_margin(forces, y, cap: float, cut: float = 1.0, floor: float = 0.0) -> float:
    """> 0 while the slide goes on: gamma_t |u'| - C, held on by ``cut`` NEAR_ONE of C + gamma_t |u'| and by
    ``floor`` (a switch's margin), so that the reset at its end leaves the trial force inside the cap."""
    _, dashpot = factors(forces, y)
    drag = dashpot * float(np.dot(y[_A], y[_V] + y[_W]))  # s is the slip's unit: u'.s = |u'|
    return drag - cap + cut * NEAR_ONE * (cap + abs(drag)) + floor


def tooth(contact, y, cap: float) -> str:
    """A stick that reached the cap: the reset (:func:`after_cap`), a Zeno point noted (:func:`note_cap`)."""
    note_cap(contact, True)
    return after_cap(contact.forces, y, cap)


def after_slide(contact, y, cap: float) -> str:
    """The slide's end: the reset along s, then a stick from A+ (inside the cap by the slide's margin)."""
    f, dashpot = factors(contact.forces, y)
    note_cap(contact, False)
    y[_A] = reset(f, cap, y[_A], dashpot * (y[_V] + y[_W]))
    return "stick"


def bounce(model, state, again):
    """The oracle's result of ``state`` (v_n, v_t, omega, v_s, omega_s, omega_n) with the classic cap, ``again(cut)``
    solving it with its cuts scaled by ``cut``: refused beyond the contact radius's reach (:func:`check_radius`),
    where its outcome has no limit (:func:`check_limit`), and where its sawtooth outruns MAX_SWITCHES (in the solve
    or in one with its cuts moved)."""
    check_radius(model, state[0])
    result, zeno = _within_reach(model, state, lambda: again(1.0))
    if zeno:
        initial = result.initial
        v_n, v_t, r_omega = initial[:3]
        _within_reach(model, state, lambda: check_limit(
            result.final, lambda cut: again(cut)[0].final, float(np.max(np.abs(initial))),
            f"state (v_n, v_t, r omega) = ({v_n:.6g}, {v_t:.6g}, {r_omega:.6g})"))
    return result


def _within_reach(model, state, solve):
    """``solve()``, its sawtooth beyond MAX_SWITCHES teeth refused by name (a small mu) instead of raised."""
    try:
        return solve()
    except RuntimeError as exc:
        if "regime switches" not in str(exc):
            raise
        raise NoMatrix(f"v_n = {float(state[0])!r}: with linear_history_classic's cap the contact saw-tooths "
                       f"through more than {MAX_SWITCHES} teeth (mu = {model.mu!r}), beyond the oracle's reach "
                       f"({exc})") from None


def _radius(model, v_n) -> float:
    """The largest contact radius sqrt(r delta) of the states ``v_n``."""
    return math.sqrt(model.r * float(np.max(model.max_overlap(np.abs(np.atleast_1d(v_n))))))


def reaches_one(model, v_n) -> bool:
    """Whether the contact radius of any of the states ``v_n`` reaches one length unit (see the module)."""
    return _radius(model, v_n) >= 1.0


def check_radius(model, v_n) -> bool:
    """Refuse a state whose contact radius reaches one length unit (f = a^q >= 1: see the module); True
    if it does not."""
    radius = _radius(model, v_n)
    if radius >= 1.0:
        raise NoMatrix(f"v_n = {float(np.min(v_n))!r}: the contact radius reaches sqrt(r delta) = {radius:.4g} >= 1, "
                       "where linear_history_classic's cap (reset by kt alone) keeps the force on the cap whatever the "
                       "slip does; no reference here follows it beyond the plane's Hookean wall")
    return True


def check_limit(final: np.ndarray, again, scale: float, what: str) -> None:
    """Refuse (:class:`.NoLimit`) an outcome ``final`` that moves with where its teeth from zero size are cut
    (``again(cut)``: the outcome with its cuts scaled by ``cut``): its LAMMPS outcome has no dt -> 0 limit.
    ``scale``: the state's size; ``what``: the state, named in the refusal."""
    spread = max(float(np.max(np.abs(again(factor) - final))) for factor in CUTS) / scale
    if spread > LIMIT_SPREAD:
        raise NoLimit(f"{what}: with linear_history_classic's cap the contact saw-tooths from teeth of zero size "
                      f"(after a slide, a tensile turn or first touch), whose phase moves the outcome by {spread:.2g} "
                      "of the state: LAMMPS's outcome has no dt -> 0 limit here")
