"""The reference folder: which files it holds, its manifest, and the one writer of both.

``MANIFEST.json`` records everything that produced the stored files: the cases'
parameters and steps, the tolerances with their reasons and measurements, and the
LAMMPS and spinbounce versions (:func:`spinbounce.records.software`).
"""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

from ...laws import own
from ...model import parameters
from ...records import json_ready, software, to_json, write_atomic
from .cases import CASES, DEFAULT_DIR
from .deviations import Violation
from .golden import GOLDEN_DECKS, render_golden
from .tables import run_case, write_table
from .tolerances import MEASUREMENTS, tolerance_record

__all__ = ["DECKS_DIR", "DEFAULT_DIR", "FORMAT", "MANIFEST", "REGENERATE_COMMAND", "compare_manifest",
           "expected_files", "manifest", "read_manifest", "regenerate"]

MANIFEST = "MANIFEST.json"
DECKS_DIR = "decks"
REGENERATE_COMMAND = "spinbounce references --regenerate --dir tests/reference"
#: Bumped when the layout of the stored files changes.
FORMAT = 1


def expected_files() -> set[str]:
    """Every file name (relative to the reference folder) that regeneration writes."""
    names = {MANIFEST} | {f"{c.name}.csv" for c in CASES}
    for golden in GOLDEN_DECKS:
        names |= {f"{DECKS_DIR}/{name}" for name in render_golden(golden)}
    return names


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
        "decks": sorted(name for golden in GOLDEN_DECKS for name in render_golden(golden)),
    }


def read_manifest(directory: Path) -> dict:
    return json.loads((Path(directory) / MANIFEST).read_text())


def _run_all(progress=None) -> dict:
    """Every case's fresh reference table, run in a temporary folder."""
    tables = {}
    with tempfile.TemporaryDirectory(prefix="spinbounce-references-") as tmp:
        for case in CASES:
            if progress:
                progress(case)
            tables[case.name] = run_case(case, Path(tmp) / case.name)
    return tables


def _remove_stale(directory: Path) -> None:
    """Files of earlier references that no case produces any more."""
    keep = expected_files()
    for path in [*directory.glob("*.csv"), *(directory / DECKS_DIR).iterdir()]:
        if path.is_file() and path.relative_to(directory).as_posix() not in keep:
            path.unlink()


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
    tables = _run_all(progress)
    decks_dir = directory / DECKS_DIR
    decks_dir.mkdir(parents=True, exist_ok=True)  # the parent of `directory` exists (checked above)
    record = manifest(software())
    _remove_stale(directory)
    for name, table in tables.items():
        write_table(table, directory / f"{name}.csv")
    for golden in GOLDEN_DECKS:
        for name, text in render_golden(golden).items():
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
