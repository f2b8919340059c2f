"""What LAMMPS integrates for two free spheres with a Coulomb cap, in 3-D: the capped reference.

``pair_style granular <normal> ... damping <model> tangential <law> KT X_T MU`` with a finite MU.
It differs from the uncapped model of :mod:`.pair_exact` in two ways, both read in LAMMPS's
tangential sub-models (``linear_history`` and the Mindlin variants):

* every step whose |h.n| k exceeds 1e-10 mu |F_n| (every step once the line of centres turns)
  projects the history h back into the tangent plane and restores its length: in continuous
  time h turns with n, h' gaining -(h.n') n, and keeps no normal component;
* |F_t| <= mu |F_n| with F_n the total normal force, damping included (LAMMPS's Fncrit): on the
  cap the history is reset so that the trial force has length mu |F_n|.

The state beyond the spheres' is the trial force A = E + gamma_t a^s u' (F_t = -A on a while
sticking), E the history's elastic force (k a^q h for a displacement history, the history itself
for a force history) and u' the slip rate. Sticking (|A| < mu |F_n|):

    A' = k a^q u' + R E - (E.n') n + (gamma_t a^s u')',

R = a'/a times q for a displacement history, once more while a shrinks with a rescale. Sliding,
A = c s rides the cap c = mu |F_n| and its direction s turns towards the sticking rate:
s' = -(s.n') n + ((n x s).A'_stick) (n x s)/c, with A'_stick the rate above at A = c s. A slide
lasts while sticking would carry A beyond the cap (s.A'_stick > c'); each switch, the normal
force's zero (the cap's kink, with gamma_n > 0), a rescale's deepest point and the end of contact
are events of scipy's DOP853 at rtol 1e-12, restarted at each: the outcome is accurate to ~1e-10
of the speeds. ``planar=True`` freezes n and the lever arms: the wall's capped problem of the
equivalent sphere (:mod:`.pair`), which the wall's references must then reproduce
(tests/test_pairs_capped.py, tests/test_pairs_nonlinear.py).

A law on the contact radius (a force K delta^p, a spring k a^q, dashpots a^s: the keys of
:data:`.pair_exact.HOOKE`) starts FIRST_TOUCH contact times after first touch and ends
LAST_OVERLAP of its depth before the overlap does, where a's rates are infinite (the wall's
oracle does the same).
"""

from __future__ import annotations

import numpy as np

from ..errors import NoLimit, NoMatrix
from . import first_use, pair_exact
from .pair_exact import (
    RTOL,
    PairOutcome,
    free_flight,
    outcome,
    start,
)
from .pair_exact import undamped_depth as pair_depth
from .oracle_classic import MAX_SWITCHES, check_limit
from . import pair_capped_phases as capped_phases
from .pair_capped_phases import TURN_FLOOR, ClassicContact, Contact, TooManyEvaluations
from .wall_law import on_contact_radius

__all__ = ["solve", "MAX_PHASES"]

#: More phases than this in one contact is chattering, not a contact (the measured cases take < 10).
MAX_PHASES = 200
#: Points inside each integrator step where a phase's switching function is also sampled.
INTERIOR_SAMPLES = 8
#: A law on the contact radius starts this many contact times after first touch and ends where the
#: overlap is back to LAST_OVERLAP of its undamped depth (the wall's oracle does the same).
FIRST_TOUCH = 1e-12
LAST_OVERLAP = 1e-10


def _first_event(solution, events) -> tuple[float, int, np.ndarray]:
    """The first event of a segment: (time, which, state). The integrator sees a switch only
    as a sign change between its steps; the phase's own switching function (``events[1]``) is
    also sampled at :data:`INTERIOR_SAMPLES` points inside each step, so that a stick or a slide
    shorter than a step is not stepped over."""
    from scipy.optimize import (
        brentq,  # here, as solve_ivp in solve: what a compiled batch never needs
    )

    fired = [(ts[0], k) for k, ts in enumerate(solution.t_events) if len(ts)]
    if not fired:
        raise RuntimeError(f"the capped pair did not separate within its window: {solution.message}")
    t_end, which = min(fired)
    switch, dense = events[1], solution.sol
    for t0, t1, step in zip(dense.ts[:-1], dense.ts[1:], dense.interpolants):
        if t0 >= t_end:
            break
        grid = np.linspace(t0, min(t1, t_end), INTERIOR_SAMPLES + 2)
        states = np.ascontiguousarray(step(grid).T)  # the step's own interpolant, at every point at once
        values = [switch(time, y) for time, y in zip(grid, states, strict=True)]
        for k in range(len(grid) - 1):
            if switch.direction * values[k] < 0.0 <= switch.direction * values[k + 1] and grid[k + 1] < t_end:
                g = lambda time: switch(time, step(time))  # noqa: E731 (the same interpolant as the samples)
                root = brentq(g, grid[k], grid[k + 1], xtol=4.0 * np.finfo(float).eps * max(1.0, abs(grid[k])))
                return root, 1, step(root)
    return t_end, which, solution.y_events[which][0].copy()


def _first_touch(contact: Contact, y, t: float) -> np.ndarray:
    """The state t after first touch (a law on the contact radius): the centres moved by v t, the
    elastic force grown as k a^q u' t (over 1 + q/2 for a force history), the dashpot's part beside it."""
    p = contact.p
    y[:3] += (y[3:6] - y[6:9]) * t
    y[18] = -((y[3:6] - y[6:9]) @ contact.n0) * t
    k = contact.kinematics(y)
    elastic = k["spring"] * k["slip"] * t / (1.0 + p["spring_power"] / 2.0 if p["force_history"] else 1.0)
    y[15:18] = elastic + k["dashpot"] * k["slip"]
    return y


def solve(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, mu, gamma_n=0.0, gamma_t=0.0,
          planar=False, rtol=RTOL, tensile=True, **law) -> PairOutcome:
    """One capped pair from first touch until it separates (:func:`_solve`); with ``classic_cap`` (the classic
    spring's reset) a pair whose teeth after a slide set its outcome is refused (:class:`.NoLimit`, carrying
    the outcome at the usual cut as ``outcome``: its contact time holds)."""
    first_use.once("capped pair")
    args = (n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, mu, gamma_n, gamma_t, planar, rtol,
            tensile)
    found, zeno = _solve(*args, **law)
    if zeno:  # velocities and r times spins, over the largest of the relative velocity and r times the spins

        def state(o) -> np.ndarray:
            return np.concatenate([o[0], o[1], r_a * np.asarray(o[2]), r_b * np.asarray(o[3])])

        scale = max(np.linalg.norm(np.subtract(v_a, v_b)), r_a * np.linalg.norm(w_a), r_b * np.linalg.norm(w_b))
        try:
            check_limit(state(found), lambda cut: state(_solve(*args, cut=cut, **law)[0]), scale, "this pair")
        except NoLimit as refused:
            refused.outcome = found
            raise
    return found


def _solve(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b, kn, kt, mu, gamma_n, gamma_t, planar, rtol,
           tensile, cut=1.0, classic_cap=False, **law) -> tuple[PairOutcome, bool]:
    """One capped pair from first touch until it separates (arguments as :func:`.pair_exact.solve`,
    ``law`` its keys of :data:`.pair_exact.HOOKE`; ``tensile`` False: LAMMPS's ``limit_damping``, the
    normal force and with it the cap cut at their turn, from which the spheres part force-free). A law
    on the contact radius is integrated at a tenth of ``rtol``, as the wall's oracle does: a stick whose
    first trial force starts just inside the cap (0.97 of it) kept 2e-7 at rtol itself, 1e-8 at a tenth."""
    if not mu > 0.0:
        raise ValueError(f"mu = {mu!r}: the capped pair reference needs a cap > 0 (mu = 0 is the uncapped "
                         "reference without a tangential force)")
    if on_contact_radius(law.get("power", 1.0), law.get("spring_power", 0.0), law.get("damping_power", 0.0)):
        rtol = rtol / 10.0
    n0, p, y, v_rel, tau, longest, atol = start(n, v_a, v_b, w_a, w_b, m_a, r_a, alpha_a, m_b, r_b, alpha_b,
                                                kn, kt, planar, rtol, mu=mu, gamma_n=gamma_n, gamma_t=gamma_t, **law)
    contact = ClassicContact(p, n0, planar, cut) if classic_cap else Contact(p, n0, planar)
    contact.tau, contact.unloading = tau, False
    radial = on_contact_radius(p["power"], p["spring_power"], p["damping_power"])
    contact.runaway = (not p["force_history"] and p["spring_power"] > p["damping_power"] and gamma_t > 0.0
                       and not classic_cap)
    m_star, speed = contact.m_star, abs(v_rel @ n0)
    depth = pair_depth(p, v_rel, n0, m_star)
    if classic_cap and np.sqrt(p["r_eff"] * depth) >= 1.0:  # where the classic cap has no reference (oracle_classic)
        raise NoMatrix(f"the contact radius sqrt(R_eff delta) reaches {np.sqrt(p['r_eff'] * depth):.4g} >= 1, where "
                       "linear_history_classic's cap keeps the force on the cap whatever the slip does")
    stiffness = p["K"] * p["power"] * depth ** (p["power"] - 1.0)  # kn for the Hookean force
    contact.f_rounding = 16.0 * stiffness * np.spacing(r_a + r_b)
    contact.force_scale = mu * speed * np.sqrt(m_star * stiffness)
    contact.turn_floor = TURN_FLOOR * contact.force_scale
    # a law on the contact radius starts a hair after first touch and ends a hair before the overlap
    # does, where a's rates are infinite (what the ends would do, ~ (1e-10)^(1 + s/2) of the speed, is left)
    contact.last = LAST_OVERLAP * depth if radial else 0.0
    t = FIRST_TOUCH * cut * tau if radial else 0.0
    y = _first_touch(contact, np.append(y, np.zeros(4)), t)
    # the overlap's tolerance: relative from its first touch on (a law on the contact radius starts at ~1e-12 of it)
    # and a stick's trial force's: of its size at first touch there (~ a, sqrt(FIRST_TOUCH) of the force's scale).
    # Held to the force's scale, a stick on the cap whose trial force and cap grow alike (dashpots of the spring's
    # power) gained 1e-6 of its size in the first steps, unseen by the error estimate, and slid the whole contact
    # (0.43 off the wall's oracle); held to 1e-12 of the scale, a stick near A = 0 took minutes
    stick_atol = rtol * contact.force_scale * (np.sqrt(FIRST_TOUCH) if radial else 1.0)
    atol = np.concatenate([np.full(15, atol), np.full(3, stick_atol), [rtol * 1e-12 * depth]])
    window = float(pair_exact.window(tau, m_a, m_b, kn, gamma_n, radial))
    contact.begin(y)
    for _ in range(phases := MAX_SWITCHES if classic_cap else MAX_PHASES):  # a classic cap's sawtooth: many
        events = contact.events()
        if contact.sliding:  # s is a unit vector: its tolerance is rtol's
            atol[15:18] = rtol
        else:
            atol[15:18] = stick_atol
        solution = _phase(contact, (t, t + window), y, rtol, atol, events, longest)
        t, which, y = _first_event(solution, events)
        if which == 0:
            if contact.last:  # the spheres part freely from the cut to the end of the overlap
                k = contact.kinematics(y)
                t += contact.last / max(abs(k["v_n"]), 1e-300)
            return outcome(y, t, n0), getattr(contact, "zeno", False)
        if not tensile and events[which].__name__ == "normal_force":  # limit_damping: no force from here
            return outcome(*free_flight(y, t, n0, planar, y[18]), n0), getattr(contact, "zeno", False)
        contact.now = t
        contact.switch(y, events[which].__name__)
    raise RuntimeError(f"the capped pair switched phase more than {phases} times (chattering)")


def _phase(contact: Contact, span, y, rtol: float, atol, events, longest: float):
    """One phase, integrated by DOP853; where its steps have not ended it within EXPLICIT_EVALUATIONS (a stiff
    turn of s), again from the same start by Radau, whose steps the stiff mode does not bound, within
    MAX_EVALUATIONS (else refused)."""
    from scipy.integrate import solve_ivp

    for method, budget in (("DOP853", capped_phases.EXPLICIT_EVALUATIONS), ("Radau", capped_phases.MAX_EVALUATIONS)):
        contact.evaluations, contact.budget = 0, budget
        try:
            return solve_ivp(contact.rates, span, y, method=method, rtol=rtol, atol=atol, events=events,
                             max_step=longest, dense_output=True)
        except TooManyEvaluations:
            if method == "Radau":
                raise


@first_use.example("capped pair", seconds=6)
def _example() -> None:
    """A law on the contact radius under a cap, free and held, cut by limit_damping, rescaled on a force history;
    and the classic spring's cap."""
    pair = pair_exact.EXAMPLE
    solve(**pair, mu=0.3, **pair_exact.HERTZ_MINDLIN)
    solve(**pair, mu=0.3, **pair_exact.HERTZ_MINDLIN, planar=True, tensile=False)
    solve(**pair, mu=0.3, **pair_exact.HERTZ_MINDLIN | {"force_history": True, "rescale": True})
    try:
        solve(**pair, mu=0.3, **pair_exact.HOOKE | {"spring_power": 1.0, "projected": True}, classic_cap=True)
    except NoLimit:  # its teeth set the outcome: refused, its functions compiled all the same
        pass
