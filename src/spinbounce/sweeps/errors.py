"""How a sweep refuses to start: one error, naming the key, its value and why."""

from __future__ import annotations

from ..errors import SweepError

__all__ = ["SweepError", "fail"]


def fail(key: str, value, why: str):
    raise SweepError(f"{key} = {value!r}: {why}")
