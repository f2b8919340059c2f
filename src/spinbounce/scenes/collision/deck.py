"""The collision deck (``collision.lmp.j2`` beside this module): its spheres inline, in a data
file or handed over in memory (:data:`ATOM_ROUTES`), and optional padding for ``bench``.

``scene`` is this folder's :class:`.scene.Collision`, which calls this module
(never the other way round).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...lammps.data import Atoms, bodies_file, data_file
from ...lammps.decks import (ATOM_ROUTES, BODIES_FILE, DATA_FILE, DECK_NAME, DUMP_NAME, INLINE_SPHERES, LIBRARY_MARKER,
                             Deck, LibraryAtoms, common_context, render_template)


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



def _collision_state(scene, padding: Padding) -> dict[str, np.ndarray]:
    """Per-sphere LAMMPS vectors: position, velocity, angular velocity (omega_y = -omega,
    omega_x = omega_s, omega_z = omega_n)."""
    n = scene.n
    zeros = np.zeros(n)
    return {
        "x": zeros, "y": zeros, "z": scene.model.r + padding.lift(scene.v_n),
        "vx": np.asarray(scene.v_t), "vy": np.asarray(scene.v_s), "vz": np.asarray(scene.v_n),
        "wx": np.asarray(scene.omega_s), "wy": -np.asarray(scene.omega) + 0.0, "wz": np.asarray(scene.omega_n),
    }


def _data_file(scene, state: dict, rigid: bool, box: dict) -> str:
    """The collision's data file: its spheres (and, for rigid bodies, their centre points)."""
    model, n = scene.model, scene.n
    ids = np.arange(1, n + 1)
    x = np.column_stack([state["x"], state["y"], state["z"]])
    v = np.column_stack([state["vx"], state["vy"], state["vz"]])
    w = np.column_stack([state["wx"], state["wy"], state["wz"]])
    spheres = Atoms(ids, np.ones(n, dtype=int), np.full(n, 2.0 * model.r), np.full(n, model.m / 2 if rigid else model.m),
                    x, v, w)  # the deck sets each mass exactly afterwards
    if rigid:
        spheres = Atoms(np.concatenate([ids, ids + n]), np.concatenate([spheres.types, np.full(n, 2)]),
                        np.concatenate([spheres.diameter, np.zeros(n)]), np.full(2 * n, model.m / 2),
                        np.vstack([x, x]), np.vstack([v, v]), np.vstack([w, np.zeros_like(w)]))
    sides = ((box["xlo"], box["xhi"]), (box["ylo"], box["yhi"]), (0.0, box["zhi"]))
    return data_file(f"{n} spheres for {DECK_NAME}", spheres, 2 if rigid else 1, sides)


def _bodies_file(scene, state: dict) -> str:
    model, n = scene.model, scene.n
    return bodies_file(np.arange(1, n + 1), np.full(n, model.m), np.column_stack([state["x"], state["y"], state["z"]]),
                       np.full(n, model.inertia), np.column_stack([state["vx"], state["vy"], state["vz"]]),
                       np.column_stack([state["wx"], state["wy"], state["wz"]]))


def _library_atoms(scene, state: dict, rigid: bool) -> LibraryAtoms:
    n = scene.n
    x = np.column_stack([state["x"], state["y"], state["z"]])
    v = np.column_stack([state["vx"], state["vy"], state["vz"]])
    omega = np.column_stack([state["wx"], state["wy"], state["wz"]])
    types = np.ones(n, dtype=np.int32)
    if rigid:  # the centre points: same position and velocity, no spin of their own
        x, v = np.vstack([x, x]), np.vstack([v, v])
        omega = np.vstack([omega, np.zeros_like(omega)])
        types = np.concatenate([types, np.full(n, 2, dtype=np.int32)])
    return LibraryAtoms(types=types, x=x, v=v, omega=omega)


def render_collision(scene, atoms: str | None = None, padding: Padding | None = None) -> Deck:
    """The collision deck. ``atoms``: one of :data:`ATOM_ROUTES`; by default inline up to
    :data:`INLINE_SPHERES` spheres and a data file beyond (either way ``lmp -in`` reruns it).
    ``padding``: work beyond the contact, for measuring its cost (:class:`Padding`)."""
    model = scene.model
    padding = Padding() if padding is None else padding
    if atoms is None:
        atoms = "inline" if scene.n <= INLINE_SPHERES else "data_file"
    if atoms not in ATOM_ROUTES:
        raise ValueError(f"atoms = {atoms!r}: must be one of {ATOM_ROUTES}")
    state = _collision_state(scene, padding)
    # room for the lifted start and for the flight away from the wall in the extra time
    fastest = float(np.max(np.abs(scene.v_n)))
    headroom = float(np.max(padding.lift(scene.v_n))) + fastest * (padding.before + padding.after)
    ctx = common_context(model, zhi=4.0 * model.r + headroom)
    rigid = ctx["rigid"]
    files = {}
    spheres = []
    if atoms == "data_file":
        files[DATA_FILE] = _data_file(scene, state, rigid, ctx["box"])
    elif atoms == "inline":
        spheres = [
            {"id": i + 1, **{k: float(v[i]) for k, v in state.items()}} for i in range(scene.n)
        ]
    if rigid and atoms != "inline":
        files[BODIES_FILE] = _bodies_file(scene, state)
    library = atoms == "library"
    # the header's run length: Hertzian contacts end at different times, the slowest last
    tau = float(np.max(model.normal_law.force_times(model, scene.v_n)))
    ctx.update(n=scene.n, spheres=spheres, tau=tau, dt=scene.dt, nsteps=scene.nsteps,
               run_steps=scene.nsteps + padding.extra_steps(scene.dt), padding=padding,
               padding_dump=PADDING_DUMP_NAME, atoms=atoms, library_marker=LIBRARY_MARKER, data_file=DATA_FILE)
    text = render_template(Path(__file__).parent, "collision.lmp.j2", **ctx)
    return Deck(text=text, rigid=rigid, files=files, dump=None if library else DUMP_NAME,
                atoms=_library_atoms(scene, state, rigid) if library else None)
