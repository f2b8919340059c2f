"""The collision deck (``collision.lmp.j2`` beside this module): its spheres inline, in a data
file or handed over in memory (:data:`ATOM_ROUTES`), and optional padding for ``bench``."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...lammps.decks import (ATOM_ROUTES, BODIES_FILE, DATA_FILE, DECK_NAME, DUMP_NAME, INLINE_SPHERES, LIBRARY_MARKER,
                             Atoms, Deck, LibraryAtoms, bodies_file, common_context, data_file,
                             lammps_vectors, render_template)

__all__ = ["Padding", "render_collision", "PADDING_DUMP_NAME"]

#: The every-step dump of a padded collision deck (:class:`Padding`).
PADDING_DUMP_NAME = "every.dump"


@dataclass(frozen=True)
class Padding:
    """Work a collision run can do beyond the contact, to measure what it costs (``spinbounce
    bench``): ``before`` time units of free flight to the wall (each sphere starts |v_n|
    ``before`` higher), ``after`` more time once the contact run would have ended, and a dump
    of every sphere each ``dump_every`` steps into :data:`PADDING_DUMP_NAME`. The physics is
    the same; the default pads nothing."""

    before: float = 0.0
    after: float = 0.0
    dump_every: int | None = None

    def lift(self, v_n) -> np.ndarray:
        """Each sphere's start above touching the wall."""
        return np.abs(np.asarray(v_n, dtype=float)) * self.before

    def extra_steps(self, dt: float) -> int:
        return math.ceil((self.before + self.after) / dt)


def render_collision(scene, atoms: str | None = None, padding: Padding | None = None) -> Deck:
    """The collision deck. ``atoms``: one of :data:`ATOM_ROUTES`; by default inline up to
    :data:`INLINE_SPHERES` spheres and a data file beyond (either way ``lmp -in`` reruns it).
    ``padding``: work beyond the contact, for measuring its cost (:class:`Padding`).

    A time-scaled batch (:attr:`.scene.Collision.time_scales`) gives each sphere s times slower
    velocities and spins and s^2 times its mass (and inertia), on every route: set per atom
    inline, in the data file, passed in memory (LAMMPS's per-atom rmass), and in the bodies
    file of the rigid route; its table multiplies the final states by s again."""
    model, n = scene.model, scene.n
    padding = Padding() if padding is None else padding
    if atoms is None:
        atoms = "inline" if n <= INLINE_SPHERES else "data_file"
    if atoms not in ATOM_ROUTES:
        raise ValueError(f"atoms = {atoms!r}: must be one of {ATOM_ROUTES}")
    scales = scene.time_scales
    v_n = np.asarray(scene.v_n) / scales  # the speeds the deck runs: lifts and headroom follow them
    x = np.column_stack([np.zeros(n), np.zeros(n), model.r + padding.lift(v_n)])
    state = (scene.v_n, scene.v_t, scene.omega, scene.v_s, scene.omega_s, scene.omega_n)
    v, w = (a / scales[:, None] for a in lammps_vectors(*state))
    mass, inertia = model.m * scales**2, model.inertia * scales**2
    # room for the lifted start and for the flight away from the wall in the extra time
    fastest = float(np.max(np.abs(v_n)))
    headroom = float(np.max(padding.lift(v_n))) + fastest * (padding.before + padding.after)
    # along the wall in one step, with all of r omega turned into sliding (a spin can leave as v_t)
    reach = (float(np.max(np.abs(v[:, :2]))) + model.r * float(np.max(np.abs(w)))) * scene.dt
    ctx = common_context(model, zhi=4.0 * model.r + headroom, reach=reach)
    rigid = ctx["rigid"]
    # a rigid sphere (id k, type 1) holds half its mass, the point at its centre (id n + k, type 2,
    # no spin of its own) the other half
    k = ctx["ntypes"]
    every_x, every_v, every_w = np.tile(x, (k, 1)), np.tile(v, (k, 1)), np.vstack([w, np.zeros_like(w)])[: k * n]
    every_mass = np.tile(mass / k, k)
    types = np.repeat([1, 2], n)[: k * n]
    files = {}
    spheres = []
    if atoms == "data_file":
        box = ctx["box"]
        spheres_file = Atoms(np.arange(1, k * n + 1), types, np.repeat([2.0 * model.r, 0.0], n)[: k * n],
                             every_mass, every_x, every_v, every_w)  # unless scaled, the deck sets each mass
        sides = ((box["xlo"], box["xhi"]), (box["ylo"], box["yhi"]), (0.0, box["zhi"]))
        files[DATA_FILE] = data_file(f"{n} spheres for {DECK_NAME}", spheres_file, k, sides)
    elif atoms == "inline":
        names = ("x", "y", "z", "vx", "vy", "vz", "wx", "wy", "wz")
        spheres = [{"id": i + 1, **dict(zip(names, map(float, (*x[i], *v[i], *w[i])))),
                    "mass": float(mass[i]), "held": float(mass[i] / k), "inertia": float(inertia[i])}
                   for i in range(n)]
    if rigid and atoms != "inline":
        files[BODIES_FILE] = bodies_file(np.arange(1, n + 1), mass, x, inertia, v, w)
    library = atoms == "library"
    # the header's run length: Hertzian contacts end at different times, the slowest last (a
    # time-scaled batch's all at once)
    ctx.update(n=n, spheres=spheres, tau=scene.force_time, dt=scene.dt, nsteps=scene.nsteps,
               run_steps=scene.nsteps + padding.extra_steps(scene.dt), padding=padding,
               padding_dump=PADDING_DUMP_NAME, atoms=atoms, library_marker=LIBRARY_MARKER,
               data_file=DATA_FILE, scaled=scene.time_scaled,
               scales={"low": float(scales.min()), "high": float(scales.max())})
    text = render_template(Path(__file__).parent, "collision.lmp.j2", **ctx)
    held = every_mass if scene.time_scaled else None  # in memory: each atom's own mass
    memory = LibraryAtoms(types.astype(np.int32), every_x, every_v, every_w, held) if library else None
    return Deck(text=text, rigid=rigid, files=files, dump=None if library else DUMP_NAME, atoms=memory)
