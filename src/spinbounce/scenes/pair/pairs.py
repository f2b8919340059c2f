"""Two spheres at first touch (:class:`Pair`, each a :class:`Sphere`), the wall contact whose
equations a pair's normal and slip motion share (:func:`equivalent_wall`), and the same pair in
slower time units (:func:`time_scaled`)."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ...exact import pair as planar
from ...lammps.decks import ALPHA_NVE_SPHERE
from ...model.contact import ContactModel
from ...model.parameters import SceneError, by_name
from .columns import pair_columns
from .contact import PairContact, checked as _checked

__all__ = ["Sphere", "Pair", "equivalent_wall", "time_scaled", "speeds", "slip_speeds", "along_z"]


def _vector(name: str, value) -> tuple[float, float, float]:
    if isinstance(value, tuple) and len(value) == 3 and all(isinstance(x, float) and math.isfinite(x) for x in value):
        return (float(value[0]) + 0.0, float(value[1]) + 0.0, float(value[2]) + 0.0)  # three finite floats already
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise SceneError(name, value, "must be three numbers") from None
    if arr.shape != (3,):
        raise SceneError(name, value, "must be three numbers (x, y, z)")
    if not np.all(np.isfinite(arr)):
        raise SceneError(name, value, "must be finite")
    return tuple((arr + 0.0).tolist())


@dataclass(frozen=True)
class Sphere:
    """One sphere: mass, radius and alpha = I/(m r^2), as declared for the wall's sphere."""

    m: float = by_name("m").default
    r: float = by_name("r").default
    alpha: float = by_name("alpha").default

    def __post_init__(self):
        _checked(self, ("m", "r", "alpha"))

    @property
    def inertia(self) -> float:
        return self.alpha * self.m * self.r**2

    @property
    def rigid(self) -> bool:
        return self.alpha != ALPHA_NVE_SPHERE


@dataclass(frozen=True)
class Pair:
    """Two spheres at first touch. ``normal``: from b's centre to a's (normalised here)."""

    a: Sphere = field(default_factory=Sphere)
    b: Sphere = field(default_factory=Sphere)
    normal: tuple = (0.0, 0.0, 1.0)
    v_a: tuple = (1.0, 0.0, -1.0)
    v_b: tuple = (0.0, 0.0, 0.0)
    w_a: tuple = (0.0, 0.0, 0.0)
    w_b: tuple = (0.0, 0.0, 0.0)

    def __hash__(self) -> int:  # hashed often (the references' cache keys): computed once
        if "_hash" not in self.__dict__:
            self.__dict__["_hash"] = hash((self.a, self.b, self.normal, self.v_a, self.v_b, self.w_a, self.w_b))
        return self.__dict__["_hash"]

    def __post_init__(self):
        for name in ("normal", "v_a", "v_b", "w_a", "w_b"):
            object.__setattr__(self, name, _vector(name, getattr(self, name)))
        length = math.sqrt(sum(x * x for x in self.normal))
        if length == 0.0:
            raise SceneError("normal", self.normal, "must not be zero")
        object.__setattr__(self, "normal", tuple(x / length for x in self.normal))
        if self.v_n >= 0.0:
            raise SceneError("v_a - v_b", self.v_n, "must have a negative component along normal "
                             "(the spheres approach at first touch)")

    @property
    def radsum(self) -> float:
        return self.a.r + self.b.r

    @cached_property
    def v_n(self) -> float:
        """Relative normal velocity (v_a - v_b).n: < 0 while approaching."""
        return float(np.dot(np.subtract(self.v_a, self.v_b), self.normal))

    @property
    def v_t(self) -> float:
        """Relative tangential speed of the centres: what turns the line of centres."""
        v = np.subtract(self.v_a, self.v_b)
        return float(np.linalg.norm(v - self.v_n * np.asarray(self.normal)))

    def properties(self) -> dict:
        """The sphere properties as :mod:`exact.pair` and :mod:`pair_exact` take them."""
        return {"m_a": self.a.m, "r_a": self.a.r, "alpha_a": self.a.alpha,
                "m_b": self.b.m, "r_b": self.b.r, "alpha_b": self.b.alpha}

    def vectors(self) -> dict:
        return {"n": self.normal, "v_a": self.v_a, "v_b": self.v_b, "w_a": self.w_a, "w_b": self.w_b}

    def equivalent_wall(self, contact: PairContact) -> ContactModel:
        """The wall contact with this pair's normal and slip equations (:func:`equivalent_wall`)."""
        return equivalent_wall(self.a, self.b, contact)

    def slip_speed(self) -> float:
        """|u'(0)|: the contact points' initial relative tangential speed."""
        return float(slip_speeds((self,))[0])

    def speed(self) -> float:
        """The larger of the impact speed |v_a - v_b| and the initial slip speed |u'(0)|:
        the scale errors are measured in."""
        return float(speeds((self,))[0])


def along_z(a: Sphere, b: Sphere, v_a: np.ndarray, w_a: np.ndarray, v_b, w_b) -> list[Pair]:
    """One :class:`Pair` per row of ``v_a`` and ``w_a`` ((N, 3), LAMMPS's frame), the line of centres along
    +z, b's ``v_b`` and ``w_b`` (3,) shared: checked as arrays (finite; approaching), then made without
    each pair's own checks (a sweep's 25,000 pairs otherwise spend half a second in them)."""
    v_a, w_a = np.atleast_2d(v_a) + 0.0, np.atleast_2d(w_a) + 0.0
    v_b, w_b = np.asarray(v_b, dtype=float) + 0.0, np.asarray(w_b, dtype=float) + 0.0
    for name, value in (("v_a", v_a), ("w_a", w_a), ("v_b", v_b), ("w_b", w_b)):
        if not np.all(np.isfinite(value)):
            raise SceneError(name, value[~np.isfinite(value)].flat[0], "must be finite")
    closing = v_a[:, 2] - v_b[2]
    if np.any(closing >= 0.0):
        raise SceneError("v_a - v_b", float(closing[closing >= 0.0][0]), "must have a negative component along "
                         "normal (the spheres approach at first touch)")
    shared = {"a": a, "b": b, "normal": (0.0, 0.0, 1.0), "v_b": tuple(v_b.tolist()), "w_b": tuple(w_b.tolist())}
    return [_trusted(Pair, **shared, v_a=tuple(va), w_a=tuple(wa)) for va, wa in zip(v_a.tolist(), w_a.tolist())]


def slip_speeds(pairs) -> np.ndarray:
    """:meth:`Pair.slip_speed` of each of ``pairs`` (or of their arrays, as :func:`.columns.pair_columns` and
    :attr:`.scene.PairBatch.columns` give them), at once."""
    x = pairs if isinstance(pairs, dict) else pair_columns(pairs)
    return np.linalg.norm(planar.slip_rate(x["normal"], x["v_a"], x["v_b"], x["w_a"], x["w_b"], x["r_a"], x["r_b"]),
                          axis=-1)


def speeds(pairs) -> np.ndarray:
    """:meth:`Pair.speed` of each of ``pairs`` (or of their arrays: :func:`slip_speeds`), at once."""
    x = pairs if isinstance(pairs, dict) else pair_columns(pairs)
    return np.maximum(np.linalg.norm(x["v_a"] - x["v_b"], axis=-1), slip_speeds(x))


@functools.lru_cache(maxsize=1024)
def equivalent_wall(a: Sphere, b: Sphere, contact: PairContact) -> ContactModel:
    """The wall contact with the normal and slip equations of spheres a and b (:mod:`exact.pair`): the
    reduced mass, the equivalent alpha and, for a law on the contact radius, the radius R_eff of
    a = sqrt(R_eff delta) (else the smaller radius, which the overlap must stay below). One object per
    spheres and law: a batch's pairs of the same spheres share it."""
    r = a.r * b.r / (a.r + b.r) if contact.on_contact_radius else min(a.r, b.r)
    return ContactModel(m=planar.reduced_mass(a.m, b.m), r=r,
                        alpha=planar.equivalent_alpha(a.m, a.alpha, b.m, b.alpha), **contact.law(),
                        damping=contact.damping, **dict(contact.damping_coefficients), **dict(contact.words))


def time_scaled(pair: Pair, scale: float) -> Pair:
    """The same collision in time units ``scale`` times longer: masses (and so moments of inertia)
    times scale^2, velocities and spins over scale, same radii, springs and geometry. Every
    overlap and spring force is the same at the same fraction of the contact, which lasts
    ``scale`` times longer; the final velocities and spins are the original's over ``scale``.
    Exact for an undamped contact only (a damping force -eta v would need eta times scale).
    Built from a checked pair by a positive finite scale, it is not checked again."""
    heavier = {side: _trusted(Sphere, m=s.m * scale**2, r=s.r, alpha=s.alpha)
               for side, s in (("a", pair.a), ("b", pair.b))}
    slower = {k: tuple(x / scale for x in getattr(pair, k)) for k in ("v_a", "v_b", "w_a", "w_b")}
    return _trusted(Pair, **heavier, normal=pair.normal, **slower)


def _trusted(cls, **fields):
    """A frozen dataclass made from values already checked, without its checks (its fields written straight
    into its ``__dict__``, as the frozen class's own ``__init__`` does through object.__setattr__)."""
    out = object.__new__(cls)
    out.__dict__.update(fields)
    return out
