"""Render LAMMPS input decks from scenes.

One Jinja2 template per scene lives in ``lammps_inputs/``. The templates use ``<< >>``
and ``<% %>`` delimiters, which cannot collide with LAMMPS's own ``${...}`` and
``$(...)``, and an undefined name is an error, never an empty string.

Geometry: the wall is the plane z = 0 with normal +z, the tangential direction is +x,
and the paper's anticlockwise omega is -omega_y (so slip = v_x - r*omega_y).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import jinja2
import numpy as np

from .. import __version__
from ..model.scenes import Collision, ContactModel, Frozen
from .data import Atoms, bodies_file, data_file, deck_number

__all__ = ["Deck", "LibraryAtoms", "Padding", "render_collision", "render_frozen", "wall_parameters", "template_dir",
           "LIBRARY_MARKER", "ATOM_ROUTES"]

DECK_NAME = "in.lammps"
DUMP_NAME = "state.dump"
BODIES_FILE = "bodies.txt"
DATA_FILE = "spheres.data"
#: Up to this many spheres the deck sets every atom inline (the deck alone is the input);
#: beyond it the atoms go to a data file beside the deck (``set atom`` is O(N) per line).
INLINE_SPHERES = 64
#: How a collision deck gets its atoms: set inline in the deck, read from a data file
#: beside it, or handed to LAMMPS in memory through the library interface (sweeps: no
#: text to format or parse, so the run loop is nearly all of a batch's time).
ATOM_ROUTES = ("inline", "data_file", "library")
#: The line of a library-route deck at which the runner creates the atoms.
LIBRARY_MARKER = "# >>> atoms are created here through the LAMMPS library interface <<<"
#: fix nve/sphere's own moment of inertia (I = 2/5 m r^2); any other alpha makes the sphere a
#: rigid body with a point mass at its centre. Declared here only.
ALPHA_NVE_SPHERE = 0.4
#: The every-step dump of a padded collision deck (:class:`Padding`).
PADDING_DUMP_NAME = "every.dump"


def template_dir() -> Path:
    """``lammps_inputs/``: inside the installed package, or at the source tree's top."""
    package = Path(__file__).resolve().parent.parent  # spinbounce/
    for candidate in (package / "lammps_inputs", package.parent.parent / "lammps_inputs"):
        if candidate.is_dir():
            return candidate
    raise FileNotFoundError(f"lammps_inputs/ not found next to {package}")


@lru_cache(maxsize=1)
def template_environment() -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(template_dir())),
        undefined=jinja2.StrictUndefined,
        block_start_string="<%",
        block_end_string="%>",
        variable_start_string="<<",
        variable_end_string=">>",
        comment_start_string="<#",
        comment_end_string="#>",
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        autoescape=False,
    )
    env.filters["num"] = deck_number
    return env


@dataclass(frozen=True)
class LibraryAtoms:
    """Atoms a library-route deck receives in memory at :data:`LIBRARY_MARKER`.

    Rows are atoms in id order (ids 1..N): the spheres, then (rigid route) their centre
    points. ``omega`` is set on the spheres only; the final state is read back from memory.
    """

    types: np.ndarray  # (N,) int
    x: np.ndarray  # (N, 3)
    v: np.ndarray  # (N, 3)
    omega: np.ndarray  # (N, 3)


@dataclass(frozen=True)
class Deck:
    """A rendered deck and the names of the files it reads and writes (relative to its folder).

    ``dump`` is None for a library-route deck, which writes no dump: its runner reads the
    final state from LAMMPS's memory.
    """

    text: str
    name: str = DECK_NAME
    dump: str | None = DUMP_NAME
    rigid: bool = False
    files: dict = field(default_factory=dict)  # other inputs it reads: name -> text
    atoms: LibraryAtoms | None = None


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


def wall_parameters(model: ContactModel) -> dict:
    """The wall's part of a deck, from the model's style and sub-models (:mod:`spinbounce.laws`):
    its numbers, its ``comment``, and ``style``, the one text after ``wall/gran`` that every deck
    and printed line uses (each word from a registry, each number in full precision)."""
    wall = model.style.wall_terms(model)
    wall["style"] = deck_words(wall.pop("terms"))
    return wall


def deck_words(terms) -> str:
    """A law's terms as deck text: each word as it is (a registry's), each number in full precision."""
    return " ".join(deck_number(x) if isinstance(x, float) else x for x in terms)


def fix_line(model: ContactModel, group: str = "all") -> str:
    """The ``fix wall/gran`` line of a flat wall at z = 0 (the one spinbounce runs), to paste."""
    return f"fix wall {group} wall/gran {wall_parameters(model)['style']} zplane 0.0 NULL"


def _common(model: ContactModel, zhi: float) -> dict:
    rigid = model.alpha != ALPHA_NVE_SPHERE
    span = 10.0 * model.r
    return {
        "version": __version__,
        "model": model,
        "wall": wall_parameters(model),
        "rigid": rigid,
        "ntypes": 2 if rigid else 1,
        "sphere_mass": model.m / 2 if rigid else model.m,
        "point_mass": model.m / 2,
        "inertia": model.inertia,
        "bodies_file": BODIES_FILE,
        "deck_name": DECK_NAME,
        "dump_name": DUMP_NAME,
        "box": {"xlo": -span, "xhi": span, "ylo": -span, "yhi": span, "zhi": zhi},
    }


def _collision_state(scene: Collision, padding: Padding) -> dict[str, np.ndarray]:
    """Per-sphere LAMMPS vectors: position, velocity, angular velocity (omega_y = -omega,
    omega_x = omega_s, omega_z = omega_n)."""
    n = scene.n
    zeros = np.zeros(n)
    return {
        "x": zeros, "y": zeros, "z": scene.model.r + padding.lift(scene.v_n),
        "vx": np.asarray(scene.v_t), "vy": np.asarray(scene.v_s), "vz": np.asarray(scene.v_n),
        "wx": np.asarray(scene.omega_s), "wy": -np.asarray(scene.omega) + 0.0, "wz": np.asarray(scene.omega_n),
    }


def _data_file(scene: Collision, state: dict, rigid: bool, box: dict) -> str:
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


def _bodies_file(scene: Collision, state: dict) -> str:
    model, n = scene.model, scene.n
    return bodies_file(np.arange(1, n + 1), np.full(n, model.m), np.column_stack([state["x"], state["y"], state["z"]]),
                       np.full(n, model.inertia), np.column_stack([state["vx"], state["vy"], state["vz"]]),
                       np.column_stack([state["wx"], state["wy"], state["wz"]]))


def _library_atoms(scene: Collision, state: dict, rigid: bool) -> LibraryAtoms:
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


def render_collision(scene: Collision, atoms: str | None = None, padding: Padding | None = None) -> Deck:
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
    ctx = _common(model, zhi=4.0 * model.r + headroom)
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
    text = template_environment().get_template("collision.lmp.j2").render(**ctx)
    return Deck(text=text, rigid=rigid, files=files, dump=None if library else DUMP_NAME,
                atoms=_library_atoms(scene, state, rigid) if library else None)


def render_frozen(scene: Frozen) -> Deck:
    model = scene.model
    ctx = _common(model, zhi=4.0 * model.r)
    ctx.update(
        z=scene.z, vx=scene.v_t, wy=-scene.omega, dt=scene.dt, nsteps=scene.nsteps, every=scene.every
    )
    text = template_environment().get_template("frozen.lmp.j2").render(**ctx)
    return Deck(text=text, rigid=ctx["rigid"])
