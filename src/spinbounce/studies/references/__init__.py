"""Stored reference outputs (docs/how-to/references.md): a fixed set of runs whose results must not drift.

A reference case (:mod:`.cases`) is a small scene (a few spheres bouncing in one run, or a
subsampled frozen-contact series) whose final states and theory are stored as plain CSV under
``tests/reference/`` (:mod:`.tables`: a column fails when any row differs by more than its
absolute tolerance, each with its reason), its rendered deck as golden text under ``decks/``
(matched exactly but for the version in its first line, so a release does not invalidate them
but any changed command does), and what produced them in ``MANIFEST.json`` (:mod:`.store`).
Only :func:`regenerate` writes them; :func:`check` and the tests run in throw-away folders.
"""

import importlib

#: Each module and the names it exports here: importing the package loads none of them (the
#: command's ``--help`` reads the case names only), a name's module loads on first use.
_EXPORTS = {
    "cases": ("CASES", "COLLISION_MU_TOLERANCES", "COLLISION_TOLERANCES", "DEFAULT_DIR", "FROZEN_TOLERANCES",
              "MEASUREMENTS", "ReferenceCase", "Tolerance", "case_by_name", "tolerances_for"),
    "tables": ("Deviation", "Violation", "compare_tables", "deviations", "read_table", "run_case",
               "write_table"),
    "store": ("CheckReport", "DECKS_DIR", "FORMAT", "GOLDEN_DECKS", "GoldenDeck", "MANIFEST",
              "REGENERATE_COMMAND", "check", "compare_decks", "compare_manifest", "expected_files",
              "format_report", "manifest", "normalise_deck", "read_manifest", "regenerate", "render_golden"),
}
_WHERE = {name: module for module, names in _EXPORTS.items() for name in names}
__all__ = sorted(_WHERE)


def __getattr__(name: str):  # no name here is also a module's: importing one would hide it
    if name in _WHERE:
        return getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
