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

Measured with 20,000 spheres at kt/kn = 0.1 (undamped Hooke, alpha = 2/5): 0.5577 +/- 0.0007 against the
closed form's 0.5732. At the magic ratio (elastic rough spheres) the gas's equilibrium is Maxwellian at
T_rot = T_tr: the closure is exact there, and DSMC finds 1 within its noise (tests/test_gas_closure.py).
The rule is linear in the velocities, so the gas is rescaled as it cools (the ratio does not change).
"""

from __future__ import annotations

import math

import numpy as np

from ...exact import kinetic
from ...exact import pair as planar
from . import rule

__all__ = ["boltzmann", "simulate", "relaxation_rate", "SPHERES"]

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


def simulate(model, collisions: float, ratio0: float, seed: int, spheres: int = SPHERES) -> tuple:
    """DSMC of ``spheres`` spheres colliding by the planar rule of ``model`` for ``collisions`` collisions per
    sphere from Maxwellian velocities and spins at T_rot/T_tr = ``ratio0``: (collisions per sphere, T_rot/T_tr)
    at SAMPLES_PER_COLLISION samples a collision per sphere."""
    rng = np.random.default_rng([seed, 7])
    law, inertia = rule.pair_law(model), model.alpha * model.m * model.r**2
    v = rng.standard_normal((spheres, 3)) * math.sqrt(1.0 / model.m)
    v -= v.mean(axis=0)
    w = rng.standard_normal((spheres, 3)) * math.sqrt(ratio0 / inertia)
    half, done, taus, ratios = spheres // 2, 0, [], []
    while 2.0 * done / spheres < collisions:
        order = rng.permutation(spheres)
        a, b = order[:half], order[half:2 * half]
        n = rng.standard_normal((half, 3))
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        closing = -np.einsum("ij,ij->i", v[a] - v[b], n)  # n from b to a: approaching where positive
        bound = 2.0 * math.sqrt(float(np.max(np.einsum("ij,ij->i", v, v))))  # no |g| exceeds it
        kept = rng.random(half) * bound < closing
        a, b, n = a[kept], b[kept], n[kept]
        v[a], v[b], w[a], w[b] = planar.predict(n, v[a], v[b], w[a], w[b], **law)
        before, done = done, done + int(kept.sum())
        if math.floor(2.0 * done * SAMPLES_PER_COLLISION / spheres) > math.floor(2.0 * before
                                                                                 * SAMPLES_PER_COLLISION / spheres):
            t_tr, t_rot = model.m * np.mean(v * v), inertia * np.mean(w * w)
            taus.append(2.0 * done / spheres)
            ratios.append(t_rot / t_tr)
            scale = 1.0 / math.sqrt(t_tr + t_rot)  # the rule is linear: a cooled gas rescaled is the same gas
            v *= scale
            w *= scale
    return np.array(taus), np.array(ratios)


def boltzmann(model, seed: int, log=None) -> dict | None:
    """The planar rule's steady ratio T_rot/T_tr by DSMC and by its closed form, their difference (the
    closure's error) and its standard error, and what was run (none for elastic rough spheres, whose closure is
    exact; ``log`` told of a DSMC run); None where the law has no planar rule (a cap,
    a law on the contact radius) or its collisions move no energy between translation and rotation."""
    if not rule.has_rule(model):
        return None
    e_n, beta = rule.restitutions(model)
    matrix = kinetic.rough_sphere_matrix(e_n, beta, model.alpha)
    closed = kinetic.steady_ratio(matrix)
    rate = relaxation_rate(matrix, closed) if math.isfinite(closed) else 0.0
    if rate == 0.0:
        return None
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
            "method": "DSMC"}
