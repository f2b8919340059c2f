"""Golden decks: each case's rendered deck (and the files it reads), stored as text that a
fresh rendering must reproduce exactly, version number aside."""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass
from pathlib import Path

from ...lammps.decks import ATOM_ROUTES
from ...scenes.collision.deck import render_collision
from ...scenes.frozen.deck import render_frozen
from ...scenes.frozen import Frozen
from .cases import CASES, case_by_name
from .tables import Violation


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

