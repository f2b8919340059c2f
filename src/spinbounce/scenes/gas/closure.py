"""What the two-temperature equations leave out, measured: the gas's steady ratio by the Boltzmann-Enskog
equation of the planar rule, solved by direct simulation Monte Carlo (DSMC), beside the rule's closed form.

The two-temperature equations (:mod:`spinbounce.exact.kinetic`) average each collision over independent
Maxwellian velocities and spins: a closure. A gas of rough spheres does not keep that shape: its collisions
correlate a sphere's spin with its velocity and fatten the spins' tails, and where a collision moves energy
between translation and rotation those correlations change how much. DSMC keeps every sphere's velocity and
spin and makes them collide as the Boltzmann-Enskog equation says (molecular chaos: pairs drawn at random,
the line of centres uniform, each pair kept with probability proportional to its closing speed), with the
planar rule (:mod:`.rule`) as the collision: no closure. The difference between its steady ratio and the
rule's closed form is the closure's error; the pair-level theories' steady ratios carry it
(``steady_ratio_boltzmann``: their own plus that difference; the rule is their control variate already, and
their collisions differ from it by a few per cent).

Measured with 20,000 spheres at kt/kn = 0.1 (undamped Hooke, alpha = 2/5): 0.5597 +/- 0.0010 against the
closed form's 0.5732 (six seeds: 0.5578 to 0.5613, a spread 1.4 times the batch means' standard error).
At the magic ratio (elastic rough spheres) the gas's equilibrium is Maxwellian at T_rot = T_tr: the closure
is exact there, and DSMC finds 1 within its noise (tests/test_gas_closure.py).
The rule is linear in the velocities, so the gas is rescaled as it cools (the ratio does not change).

:func:`pair_path` runs the same DSMC with the exact pair references' outcomes (the line of centres turning):
the isolated pairs' energy drift over a run with no closure and little noise (a collision's loss is heavy-tailed,
so drawn collisions average it slowly; four seeds of 20,000 spheres over 12 collisions span 0.043 points),
which replaces the two-temperature equations' part in the pair-level drifts (:mod:`.run`).
"""

from __future__ import annotations

import math

import numpy as np

from ...exact import kinetic
from ...exact import pair as planar
from . import rule

__all__ = ["boltzmann", "absent", "simulate", "pair_path", "relaxation_rate", "SPHERES"]

#: DSMC's spheres: the steady ratio's standard error is about 1e-3 with 20,000 (a sample's own noise
#: sqrt(4/(3N)) of the ratio, averaged over the window's independent stretches).
SPHERES = 20_000
#: Samples a collision per sphere. The run starts at the closed form's fixed point and settles for SETTLE_TIMES
#: of the ratio's relaxation times (the closure's error, about 0.015, decays to e^-5 of itself); then a window
#: of STRETCHES stretches, each STRETCH_TIMES relaxation times long (the ratio's fluctuations outlive about one:
#: the stretches' means are then nearly independent, and their spread gives the standard error).
SAMPLES_PER_COLLISION = 4
SETTLE_TIMES, STRETCH_TIMES, STRETCHES = 5.0, 5.0, 8
#: Bounds on the window and on the whole run, in collisions per sphere (a 20,000-sphere DSMC runs about
#: 25 collisions per sphere a second): a slow exchange (kt/kn far from the magic ratio, where the closure's
#: error is smallest) settles for at most half of the run.
SHORTEST_WINDOW, MOST_COLLISIONS = 20.0, 400.0
#: Restitutions within this of 1 are elastic rough spheres (the magic ratio): their collisions conserve energy and
#: the gas's equilibrium is Maxwellian at T_rot = T_tr, so the closure is exact and no DSMC is run.
ELASTIC = 1e-9
#: The record's ``method`` where no DSMC is needed.
EXACT = "none needed: elastic rough spheres reach Maxwell-Boltzmann equilibrium, where the closure is exact"


def relaxation_rate(matrix: np.ndarray, steady: float) -> float:
    """|d(dr/dtau)/dr| at the steady ratio r of d(T_tr, T_rot)/dtau = L (T_tr, T_rot): how fast the ratio
    r = T_rot/T_tr returns to it, a collision per sphere (dr/dtau = L10 + (L11 - L00) r - L01 r^2)."""
    (l00, l01), (_, l11) = matrix
    return abs(l11 - l00 - 2.0 * l01 * steady)


def _dsmc(collide, m: float, inertia: float, t_tr: float, t_rot: float, collisions: float, seed: int, spheres: int,
          rescale: bool) -> tuple:
    """DSMC of ``spheres`` spheres from Maxwellian velocities at ``t_tr`` and spins at ``t_rot`` for ``collisions``
    collisions per sphere, each pair's outcome by ``collide(n, v_a, v_b, w_a, w_b)`` (n from b to a at first
    touch): (collisions per sphere, T_tr, T_rot) at SAMPLES_PER_COLLISION samples a collision per sphere (and
    at the start). ``rescale``: the gas is brought back to unit energy at each sample (a rule linear in the
    velocities: the ratio is unchanged, and a long cooling run does not underflow)."""
    rng = np.random.default_rng([seed, 7])
    v = rng.standard_normal((spheres, 3))
    v -= v.mean(axis=0)
    v *= math.sqrt(t_tr / (m * np.mean(v * v)))  # the sample at exactly the asked temperatures
    w = rng.standard_normal((spheres, 3))
    w *= math.sqrt(t_rot / (inertia * np.mean(w * w)))
    half, done = spheres // 2, 0

    def sample():
        return 2.0 * done / spheres, m * np.mean(v * v), inertia * np.mean(w * w)

    samples = [sample()]
    while 2.0 * done / spheres < collisions:
        order = rng.permutation(spheres)
        a, b = order[:half], order[half:2 * half]
        n = rng.standard_normal((half, 3))
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        closing = -np.einsum("ij,ij->i", v[a] - v[b], n)  # n from b to a: approaching where positive
        bound = 2.0 * math.sqrt(float(np.max(np.einsum("ij,ij->i", v, v))))  # no |g| exceeds it
        kept = rng.random(half) * bound < closing
        a, b, n = a[kept], b[kept], n[kept]
        if len(a) == 0:  # a small gas's round may keep no pair
            continue
        v[a], v[b], w[a], w[b] = collide(n, v[a], v[b], w[a], w[b])
        before, done = done, done + int(kept.sum())
        if math.floor(2.0 * done * SAMPLES_PER_COLLISION / spheres) > math.floor(2.0 * before
                                                                                 * SAMPLES_PER_COLLISION / spheres):
            samples.append(sample())
            if rescale:
                scale = 1.0 / math.sqrt(samples[-1][1] + samples[-1][2])
                v *= scale
                w *= scale
    if samples[-1][0] < 2.0 * done / spheres:  # the run's end, past its last quarter-collision mark
        samples.append(sample())
    return tuple(np.array(x) for x in zip(*samples, strict=True))


def simulate(model, collisions: float, ratio0: float, seed: int, spheres: int = SPHERES) -> tuple:
    """DSMC of ``spheres`` spheres colliding by the planar rule of ``model`` for ``collisions`` collisions per
    sphere from Maxwellian velocities and spins at T_rot/T_tr = ``ratio0``: (collisions per sphere, T_rot/T_tr)
    at SAMPLES_PER_COLLISION samples a collision per sphere (the start left out)."""
    law = rule.pair_law(model)

    def collide(n, v_a, v_b, w_a, w_b):
        return planar.predict(n, v_a, v_b, w_a, w_b, **law)

    tau, t_tr, t_rot = _dsmc(collide, model.m, model.inertia, 1.0, ratio0, collisions, seed, spheres, rescale=True)
    return tau[1:], (t_rot / t_tr)[1:]


def pair_path(model, t_tr: float, t_rot: float, collisions: float, seed: int, log=None, spheres: int = SPHERES):
    """DSMC with the exact pair references' outcomes (:mod:`spinbounce.exact.pair_batch`: the line of centres
    turns, each collision loses what it loses) from T_tr = ``t_tr``, T_rot = ``t_rot``, for ``collisions``
    collisions per sphere: :class:`~spinbounce.exact.kinetic.Evolution` (its time NaN: DSMC counts collisions),
    or None where the compiled references do not take the law (``log`` told of a run)."""
    from ...exact import pair_batch

    if not rule.has_rule(model):  # a cap, a law on the contact radius: what is left is Hooke's, which it takes
        return None
    law = rule.pair_law(model)
    if log is not None:
        log(f"the isolated pairs' drift without the closure: DSMC of the exact pairs, {spheres} spheres over "
            f"{collisions:.3g} collisions per sphere")

    def collide(n, v_a, v_b, w_a, w_b):
        found = pair_batch.solve(n, v_a, v_b, w_a, w_b, **law)
        return tuple(np.array([getattr(o, k) for o in found]) for k in ("v_a", "v_b", "w_a", "w_b"))

    tau, t_tr, t_rot = _dsmc(collide, model.m, model.inertia, t_tr, t_rot, collisions, seed, spheres, rescale=False)
    return kinetic.Evolution(tau, np.full_like(tau, np.nan), t_tr, t_rot)


def _closed_form(model) -> tuple | str:
    """The planar rule's (e_n, beta, closed-form steady ratio, relaxation rate), or why ``model`` has no
    closure's error to measure."""
    if not rule.has_rule(model):
        return "the law has no planar rule (a cap, a law on the contact radius) for DSMC"
    e_n, beta = rule.restitutions(model)
    matrix = kinetic.rough_sphere_matrix(e_n, beta, model.alpha)
    closed = kinetic.steady_ratio(matrix)
    rate = relaxation_rate(matrix, closed) if math.isfinite(closed) else 0.0
    if rate == 0.0:
        return "its collisions move no energy between translation and rotation"
    return e_n, beta, closed, rate


def absent(model) -> str | None:
    """Why :func:`boltzmann` gives ``model`` no closure's error (None: it gives one)."""
    found = _closed_form(model)
    return found if isinstance(found, str) else None


def boltzmann(model, seed: int, log=None) -> dict | None:
    """The planar rule's steady ratio T_rot/T_tr by DSMC and by its closed form, their difference (the
    closure's error) and its standard error, and what was run (none for elastic rough spheres, whose closure is
    exact; ``log`` told of a DSMC run; a slow exchange settles and averages for fewer relaxation times than asked,
    within MOST_COLLISIONS, and the record says how many); None where the law has no planar rule (a cap,
    a law on the contact radius) or its collisions move no energy between translation and rotation."""
    found = _closed_form(model)
    if isinstance(found, str):
        return None
    e_n, beta, closed, rate = found
    if abs(e_n - 1.0) <= ELASTIC and abs(beta - 1.0) <= ELASTIC:  # equilibrium: Maxwellian at T_rot = T_tr
        return {"steady_ratio_dsmc": closed, "steady_ratio_closed_form": closed, "closure_error": 0.0,
                "standard_error": 0.0, "spheres": 0, "collisions_per_sphere": 0.0, "settled_collisions": 0.0,
                "relaxation_rate": float(rate), "e_n": e_n, "beta": beta,
                "method": EXACT}
    settle = min(SETTLE_TIMES / rate, MOST_COLLISIONS / 2.0)
    window = min(max(SHORTEST_WINDOW, STRETCHES * STRETCH_TIMES / rate), MOST_COLLISIONS - settle)
    if log is not None:
        log(f"the closure's error: DSMC of the planar rule, {SPHERES} spheres over {settle + window:.0f} collisions "
            "per sphere")
    tau, ratio = simulate(model, settle + window, closed, seed)
    late = tau > settle
    stretches = np.array_split(ratio[late], STRETCHES)
    mean = float(np.mean(ratio[late]))
    error = float(np.std([s.mean() for s in stretches], ddof=1) / math.sqrt(STRETCHES))
    return {"steady_ratio_dsmc": mean, "steady_ratio_closed_form": closed, "closure_error": mean - closed,
            "standard_error": error, "spheres": SPHERES, "collisions_per_sphere": float(tau[-1]),
            "settled_collisions": float(settle), "relaxation_rate": float(rate), "e_n": e_n, "beta": beta,
            "method": "DSMC", "settled_relaxation_times": float(settle * rate),
            "window_relaxation_times": float(window * rate)}
