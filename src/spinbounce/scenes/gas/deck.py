"""Render a gas's deck (``gas.lmp.j2`` beside this module) and its data file: the spheres on a
jittered cubic lattice, a random subset of its sites (every draw from the gas's seed)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...lammps.decks import DECK_NAME, Atoms, Deck, data_file, render_template
from ..pair.deck import pair_law
from ..pair.pairs import Pair
from ..pair.kind import equal_pair
from .scene import BURN, LATTICE_GAP, SETTLE

__all__ = ["render_gas", "SERIES_FILE", "CONTACTS_FILE", "DATA_FILE"]

DATA_FILE = "gas.data"
SERIES_FILE = "gas.energies"
CONTACTS_FILE = "gas.contacts"


def lattice_positions(gas) -> np.ndarray:
    """(N, 3) centres: N distinct sites of a cubic lattice filling the box, each moved at random by up to
    half its spare room (the spacing less a diameter and the gap) along each axis."""
    rng = np.random.default_rng(gas.seed)
    side = gas.lattice_side
    spacing = gas.box / side
    sites = rng.choice(side**3, size=gas.spheres, replace=False)
    cells = np.column_stack([sites % side, (sites // side) % side, sites // side**2])
    room = max(0.0, spacing - gas.sigma * (1.0 + LATTICE_GAP)) / 2.0
    return (cells + 0.5) * spacing + rng.uniform(-room, room, size=(gas.spheres, 3))


def law_words(model) -> dict:
    """The pair law of two of a gas's spheres (the pair deck's words: :func:`..pair.deck.pair_law`)."""
    sphere, contact = equal_pair(model)
    return pair_law(Pair(sphere, sphere), contact)[1]


def render_gas(gas, measure: bool = True) -> Deck:
    """The gas's deck and data file; ``measure`` False: the bare deck, which measures nothing (its cost beside
    the measured one is what the measurement costs: spinbounce bench)."""
    m, n = gas.model, gas.spheres
    x = lattice_positions(gas)
    zeros = np.zeros((n, 3))
    atoms = Atoms(np.arange(1, n + 1), np.ones(n, dtype=int), np.full(n, gas.sigma), np.full(n, m.m), x, zeros, zeros)
    dof = 3.0 * n - 3.0  # LAMMPS's temperature after mom yes; the gas's is 2 KE / (3 N)
    files = {DATA_FILE: data_file(f"a gas of {n} spheres", atoms, 1, ((0.0, gas.box),) * 3)}
    text = render_template(
        Path(__file__).parent, "gas.lmp.j2", deck_name=DECK_NAME, n=n, packing=gas.packing, box=gas.box,
        t_tr=gas.t_tr, t_rot=gas.t_rot, skin=0.2 * gas.sigma, sigma=gas.sigma, mass=m.m, data_file=DATA_FILE,
        law=law_words(gas.model), dt=gas.dt, settle_steps=gas.settle_steps, settle=SETTLE, seed=gas.seed,
        burn_steps=gas.burn_steps, burn=BURN,
        spin_scale=math.sqrt(m.m * gas.t_rot * 3.0 * n / dof / m.inertia), t_create=gas.t_tr * 3.0 * n / dof,
        interval=gas.interval, contact_every=gas.contact_every, contact_repeat=gas.interval // gas.contact_every,
        series_file=SERIES_FILE, contacts_file=CONTACTS_FILE, nsteps=gas.nsteps, measure=measure)
    return Deck(text=text, name=DECK_NAME, dump=None, files=files)
