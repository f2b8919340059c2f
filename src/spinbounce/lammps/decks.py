"""What every deck shares: the Deck itself, templates, the wall's words, the sphere's inertia,
and the files a deck reads beside it (the data file of spheres, ``read_data``, and the rigid
bodies' file, ``fix rigid ... infile``).

Each scene renders its own deck from its own template, in its folder
(:mod:`spinbounce.scenes`); this module gives them one way to do it. Templates use
``<< >>`` and ``<% %>`` delimiters, which cannot collide with LAMMPS's own ``${...}`` and
``$(...)``, and an undefined name is an error, never an empty string. Numbers are written in
their shortest round-trip form, so LAMMPS reads exactly the values the scene holds.

A sphere whose alpha is not fix nve/sphere's 2/5 is a rigid body of two atoms: the sphere,
holding half its mass, and a point (diameter 0) at its centre holding the other half, whose
inertia the bodies file sets.

Geometry: the wall is the plane z = 0 with normal +z, the tangential direction is +x,
and the paper's anticlockwise omega is -omega_y (so slip = v_x - r*omega_y); in 3-D v_s is
v_y, omega_s is omega_x (slip v_y + r omega_x) and omega_n is omega_z (:func:`lammps_vectors`,
:func:`wall_frame`). A pair uses the same frame, its line of centres along z.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .. import __version__
from ..records import arrow_table, write_atomic
from .runner import LIBRARY_MARKER

if TYPE_CHECKING:
    from ..model.contact import ContactModel

__all__ = ["Deck", "LibraryAtoms", "wall_parameters", "render_template", "deck_words", "fix_line", "common_context",
           "prepare_run_dir", "lammps_vectors", "wall_frame", "Atoms", "data_file", "bodies_file", "table",
           "deck_number", "LIBRARY_MARKER", "ATOM_ROUTES", "ALPHA_NVE_SPHERE", "RESULT_TABLE"]

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
#: fix nve/sphere's own moment of inertia (I = 2/5 m r^2); any other alpha makes the sphere a
#: rigid body with a point mass at its centre. Declared here only.
ALPHA_NVE_SPHERE = 0.4
#: A batch's per-row table, beside result.json, when it has more rows than a record holds inline.
RESULT_TABLE = "result.parquet"


def deck_number(x) -> str:
    """A float in full precision (repr round-trips exactly)."""
    v = float(x)
    if not math.isfinite(v):
        raise ValueError(f"non-finite number {v!r} in a deck")
    return repr(v + 0.0)  # + 0.0 turns -0.0 into 0.0


def table(columns: list[np.ndarray]) -> str:
    """Space-separated rows; every float in its shortest round-trip form (exact on reading).

    Written by Arrow's CSV writer: about five times faster than ``numpy.savetxt``.
    """
    import pyarrow as pa
    import pyarrow.csv as pacsv

    arrays = arrow_table({f"c{i}": np.asarray(c) for i, c in enumerate(columns)})
    sink = pa.BufferOutputStream()
    pacsv.write_csv(arrays, sink, pacsv.WriteOptions(include_header=False, delimiter=" ", quoting_style="none"))
    return sink.getvalue().to_pybytes().decode()


@dataclass(frozen=True)
class Atoms:
    """The atoms of a data file: ids, types, diameters and masses, positions x, velocities v and
    angular velocities w ((n, 3) each). A point (diameter 0) is written with its mass as its
    'density', as LAMMPS reads it; a sphere with mass over volume."""

    ids: np.ndarray
    types: np.ndarray
    diameter: np.ndarray
    mass: np.ndarray
    x: np.ndarray
    v: np.ndarray
    w: np.ndarray

    @property
    def density(self) -> np.ndarray:
        d = np.asarray(self.diameter, dtype=float)
        volume = math.pi * d**3 / 6.0
        return np.where(d > 0.0, np.asarray(self.mass, dtype=float) / np.where(d > 0.0, volume, 1.0), self.mass)


def data_file(title: str, atoms: Atoms, ntypes: int, box: tuple) -> str:
    """A data file (atom_style sphere): ``box`` is ((xlo, xhi), (ylo, yhi), (zlo, zhi)); atoms in
    id order."""
    order = np.argsort(atoms.ids, kind="stable")
    x, v, w = (np.asarray(a, dtype=float)[order] for a in (atoms.x, atoms.v, atoms.w))
    ids = np.asarray(atoms.ids)[order]
    rows = table([ids, np.asarray(atoms.types)[order], np.asarray(atoms.diameter, dtype=float)[order],
                  atoms.density[order], x[:, 0], x[:, 1], x[:, 2]])
    velocities = table([ids, v[:, 0], v[:, 1], v[:, 2], w[:, 0], w[:, 1], w[:, 2]])
    sides = "".join(f"{deck_number(lo)} {deck_number(hi)} {axis}lo {axis}hi\n" for axis, (lo, hi) in zip("xyz", box))
    return (f"spinbounce {__version__}: {title}\n\n{len(ids)} atoms\n{ntypes} atom types\n\n{sides}\n"
            f"Atoms # sphere\n\n{rows}\nVelocities\n\n{velocities}")


def bodies_file(ids: np.ndarray, mass: np.ndarray, x: np.ndarray, inertia: np.ndarray, v: np.ndarray,
                w: np.ndarray) -> str:
    """fix rigid infile: id mass xcm ycm zcm ixx iyy izz ixy ixz iyz vxcm vycm vzcm lx ly lz ix iy iz,
    one body per sphere (a sphere's moment of inertia is the same about every axis)."""
    n = len(ids)
    i, zeros = np.asarray(inertia, dtype=float), np.zeros(n)
    x, v, w = (np.asarray(a, dtype=float) for a in (x, v, w))
    columns = [np.asarray(ids), np.asarray(mass, dtype=float), x[:, 0], x[:, 1], x[:, 2], i, i, i, zeros, zeros, zeros,
               v[:, 0], v[:, 1], v[:, 2], i * w[:, 0], i * w[:, 1], i * w[:, 2], zeros, zeros, zeros]
    return f"{n}\n" + table(columns)


#: The templates' delimiters and whitespace rules (in the bytecode cache's file names: a cached template
#: compiled under other rules is not read).
_OPTIONS = dict(block_start_string="<%", block_end_string="%>", variable_start_string="<<", variable_end_string=">>",
               comment_start_string="<#", comment_end_string="#>", trim_blocks=True, lstrip_blocks=True,
               keep_trailing_newline=True, autoescape=False)
_OPTIONS_DIGEST = hashlib.sha1(repr(sorted(_OPTIONS.items())).encode()).hexdigest()[:12]


@lru_cache(maxsize=None)
def _environment(folder: str):
    import jinja2  # when a deck is rendered, not when a scene is built

    env = jinja2.Environment(loader=jinja2.FileSystemLoader(folder), undefined=jinja2.StrictUndefined,
                             bytecode_cache=_bytecode_cache(jinja2), **_OPTIONS)
    env.filters["num"] = deck_number
    return env


def _bytecode_cache(jinja2):
    """Compiled templates kept between processes in jinja's own per-user cache folder (its files checked
    against each template's source, named by this version and the environment's delimiters): a sweep, and
    each of its workers, skips 40 ms of compiling. A cache that cannot be read or written is passed by (the
    template compiled as without one); none where the system's temporary folder cannot hold it."""

    class Cache(jinja2.FileSystemBytecodeCache):
        def load_bytecode(self, bucket):
            try:
                super().load_bytecode(bucket)
            except OSError:
                pass

        def dump_bytecode(self, bucket):
            try:
                super().dump_bytecode(bucket)
            except OSError:  # a full disk, or a folder removed by a cleaner meanwhile
                pass

    try:
        return Cache(pattern=f"__spinbounce_{__version__}_{_OPTIONS_DIGEST}_%s.cache")
    except (OSError, RuntimeError):  # jinja's errors for a cache folder it cannot make or trust
        return None


def render_template(folder: Path, name: str, **context) -> str:
    """The template ``name`` of a scene's ``folder``, rendered with ``context`` (and the version)."""
    return _environment(str(Path(folder).resolve())).get_template(name).render(version=__version__, **context)


@dataclass(frozen=True)
class LibraryAtoms:
    """Atoms a library-route deck receives in memory at :data:`LIBRARY_MARKER`.

    Rows are atoms in id order (ids 1..N): the spheres, then (rigid route) their centre
    points. ``omega`` is set on the spheres only; the final state is read back from memory.
    ``mass``: each atom's own mass (LAMMPS's per-atom rmass), for a batch whose spheres differ
    in mass (a time-scaled one); None: the deck sets the masses per type. ``radius``: each atom's
    own radius (a pair batch's spheres and their centre points, 0), set before the masses.
    """

    types: np.ndarray  # (N,) int
    x: np.ndarray  # (N, 3)
    v: np.ndarray  # (N, 3)
    omega: np.ndarray  # (N, 3)
    mass: np.ndarray | None = None  # (N,)
    radius: np.ndarray | None = None  # (N,)


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
    #: Per row of the scene, the atom ids of its spheres (an (n, k) array; None: ids 1..n).
    ids: np.ndarray | None = None


def lammps_vectors(v_n, v_t, omega, v_s=0.0, omega_s=0.0, omega_n=0.0) -> tuple[np.ndarray, np.ndarray]:
    """LAMMPS's velocity (v_t, v_s, v_n) and angular velocity (omega_s, -omega, omega_n) of the
    paper's state, one row per sphere ((3,) for numbers, (n, 3) for per-sphere values)."""
    v_n, v_t, omega, v_s, omega_s, omega_n = np.broadcast_arrays(v_n, v_t, omega, v_s, omega_s, omega_n)
    return np.stack([v_t, v_s, v_n], axis=-1) + 0.0, np.stack([omega_s, -omega, omega_n], axis=-1) + 0.0


def wall_frame(v: np.ndarray, w: np.ndarray, r: float) -> np.ndarray:
    """(n, 6) states (v_n, v_t, r omega, v_s, r omega_s, r omega_n) of a sphere's (n, 3) v and w."""
    v, w = np.atleast_2d(v), np.atleast_2d(w)
    return np.column_stack([v[:, 2], v[:, 0], -r * w[:, 1], v[:, 1], r * w[:, 0], r * w[:, 2]]) + 0.0


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


def common_context(model: ContactModel, zhi: float, reach: float = 0.0) -> dict:
    """What every wall deck's template reads: the model, the wall's words, the sphere and the box.
    ``reach``: the farthest any sphere moves along the wall in one step. The box is periodic there,
    and LAMMPS maps an atom back by one period only: the box is made wider than four steps' reach."""
    rigid = model.alpha != ALPHA_NVE_SPHERE
    span = max(10.0 * model.r, 2.0 * reach)
    return {
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


def prepare_run_dir(out_dir: Path, deck: Deck, durable: bool = True) -> Path:
    """``out_dir`` made ready to run ``deck`` (created, earlier outputs removed, the deck and the
    files it reads written); the deck's path. Every scene's run goes through it. ``durable``: the
    files forced to disk (a run that records nothing, a sweep's chunk, is remade if lost)."""
    out_dir = Path(out_dir).resolve()
    out_dir.mkdir(parents=True, exist_ok=True)
    for stale in (DUMP_NAME, "log.lammps", "result.json", RESULT_TABLE):
        (out_dir / stale).unlink(missing_ok=True)
    for name, text in deck.files.items():
        write_atomic(out_dir / name, text, durable)
    deck_path = out_dir / deck.name
    write_atomic(deck_path, deck.text, durable)
    return deck_path
