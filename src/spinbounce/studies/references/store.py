"""The reference folder: its files (tables, golden decks: each case's rendered deck and the files
it reads, and ``MANIFEST.json``: the cases' parameters and steps, the tolerances with their reasons
and measurements, the LAMMPS and spinbounce versions), their one writer, and the check of fresh
runs (in a temporary folder) against them, which only reads them.
"""

from __future__ import annotations

import difflib
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ...laws import own
from ...lammps.decks import ATOM_ROUTES
from ...model import parameters
from ...records import json_ready, read_json, software, to_json, write_atomic
from ...scenes.collision.deck import render_collision
from ...scenes.frozen import Frozen
from ...scenes.frozen.deck import render_frozen
from .cases import CASES, DEFAULT_DIR, MEASUREMENTS, case_by_name, tolerance_record, tolerances_for
from .tables import Deviation, Violation, compare_tables, deviations, read_table, run_case, write_table

MANIFEST = "MANIFEST.json"
DECKS_DIR = "decks"
REGENERATE_COMMAND = "spinbounce references --regenerate --dir tests/reference"
#: Bumped when the layout of the stored files changes.
FORMAT = 1


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
    files = {golden.extra_file(name): text for name, text in sorted(deck.files.items())}
    return {golden.deck_file: deck.text, **files}


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


def _golden_files() -> dict[str, str]:
    """Every golden deck's stored files: name (in the decks folder) -> text."""
    return {name: text for golden in GOLDEN_DECKS for name, text in render_golden(golden).items()}


def expected_files() -> set[str]:
    """Every file name (relative to the reference folder) that regeneration writes."""
    return {MANIFEST, *(f"{c.name}.csv" for c in CASES), *(f"{DECKS_DIR}/{name}" for name in _golden_files())}


def _stale_files(directory: Path) -> list[str]:
    """Stored files (relative names) that no case in the code produces: left by earlier references."""
    stored = [*directory.glob("*.csv"), *(directory / DECKS_DIR).glob("*")]
    return sorted({p.relative_to(directory).as_posix() for p in stored if p.is_file()} - expected_files())


def _scratch_runs(cases, prefix: str, progress):
    """Each case with a fresh run folder, in a temporary folder removed afterwards."""
    with tempfile.TemporaryDirectory(prefix=prefix) as tmp:
        for case in cases:
            if progress:
                progress(case)
            yield case, Path(tmp) / case.name


def manifest(provenance: dict) -> dict:
    """The manifest for the cases in this code, with the versions of ``provenance``
    (a :func:`spinbounce.records.software` record of the build that ran them)."""
    return {
        "format": FORMAT,
        "regenerate": REGENERATE_COMMAND,
        "lammps_version": provenance["lammps_version"],
        "spinbounce_version": provenance["spinbounce_version"],
        "comparison": "a column fails when any row has |fresh - stored| > atol; golden decks must match "
                      "exactly except the version number in their first line",
        "measurements": MEASUREMENTS,
        "tolerances": tolerance_record(),
        "cases": {case.name: case.describe() for case in CASES},
        "decks": sorted(_golden_files()),
    }


def read_manifest(directory: Path) -> dict:
    """The stored references' manifest (a :class:`~spinbounce.errors.FileFault` if it cannot be read)."""
    return read_json(Path(directory) / MANIFEST, "references manifest")


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
    tables = {case.name: run_case(case, run_dir)
              for case, run_dir in _scratch_runs(CASES, "spinbounce-references-", progress)}
    decks_dir = directory / DECKS_DIR
    decks_dir.mkdir(parents=True, exist_ok=True)  # the parent of `directory` exists (checked above)
    record = manifest(software())
    for name in _stale_files(directory):
        (directory / name).unlink()
    for name, table in tables.items():
        write_table(table, directory / f"{name}.csv")
    for name, text in _golden_files().items():
        write_atomic(decks_dir / name, text)
    write_atomic(directory / MANIFEST, to_json(record))
    return record


def _with_declared_defaults(case: dict) -> dict:
    """A stored case's model as this code declares it: a parameter declared since the
    references were made takes its default, which is what those runs had."""
    model = {p.name: p.default for p in parameters.MODEL}
    return {**case, "model": own({**model, **case.get("model", {})})} if "model" in case else case


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
        stored_case = _with_declared_defaults(stored_cases[name])
        changed = sorted(k for k in set(code[name]) | set(stored_case) if code[name].get(k) != stored_case.get(k))
        if changed:
            found.append(Violation(name, "*", f"case definition changed since the references were made: "
                                              f"{', '.join(changed)} (regenerate)"))
    if stored.get("tolerances") != json_ready(tolerance_record()):
        found.append(Violation("*", "tolerances", "the manifest's tolerances differ from the code's (regenerate)"))
    return found


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
    violations = compare_manifest(stored_manifest) + [
        Violation("*", name, "stored file that no case in the code produces (regenerate)")
        for name in _stale_files(directory)]
    found = {}
    for case, run_dir in _scratch_runs(cases, "spinbounce-check-", progress):
        path = directory / f"{case.name}.csv"
        if not path.is_file():
            violations.append(Violation(case.name, "*", f"{path} is missing"))
            continue
        stored, fresh, tolerances = read_table(path), run_case(case, run_dir), tolerances_for(case)
        found[case.name] = deviations(fresh, stored, tolerances)
        violations += compare_tables(fresh, stored, tolerances, case=case.name)
    if decks:
        goldens = [g for g in GOLDEN_DECKS if g.case in {c.name for c in cases}]
        violations += compare_decks(directory / DECKS_DIR, goldens)
    return CheckReport(software()["lammps_version"], stored_manifest.get("lammps_version"), found, violations)


def format_report(report: CheckReport) -> str:
    """The largest deviation per case and column, then the violations."""
    made = report.stored_lammps_version
    note = f" (references made with {made})" if made and made != report.lammps_version else ""
    lines = [f"LAMMPS {report.lammps_version}{note}",
             f"{'case':<22}{'column':<16}{'max |dev|':>11}{'tolerance':>11}{'row':>5}  status"]
    for name, devs in report.deviations.items():
        for d in devs:
            status = "ok" if d.ok else f"FAIL ({d.beyond} row(s))"
            row = "-" if d.row is None or d.deviation == 0.0 else str(d.row)
            lines.append(f"{name:<22}{d.column:<16}{d.deviation:>11.2e}{d.tolerance:>11.1e}{row:>5}  {status}")
    if report.violations:
        lines += ["", f"{len(report.violations)} violation(s):", *(f"  {v}" for v in report.violations)]
    return "\n".join(lines) + "\n"
