"""Overlapping contacts: what a gas's three-sphere encounters change beyond its isolated collisions.

At a packing phi a sphere sometimes meets a second partner while it still touches the first: about
2 omega t_c of a gas's collisions overlap another (omega the collision rate, t_c a contact's time).
Binary-collision theory counts each as an isolated collision; where the contact law almost conserves
energy pairwise (the paper's magic ratio), the overlaps lose more than the pairs (at packing 0.05,
kn = 1e4 and T_rot = T_tr, more than twice), at a rate that grows as phi t_c. This module measures
their share of the matrix L of :mod:`spinbounce.exact.kinetic`.

An encounter: sphere A touches B at time 0 (a collision drawn as :mod:`.collisions` draws them) and a
third sphere C at time s. C's velocity is Maxwellian and its line of centres n_C uniform; each draw is
weighted by the closing speed w_C = ((v_A - v_C).n_C)+ with which C meets A. Per collision of A, the
others of A arrive at omega per unit time, so the energies change per collision beyond the isolated
pairs' mean by

    omega J,   J = < w_C (2 S) dE(s) > / <w>,   <w> = sqrt(T_tr / (pi m)),

S = max(t_AB, t_AC) the longer of the two isolated contacts' times (per draw), s uniform in (-S, S),
dE the excess: the three spheres' energy change less those of A with B alone and A with C alone
(common draws), zero where the contacts do not overlap (s outside (-t_AC, t_AB)) or cannot happen
(B and C would start overlapping). Each unordered
overlap is met from both of its collisions, and a sphere's energy change is half its collision's, so
omega J adds to a collision's mean energy change exactly as a pair's own dE does.

LAMMPS runs every encounter at the gas's step, each alone in its cell, in three cells: A, B and C;
A and B; A and C. B and C never touch (``neigh_modify exclude``): the encounter is A's two
contacts. A meeting of B and C after both leave A is another collision of the gas, which the binary
theory counts; in about 2% of the kept draws they would come within a diameter while one still
touches A, a four-contact event left out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...errors import ResultError
from ...exact import kinetic
from ...lammps.decks import DECK_NAME, Deck, LibraryAtoms, prepare_run_dir, render_template
from ...lammps.runner import LIBRARY_MARKER, run_deck
from ..pair.kind import equal_pair
from ..pair.pairs import equivalent_wall
from .deck import law_words

__all__ = ["EncounterDraws", "encounter_draws", "encounter_count", "Crowd", "placements", "cell_side", "CELL"]

#: A cell's least side, in diameters; wider where a sphere could reach further during the run (:func:`cell_side`).
CELL = 8.0
#: A run lasts this many windows S (an encounter spans at most two; A meeting B or C again lengthens it).
RUN_WINDOWS = 6.0
#: The largest share of encounters whose contacts may still be open at the run's end (counted as none: A
#: caught between B and C, which pass through each other, meets them again and again; 4e-4 of them at the
#: magic ratio, 6e-3 at kt/kn = 0.1 in a gas at 1e-5 of its starting temperature).
MOST_UNFINISHED = 0.02
#: The cells of one encounter: A with B and C, A with B, A with C.
KINDS = (("a", "b", "c"), ("a", "b"), ("a", "c"))


@dataclass(frozen=True)
class EncounterDraws:
    """Unit variates of ``count`` encounters (scaled to each temperature: common random numbers): the lines
    of centres A->B (``first``) and A->C (``second``), the AB pair's centre-of-mass velocity (``centre``),
    its relative velocity's tangential part and closing speed (Rayleigh), C's velocity (``third``), the
    spins of A, B, C (``spins``, (count, 9)), s / S (``offset``) and the phase of a step at first touch."""

    first: np.ndarray
    second: np.ndarray
    centre: np.ndarray
    tangential: np.ndarray
    closing: np.ndarray
    third: np.ndarray
    spins: np.ndarray
    offset: np.ndarray
    phase: np.ndarray

    @property
    def count(self) -> int:
        return len(self.offset)


def encounter_count(draws: int) -> int:
    """Encounters drawn beside a theory's ``draws`` collisions: half as many (at least 1,000). Each costs about
    seven spheres' runs in three variants (130 us here, three times a pair's); with the planar rule as the
    pairs' control variate their standard error is still the larger part of the theory's (with a quarter as
    many, 10,000 beside 40,000 draws, the theory's drift over 12 collisions at the magic ratio, packing 0.05,
    had a standard error of 0.11 points)."""
    return max(1000, draws // 2)


def encounter_draws(count: int, seed: int) -> EncounterDraws:
    rng = np.random.default_rng([seed, 3])
    normal = [rng.standard_normal((count, 3)) for _ in range(5)]
    return EncounterDraws(normal[0], normal[1], normal[2], normal[3], np.sqrt(-2.0 * np.log1p(-rng.random(count))),
                          normal[4], rng.standard_normal((count, 9)), rng.uniform(-1.0, 1.0, count), rng.random(count))


def _unit(a: np.ndarray) -> np.ndarray:
    return a / np.linalg.norm(a, axis=1)[:, None]


@dataclass(frozen=True)
class Placements:
    """The encounters kept at one temperature (``kept``: their indices among the draws): the three spheres'
    positions and velocities at the run's start ((k, 3, 3): encounter, sphere A B C, axis), each one's
    ``weight`` w_C 2S / <w>, and the longest window S (what a run must cover)."""

    kept: np.ndarray
    x: np.ndarray
    v: np.ndarray
    weight: np.ndarray
    window: float


def placements(model, t_tr: float, sample: EncounterDraws, dt: float) -> Placements:
    """Where each drawn encounter starts at ``t_tr``: A at the origin at time 0, when B touches it (B at
    sigma n_1), C touching A at time s (A moving straight), everything moved back to a start a phase
    of a step before the first touch; drawn encounters that cannot happen are dropped."""
    sigma, m = 2.0 * model.r, model.m
    n1, n2 = _unit(sample.first), _unit(sample.second)
    tangential = sample.tangential - np.sum(sample.tangential * n1, axis=1)[:, None] * n1
    g = math.sqrt(2.0 * t_tr / m) * (tangential + sample.closing[:, None] * n1)  # v_A - v_B: closing along n1
    centre = math.sqrt(t_tr / (2.0 * m)) * sample.centre
    v_a, v_b, v_c = centre + g / 2.0, centre - g / 2.0, math.sqrt(t_tr / m) * sample.third
    w_c = np.maximum(0.0, np.sum((v_a - v_c) * n2, axis=1))
    sphere, contact = equal_pair(model)
    wall = equivalent_wall(sphere, sphere, contact)
    t_ab = wall.contact_times(np.sum(g * n1, axis=1))
    meets = w_c > 0.0
    t_ac = np.zeros_like(w_c)
    t_ac[meets] = wall.contact_times(w_c[meets])
    window = np.maximum(t_ab, t_ac)  # per draw: one slow contact (Hertz: t_c grows as w^-1/5) widens no other
    s = sample.offset * window
    start = np.minimum(0.0, s) - sample.phase * dt
    x_a, x_b = v_a * start[:, None], sigma * n1 + v_b * start[:, None]
    x_c = v_a * s[:, None] + sigma * n2 + v_c * (start - s)[:, None]
    kept = np.nonzero(meets & (s > -t_ac) & (s < t_ab) & (np.linalg.norm(x_b - x_c, axis=1) > sigma))[0]
    weight = w_c[kept] * 2.0 * window[kept] / math.sqrt(t_tr / (math.pi * m))
    return Placements(kept, np.stack([x_a, x_b, x_c], axis=1)[kept], np.stack([v_a, v_b, v_c], axis=1)[kept],
                      weight, float(window[kept].max(initial=0.0)))


@dataclass(frozen=True)
class Crowd:
    """A gas's crowding: its ``packing`` (the collision rate that brings the third spheres) and the encounters
    drawn for it."""

    packing: float
    sample: EncounterDraws

    def excess(self, model, t_tr: float, spins: dict, dt: float, folder: Path) -> dict:
        """Per spin variant (``spins``: name -> the spins' scale sqrt(T_rot / I) and sign), each drawn
        encounter's omega w_C 2S dE / <w> ((2, count): translational and rotational; zero where none
        is kept): averaged over the draws, what the overlaps add to a collision's mean energy change."""
        placed = placements(model, t_tr, self.sample, dt)
        if len(placed.kept) == 0:  # nothing can overlap: nothing to add
            return {name: np.zeros((2, self.sample.count)) for name in spins}
        omega = float(kinetic.enskog_rate(t_tr, self.packing, 2.0 * model.r, model.m))
        spin = {name: scale * self.sample.spins[placed.kept].reshape(-1, 3, 3) for name, scale in spins.items()}
        changes = _run(model, placed, spin, dt, folder)
        out = {}
        for name, change in changes.items():
            full = np.zeros((2, self.sample.count))
            full[:, placed.kept] = omega * placed.weight * change
            out[name] = full
        return out


def cell_side(model, placed: Placements, spin: dict, duration: float) -> float:
    """A cell's side: CELL diameters, or wider where a sphere could leave it within ``duration``. No sphere moves
    faster than its encounter's whole kinetic energy allows (its three spheres', the largest spin variant's
    rotation included: the contact law gives none back beyond it), so each stays within its start's distance from
    the cell's centre (A's place at first touch) plus that speed times the run; a diameter more keeps it from
    the next cell's spheres. A soft capped Hertz-Mindlin gas (E = 1e5, mu 0.3) at T_tr = 1 needs 12 diameters: its
    slowest impacts' contacts last long enough that CELL's 8 let a sphere out."""
    sigma = 2.0 * model.r
    rotation = np.max([0.5 * model.inertia * np.sum(w**2, axis=(1, 2)) for w in spin.values()], axis=0)
    energy = 0.5 * model.m * np.sum(placed.v**2, axis=(1, 2)) + rotation
    reach = np.linalg.norm(placed.x, axis=2).max(axis=1) + np.sqrt(2.0 * energy / model.m) * duration
    return max(CELL * sigma, 2.0 * (float(reach.max()) + sigma))


def _centres(count: int, cell: float) -> tuple[np.ndarray, int]:
    """The centres of ``count`` cells ``cell`` wide, filling a cube of cells row by row, and the cube's side in
    cells."""
    side = max(1, math.ceil(round(count ** (1.0 / 3.0), 9)))
    return (np.stack(np.unravel_index(np.arange(count), (side, side, side)), axis=1) + 0.5) * cell, side


def _cells(placed: Placements, spin: dict, cell: float) -> tuple[LibraryAtoms, np.ndarray, float]:
    """Every variant's three cells per encounter (each ``cell`` wide), as atoms (types 1, 2, 3: A, B, C), each
    atom's cell, and the box's side."""
    k = len(placed.kept)
    count = len(spin) * len(KINDS) * k
    corner, side = _centres(count, cell)
    x, v, w, types, cells = [], [], [], [], []
    for c, (spins, kind) in enumerate((s, kind) for s in spin.values() for kind in KINDS):
        for j, name in enumerate("abc"):
            if name in kind:
                rows = c * k + np.arange(k)
                x.append(corner[rows] + placed.x[:, j]), v.append(placed.v[:, j]), w.append(spins[:, j])
                types.append(np.full(k, j + 1)), cells.append(rows)
    return LibraryAtoms(np.concatenate(types), np.concatenate(x), np.concatenate(v), np.concatenate(w)), \
        np.concatenate(cells), side * cell


def _run(model, placed: Placements, spin: dict, dt: float, folder: Path) -> dict:
    """LAMMPS's encounters: per variant, each encounter's excess (dE_tr, dE_rot), (2, k)."""
    k = len(placed.kept)
    nsteps = math.ceil(RUN_WINDOWS * placed.window / dt) + 1
    cell = cell_side(model, placed, spin, nsteps * dt)
    atoms, cells, box = _cells(placed, spin, cell)
    n = len(cells)
    atoms = LibraryAtoms(atoms.types, atoms.x, atoms.v, atoms.omega, np.full(n, model.m), np.full(n, model.r))
    text = render_template(Path(__file__).parent, "encounters.lmp.j2", deck_name=DECK_NAME, count=k, box=box,
                           cell=cell, skin=0.2 * model.r, binsize=cell / 2.0, marker=LIBRARY_MARKER,
                           dt=dt, nsteps=nsteps, law=law_words(model))
    deck = Deck(text=text, name=DECK_NAME, dump=None, atoms=atoms)
    info = run_deck(prepare_run_dir(folder, deck, durable=False), atoms)
    unfinished = np.zeros(len(spin) * len(KINDS) * k, dtype=bool)
    unfinished[_open_cells(info.final, cells, 2.0 * model.r, cell, folder)] = True
    unfinished = unfinished.reshape(-1, k).any(axis=0)
    if unfinished.mean() > MOST_UNFINISHED:
        raise ResultError(f"{folder}: {int(unfinished.sum())} of {k} encounters still touch at the run's end")
    energies = []
    for state in (info.initial, info.final):
        tr = 0.5 * model.m * np.sum(state["v"] ** 2, axis=1)
        rot = 0.5 * model.inertia * np.sum(state["omega"] ** 2, axis=1)
        size = len(spin) * len(KINDS) * k
        energies.append(np.stack([np.bincount(cells, tr, size), np.bincount(cells, rot, size)]))
    change = (energies[1] - energies[0]).reshape(2, len(spin), 3, k)
    return {name: np.where(unfinished, 0.0, change[:, i, 0] - change[:, i, 1] - change[:, i, 2])
            for i, name in enumerate(spin)}


def _open_cells(final: dict, cells: np.ndarray, sigma: float, cell: float, folder: Path) -> np.ndarray:
    """The cells whose contacts with A are still open at the run's end; refused: a sphere out of its cell (which
    :func:`cell_side` allows only where energy was gained, or a position is not finite)."""
    x = final["x"]
    if not np.all(np.abs(x - _centres(int(cells.max()) + 1, cell)[0][cells]) <= cell / 2.0):
        raise ResultError(f"{folder}: an encounter's sphere left its cell (or a position is not finite)")
    order = np.argsort(cells, kind="stable")  # each cell's A first
    first = np.r_[True, cells[order][1:] != cells[order][:-1]]
    a = np.repeat(x[order][first], np.diff(np.r_[np.nonzero(first)[0], len(order)]), axis=0)
    gaps = np.linalg.norm(x[order] - a, axis=1)[~first]
    return np.unique(cells[order][~first][gaps <= sigma])
