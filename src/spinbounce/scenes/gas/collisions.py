"""A gas's collisions, one at a time: the energy each moves, averaged over a Maxwellian gas's collisions.

Collisions are drawn as a dilute gas meets them (molecular chaos): the line of centres n uniform,
the relative velocity g Maxwellian with variance 2 T_tr/m a component, weighted by its closing speed
|g.n| (so |g.n| has density x exp(-x^2 m / (4 T_tr))), each sphere's spin Maxwellian at T_rot. In the
frame n = z, b at rest: v_a = g. Each draw is kept as unit variates, so that every temperature's
collisions are the same draws scaled (common random numbers: differences between temperatures and
spins are not noise).

Outcomes come from the project's pair references (``route`` "exact": what LAMMPS integrates as dt
goes to 0, the line of centres turning) or from LAMMPS itself at the gas's step (``route`` "lammps":
isolated pairs that first touch at a uniformly random phase of a step, as a gas's do, so that the
first step's extra slip and every other error of the step are in the averages). From them
:func:`averages_at` measures the matrix L of :mod:`spinbounce.exact.kinetic`: the collisions without
spin give its first column; with spins at T_rot = T_tr, drawn and then reversed (so that the part of
the energy change odd in the spins cancels), its second.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from ...exact import kinetic
from ...lammps.decks import prepare_run_dir
from ...lammps.runner import run_deck
from ..pair.kind import equal_pair
from ..pair.pairs import Pair
from ..pair.scene import PairBatch
from ..pair.table import pair_frames, pair_states
from . import rule
from .encounters import Crowd

__all__ = ["Draws", "draws", "outcomes", "mean_contact_time", "averages_at", "averages"]



@dataclass(frozen=True)
class Draws:
    """Unit variates of ``count`` collisions: the relative velocity's tangential parts (``tangential``,
    (count, 2), standard normal), its closing speed (``closing``, Rayleigh of unit scale), both spins
    (``spins``, (count, 6), standard normal) and the phase of a step at first touch (``phase``)."""

    tangential: np.ndarray
    closing: np.ndarray
    spins: np.ndarray
    phase: np.ndarray

    def velocities(self, t_tr: float, m: float) -> np.ndarray:
        """(count, 3) relative velocities g = v_a - v_b at ``t_tr``, n = +z (b below a: g_z < 0)."""
        s = math.sqrt(2.0 * t_tr / m)
        return s * np.column_stack([self.tangential, -self.closing])

    def spin(self, t_rot: float, inertia: float) -> np.ndarray:
        """(count, 6) spins of a and b at ``t_rot``."""
        return math.sqrt(t_rot / inertia) * self.spins


def draws(count: int, seed: int) -> Draws:
    rng = np.random.default_rng(seed)
    return Draws(rng.standard_normal((count, 2)), np.sqrt(-2.0 * np.log1p(-rng.random(count))),
                 rng.standard_normal((count, 6)), rng.random(count))


@dataclass(frozen=True)
class _PhasedBatch(PairBatch):
    """Isolated pairs that first touch at the given ``phase`` of a step, as a gas's collisions do."""

    phase: np.ndarray = field(default=None, compare=False, repr=False)

    @cached_property
    def lead(self) -> np.ndarray:
        return self.phase * self.dt


def _pairs(model, velocities, spins) -> tuple:
    sphere, contact = equal_pair(model)
    return tuple(Pair(sphere, sphere, (0.0, 0.0, 1.0), tuple(v), (0.0, 0.0, 0.0), tuple(w[:3]), tuple(w[3:]))
                 for v, w in zip(velocities.tolist(), spins.tolist())), contact


def _exact(outcomes) -> tuple[np.ndarray, np.ndarray]:
    return (np.array([o.v_a - o.v_b for o in outcomes]),
            np.array([np.concatenate([o.w_a, o.w_b]) for o in outcomes]))


def outcomes(model, velocities, spins, dt: float | None, phase, folder: Path | None) -> dict:
    """Each collision's relative velocity g' and spins (w_a', w_b') by each route ("exact"; with ``folder``,
    also "lammps": isolated pairs at step ``dt`` touching at ``phase`` of a step), and its exact contact time."""
    pairs, contact = _pairs(model, velocities, spins)
    if folder is None:
        exact = contact.solve_all(pairs)
        return {"exact": _exact(exact), "contact_time": np.array([o.contact_time for o in exact])}
    batch = _PhasedBatch(pairs, contact, dt, phase=phase)
    found = {"exact": _exact(batch.exact), "contact_time": batch.contact_times}
    deck = batch.render("library")
    info = run_deck(prepare_run_dir(folder, deck, durable=False), deck.atoms)
    batch.read(info, deck, folder)  # every pair apart at the end, every number finite
    states = pair_states(batch, deck.ids, pair_frames(info, deck, folder, batch.nsteps), batch.nsteps)
    found["lammps"] = (states["a_v"] - states["b_v"], np.hstack([states["a_w"], states["b_w"]]))
    return found


def mean_contact_time(model, t_tr: float, sample: Draws) -> float:
    """The mean contact time of a gas's collisions at ``t_tr`` (the exact references'; spins do not change it
    where the normal force does not feel the tangential)."""
    return float(np.mean(outcomes(model, sample.velocities(t_tr, model.m), np.zeros((len(sample.phase), 6)),
                                  None, None, None)["contact_time"]))


def _energy_changes(model, before, after) -> tuple[np.ndarray, np.ndarray]:
    """Each collision's change of translational (m/4 |g|^2: the pair's centre of mass keeps its own) and
    rotational kinetic energy."""
    (g0, w0), (g1, w1) = before, after
    d_tr = model.m / 4.0 * (np.sum(g1**2, axis=1) - np.sum(g0**2, axis=1))
    d_rot = model.inertia / 2.0 * (np.sum(w1**2, axis=1) - np.sum(w0**2, axis=1))
    return d_tr, d_rot


def averages_at(model, t_tr: float, sample: Draws, dt: float | None = None, folder: Path | None = None,
                crowd: Crowd | None = None) -> dict:
    """Per route (:func:`outcomes`): L at ``t_tr`` (:mod:`spinbounce.exact.kinetic`) and the standard
    errors of its entries (rows 0 and 1) and of its columns' sums (row 2: the energy a collision loses);
    and the mean contact time of the collisions. With a ``crowd`` (and a ``folder``), each route's L
    holds the gas's overlapping contacts too (:mod:`.encounters`: LAMMPS's at ``dt``, in either route),
    and "overlaps" their share alone. Where the law has the planar rule (:mod:`.rule`), each outcome's
    energy change is taken less the rule's, whose exact mean is added back: the same mean, with the
    variance of the small difference."""
    g = sample.velocities(t_tr, model.m)
    scale = math.sqrt(t_tr / model.inertia)
    spins = sample.spin(t_tr, model.inertia)
    runs = {}
    for name, w in (("still", np.zeros_like(spins)), ("spun", spins), ("reversed", -spins)):
        runs[name] = outcomes(model, g, w, dt, sample.phase, None if folder is None else Path(folder) / name)
        runs[name]["before"] = (g, w)
    found = {"contact_time": float(np.mean(runs["still"]["contact_time"]))}
    crowded = None
    if crowd is not None and folder is not None:
        crowded = _columns(crowd.excess(model, t_tr, {"still": 0.0, "spun": scale, "reversed": -scale}, dt,
                                        Path(folder) / "encounters"))
    control = None
    if rule.has_rule(model):  # each collision's change by the planar rule, whose mean is known exactly
        control = {name: np.array(_energy_changes(model, run["before"], rule.outcomes(model, *run["before"])))
                   for name, run in runs.items()}
    for route in ("exact", "lammps") if folder is not None else ("exact",):
        changes = {name: np.array(_energy_changes(model, run["before"], run[route])) for name, run in runs.items()}
        if control is not None:
            changes = {name: change - control[name] for name, change in changes.items()}
        mean, error = _columns(changes)
        if control is not None:
            mean = mean + rule.mean_changes(model, t_tr)
        if crowded is not None:  # independent draws: their means add, and their variances
            mean, error = mean + crowded[0], np.hypot(error, crowded[1])
        found[route] = (mean[:2] / (3.0 * t_tr), error / (3.0 * t_tr))
    if crowded is not None:  # the overlaps' own share, as a record
        found["overlaps"] = (crowded[0][:2] / (3.0 * t_tr), crowded[1] / (3.0 * t_tr))
    return found


def _columns(changes: dict) -> tuple[np.ndarray, np.ndarray]:
    """From each collision's energy changes (rows tr and rot) with spins none, drawn and reversed: the mean
    energy change of L's two columns (rows tr, rot and their sum; the part odd in the spins cancels) and
    their standard errors."""
    still = changes["still"]
    spun = (changes["spun"] + changes["reversed"]) / 2.0 - still
    parts = [np.vstack([part, part.sum(axis=0)]) for part in (still, spun)]  # rows: tr, rot, their sum
    return (np.column_stack([part.mean(axis=1) for part in parts]),
            np.column_stack([part.std(axis=1) / math.sqrt(part.shape[1]) for part in parts]))


def averages(model, temperatures, sample: Draws, dt: float | None = None, folder: Path | None = None,
             crowd: Crowd | None = None) -> dict:
    """Per route: :class:`kinetic.Averages` at each of ``temperatures`` (T_tr) and the largest standard
    error of its L."""
    temperatures = np.sort(np.atleast_1d(np.asarray(temperatures, dtype=float)))
    found = [averages_at(model, t, sample, dt, None if folder is None else Path(folder) / f"T{k}", crowd)
             for k, t in enumerate(temperatures)]
    times = np.array([f["contact_time"] for f in found])
    return {route: (kinetic.Averages(temperatures, np.array([f[route][0] for f in found]), times),
                    np.max([f[route][1] for f in found], axis=0))
            for route in found[0] if route != "contact_time"}
