"""Stored reference outputs (docs/how-to/references.md): a fixed set of runs whose results must not drift.

A reference case (:mod:`.cases`) is a small scene (a few spheres bouncing in one run, or a
subsampled frozen-contact series) whose final states and theory are stored as plain CSV under
``tests/reference/`` (:mod:`.tables`: a column fails when any row differs by more than its
absolute tolerance, each with its reason), its rendered deck as golden text under ``decks/``
(matched exactly but for the version in its first line, so a release does not invalidate them
but any changed command does), and what produced them in ``MANIFEST.json`` (:mod:`.store`).
Only :func:`regenerate` writes them; :func:`check` and the tests run in throw-away folders.
"""

from .. import lazy_exports

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
__all__, __getattr__ = lazy_exports(__name__, _EXPORTS)
