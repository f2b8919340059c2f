"""Griffe extension: read the package's reST-flavoured docstrings as Markdown.

Docstrings use Sphinx roles (:class:`~a.b.C`) and ``::`` before literal blocks. Roles
become autorefs links that resolve when the target is on the site and stay plain code
when it is not (``optional``); a paragraph's closing ``::`` becomes ``:``.
"""

from __future__ import annotations

import re

import griffe

_ROLE = re.compile(r":(?:class|func|meth|mod|data|attr|exc|obj):`(~?)([\w.]+)`")


def _link(match: re.Match) -> str:
    short, target = match.groups()
    shown = target.rsplit(".", 1)[-1] if short else target
    return f'<autoref identifier="{target}" optional><code>{shown}</code></autoref>'


def markdown(text: str) -> str:
    text = _ROLE.sub(_link, text)
    return re.sub(r"(\S)::\n", r"\1:\n", text)


class RestToMarkdown(griffe.Extension):
    """Rewrite every docstring once it is loaded."""

    def on_object(self, *, obj: griffe.Object, **kwargs) -> None:
        if obj.docstring is not None:
            obj.docstring.value = markdown(obj.docstring.value)
