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
--regenerate``); :func:`check` (:mod:`.checker`) and the tests run into throw-away folders
and only read the stored files.
"""

import importlib

#: Where each name lives: importing the package loads none of its modules (the command's
#: ``--help`` reads the case names only), a name's module loads on first use.
_WHERE = {
    "CASES": "cases",
    "COLLISION_MU_TOLERANCES": "tolerances",
    "COLLISION_TOLERANCES": "tolerances",
    "CheckReport": "checker",
    "DECKS_DIR": "store",
    "DEFAULT_DIR": "cases",
    "Deviation": "deviations",
    "FORMAT": "store",
    "FROZEN_TOLERANCES": "tolerances",
    "GOLDEN_DECKS": "golden",
    "GoldenDeck": "golden",
    "MANIFEST": "store",
    "MEASUREMENTS": "tolerances",
    "REGENERATE_COMMAND": "store",
    "ReferenceCase": "cases",
    "Tolerance": "tolerances",
    "Violation": "deviations",
    "case_by_name": "cases",
    "check": "checker",
    "compare_decks": "golden",
    "compare_manifest": "store",
    "compare_tables": "deviations",
    "deviations": "deviations",
    "expected_files": "store",
    "format_report": "checker",
    "manifest": "store",
    "normalise_deck": "golden",
    "read_manifest": "store",
    "read_table": "tables",
    "reference_table": "tables",
    "regenerate": "store",
    "render_golden": "golden",
    "run_case": "tables",
    "tolerances_for": "cases",
    "write_table": "tables",
}

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


def __getattr__(name: str):  # no name here is also a module's: importing one would hide it
    if name in _WHERE:
        return getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
