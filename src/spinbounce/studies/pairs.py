"""Pair studies: the checked cases, the planar theory's validity map, and the cost against the wall.

* :func:`cases`: pairs with unequal radii, masses and alpha, both spinning in 3-D, from
  head-on to grazing incidence (tests/test_pairs.py checks LAMMPS on them);
* :func:`validity_map`: the planar theory's error against the exact reference over a grid
  of eps = v_t tau/(r_a + r_b) and the centrifugal ratio v_t^2 tau/(pi (r_a + r_b) |v_n|)
  (no LAMMPS: the exact reference is what LAMMPS integrates, checked on the cases);
* :func:`pair_to_wall_cost`: LAMMPS's loop time per collision of pair batches (small eps,
  the default radii, the hard cases) over that of a wall batch, each at its default step.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np

from ..model.contact import ContactModel
from ..scenes.collision import Collision
from ..pipeline import run_scene
from ..exact import pair as planar
from ..exact import pair_exact
from ..scenes.pair import Pair, PairBatch, PairContact, Sphere
from ..sweeps.pair_ladder import ladder_steps, run_ladder

__all__ = ["cases", "validity_map", "pair_to_wall_cost", "cost_lines"]

#: (sphere a, sphere b): unequal radii, masses and alpha (2/5 and rigid-body ones).
_SPHERE_PAIRS = (
    (Sphere(1.0, 0.5, 0.4), Sphere(1.0, 0.5, 0.4)),
    (Sphere(1.0, 0.5, 0.25), Sphere(3.0, 0.8, 0.4)),
    (Sphere(0.5, 0.3, 0.4), Sphere(2.0, 0.7, 0.6)),
    (Sphere(2.0, 0.6, 0.1), Sphere(1.0, 0.4, 0.5)),
)
#: (tangential over normal speed of approach): head-on, oblique and grazing.
_INCIDENCE = (0.0, 0.5, 1.0, 2.0, 4.0, 8.0)


def cases(seed: int = 7) -> list[Pair]:
    """24 pairs: each sphere pair at each incidence, with random 3-D spins and line of centres."""
    rng = np.random.default_rng(seed)
    out = []
    for a, b in _SPHERE_PAIRS:
        for ratio in _INCIDENCE:
            n = rng.normal(size=3)
            n /= np.linalg.norm(n)
            t = np.cross(n, rng.normal(size=3))
            t /= np.linalg.norm(t)
            v_b = rng.uniform(-0.5, 0.5, size=3)
            v_rel = -0.6 * n + 0.6 * ratio * t
            out.append(Pair(a=a, b=b, normal=n, v_a=v_b + v_rel, v_b=v_b,
                            w_a=rng.uniform(-1.0, 1.0, size=3) / a.r, w_b=rng.uniform(-1.0, 1.0, size=3) / b.r))
    return out


def validity_map(eps_values, centrifugal_values, kn: float = 10.0, kt: float = 1.0) -> dict:
    """The planar theory's error (in units of the speed) over a grid of eps and the centrifugal ratio.

    Equal spheres (m = 1, r = 0.5, alpha = 2/5), b at rest, no spin. For a given eps and
    centrifugal ratio c: v_t = eps (r_a + r_b)/tau and |v_n| = v_t eps/(pi c).
    """
    eps_values, centrifugal_values = np.asarray(eps_values, float), np.asarray(centrifugal_values, float)
    sphere = Sphere()
    tau = float(planar.contact_time(sphere.m, sphere.m, kn))
    radsum = 2 * sphere.r
    error = np.full((len(centrifugal_values), len(eps_values)), np.nan)
    for i, c in enumerate(centrifugal_values):
        for j, eps in enumerate(eps_values):
            v_t = eps * radsum / tau
            v_n = v_t * eps / (math.pi * c)
            if v_n * math.sqrt(planar.reduced_mass(1.0, 1.0) / kn) >= 0.5 * sphere.r:
                continue  # the overlap would reach half the radius: not a contact worth mapping
            pair = Pair(a=sphere, b=sphere, v_a=(v_t, 0.0, -v_n))
            exact = pair_exact.solve(**pair.vectors(), **pair.properties(), kn=kn, kt=kt)
            theory = planar.predict(**{k: np.asarray(v)[None] for k, v in pair.vectors().items()},
                                    **pair.properties(), kn=kn, kt=kt)
            got = np.concatenate([exact.v_a, exact.v_b, sphere.r * exact.w_a, sphere.r * exact.w_b])
            want = np.concatenate([theory[0][0], theory[1][0], sphere.r * theory[2][0], sphere.r * theory[3][0]])
            error[i, j] = np.max(np.abs(got - want)) / pair.speed()
    return {"eps": eps_values.tolist(), "centrifugal": centrifugal_values.tolist(), "planar_error": error.tolist(),
            "kn": kn, "kt": kt, "sphere": {"m": sphere.m, "r": sphere.r, "alpha": sphere.alpha}}


#: The damped batches' normal damping (restitution 0.76).
DAMPED_GAMMA_N = 0.5


def _sweep_pairs(n: int, r: float, seed: int) -> tuple[list[Pair], dict]:
    """Equal spheres of radius r, b at rest: |v_n| in [0.5, 1.5], v_t and r omega in [-1, 1];
    and the same impacts as the wall's states."""
    rng = np.random.default_rng(seed)
    v_n, v_t, r_omega = -rng.uniform(0.5, 1.5, n), rng.uniform(-1.0, 1.0, n), rng.uniform(-1.0, 1.0, n)
    sphere = Sphere(1.0, r, 0.4)
    pairs = [Pair(a=sphere, b=sphere, v_a=(t, 0.0, vn), w_a=(0.0, -w / r, 0.0))
             for vn, t, w in zip(v_n, v_t, r_omega, strict=True)]
    return pairs, {"v_n": v_n, "v_t": v_t, "omega": r_omega / 0.5}


def pair_to_wall_cost(n: int = 200, seed: int = 3, out_dir: Path | None = None) -> dict:
    """LAMMPS's loop seconds per collision, pair batches against a wall batch, each at its default step.

    The wall: n spheres (m = 1, r = 0.5) at its default step, undamped and with
    :data:`DAMPED_GAMMA_N`. The pairs, n in each batch: a sweep's states with radii 5e3 (the line
    of centres barely turns: where a fit may claim the planar matrix), the same states with the
    default radii 0.5 (eps up to 0.7), undamped and damped, and the 24 hard cases of :func:`cases`
    (repeated); each against the wall batch of its damping, at the step its probe chose
    (:func:`.stepping.tune_pairs`; the probe's own runs are not counted); and the default radii
    as a sweep runs them, two aligned runs combined (:mod:`spinbounce.sweeps.pair_ladder`: both runs
    counted). Every batch is checked against its reference, so each cost is at the accuracy its rows reach.
    """
    small, wall_states = _sweep_pairs(n, 5e3, seed)
    default = _sweep_pairs(n, 0.5, seed)[0]
    batches = {"small eps": (small, 0.0), "default radii": (default, 0.0),
               "default radii, damped": (default, DAMPED_GAMMA_N),
               "hard cases": ([cases()[k % 24] for k in range(n)], 0.0)}
    with tempfile.TemporaryDirectory() as scratch:
        where = Path(out_dir or scratch)
        walls = {gamma_n: run_scene(Collision(ContactModel(gamma_n=gamma_n), **wall_states), where / f"wall-{gamma_n:g}",
                                        record=False) for gamma_n in (0.0, DAMPED_GAMMA_N)}
        wall = walls[0.0]
        out = {"collisions": n, "wall_seconds_per_collision": wall.info.loop_seconds / n,
               "wall_steps": wall.scene.nsteps, "wall_max_error": wall.max_abs_error, "batches": {}}
        for name, (pairs, gamma_n) in batches.items():
            pair = run_scene(PairBatch(pairs, PairContact(gamma_n=gamma_n)), where / name.replace(" ", "-").replace(",", ""),
                             record=False)
            out["batches"][name] = _against(walls[gamma_n], n, pair.info.loop_seconds, pair.scene.nsteps,
                                            pair.step.record(), pair.columns)
        # the default radii as a sweep runs them: two aligned runs combined (spinbounce.sweeps.pair_ladder)
        batch = PairBatch(default, PairContact())
        chosen = ladder_steps(batch, where / "ladder-probe")
        if chosen is not None:
            ladder = run_ladder(batch, chosen[0], where / "ladder", contact_time=chosen[1])
            out["batches"]["default radii, two runs combined"] = _against(
                wall, n, ladder.result.info.loop_seconds, ladder.nsteps, ladder.result.step.record(), ladder.columns)
    return out


def _against(wall, n: int, seconds: float, steps: int, step: dict, columns: dict) -> dict:
    """A pair batch's LAMMPS ``seconds`` over ``steps`` beside ``wall``'s, per collision and per step."""
    per_pair, per_wall = seconds / n, wall.info.loop_seconds / n
    return {"pair_seconds_per_collision": per_pair, "pair_to_wall": per_pair / per_wall,
            "pair_to_wall_per_step": (per_pair / steps) / (per_wall / wall.scene.nsteps), "pair_steps": steps,
            "wall_steps": wall.scene.nsteps, "wall_max_error": wall.max_abs_error, "step": step,
            "max_eps": float(np.max(columns["eps"])), "pair_max_error": float(np.max(columns["error"]))}


def cost_lines(report: dict) -> list[str]:
    """One printed line per batch of :func:`pair_to_wall_cost`."""
    return [f"pair / wall, per collision, {name} (eps up to {b['max_eps']:.2g}): {b['pair_to_wall']:.1f}x "
            f"({b['pair_steps']} vs {b['wall_steps']} steps, {b['step']['method']}; per step "
            f"{b['pair_to_wall_per_step']:.2f}x; max errors {b['pair_max_error']:.1e} and {b['wall_max_error']:.1e})"
            for name, b in report["batches"].items()]
