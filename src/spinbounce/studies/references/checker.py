"""Checking the stored references: fresh runs in a temporary folder, compared column by
column; the stored folder is only read."""

from __future__ import annotations

import io
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ...records import software
from .cases import CASES, ReferenceCase, case_by_name, tolerances_for
from .deviations import Deviation, Violation, compare_tables, deviations
from .golden import GOLDEN_DECKS, compare_decks
from .store import DECKS_DIR, DEFAULT_DIR, MANIFEST, REGENERATE_COMMAND, compare_manifest, expected_files, read_manifest
from .tables import read_table, run_case

__all__ = ["CheckReport", "check", "format_report"]


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


def _stray_files(directory: Path) -> list[Violation]:
    """Stored files that no case in the code produces."""
    stored_files = [*directory.glob("*.csv"), *(directory / DECKS_DIR).glob("*")]
    present = {p.relative_to(directory).as_posix() for p in stored_files if p.is_file()}
    return [Violation("*", name, "stored file that no case in the code produces (regenerate)")
            for name in sorted(present - expected_files())]


def _check_case(case: ReferenceCase, directory: Path, run_dir: Path) -> tuple[list[Deviation] | None, list[Violation]]:
    """A fresh run of ``case`` against its stored table: deviations (None if no table) and violations."""
    path = directory / f"{case.name}.csv"
    if not path.is_file():
        return None, [Violation(case.name, "*", f"{path} is missing")]
    stored = read_table(path)
    fresh = run_case(case, run_dir)
    tolerances = tolerances_for(case)
    return deviations(fresh, stored, tolerances), compare_tables(fresh, stored, tolerances, case=case.name)


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
    violations = compare_manifest(stored_manifest) + _stray_files(directory)
    found = {}
    with tempfile.TemporaryDirectory(prefix="spinbounce-check-") as tmp:
        for case in cases:
            if progress:
                progress(case)
            case_deviations, case_violations = _check_case(case, directory, Path(tmp) / case.name)
            if case_deviations is not None:
                found[case.name] = case_deviations
            violations += case_violations
    if decks:
        goldens = [g for g in GOLDEN_DECKS if g.case in {c.name for c in cases}]
        violations += compare_decks(directory / DECKS_DIR, goldens)
    return CheckReport(software()["lammps_version"], stored_manifest.get("lammps_version"), found, violations)


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
