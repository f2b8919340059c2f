"""Render a pair batch's deck (``pair.lmp.j2`` beside this module), its data file and bodies file.

Layout: pair k sits in cell k of a cubic grid, its contact point at the cell's centre, its
spheres backed off along their velocities by the pair's lead time (free flight, which the
step integrates exactly) so that they touch that much later; each pair at its time scale
(:attr:`.scene.PairBatch.time_scales`: heavier and slower by it, in an aligned batch). Atom
ids: the spheres that are rigid bodies (alpha other than 2/5) first, then their centre points
in the same order, then the free spheres; the deck's ``ids`` map each pair's a and b to its
sphere's id.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ...lammps.decks import (BODIES_FILE, DECK_NAME, DUMP_NAME, LIBRARY_MARKER, Atoms, Deck, LibraryAtoms,
                             bodies_file, data_file, deck_words, render_template, wall_parameters)

__all__ = ["render_pairs", "pair_law", "DECK_NAME", "DUMP_NAME", "DATA_FILE", "BODIES_FILE"]

DATA_FILE = "pairs.data"
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


def atom_type(kind: str, scale_class) -> int:
    """A time-scale class's atom type of each kind: free sphere, rigid sphere, or a rigid one's
    centre point (three types per class, :attr:`.scene.PairBatch.scale_classes`)."""
    return 3 * scale_class + {"free": 1, "rigid": 2, "point": 3}[kind]


def _spheres(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Per-pair values of spheres a and b, interleaved: one row per sphere, a then b."""
    return np.stack([a, b], axis=1).reshape(-1, *a.shape[1:])


def _in_memory(atoms: Atoms) -> LibraryAtoms:
    """The atoms as the library route hands them over: in id order, with their radii and masses."""
    order = np.argsort(atoms.ids, kind="stable")
    return LibraryAtoms(types=atoms.types[order], x=atoms.x[order], v=atoms.v[order], omega=atoms.w[order],
                        mass=atoms.mass[order], radius=atoms.diameter[order] / 2.0)


def pair_law(pair, contact) -> tuple:
    """The equivalent wall model of ``pair`` under ``contact`` and the deck's words of its law: the wall's
    numbers, ``comment`` and ``coefficients``, what follows ``pair_coeff * *`` (the pair's and the gas's decks)."""
    model = pair.equivalent_wall(contact)  # the law's words are the wall's, after the types
    wall = wall_parameters(model)
    if contact.mu is None:
        wall.update(mu=PAIR_NO_CAP_MU, comment=f"no Coulomb cap: mu = {PAIR_NO_CAP_MU:g} (spinbounce.scenes.pair.deck)")
    else:
        wall.update(mu=contact.mu, comment=f"Coulomb cap mu = {contact.mu:g}")
    wall["coefficients"] = deck_words(model.style.coefficient_terms(model, wall["eta_n"], wall["x_t"], wall["damping"],
                                                                    wall["mu"]))
    return model, wall


def render_pairs(batch, route: str | None = None) -> Deck:
    """The batch's deck, with its data file (and bodies file, if any sphere is a rigid body); ``route``
    "library": its atoms handed over in memory and its states read back from there (no data file and
    no dump to format and parse: a sweep's chunks), a deck that runs only in process."""
    c = batch.columns
    reach = float(np.max(np.abs(_spheres(c["v_a"], c["v_b"]))))
    out_speed = max(float(np.max(np.abs(np.array([getattr(o, v) for o in batch.exact])))) for v in ("v_a", "v_b"))
    travel = math.sqrt(3.0) * max(reach, out_speed) * batch.nsteps * batch.dt
    cell = 4.0 * (float(np.max(c["r_a"] + c["r_b"])) + travel)
    grid = math.ceil(round(batch.n ** (1.0 / 3.0), 9))
    # every sphere, pair by pair (a then b), backed off from its first touch by its pair's lead; each pair
    # at its time scale s (spinbounce.scenes.pair.pairs.time_scaled: masses times s^2, velocities over s)
    k = np.repeat(np.arange(batch.n), 2)
    centre = (np.column_stack([k % grid, (k // grid) % grid, k // grid**2]) + 0.5) * cell
    scale = np.repeat(batch.time_scales, 2)
    place = _spheres(c["r_a"][:, None] * c["normal"], -c["r_b"][:, None] * c["normal"])
    v = _spheres(c["v_a"], c["v_b"]) / scale[:, None]
    w = _spheres(c["w_a"], c["w_b"]) / scale[:, None]
    x = centre + place - np.repeat(batch.lead, 2)[:, None] * v
    rigid = _spheres(c["rigid_a"], c["rigid_b"]).astype(bool)
    of_class = np.repeat(batch.scale_classes[0], 2)
    # ids: the rigid spheres first, then their centre points in the same order, then the free ones
    nrigid, nfree = int(rigid.sum()), int((~rigid).sum())
    ids = np.empty(2 * batch.n, dtype=np.int64)
    ids[rigid], ids[~rigid] = np.arange(1, nrigid + 1), np.arange(2 * nrigid + 1, 2 * nrigid + nfree + 1)
    mass, radius = _spheres(c["m_a"], c["m_b"]) * scale**2, _spheres(c["r_a"], c["r_b"])
    # a rigid sphere holds half its mass, its centre point (no spin of its own) the other half
    held = np.where(rigid, mass / 2, mass)
    atoms = Atoms(np.concatenate([ids, ids[rigid] + nrigid]),
                  np.concatenate([np.where(rigid, atom_type("rigid", of_class), atom_type("free", of_class)),
                                  atom_type("point", of_class[rigid])]),
                  np.concatenate([2 * radius, np.zeros(nrigid)]), np.concatenate([held, mass[rigid] / 2]),
                  np.vstack([x, x[rigid]]), np.vstack([v, v[rigid]]), np.vstack([w, np.zeros((nrigid, 3))]))
    smallest = float(np.min(radius))
    model, wall = pair_law(batch.pairs[0], batch.contact)
    scales = batch.scale_classes[1]
    power = model.damping_law.eta_time_power  # how ETA_N follows each class's time scale
    classes = [{"types": f"{atom_type('free', c)}*{atom_type('point', c)}",
                "coefficients": deck_words(model.style.coefficient_terms(model, wall["eta_n"] * scale**power,
                                                                         wall["x_t"], True, wall["mu"]))}
               for c, scale in enumerate(scales)]
    box = ((0.0, grid * cell),) * 3
    library = route == "library"
    atoms, memory = (None, _in_memory(atoms)) if library else (atoms, None)
    files = {} if library else {DATA_FILE: data_file(f"sphere pairs for {DECK_NAME}", atoms, 3 * len(scales), box)}
    if nrigid:
        inertia = (_spheres(c["alpha_a"], c["alpha_b"]) * mass * radius**2)[rigid]
        files[BODIES_FILE] = bodies_file(ids[rigid], mass[rigid], x[rigid], inertia, v[rigid], w[rigid])
    text = render_template(
        Path(__file__).parent, "pair.lmp.j2", deck_name=DECK_NAME, npairs=batch.n, grid=grid, cell=cell,
        nsteps=batch.nsteps, dt=batch.dt, skin=0.2 * smallest, binsize=cell / 2, data_file=DATA_FILE,
        contact=batch.contact, wall=wall, nfree=nfree, nrigid=nrigid, classes=classes,
        types={kind: " ".join(str(atom_type(kind, c)) for c in range(len(scales))) for kind in ("free", "rigid", "point")},
        bodies_file=BODIES_FILE, dump_name=None if library else DUMP_NAME, box=box, ntypes=3 * len(scales),
        library_marker=LIBRARY_MARKER)
    return Deck(text=text, name=DECK_NAME, dump=None if library else DUMP_NAME, rigid=bool(nrigid), files=files,
                ids=ids.reshape(-1, 2), atoms=memory)
