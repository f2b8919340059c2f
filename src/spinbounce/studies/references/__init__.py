"""Stored reference outputs: a fixed set of runs whose results must not drift.

A reference case (:mod:`.cases`) is a small scene (a few spheres bouncing in one run, or
a subsampled frozen-contact series) with its final states and theory stored as plain CSV
under ``tests/reference/`` (:mod:`.tables`), its rendered deck stored as golden text under
``tests/reference/decks/``, and everything that produced them
(parameters, dt, the LAMMPS and spinbounce versions, the tolerances) in
``tests/reference/MANIFEST.json`` (:mod:`.store`).

A fresh run is compared with a stored table column by column (:mod:`.tables`): a
column fails when any row differs by more than that column's absolute tolerance
(:mod:`.cases`, each with its reason). Golden decks must match exactly, except for
the version number in their first line, so a release does not invalidate them but any
changed command does.

References are written only by :func:`regenerate` (``spinbounce references
--regenerate``); :func:`check` and the tests run into throw-away folders
and only read the stored files.
"""

import importlib

#: Each module and the names it exports here: importing the package loads none of them (the
#: command's ``--help`` reads the case names only), a name's module loads on first use.
_EXPORTS = {
    "cases": ("CASES", "COLLISION_MU_TOLERANCES", "COLLISION_TOLERANCES", "DEFAULT_DIR", "FROZEN_TOLERANCES",
              "MEASUREMENTS", "ReferenceCase", "Tolerance", "case_by_name", "tolerances_for"),
    "tables": ("Deviation", "Violation", "compare_tables", "deviations", "read_table", "run_case", "write_table"),
    "store": ("CheckReport", "DECKS_DIR", "FORMAT", "GOLDEN_DECKS", "GoldenDeck", "MANIFEST", "REGENERATE_COMMAND",
              "check", "compare_decks", "compare_manifest", "expected_files", "format_report", "manifest",
              "normalise_deck", "read_manifest", "regenerate", "render_golden"),
}
_WHERE = {name: module for module, names in _EXPORTS.items() for name in names}
__all__ = sorted(_WHERE)


def __getattr__(name: str):  # no name here is also a module's: importing one would hide it
    if name in _WHERE:
        return getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
