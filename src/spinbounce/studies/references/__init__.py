"""Stored reference outputs: a fixed set of runs whose results must not drift.

A reference case (:mod:`.cases`) is a small scene (a few spheres bouncing in one run, or
a subsampled frozen-contact series) with its final states and theory stored as plain CSV
under ``tests/reference/`` (:mod:`.tables`), its rendered deck stored as golden text under
``tests/reference/decks/`` (:mod:`.golden`), and everything that produced them
(parameters, dt, the LAMMPS and spinbounce versions, the tolerances) in
``tests/reference/MANIFEST.json`` (:mod:`.store`).

A fresh run is compared with a stored table column by column (:mod:`.deviations`): a
column fails when any row differs by more than that column's absolute tolerance
(:mod:`.tolerances`, each with its reason). Golden decks must match exactly, except for
the version number in their first line, so a release does not invalidate them but any
changed command does.

References are written only by :func:`regenerate` (``spinbounce references
--regenerate``); :func:`check` (:mod:`.check`) and the tests run into throw-away folders
and only read the stored files.
"""

from .cases import CASES, ReferenceCase, case_by_name, tolerances_for
from .check import CheckReport, check, format_report
from .deviations import Deviation, Violation, compare_tables, deviations
from .golden import GOLDEN_DECKS, GoldenDeck, compare_decks, normalise_deck, render_golden
from .store import (DECKS_DIR, DEFAULT_DIR, FORMAT, MANIFEST, REGENERATE_COMMAND, compare_manifest, expected_files,
                    manifest, read_manifest, regenerate)
from .tables import read_table, reference_table, run_case, write_table
from .tolerances import COLLISION_MU_TOLERANCES, COLLISION_TOLERANCES, FROZEN_TOLERANCES, MEASUREMENTS, Tolerance

__all__ = [
    "CASES",
    "COLLISION_MU_TOLERANCES",
    "COLLISION_TOLERANCES",
    "DECKS_DIR",
    "DEFAULT_DIR",
    "FORMAT",
    "FROZEN_TOLERANCES",
    "GOLDEN_DECKS",
    "MANIFEST",
    "MEASUREMENTS",
    "REGENERATE_COMMAND",
    "CheckReport",
    "Deviation",
    "GoldenDeck",
    "ReferenceCase",
    "Tolerance",
    "Violation",
    "case_by_name",
    "check",
    "compare_decks",
    "compare_manifest",
    "compare_tables",
    "deviations",
    "expected_files",
    "format_report",
    "manifest",
    "normalise_deck",
    "read_manifest",
    "read_table",
    "reference_table",
    "regenerate",
    "render_golden",
    "run_case",
    "tolerances_for",
    "write_table",
]
