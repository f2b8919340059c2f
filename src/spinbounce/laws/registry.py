"""One registry of sub-models per kind: each kind's ``__init__`` names its modules, each module
defines its entry, and a keyword finds it (or is refused with the registered ones)."""

from __future__ import annotations

import importlib

from ..errors import SceneError

__all__ = ["registry", "lookup"]


def registry(package: str, modules: tuple[str, ...], entry: str) -> dict:
    """``{keyword: entry}`` of every module of ``package`` named in ``modules``, in their order."""
    found = (getattr(importlib.import_module(f".{name}", package), entry) for name in modules)
    return {item.keyword: item for item in found}


def lookup(entries: dict, parameter: str, keyword):
    """The entry of ``keyword``, or a :class:`SceneError` naming ``parameter`` and the choices."""
    try:
        return entries[keyword]
    except (KeyError, TypeError):
        raise SceneError(parameter, keyword, f"must be one of {', '.join(entries)}") from None
