"""Pair scenes: two free spheres that meet once, many such pairs in one run.

A :class:`Pair` is given at the moment its spheres first touch: sphere b's centre at the
origin, a's at (r_a + r_b) ``normal``, with any velocities and spins (LAMMPS's frame and
sign: omega is LAMMPS's angular velocity). A :class:`PairBatch` holds pairs that share
one contact law (:class:`PairContact`) and one step, and works out what the deck needs:
the exact reference of each pair (:mod:`spinbounce.exact.pair_exact`), the step, and
how long before touching each pair starts (:attr:`PairBatch.lead`: where its first-order errors
cancel best) and, in an aligned batch, the time scale each pair runs at in the deck
(:attr:`PairBatch.time_scales`: every contact then ends in the middle of a step).

Each sphere's m, r and alpha, and the contact's kn, kt, gamma_n and gamma_t, are checked
against their declaration (:mod:`spinbounce.model.parameters`). Every pair is also checked
as its equivalent wall contact (reduced mass, :func:`exact.pair.equivalent_alpha`):
critical damping, the step's stability and resolution.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ... import checks
from ...lammps.decks import ALPHA_NVE_SPHERE
from ...errors import PhysicsWarning
from ...model.contact import ContactModel
from ...model.parameters import SceneError
from ...model.stability import overlap_stretch
from ...model.timestep import MAX_STEPS, check_steps, steps_per_contact, steps_through
from ..jump import beyond_reach, near_the_jump, slow_start, warn_slow_start
from .contact import PairContact
from .columns import pair_columns
from .pairs import Pair, Sphere, slip_speeds, time_scaled  # noqa: F401 (time_scaled: exported)
from .deck import PAIR_NO_CAP_MU, render_pairs

__all__ = ["Sphere", "PairContact", "Pair", "PairBatch", "ALPHA_NVE_SPHERE", "PAIR_STEPS_PER_HALF_PERIOD",
           "time_scaled"]

#: The finest default resolution: steps per half-period of the fastest mode of any pair, what
#: a batch falls back to when a probe of its own pairs cannot reach the accuracy coarser
#: (:func:`spinbounce.stepping.tune`). Two errors are first order in dt for pairs, unlike the wall: LAMMPS's
#: pair granular (this build) projects the half-step relative velocity on the full-step line
#: of centres, which turns; and one step shared by pairs of different contact times cannot
#: put every contact in its best place within the steps (:attr:`PairBatch.lead`).
#: Largest error against the exact reference over the 24 cases of studies.cases(), with
#: the placement of :attr:`PairBatch.lead`: 5.8e-5 of the speed at this resolution.
PAIR_STEPS_PER_HALF_PERIOD = 8000
#: A batch runs this fraction of its longest contact beyond the last pair's end (:attr:`PairBatch.nsteps`).
CONTACT_MARGIN = 0.05
#: The probe's coarser run: steps per contact (the wall's rule takes 174 at its defaults).
START_STEPS = 100
#: The most time-scale classes (atom types per kind of sphere) of an aligned damped batch.
SCALE_CLASSES = 32
#: A probe may take a batch up to this many times its fine rule's steps. At the rule itself four of a
#: helper's capped Mindlin pairs missed 1e-4 (1.04e-4 to 4.4e-4), each converging at first order, which
#: their probes had measured; probed on, they met it at 1.7 to 8.2 times the rule's steps (5.0e-5 to 6.4e-5).
RULE_REACH = 16


#: What a batch computes of its pairs and law alone, whatever its step, by name: (pairs, contact, value) of the
#: last SHARED batches that computed it (a batch at another step, of the same tuple of pairs, takes it from there:
#: a chunk's probe and its runs alternate). Each holds up to a chunk's outcomes, ~1 kB a pair.
SHARED = 2
_LAST: dict[str, list[tuple]] = {}


def _shared(batch: "PairBatch", name: str, compute):
    """``compute()`` of ``batch``, or the same value of a recent batch of the same pairs and law."""
    recent = _LAST.setdefault(name, [])
    for k, (pairs, contact, value) in enumerate(recent):
        if pairs is batch.pairs and contact == batch.contact:
            recent.append(recent.pop(k))  # the most recently used, dropped last
            return value
    value = compute()
    recent.append((batch.pairs, batch.contact, value))
    del recent[:-SHARED]
    return value


@dataclass(frozen=True)
class PairBatch:
    """Pairs run together, each in its own cell. ``dt = None``: PAIR_STEPS_PER_HALF_PERIOD steps
    per half-period of the fastest mode of any pair (``default_step``: a run probes for a
    coarser one, :func:`spinbounce.stepping.tune`); a given dt must keep every pair stable.
    ``aligned``: each pair runs at its own time scale (:attr:`time_scales`; a damped batch's
    from a few classes), what the probed step assumes; off, every pair runs at ``dt``. ``rule_reach``: how
    many times its fine rule's steps a probe may take it to (:meth:`step_limit`; a sweep's chunk, whose rows
    beyond the accuracy run again alone and whose job was sized at the rule, 1)."""

    pairs: tuple = (Pair(),)
    contact: PairContact = field(default_factory=PairContact)
    dt: float | None = None
    aligned: bool = False
    rule_reach: int = RULE_REACH
    default_step: bool = field(init=False)

    def __post_init__(self):
        object.__setattr__(self, "default_step", self.dt is None)
        pairs = (self.pairs,) if isinstance(self.pairs, Pair) else tuple(self.pairs)
        if not pairs or not all(isinstance(p, Pair) for p in pairs):
            raise SceneError("pairs", self.pairs, "must be one or more Pair")
        object.__setattr__(self, "pairs", pairs)
        for model, k in self._fastest():  # a mode no run resolves, refused before a step is computed from it
            speed = self.impact_speeds[k]
            model.check_resolvable(float(model.contact_times(-speed)[0]), speed, "against the pair's contact",
                                   2 * len(pairs))
        if self.dt is None:  # the wall's limits of the default step, for each distinct equivalent contact
            for model, _ in self.wall_groups:
                model.replace(mu=self.contact.mu).check_default_step()
            dt = min(math.pi / m.fastest_rate(frozen=False, speed=self.impact_speeds[k]) / PAIR_STEPS_PER_HALF_PERIOD
                     for m, k in self._fastest())
        else:
            dt = self.dt
        # each check grows with |v_n| (the stiffest rate, the deepest overlap): the fastest pair of each
        # equivalent contact stands for all of its pairs
        for model, k in self._fastest():
            dt = model.check_dt(dt, frozen=False, speed=self.impact_speeds[k])
            # the deepest overlap, stretched by the step as for the wall, must stay below the smaller
            # radius, or the smaller centre would enter the larger sphere
            reach = float(model.max_overlap(self.impact_speeds[k]))
            reach *= overlap_stretch(model.normal_law.normal_mode(model, self.impact_speeds[k])[0], dt)
            smaller = min(pairs[k].a.r, pairs[k].b.r)  # not the equivalent wall's r (R_eff on the contact radius)
            if reach >= smaller:
                raise SceneError(f"pairs[{k}].v_n", pairs[k].v_n, "|v_n| is too large: the overlap would reach "
                                 f"{reach:.6g} >= the smaller radius {smaller:g}")
        object.__setattr__(self, "dt", dt)
        if self.default_step:
            warn_slow_start(self.walls[0], self.slow_start())
        else:  # a given step: refused if no run may take it
            check_steps(self.nsteps, "dt", dt, "to end the longest contact", spheres=2 * len(pairs))

    @property
    def n(self) -> int:
        return len(self.pairs)

    @cached_property
    def walls(self) -> tuple[ContactModel, ...]:
        """Each pair's equivalent wall contact (:meth:`Pair.equivalent_wall`), built once per spheres (and
        shared by the batches of the same pairs and law: a probe's and a ladder's at their steps)."""
        return _shared(self, "walls", self._walls)

    def _walls(self) -> tuple[ContactModel, ...]:
        made: dict = {}
        for p in self.pairs:  # a batch's pairs share a few sphere objects: looked up by identity first
            if (id(p.a), id(p.b)) not in made:
                made[id(p.a), id(p.b)] = p.equivalent_wall(self.contact)
        return tuple(made[id(p.a), id(p.b)] for p in self.pairs)

    @cached_property
    def wall_groups(self) -> tuple[tuple[ContactModel, np.ndarray], ...]:
        """The distinct equivalent walls of the batch, each with the indices of its pairs."""
        return _shared(self, "wall_groups", self._wall_groups)

    def _wall_groups(self) -> tuple[tuple[ContactModel, np.ndarray], ...]:
        groups: dict[int, tuple[ContactModel, list]] = {}
        for k, wall in enumerate(self.walls):
            groups.setdefault(id(wall), (wall, []))[1].append(k)
        return tuple((wall, np.array(index)) for wall, index in groups.values())

    @cached_property
    def impact_speeds(self) -> np.ndarray:
        """Each pair's impact speed |v_n| (its error's scale is :func:`.pairs.speeds`)."""
        c = self.columns
        return np.abs(np.einsum("mi,mi->m", c["v_a"] - c["v_b"], c["normal"]))

    def _fastest(self) -> list[tuple[ContactModel, int]]:
        """Each distinct equivalent wall with the index of its fastest pair."""
        return [(wall, int(index[np.argmax(self.impact_speeds[index])])) for wall, index in self.wall_groups]

    @cached_property
    def exact(self) -> tuple:
        """Each pair's exact outcome (:meth:`PairContact.solve`: what LAMMPS integrates)."""
        return _shared(self, "exact", lambda: self.contact.solve_all(self.pairs))

    @cached_property
    def held(self) -> tuple:
        """Each pair's exact outcome with its line of centres held (:meth:`PairContact.solve`, planar)."""
        return _shared(self, "held", lambda: self.contact.solve_all(self.pairs, planar=True))

    @cached_property
    def time_scales(self) -> np.ndarray:
        """Per pair, how many times slower its time runs in the deck (:func:`time_scaled`).

        One step shared by pairs of different contact times T puts their contacts' ends at
        different phases g = frac(T/dt) of a step, and LAMMPS's error is first order in dt
        unless g = 1/2 (:attr:`lead`). Run in time units lambda = (floor(T/dt) + 1/2)/(T/dt)
        times longer, a pair's contact lasts a whole number of steps and a half: each pair
        has in effect its own step dt/lambda, within half a step per contact of the batch's.
        Measured on one pair (eps 0.84), LAMMPS's error at g = 1/2 is what is left, and the
        probe of :mod:`.stepping` sees it. A damped contact's damping force must scale with
        lambda too, which the deck can only do per atom type: its pairs take the nearest of
        :data:`SCALE_CLASSES` values (:attr:`scale_classes`). All ones unless ``aligned``.
        """
        if not self.aligned:
            return np.ones(self.n)
        if self.contact.damped:
            index, values = self.scale_classes
            return values[index]
        ends = self.contact_times / self.dt
        return (np.floor(ends) + 0.5) / ends

    @cached_property
    def scale_classes(self) -> tuple[np.ndarray, np.ndarray]:
        """Each pair's time-scale class and the classes' scales: one class (scale 1) unless the
        batch is aligned and damped. Then :data:`SCALE_CLASSES` scales 1 + (k - K/2)/(K N), N the
        fewest steps of any contact, sweep the phase g of every contact's end through a whole
        step; each pair takes the class whose g is nearest 1/2, within about 1/(2K) of it
        (where a contact lasts much longer than the shortest, proportionally more)."""
        if not (self.aligned and self.contact.damped):
            return np.zeros(self.n, dtype=int), np.ones(1)
        ends = self.contact_times / self.dt
        values = 1.0 + (np.arange(SCALE_CLASSES) - SCALE_CLASSES / 2) / (SCALE_CLASSES * ends.min())
        phase = np.outer(ends, values) % 1.0
        index = np.argmin(np.abs(phase - 0.5), axis=1)
        used, index = np.unique(index, return_inverse=True)
        return index, values[used]

    @cached_property
    def columns(self) -> dict[str, np.ndarray]:
        """The pairs as arrays: per sphere ``x`` of ``a`` and ``b``, its ``m_x``, ``r_x``, ``alpha_x`` and
        ``rigid_x`` (N,) and its ``v_x`` and ``w_x`` (N, 3); and the ``normal`` (N, 3)."""
        return _shared(self, "columns", self._columns)

    def _columns(self) -> dict[str, np.ndarray]:
        out = pair_columns(self.pairs)
        for values in out.values():  # shared with the batches of the same pairs (_shared): never changed in place
            values.setflags(write=False)
        return out

    @cached_property
    def lead(self) -> np.ndarray:
        """Time in the deck from each pair's start to its first touch, in [0, dt).

        Where a contact of length T sits within the steps decides LAMMPS's first-order error:
        with touch at a fraction phi of a step and release at a fraction psi, the history's
        first increment counts phi dt of slip that never happened, and the last force acts
        (psi - 1/2) dt too short; for a planar slip both move the final slip velocity along
        the same direction, by dt (phi + 1/2 - psi) times one factor, so they cancel when
        psi = phi + 1/2, which needs T/dt to end in a half (g = frac(T/dt) = 1/2). Measured
        (one pair, eps 1e-4, 200 steps): 2e-6 of the speed there, 4.6e-4 at g = 1/4 for
        any phi. For other g the error is least, |g - 1/2| times that factor, when touch and
        release fall in one step's count (phi < 1 - g); phi = (1 - g)/2, the middle of that
        range, was the best of eight measured placements at g = 1/2.
        """
        ends = self.deck_contact_times / self.dt
        fraction = ends - np.floor(ends)
        return 0.5 * (1.0 - fraction) * self.dt

    @cached_property
    def contact_times(self) -> np.ndarray:
        return np.array([o.contact_time for o in self.exact])

    @property
    def deck_contact_times(self) -> np.ndarray:
        return self.contact_times * self.time_scales

    @property
    def nsteps(self) -> int:
        """Steps that carry every pair past the end of its contact, CONTACT_MARGIN of the longest more (and
        one more): a contact LAMMPS ends later than the reference (a coarse step; a state near its law's
        jump) is then measured and reported, not lost."""
        longest = float(np.max(self.deck_contact_times))
        return steps_through(float(np.max(self.lead + self.deck_contact_times)) + CONTACT_MARGIN * longest, self.dt)

    # --- what the pipeline and the step probe ask of every scene (spinbounce.scenes) ---

    kind = "pair"

    def render(self, atoms: str | None = None):
        """The deck (:func:`.deck.render_pairs`): its atoms from a data file, or ``atoms`` "library"
        (the route a sweep's and a probe's runs take) in memory."""
        return render_pairs(self, atoms)

    def read(self, info, deck, folder) -> dict:
        from .table import read_pairs

        return read_pairs(self, deck, folder, info)

    def row_states(self, columns: dict) -> checks.RowStates:
        """Both spheres' velocities and r times spins (LAMMPS's frame): LAMMPS's, the exact
        reference's and the initial ones; errors in units of each pair's speed."""
        c = self.columns
        radii = {side: c[f"r_{side}"][:, None] for side in "ab"}

        def states(suffix: str) -> np.ndarray:
            return np.column_stack([np.column_stack([columns[f"{side}_{q}{x}{suffix}"] for x in "xyz"])
                                    * (radii[side] if q == "w" else 1.0) for side in "ab" for q in "vw"])

        initial = np.column_stack([c[f"{q}_{side}"] * (radii[side] if q == "w" else 1.0)
                                   for side in "ab" for q in "vw"])
        weights = np.column_stack([np.repeat((c[f"m_{side}"] * (c[f"alpha_{side}"] if q == "w" else 1.0))[:, None], 3,
                                             axis=1) for side in "ab" for q in "vw"])
        overlap = np.empty(self.n)
        for wall, index in self.wall_groups:
            overlap[index] = wall.max_overlap(self.impact_speeds[index])
        return checks.RowStates(initial, states(""), states("_theory"), weights, columns["speed"], overlap,
                                columns["r_a"] + columns["r_b"])

    def record(self, deck) -> dict:
        cap = self.contact.mu if self.contact.mu is not None else f"none ({PAIR_NO_CAP_MU:g})"
        return {"contact": self.contact.law() | dict(self.contact.words), "dt": self.dt, "nsteps": self.nsteps,
                "mu": cap}

    def needs_probe(self) -> bool:
        return True

    def probe_time(self, sample: "PairBatch") -> float:
        """The probe's contact time: the median of its pairs'."""
        return float(np.median(sample.contact_times))

    def first_probe_steps(self, t_contact: float) -> int:
        """START_STEPS a contact, or as many as the coarsest step every pair accepts needs (MIN_STEPS_PER_HALF_PERIOD
        of its fastest mode: a stiff Hertzian pair refused the first probe's step, and so the default)."""
        coarsest = min(model.coarsest_dt(False, self.impact_speeds[k]) for model, k in self._fastest())
        return max(START_STEPS, steps_per_contact(t_contact, coarsest))

    def step_limit(self, t_contact: float) -> int:
        """``rule_reach`` times the fine rule's steps per contact: a probe that needs as many keeps the fine rule;
        with a pair LAMMPS converges to slowly (:meth:`slow_start`), where the rule falls short, a quarter of a
        run's limit."""
        reach = self.rule_reach * steps_per_contact(t_contact, self.dt)
        return MAX_STEPS // 4 if np.any(self.slow_start()) else reach

    def slow_start(self) -> np.ndarray:
        """Per pair, whether LAMMPS converges to it slowly from its first step (:func:`spinbounce.scenes.jump.
        slow_start` of its equivalent wall at its own v_n and slip speed)."""
        return self._as_wall(slow_start)

    def near_the_jump(self) -> np.ndarray:
        """Per pair, whether its law's outcome jumps just below it (:func:`spinbounce.scenes.jump.near_the_jump`
        of its equivalent wall at its own v_n and slip speed)."""
        return self._as_wall(near_the_jump)

    def beyond_reach(self) -> np.ndarray:
        """Per pair, whether no affordable step reaches the target (:func:`spinbounce.scenes.jump.beyond_reach`)."""
        return self._as_wall(beyond_reach)

    def _as_wall(self, test) -> np.ndarray:
        """``test(model, states)`` per pair, of its equivalent wall at its own v_n and slip speed."""
        if not self.contact.mu:  # no cap, or a cap of zero: no friction, no jump
            return np.zeros(self.n, dtype=bool)
        out = np.zeros(self.n, dtype=bool)
        for wall, index in self.wall_groups:
            chosen = [self.pairs[k] for k in index]
            states = np.column_stack([[p.v_n for p in chosen], slip_speeds(chosen), np.zeros(len(chosen))])
            out[index] = test(wall.replace(mu=self.contact.mu), states)
        return out

    def fallback(self) -> "PairBatch":
        """The batch at its fine rule's step, aligned."""
        return PairBatch(self.pairs, self.contact, self.dt, aligned=True)

    def rows(self, index) -> "PairBatch":
        with warnings.catch_warnings(action="ignore", category=PhysicsWarning):  # this batch's own: warned once
            return PairBatch(tuple(self.pairs[i] for i in index), self.contact)

    def at_step(self, dt: float) -> "PairBatch":
        return PairBatch(self.pairs, self.contact, dt, aligned=True)
