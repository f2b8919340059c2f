"""A collision run's table: LAMMPS's first and last frames beside the theory, one row per sphere.

LAMMPS's frame -> the paper's: :func:`~spinbounce.lammps.decks.wall_frame`. Frames come from
the dump, or from LAMMPS's memory for a library-route deck; both are checked (lost spheres,
non-finite values, a contact that had not finished) before the table is made.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ...errors import ResultError
from ...lammps.decks import wall_frame

if TYPE_CHECKING:
    from ...lammps.decks import Deck
    from ...lammps.runner import RunInfo

__all__ = ["collision_table", "read_collision", "FRAME_COLUMNS"]

#: The spin columns and the angular velocity each one carries.
SPINS = {"r_omega": "omega", "r_omega_s": "omega_s", "r_omega_n": "omega_n"}


def collision_table(scene, initial, final) -> dict[str, np.ndarray]:
    """One row per sphere: requested, initial (as LAMMPS saw it), final, theory and error.

    ``initial`` and ``final`` map LAMMPS's column names (z, vx, vz, omegay, ...) to one
    value per sphere in id order (ids 1..n): a dump frame or a dict of arrays. The theory
    acts on the *requested* initial state, so a mangled input would show as an error.
    A 3-D scene adds the columns of :data:`STATE_3D` beyond the paper's three. A time-scaled
    sphere's velocities and spins are LAMMPS's times its scale (:attr:`Collision.time_scales`).
    """
    r, names, scales = scene.model.r, scene.state_names, scene.time_scales[:, None]
    spins = tuple(SPINS[s] for s in names if s in SPINS)
    columns = {"id": np.arange(1, scene.n + 1)}
    columns.update({f"{name}_initial": value for name, value in zip(names, scene.initial.T)})
    columns.update({f"{spin}_initial": np.asarray(getattr(scene, spin)) for spin in spins})
    for when, frame in (("lammps_initial", initial), ("lammps", final)):
        # the state at r = 1: its spins are the angular velocities, in the paper's signs
        v, w = (np.column_stack([frame[f"{q}{axis}"] for axis in "xyz"]) * scales for q in ("v", "omega"))
        state = wall_frame(v, w, 1.0)
        values = {name: r * state[:, k] if name in SPINS else state[:, k] for k, name in enumerate(names)}
        values.update({SPINS[name]: state[:, k] for k, name in enumerate(names) if name in SPINS})
        values["z"] = np.asarray(frame["z"])
        columns.update({f"{name}_{when}": values[name] for name in names + spins + ("z",)})
    theory = scene.predicted()
    columns.update({f"{name}_theory": theory[:, k] for k, name in enumerate(names)})
    columns.update({f"{SPINS[n]}_theory": columns[f"{n}_theory"] / r for n in names if n in SPINS})
    for name in names + spins:
        columns[f"{name}_error"] = columns[f"{name}_lammps"] - columns[f"{name}_theory"]
    return columns


#: Per-sphere columns of a collision frame, as LAMMPS names them (the dump's columns).
FRAME_COLUMNS = ("x", "y", "z", "vx", "vy", "vz", "omegax", "omegay", "omegaz")


def read_collision(scene, info: RunInfo, deck: Deck, folder: Path) -> dict:
    """The run's checked table columns (from its dump, or from memory for a library-route deck)."""
    if deck.dump is None:  # a library-route run: the spheres (type-1 atoms) LAMMPS held at steps 0 and nsteps
        source, frames = info.log, {}
        for step, state in ((0, info.initial), (scene.nsteps, info.final)):
            keep = state["type"] == 1
            keep = slice(None) if keep.all() else keep  # no wall atoms: views, not copies
            frames[step] = {"id": state["id"][keep].astype(np.int64),
                            **{f"{name}{axis}": state[key][keep, k] for key, name in (("x", ""), ("v", "v"),
                                                                                     ("omega", "omega"))
                               for k, axis in enumerate("xyz")}}
    else:
        from ...lammps.dumps import read_dump  # pandas: loaded only for a dump

        source = folder / deck.dump
        frames = {int(step): {name: rows[name].to_numpy() for name in ("id", *FRAME_COLUMNS)}
                  for step, rows in read_dump(source).groupby("step")}
    # checked: frames at the first and last step, every sphere there in id order, finite
    steps = sorted(frames)
    if steps != [0, scene.nsteps]:
        raise ResultError(f"{source}: expected frames at steps 0 and {scene.nsteps}, found {steps}")
    for step in steps:
        frame = frames[step]
        if len(frame["id"]) != scene.n:
            raise ResultError(f"{source}: {len(frame['id'])} of {scene.n} spheres at step {step} "
                              "(lost atoms)")
        if not np.array_equal(frame["id"], np.arange(1, scene.n + 1)):
            raise ResultError(f"{source}: sphere ids at step {step} are not 1..{scene.n} in order")
        finite = np.logical_and.reduce([np.isfinite(frame[c]) for c in FRAME_COLUMNS])
        if not finite.all():
            raise ResultError(
                f"{source}: non-finite positions or velocities (first at step {step}, "
                f"atom {int(frame['id'][~finite][0])}): the integration blew up"
            )
    initial, final = frames[0], frames[scene.nsteps]
    columns = collision_table(scene, initial, final)
    touching = np.flatnonzero(columns["z_lammps"] <= scene.model.r)
    if touching.size:
        first = touching[0]
        raise ResultError(
            f"{source}: {touching.size} sphere(s) still touch the wall after {scene.nsteps} steps "
            f"(first: id {int(columns['id'][first])}, z = {float(columns['z_lammps'][first])!r}): "
            "the contact had not finished"
        )
    return columns
