"""Render a pair batch's deck (``pair.lmp.j2`` beside this module), its data file and bodies file.

Layout: pair k sits in cell k of a cubic grid, its contact point at the cell's centre, its
spheres backed off along their velocities by the pair's lead time (free flight, which the
step integrates exactly) so that they touch that much later; each pair at its time scale
(:attr:`.scene.PairBatch.time_scales`: heavier and slower by it, in an aligned batch). Atom ids: the spheres that
are rigid bodies (alpha other than 2/5) first, then their centre points in the same order,
then the free spheres; the deck's ``ids`` map each pair's a and b to its sphere's id.

``batch`` is this folder's :class:`.scene.PairBatch`, which calls this module
(never the other way round).
"""

from __future__ import annotations

import math

import numpy as np

from pathlib import Path

from ...lammps.data import Atoms, bodies_file, data_file
from ...lammps.decks import Deck, deck_words, render_template, wall_parameters


__all__ = ["render_pairs", "DECK_NAME", "DUMP_NAME", "DATA_FILE", "BODIES_FILE"]

DECK_NAME = "in.lammps"
DUMP_NAME = "state.dump"
DATA_FILE = "pairs.data"
BODIES_FILE = "bodies.txt"
#: The final quantities of each sphere the deck reports, in table order (LAMMPS's frame).
QUANTITIES = tuple(f"{side}_{q}{axis}" for side in "ab" for q in "vw" for axis in "xyz")
#: LAMMPS caps |F_t| <= mu |F_n| and turns the history back into the tangent plane when
#: |xi.n| kt > 1e-10 mu |F_n|. With the wall's no-cap mu = 1e12 that rule does fire in the
#: last steps of a pair's contact (|F_n| -> 0 while xi.n, from the turning line of centres,
#: does not): measured with a step-by-step copy of LAMMPS that matches it to 1e-14, it moves
#: the result by 3e-5 of the impact speed at dt = tau/4700 and depends on dt. With 1e100 the
#: rule and the cap can only fire at |F_n| < 1e-90 |F_t|: the paper's model, with a history
#: that is never rotated (what :mod:`spinbounce.exact.pair_exact` integrates).
PAIR_NO_CAP_MU = 1.0e100


def _spheres(batch) -> tuple[list[dict], float, int]:
    """One record per sphere (pair by pair, a then b): its sphere, start position and
    velocities; and the cell size and the grid's cells per side."""
    reach = max(max(abs(x) for x in (*p.v_a, *p.v_b)) for p in batch.pairs)
    out_speed = max(float(np.max(np.abs(np.concatenate([o.v_a, o.v_b])))) for o in batch.exact)
    travel = math.sqrt(3.0) * max(reach, out_speed) * batch.nsteps * batch.dt
    largest = max(p.radsum for p in batch.pairs)
    cell = 4.0 * (largest + travel)
    grid = math.ceil(round(batch.n ** (1.0 / 3.0), 9))
    records = []
    classes = batch.scale_classes[0]
    for k, (pair, lead) in enumerate(zip(batch.deck_pairs, batch.lead, strict=True)):
        centre = (np.array([k % grid, (k // grid) % grid, k // grid**2]) + 0.5) * cell
        n = np.asarray(pair.normal)
        for side, sphere, v, w, place in (("a", pair.a, pair.v_a, pair.w_a, pair.a.r * n),
                                          ("b", pair.b, pair.v_b, pair.w_b, -pair.b.r * n)):
            records.append({"pair": k, "side": side, "sphere": sphere, "x": centre + place - lead * np.asarray(v),
                            "v": np.asarray(v), "w": np.asarray(w), "class": int(classes[k])})
    return records, cell, grid


def atom_type(kind: str, scale_class: int) -> int:
    """A time-scale class's atom type of each kind: free sphere, rigid sphere, or a rigid one's
    centre point (three types per class, :attr:`.scene.PairBatch.scale_classes`)."""
    return 3 * scale_class + {"free": 1, "rigid": 2, "point": 3}[kind]


def _number_atoms(records: list[dict]) -> tuple[list[dict], list[dict]]:
    """Give each sphere its id and type; the rigid spheres and the free ones, in id order."""
    rigid = [r for r in records if r["sphere"].rigid]
    free = [r for r in records if not r["sphere"].rigid]
    for i, record in enumerate(rigid, start=1):
        record["id"], record["type"] = i, atom_type("rigid", record["class"])
    for i, record in enumerate(free, start=2 * len(rigid) + 1):
        record["id"], record["type"] = i, atom_type("free", record["class"])
    return rigid, free


def _data_file(rigid: list[dict], free: list[dict], box: float, ntypes: int) -> str:
    """The batch's data file: every sphere (a rigid one holding half its mass, its centre point
    the other half; :mod:`spinbounce.lammps.data`)."""
    spheres = rigid + free
    points = [dict(r, id=r["id"] + len(rigid), type=atom_type("point", r["class"])) for r in rigid]
    atoms = Atoms(np.array([r["id"] for r in spheres + points]), np.array([r["type"] for r in spheres + points]),
                  np.array([2 * r["sphere"].r for r in spheres] + [0.0] * len(points)),
                  np.array([r["sphere"].m / 2 if r["sphere"].rigid else r["sphere"].m for r in spheres]
                           + [r["sphere"].m / 2 for r in points]),
                  np.array([r["x"] for r in spheres + points]), np.array([r["v"] for r in spheres + points]),
                  np.array([r["w"] for r in spheres] + [np.zeros(3)] * len(points)))
    return data_file(f"sphere pairs for {DECK_NAME}", atoms, ntypes, ((0.0, box),) * 3)


def _bodies_file(rigid: list[dict]) -> str:
    return bodies_file(np.array([r["id"] for r in rigid]), np.array([r["sphere"].m for r in rigid]),
                       np.array([r["x"] for r in rigid]), np.array([r["sphere"].inertia for r in rigid]),
                       np.array([r["v"] for r in rigid]), np.array([r["w"] for r in rigid]))


def render_pairs(batch) -> Deck:
    """The batch's deck, with its data file (and bodies file, if any sphere is a rigid body)."""
    records, cell, grid = _spheres(batch)
    rigid, free = _number_atoms(records)
    smallest = min(min(p.a.r, p.b.r) for p in batch.pairs)
    model = batch.pairs[0].equivalent_wall(batch.contact)  # the law's words are the wall's, after the types
    wall = wall_parameters(model)
    if batch.contact.mu is None:
        wall.update(mu=PAIR_NO_CAP_MU, comment=f"no Coulomb cap: mu = {PAIR_NO_CAP_MU:g} (spinbounce.scenes.pair.deck)")
    else:
        wall.update(mu=batch.contact.mu, comment=f"Coulomb cap mu = {batch.contact.mu:g}")
    wall["coefficients"] = deck_words(model.style.coefficient_terms(model, wall["eta_n"], wall["x_t"], wall["damping"],
                                                                    wall["mu"]))
    scales = batch.scale_classes[1]
    classes = [{"types": f"{atom_type('free', c)}*{atom_type('point', c)}",
                "coefficients": deck_words(model.style.coefficient_terms(model, wall["eta_n"] * scale, wall["x_t"],
                                                                         True, wall["mu"]))}
               for c, scale in enumerate(scales)]
    files = {DATA_FILE: _data_file(rigid, free, grid * cell, 3 * len(scales))}
    if rigid:
        files[BODIES_FILE] = _bodies_file(rigid)
    text = render_template(
        Path(__file__).parent, "pair.lmp.j2", deck_name=DECK_NAME, npairs=batch.n, grid=grid, cell=cell,
        nsteps=batch.nsteps, dt=batch.dt, skin=0.2 * smallest, binsize=cell / 2, data_file=DATA_FILE,
        contact=batch.contact, wall=wall, nfree=len(free), nrigid=len(rigid), classes=classes,
        types={kind: " ".join(str(atom_type(kind, c)) for c in range(len(scales))) for kind in ("free", "rigid", "point")},
        bodies_file=BODIES_FILE, dump_name=DUMP_NAME)
    ids = np.zeros((batch.n, 2), dtype=np.int64)
    for record in records:
        ids[record["pair"], 0 if record["side"] == "a" else 1] = record["id"]
    return Deck(text=text, name=DECK_NAME, dump=DUMP_NAME, rigid=bool(rigid), files=files, ids=ids)
