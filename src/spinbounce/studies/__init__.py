"""The studies (claims, accuracy, validation, restitution, tangential, ...), and the one way two of
its packages load their modules: on a name's first use, so a command's ``--help`` loads none."""

import importlib

__all__ = ["lazy_exports"]


def lazy_exports(package: str, exports: dict[str, tuple[str, ...]]):
    """``(__all__, __getattr__)`` for ``package``: each name of ``exports`` (module -> names) loads
    its module on first use. No name may also be a module's: importing one would hide it."""
    where = {name: module for module, names in exports.items() for name in names}

    def __getattr__(name: str):
        if name in where:
            return getattr(importlib.import_module(f".{where[name]}", package), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    return sorted(where), __getattr__
