"""The frozen contact (theory.md): one sphere held at a fixed overlap, its slip against Eq. 10."""

from .scene import Frozen

__all__ = ["Frozen"]
