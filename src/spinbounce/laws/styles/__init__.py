"""The wall command's styles, registered by keyword: one entry each in :data:`STYLES`.

LAMMPS's ``fix wall/gran`` takes either ``granular`` with sub-models chosen by keyword (the
paper's model: :mod:`.granular`) or a classic style, a fixed assembly of sub-models
(``hooke/history``: :mod:`.classic`). The ``wall`` parameter picks one; the rest of
spinbounce asks the style's flags, never its keyword.
"""

from __future__ import annotations

from ...declaration import Parameter
from ..base import Style, lookup, registry

__all__ = ["STYLES", "Style", "style", "style_parameter"]

#: The registry: one entry per style, the module (here) that defines its ``STYLE``.
MODULES = (
    "granular",
    "classic",
)
#: Every wall style, by its keyword (the ``wall`` parameter's value).
STYLES: dict[str, Style] = registry(__name__, MODULES, "STYLE")


def style(keyword: str) -> Style:
    """The style of ``keyword``, or a :class:`SceneError` listing the registered ones."""
    return lookup(STYLES, "wall", keyword)


def style_parameter() -> Parameter:
    """The ``wall`` choice: one of the registered styles."""
    styles = "; ".join(f"{s.keyword}: {s.summary}" for s in STYLES.values())
    return Parameter("wall", f"the wall command ({styles})", "-", "granular", kind="choice", choices=tuple(STYLES),
                     deck="wall/gran granular ... | wall/gran hooke/history KN KT GAMMA_N/m GAMMA_T/m MU 1")
