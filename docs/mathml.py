"""MkDocs hook: the docs' math typeset as MathML when the site is built.

``pymdownx.arithmatex`` (generic mode) wraps each ``$...$`` and ``$$...$$`` of the pages in an
``arithmatex`` span or div; this hook replaces each with the MathML that ``latex2mathml`` makes of
it. Browsers draw MathML themselves: the equations render offline, with no script and no font
fetched from elsewhere.
"""

from __future__ import annotations

import html
import re

from latex2mathml.converter import convert

_MATH = re.compile(r'<(span|div) class="arithmatex">(.*?)</\1>', re.S)


def _typeset(match: re.Match) -> str:
    tex = html.unescape(match.group(2)).strip()[2:-2]  # arithmatex's \( ... \) or \[ ... \]
    return convert(tex, display="block" if match.group(1) == "div" else "inline")


def on_page_content(content: str, **_) -> str:
    return _MATH.sub(_typeset, content)
