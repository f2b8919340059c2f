"""Stored reference outputs: a fixed set of runs whose results must not drift.

A reference case is a small scene (a few spheres bouncing in one run, or a subsampled
frozen-contact series) with its final states and theory stored as plain CSV under
``tests/reference/``, its rendered deck stored as golden text under
``tests/reference/decks/``, and everything that produced them (parameters, dt, the
LAMMPS and spinbounce versions, the tolerances) in ``tests/reference/MANIFEST.json``.

A fresh run is compared with a stored table column by column: a column fails when any
row differs by more than that column's absolute tolerance (:data:`COLLISION_TOLERANCES`,
:data:`FROZEN_TOLERANCES`, each with its reason). Golden decks must match exactly, except
for the version number in their first line, so a release does not invalidate them but
any changed command does.

References are written only by :func:`regenerate` (``spinbounce references
--regenerate``); :func:`check` and the tests run into throw-away folders and only read
the stored files.
"""

from __future__ import annotations

import csv
import dataclasses
import difflib
import io
import json
import math
import re
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from .. import __version__, theory
from ..lammps.decks import ATOM_ROUTES, render_collision, render_frozen
from ..pipeline import run_collision, run_frozen
from ..lammps.runner import lammps_version
from ..model.scenes import Collision, ContactModel, Frozen

__all__ = [
    "CASES",
    "COLLISION_TOLERANCES",
    "DECKS_DIR",
    "DEFAULT_DIR",
    "FROZEN_TOLERANCES",
    "GOLDEN_DECKS",
    "MANIFEST",
    "REGENERATE_COMMAND",
    "GoldenDeck",
    "ReferenceCase",
    "Tolerance",
    "Violation",
    "case_by_name",
    "check",
    "compare_decks",
    "compare_tables",
    "deviations",
    "expected_files",
    "manifest",
    "normalise_deck",
    "read_table",
    "reference_table",
    "regenerate",
    "render_golden",
    "run_case",
    "tolerances_for",
    "write_table",
]

MANIFEST = "MANIFEST.json"
DECKS_DIR = "decks"
#: Where the references live, relative to the repository's top folder.
DEFAULT_DIR = Path("tests") / "reference"
REGENERATE_COMMAND = "spinbounce references --regenerate --dir tests/reference"
#: Bumped when the layout of the stored files changes.
FORMAT = 1


# -- tolerances ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Tolerance:
    """Largest allowed |fresh - stored| for every row of one column, and why that much.

    ``name`` labels the reason, shared by the columns it covers (manifest key).
    """

    name: str
    atol: float
    why: str


# LAMMPS runs serially here and is deterministic: two runs on one build agree bit for bit
# (measured: 0.0 in every column of every case; so do the data-file and library atom
# routes and the lmp executable). What can differ on another machine is the last bit of
# a libm call; velocity Verlet is neutrally stable for these linear springs, so such a
# difference is carried along, not amplified. As a stand-in, moving every initial
# velocity by 1 ulp moved no collision output by more than 7.1e-15 and no frozen output
# (6000 steps) by more than 1.1e-15. The LAMMPS tolerance, 1e-10, is four orders above
# that and still catches the smallest real changes tried: dt*(1 + 1e-9) moved every
# case by 9.6e-10 to 5.9e-8, kt*(1 + 1e-8) by 4.9e-10 to 2.8e-5 (the integration error
# itself is ~1e-5). The measurements are recorded in the manifest (_MEASUREMENTS).
_EXACT = Tolerance(
    "case_input", 0.0,
    "an input of the case definition, written and read back exactly (repr): any difference means the "
    "case itself was changed")
_THEORY = Tolerance(
    "theory", 1e-12,
    "pure Python/numpy theory (sqrt, exp, sin, cos of O(10) arguments): another libm may differ in the "
    "last bit, ~1e-15; 1e-12 allows that, and any change of a formula or a parameter moves it by far more")
_ORACLE = Tolerance(
    "oracle", 1e-9,
    "the Coulomb oracle (finite mu): adaptive DOP853 at rtol 1e-12 with located events, whose steps "
    "depend on scipy's version and on rounding (two revisions of its event handling differed by 3.7e-12); "
    "1e-9 allows that, while mu*(1 + 1e-7) moves the outputs by 5e-8")
_LAMMPS_FINAL = Tolerance(
    "lammps_final_state", 1e-10,
    "LAMMPS final state after <= ~1050 steps: bit-identical on this build; a 1-ulp change of the inputs "
    "moves it by <= 7.1e-15, so rounding on another CPU stays far below 1e-10, while dt*(1 + 1e-9) moves "
    "it by >= 1.2e-9 and kt*(1 + 1e-8) by >= 4.9e-10")
_LAMMPS_SERIES = Tolerance(
    "lammps_series", 1e-10,
    "LAMMPS frozen series over ~6000 steps: bit-identical on this build; a rounding difference would "
    "drift in phase, linearly in time: a 1-ulp change of the inputs moves it by <= 1.1e-15 at the end, so "
    "1e-10 has a 10^5 margin, while dt*(1 + 1e-9) moves it by >= 9.6e-10 and kt*(1 + 1e-8) by >= 4.6e-9")
_HELD = Tolerance(
    "held", 1e-12,
    "held height and normal velocity of the frozen sphere: exactly constant in LAMMPS (normal force "
    "cancelled, v_n = 0); the pipeline itself allows 1e-12 in z")
_TIME = Tolerance(
    "time", 1e-12,
    "step * dt, with dt from arithmetic and sqrt only (correctly rounded): reproduced exactly; 1e-12 is "
    "far below one step")

#: Collision reference columns -> tolerance. ``omega_final`` carries the spin in the
#: paper's units; r*omega is r times it and adds nothing.
COLLISION_TOLERANCES: dict[str, Tolerance] = {
    "id": _EXACT,
    "vn_0": _EXACT,
    "vt_0": _EXACT,
    "omega_0": _EXACT,
    "vn_final": _LAMMPS_FINAL,
    "vt_final": _LAMMPS_FINAL,
    "omega_final": _LAMMPS_FINAL,
    "z_final": _LAMMPS_FINAL,
    "vn_theory": _THEORY,
    "vt_theory": _THEORY,
    "omega_theory": _THEORY,
}

#: A collision with a finite mu: the same, with the oracle's tolerance on its theory columns.
COLLISION_MU_TOLERANCES = {k: (_ORACLE if v is _THEORY else v) for k, v in COLLISION_TOLERANCES.items()}

#: Frozen-contact reference columns -> tolerance.
FROZEN_TOLERANCES: dict[str, Tolerance] = {
    "t": _TIME,
    "vt": _LAMMPS_SERIES,
    "omega": _LAMMPS_SERIES,
    "z": _HELD,
    "vn": _HELD,
    "vt_theory": _THEORY,
    "r_omega_theory": _THEORY,
}

#: The measurements behind the tolerances, recorded in the manifest next to them.
_MEASUREMENTS = {
    "rerun": "two fresh runs of every case: largest difference 0.0 in every column; the data-file and "
             "library atom routes and the lmp executable reproduce the inline route exactly",
    "rounding_stand_in": "every initial velocity moved by 1 ulp: collision outputs move by <= 7.1e-15, "
                         "frozen outputs by <= 1.1e-15",
    "real_changes": "dt*(1 + 1e-9): collisions move by 1.2e-9 to 5.9e-8, frozen series by 9.6e-10 and "
                    "2.5e-8; dt*(1 + 1e-6): 9.6e-7 to 5.9e-5; kt*(1 + 1e-8): collisions by 4.9e-10 to "
                    "2.8e-5, frozen series by 4.6e-9 and 1.2e-7",
}


# -- the cases --------------------------------------------------------------------------


# (v_n, v_t, omega) per sphere: head-on, pure spin, mixed signs, near-rolling, glancing.
_STANDARD = (
    (-1.0, 1.0, 0.0),
    (-1.0, 0.0, 2.0),
    (-0.5, -0.7, 1.3),
    (-1.2, 0.3, -2.5),
    (-0.3, 2.0, 0.0),
    (-0.8, -1.5, -1.0),
)


@dataclass(frozen=True)
class ReferenceCase:
    """One stored reference: a scene kind, its model, its states and its step.

    ``states``: collision, one (v_n, v_t, omega) per sphere, all in one run; frozen, a
    single (z, v_t, omega). ``dt = None`` takes the scene's default step (recorded in the
    manifest). ``t_end`` and ``every`` (dump cadence, which subsamples the series) are for
    frozen cases only.
    """

    name: str
    kind: str  # "collision" or "frozen"
    description: str
    model: dict = field(default_factory=dict)  # ContactModel arguments that differ from the defaults
    states: tuple = ()
    dt: float | None = None
    t_end: float | None = None
    every: int | None = None

    def contact_model(self) -> ContactModel:
        return ContactModel(**self.model)

    def scene(self) -> Collision | Frozen:
        model = self.contact_model()
        if self.kind == "collision":
            vn, vt, om = (list(column) for column in zip(*self.states, strict=True))
            return Collision(model, v_n=vn, v_t=vt, omega=om, dt=self.dt)
        if self.kind == "frozen":
            (z, vt, om), = self.states
            return Frozen(model, z=z, v_t=vt, omega=om, t_end=self.t_end, dt=self.dt, every=self.every)
        raise ValueError(f"case {self.name!r}: unknown kind {self.kind!r}")

    def rows(self, scene=None) -> int:
        scene = scene or self.scene()
        return scene.n if self.kind == "collision" else scene.nsteps // scene.every + 1

    def describe(self) -> dict:
        """The case as the manifest records it (JSON types; computable without LAMMPS)."""
        scene = self.scene()
        out = {
            "kind": self.kind,
            "description": self.description,
            "model": dataclasses.asdict(scene.model),
            "states": [list(s) for s in self.states],
            "dt": scene.dt,
            "nsteps": scene.nsteps,
        }
        if self.kind == "frozen":
            out.update(t_end=self.t_end, every=scene.every)
        out.update(rows=self.rows(scene), table=f"{self.name}.csv")
        return json.loads(json.dumps(out))


_KN = ContactModel().kn

CASES: tuple[ReferenceCase, ...] = (
    ReferenceCase("defaults", "collision", "the paper's model: m = 1, r = 0.5, alpha = 2/5, kn = 10, kt = 1",
                  states=_STANDARD),
    ReferenceCase("magic_ratio", "collision", "kt/kn = alpha/(1 + alpha) = 2/7: Omega = -2, energy conserved",
                  model={"kt": _KN * theory.magic_kt_over_kn(0.4)}, states=_STANDARD),
    ReferenceCase("alpha_0.1", "collision", "alpha = 0.1: mass near the centre, the rigid-body route",
                  model={"alpha": 0.1}, states=_STANDARD),
    ReferenceCase("shell_magic", "collision", "alpha = 2/3 (thin shell) at its magic ratio kt/kn = 2/5",
                  model={"alpha": 2.0 / 3.0, "kt": _KN * theory.magic_kt_over_kn(2.0 / 3.0)}, states=_STANDARD),
    ReferenceCase("damped_tangential", "collision", "tangential damping gamma_t = 0.3, no normal damping",
                  model={"gamma_t": 0.3}, states=_STANDARD),
    ReferenceCase("damped_normal", "collision", "normal damping gamma_n = 1 (restitution 0.60) with gamma_t = 0.2",
                  model={"gamma_n": 1.0, "gamma_t": 0.2}, states=_STANDARD),
    ReferenceCase("overdamped_tangential", "collision",
                  "gamma_t = 2: the slip mode is overdamped (zeta = 3.5 > sqrt(Q) = 1.87); it sets dt",
                  model={"gamma_t": 2.0}, states=_STANDARD),
    ReferenceCase("grazing", "collision", "grazing incidence |v_n| = 1e-3 with large slip",
                  states=((-1e-3, 2.0, 0.0), (-1e-3, -3.0, 1.0), (-1e-3, 0.5, -6.0), (-1e-3, 0.0, 4.0))),
    ReferenceCase("near_tunnelling", "collision",
                  "|v_n| close to the tunnelling limit 1.58: overlap up to 0.49 of r = 0.5",
                  states=((-1.5, 1.0, 0.0), (-1.5, -0.5, 3.0), (-1.55, 0.2, -1.0), (-1.55, 0.0, 0.0))),
    ReferenceCase("soft_kt", "collision", "very soft tangential spring kt/kn = 1e-3",
                  model={"kt": 1e-3 * _KN}, states=_STANDARD),
    ReferenceCase("stiff_kt", "collision", "stiff tangential spring kt/kn = 5: the slip mode sets a smaller dt",
                  model={"kt": 5.0 * _KN}, states=_STANDARD),
    ReferenceCase("large_spin", "collision", "large spin |r omega| = 20 |v_n| (r = 0.5: |omega| = 40 |v_n|)",
                  states=((-1.0, 0.0, 40.0), (-0.5, 0.3, -20.0), (-0.1, -0.2, 4.0), (-1.2, 1.0, -48.0))),
    ReferenceCase("mu_0.1", "collision", "Coulomb limit mu = 0.1: the spheres slide (not the paper's model)",
                  model={"mu": 0.1}, states=_STANDARD),
    ReferenceCase("frozen_defaults", "frozen", "frozen contact at the paper's defaults (its Fig. 2), ~200 rows",
                  states=((0.1, 1.0, 0.0),), t_end=10.0, every=30),
    ReferenceCase("frozen_damped", "frozen", "frozen contact with tangential damping gamma_t = 0.3, ~200 rows",
                  model={"gamma_t": 0.3}, states=((0.1, 1.0, -1.0),), t_end=10.0, every=30),
)


def case_by_name(name: str) -> ReferenceCase:
    for case in CASES:
        if case.name == name:
            return case
    raise KeyError(f"no reference case {name!r}; known: {', '.join(c.name for c in CASES)}")


def tolerances_for(case: ReferenceCase) -> dict[str, Tolerance]:
    if case.kind != "collision":
        return FROZEN_TOLERANCES
    if case.model.get("mu") is not None:  # the theory columns are the oracle's
        return COLLISION_MU_TOLERANCES
    return COLLISION_TOLERANCES


# -- tables -----------------------------------------------------------------------------


def reference_table(case: ReferenceCase, result) -> pd.DataFrame:
    """The stored columns of a run's result table, in the stored order."""
    return result.table[list(tolerances_for(case))].reset_index(drop=True)


def run_case(case: ReferenceCase, out_dir: Path, atoms: str | None = None) -> pd.DataFrame:
    """Run one case in ``out_dir`` (a fresh folder) and return its reference table.

    ``atoms``: a collision's atom route (:data:`decks.ATOM_ROUTES`); the stored tables
    come from the default (inline) route, and every route must reproduce them.
    """
    scene = case.scene()
    if case.kind == "collision":
        result = run_collision(scene, out_dir, atoms=atoms, record=False)
    elif atoms is not None:
        raise ValueError(f"case {case.name!r}: a frozen contact has no atom routes")
    else:
        result = run_frozen(scene, out_dir)
    return reference_table(case, result)


def write_table(table: pd.DataFrame, path: Path) -> None:
    """Plain CSV, one header line, every value as ``repr`` of its float (exact on reading)."""
    cells = []
    for name in table.columns:
        values = table[name].to_numpy(dtype=float)
        if name == "id":
            if not np.array_equal(values, np.round(values)):
                raise ValueError(f"ids {values.tolist()} are not all whole numbers")
            cells.append([str(int(v)) for v in values])
        else:
            cells.append([repr(v) for v in values.tolist()])
    lines = [",".join(table.columns), *(",".join(row) for row in zip(*cells, strict=True))]
    Path(path).write_text("\n".join(lines) + "\n")


def read_table(path: Path) -> pd.DataFrame:
    """A stored table, every value parsed with ``float`` (exactly what was written)."""
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    if not rows:
        raise ValueError(f"{path}: empty reference table")
    header, body = rows[0], rows[1:]
    bad = [i + 2 for i, row in enumerate(body) if len(row) != len(header)]
    if bad:
        raise ValueError(f"{path}: line {bad[0]} has a different number of fields than the header")
    data = np.array([[float(x) for x in row] for row in body], dtype=float).reshape(len(body), len(header))
    return pd.DataFrame(data, columns=header)


# -- comparison -------------------------------------------------------------------------


@dataclass(frozen=True)
class Violation:
    """A stored column that a fresh table does not reproduce within its tolerance.

    ``row`` is the worst row (None for a structural problem: a missing column, a
    different number of rows); ``rows`` counts the rows beyond tolerance.
    """

    case: str
    column: str
    message: str
    row: int | None = None
    fresh: float = math.nan
    stored: float = math.nan
    deviation: float = math.nan
    tolerance: float = math.nan
    rows: int = 0

    def __str__(self) -> str:
        return f"{self.case}: {self.column}: {self.message}"


@dataclass(frozen=True)
class Deviation:
    """The largest |fresh - stored| of one column and where it is."""

    column: str
    deviation: float
    row: int | None
    tolerance: float
    beyond: int  # rows beyond tolerance

    @property
    def ok(self) -> bool:
        return self.beyond == 0


def _as_tolerance(value) -> float:
    return value.atol if isinstance(value, Tolerance) else float(value)


def deviations(fresh: pd.DataFrame, stored: pd.DataFrame, tolerances: dict) -> list[Deviation]:
    """Per stored column: the largest deviation, its row, and the rows beyond tolerance.

    A NaN on either side that is not NaN on the other counts as an infinite deviation.
    Columns missing on either side and a different number of rows are left to
    :func:`compare_tables`.
    """
    out = []
    for column, tol in tolerances.items():
        if column not in fresh.columns or column not in stored.columns or len(fresh) != len(stored):
            continue
        a = fresh[column].to_numpy(dtype=float)
        b = stored[column].to_numpy(dtype=float)
        same_nan = np.isnan(a) & np.isnan(b)
        dev = np.where(same_nan, 0.0, np.abs(a - b))
        dev = np.where(np.isnan(dev), np.inf, dev)
        atol = _as_tolerance(tol)
        worst = int(np.argmax(dev)) if dev.size else None
        out.append(Deviation(column, float(dev[worst]) if dev.size else 0.0, worst, atol, int(np.sum(dev > atol))))
    return out


def compare_tables(fresh: pd.DataFrame, stored: pd.DataFrame, tolerances: dict, case: str = "") -> list[Violation]:
    """Every way ``fresh`` fails to reproduce ``stored``: one :class:`Violation` per failing column.

    ``tolerances`` maps each stored column to a :class:`Tolerance` (or a plain absolute
    tolerance); a column fails when any row differs by more than it. A stored column with
    no tolerance, a column missing from either table and a different number of rows are
    violations too: nothing is compared loosely by default.
    """
    found = []
    for column in tolerances:
        for table, which in ((stored, "stored"), (fresh, "fresh")):
            if column not in table.columns:
                found.append(Violation(case, column, f"missing from the {which} table"))
    for column in stored.columns:
        if column not in tolerances:
            found.append(Violation(case, column, "stored column has no tolerance"))
    if len(fresh) != len(stored):
        found.append(Violation(case, "*", f"{len(fresh)} fresh rows, {len(stored)} stored"))
        return found
    for d in deviations(fresh, stored, tolerances):
        if d.ok:
            continue
        a, b = float(fresh[d.column].iloc[d.row]), float(stored[d.column].iloc[d.row])
        found.append(Violation(
            case, d.column,
            f"{d.beyond} row(s) beyond tolerance {d.tolerance:.1e}; worst row {d.row}: "
            f"fresh {a!r}, stored {b!r}, |difference| {d.deviation:.3e}",
            row=d.row, fresh=a, stored=b, deviation=d.deviation, tolerance=d.tolerance, rows=d.beyond))
    return found


# -- golden decks -----------------------------------------------------------------------


@dataclass(frozen=True)
class GoldenDeck:
    """A deck stored as golden text: a case's deck through one atom route.

    ``route = None`` is the route the case runs with (inline for these small collisions).
    """

    case: str
    route: str | None = None

    @property
    def key(self) -> str:
        return self.case if self.route is None else f"{self.case}.{self.route}"

    @property
    def deck_file(self) -> str:
        return f"{self.key}.lmp"

    def extra_file(self, name: str) -> str:
        return f"{self.key}.{name}"


#: Every case's own deck, and the two other atom routes for one sphere-only
#: (nve/sphere) case and one rigid-body case: their data and bodies files are small.
GOLDEN_DECKS: tuple[GoldenDeck, ...] = tuple(GoldenDeck(c.name) for c in CASES) + tuple(
    GoldenDeck(case, route) for case in ("defaults", "alpha_0.1") for route in ATOM_ROUTES if route != "inline"
)

_HEADER_VERSION = re.compile(r"^(#\s*)?spinbounce \S+?(:)")


def normalise_deck(text: str) -> str:
    """The text with the package version in its first line replaced by a placeholder."""
    first, newline, rest = text.partition("\n")
    return _HEADER_VERSION.sub(r"\1spinbounce <version>\2", first, count=1) + newline + rest


def render_golden(golden: GoldenDeck) -> dict[str, str]:
    """Stored file name -> text for one golden deck: the deck, then any files it reads."""
    scene = case_by_name(golden.case).scene()
    deck = render_frozen(scene) if isinstance(scene, Frozen) else render_collision(scene, golden.route)
    out = {golden.deck_file: deck.text}
    for name, text in sorted(deck.files.items()):
        out[golden.extra_file(name)] = text
    return out


def compare_decks(decks_dir: Path, goldens=GOLDEN_DECKS) -> list[Violation]:
    """Golden files that a fresh rendering does not reproduce (version number aside)."""
    found = []
    for golden in goldens:
        for name, text in render_golden(golden).items():
            path = Path(decks_dir) / name
            if not path.is_file():
                found.append(Violation(golden.case, name, f"golden file {path} is missing"))
                continue
            stored = normalise_deck(path.read_text())
            fresh = normalise_deck(text)
            if stored != fresh:
                diff = list(difflib.unified_diff(stored.splitlines(), fresh.splitlines(), "stored", "fresh",
                                                 lineterm="", n=0))
                shown = "\n    ".join(diff[2:8]) + ("\n    ..." if len(diff) > 8 else "")
                found.append(Violation(golden.case, name, f"rendering differs from {path}:\n    {shown}"))
    return found


# -- manifest, regeneration, check ------------------------------------------------------


def expected_files() -> set[str]:
    """Every file name (relative to the reference folder) that regeneration writes."""
    names = {MANIFEST} | {f"{c.name}.csv" for c in CASES}
    for golden in GOLDEN_DECKS:
        names |= {f"{DECKS_DIR}/{name}" for name in render_golden(golden)}
    return names


def _tolerance_record() -> dict:
    """Per scene kind, column -> atol and the name of its reason; then the reasons."""
    tables = {"collision": COLLISION_TOLERANCES, "collision_finite_mu": COLLISION_MU_TOLERANCES,
              "frozen": FROZEN_TOLERANCES}
    record = {kind: {column: {"atol": tol.atol, "reason": tol.name} for column, tol in table.items()}
              for kind, table in tables.items()}
    record["reasons"] = {tol.name: tol.why for table in tables.values() for tol in table.values()}
    return record


def manifest(lammps_version: str) -> dict:
    """The manifest for the cases in this code (and the LAMMPS build that ran them)."""
    return {
        "format": FORMAT,
        "regenerate": REGENERATE_COMMAND,
        "lammps_version": lammps_version,
        "spinbounce_version": __version__,
        "comparison": "a column fails when any row has |fresh - stored| > atol; golden decks must match "
                      "exactly except the version number in their first line",
        "measurements": _MEASUREMENTS,
        "tolerances": _tolerance_record(),
        "cases": {case.name: case.describe() for case in CASES},
        "decks": sorted(name for golden in GOLDEN_DECKS for name in render_golden(golden)),
    }


def read_manifest(directory: Path) -> dict:
    return json.loads((Path(directory) / MANIFEST).read_text())


def regenerate(directory: Path = DEFAULT_DIR, progress=None) -> dict:
    """Run every case and write its table, every golden deck and the manifest into ``directory``.

    The only writer of references. Runs go to a temporary folder; files of earlier
    references that no case produces any more are removed, so the folder holds exactly
    what the code defines. Returns the manifest.
    """
    directory = Path(directory)
    if not directory.parent.is_dir():  # most likely run from the wrong folder: create nothing
        raise FileNotFoundError(f"{directory.parent} does not exist: run from the repository's top folder "
                                "or give --dir")
    tables = {}
    with tempfile.TemporaryDirectory(prefix="spinbounce-references-") as tmp:
        for case in CASES:
            if progress:
                progress(case)
            tables[case.name] = run_case(case, Path(tmp) / case.name)
    decks_dir = directory / DECKS_DIR
    decks_dir.mkdir(parents=True, exist_ok=True)  # the parent of `directory` exists (checked above)
    record = manifest(lammps_version())
    keep = expected_files()
    for path in [*directory.glob("*.csv"), *decks_dir.iterdir()]:
        if path.is_file() and path.relative_to(directory).as_posix() not in keep:
            path.unlink()
    for name, table in tables.items():
        write_table(table, directory / f"{name}.csv")
    for golden in GOLDEN_DECKS:
        for name, text in render_golden(golden).items():
            (decks_dir / name).write_text(text)
    (directory / MANIFEST).write_text(json.dumps(record, indent=2) + "\n")
    return record


@dataclass
class CheckReport:
    """What :func:`check` found: per case, the deviation of every column; the violations."""

    lammps_version: str
    stored_lammps_version: str | None
    deviations: dict[str, list[Deviation]]
    violations: list[Violation]

    @property
    def ok(self) -> bool:
        return not self.violations


def check(directory: Path = DEFAULT_DIR, names=None, decks: bool = True, progress=None) -> CheckReport:
    """Run the cases (all, or those in ``names``) afresh and compare them with ``directory``.

    Reads ``directory`` only; runs go to a temporary folder. Also checks that the manifest
    and the stored tables list exactly the cases in the code, with the same parameters.
    """
    directory = Path(directory)
    if not (directory / MANIFEST).is_file():
        raise FileNotFoundError(f"{directory / MANIFEST} not found: no references there "
                                f"(create them with: {REGENERATE_COMMAND})")
    stored_manifest = read_manifest(directory)
    cases = CASES if names is None else tuple(case_by_name(n) for n in names)
    violations = list(compare_manifest(stored_manifest))
    stored_files = [*directory.glob("*.csv"), *(directory / DECKS_DIR).glob("*")]
    present = {p.relative_to(directory).as_posix() for p in stored_files if p.is_file()}
    for name in sorted(present - expected_files()):
        violations.append(Violation("*", name, "stored file that no case in the code produces (regenerate)"))
    found = {}
    with tempfile.TemporaryDirectory(prefix="spinbounce-check-") as tmp:
        for case in cases:
            if progress:
                progress(case)
            path = directory / f"{case.name}.csv"
            if not path.is_file():
                violations.append(Violation(case.name, "*", f"{path} is missing"))
                continue
            stored = read_table(path)
            fresh = run_case(case, Path(tmp) / case.name)
            tolerances = tolerances_for(case)
            found[case.name] = deviations(fresh, stored, tolerances)
            violations += compare_tables(fresh, stored, tolerances, case=case.name)
    if decks:
        goldens = [g for g in GOLDEN_DECKS if g.case in {c.name for c in cases}]
        violations += compare_decks(directory / DECKS_DIR, goldens)
    return CheckReport(lammps_version(), stored_manifest.get("lammps_version"), found, violations)


def compare_manifest(stored: dict) -> list[Violation]:
    """Differences between a stored manifest and the cases and tolerances in this code."""
    found = []
    code = {case.name: case.describe() for case in CASES}
    stored_cases = stored.get("cases", {})
    for name in sorted(set(code) - set(stored_cases)):
        found.append(Violation(name, "*", "case is in the code but not in the manifest (regenerate)"))
    for name in sorted(set(stored_cases) - set(code)):
        found.append(Violation(name, "*", "case is in the manifest but not in the code (regenerate)"))
    for name in sorted(set(code) & set(stored_cases)):
        changed = sorted(k for k in set(code[name]) | set(stored_cases[name])
                         if code[name].get(k) != stored_cases[name].get(k))
        if changed:
            found.append(Violation(name, "*", f"case definition changed since the references were made: "
                                              f"{', '.join(changed)} (regenerate)"))
    if stored.get("tolerances") != json.loads(json.dumps(_tolerance_record())):
        found.append(Violation("*", "tolerances", "the manifest's tolerances differ from the code's (regenerate)"))
    return found


def format_report(report: CheckReport) -> str:
    """The largest deviation per case and column, then the violations."""
    out = io.StringIO()
    out.write(f"LAMMPS {report.lammps_version}")
    if report.stored_lammps_version and report.stored_lammps_version != report.lammps_version:
        out.write(f" (references made with {report.stored_lammps_version})")
    out.write("\n")
    out.write(f"{'case':<22}{'column':<16}{'max |dev|':>11}{'tolerance':>11}{'row':>5}  status\n")
    for name, devs in report.deviations.items():
        for d in devs:
            status = "ok" if d.ok else f"FAIL ({d.beyond} row(s))"
            row = "-" if d.row is None or d.deviation == 0.0 else str(d.row)
            out.write(f"{name:<22}{d.column:<16}{d.deviation:>11.2e}{d.tolerance:>11.1e}{row:>5}  {status}\n")
    if report.violations:
        out.write(f"\n{len(report.violations)} violation(s):\n")
        for v in report.violations:
            out.write(f"  {v}\n")
    return out.getvalue()
