"""3-vectors as tuples in compiled code (numba keeps them in registers: no array is made per call)."""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["FLAGS", "dot", "cross", "axpy", "unit"]

#: The compiled references' numba options: cached on disk, and IEEE arithmetic (a division by zero is
#: inf or NaN, as numpy's, not an exception).
FLAGS = dict(cache=True, error_model="numpy")


@njit(**FLAGS)
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(**FLAGS)
def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@njit(**FLAGS)
def axpy(c, a, b):
    """c a + b of 3-tuples."""
    return (c * a[0] + b[0], c * a[1] + b[1], c * a[2] + b[2])


@njit(**FLAGS)
def unit(a):
    size = np.sqrt(dot(a, a))
    return (a[0] / size, a[1] / size, a[2] / size), size
