"""The contact law shared by every pair of a batch (:class:`PairContact`): what the deck writes and
what the pair references (:mod:`spinbounce.exact.pair_exact`, :mod:`spinbounce.exact.pair_capped`)
integrate."""

from __future__ import annotations

import functools
from dataclasses import dataclass

from ...exact import pair_capped, pair_exact
from ...model.parameters import by_name

__all__ = ["PairContact", "checked"]


def checked(owner, names: tuple[str, ...]) -> None:
    """Each of ``names`` of a frozen ``owner`` checked against its declaration (and set so)."""
    for name in names:
        object.__setattr__(owner, name, by_name(name).check(getattr(owner, name)))


@dataclass(frozen=True)
class PairContact:
    """The contact law shared by every pair of a batch. ``mu``: the Coulomb cap (None: the
    paper's uncapped model; a capped pair's reference is :mod:`spinbounce.exact.pair_capped`)."""

    kn: float = by_name("kn").default  # the declared defaults (spinbounce.model.parameters), not copies
    kt: float = by_name("kt").default
    gamma_n: float = by_name("gamma_n").default
    gamma_t: float = by_name("gamma_t").default
    mu: float | None = by_name("mu").default
    #: The damping sub-model whose dashpots gamma_n and gamma_t are (for this batch's spheres), and
    #: its own coefficients as (name, value) pairs: the deck writes those, LAMMPS scaling them.
    damping: str = by_name("damping").default
    damping_coefficients: tuple = ()
    #: The law's shape beyond Hooke's force and linear_history's spring, as (name, value) pairs of
    #: :data:`spinbounce.exact.pair_exact.HOOKE` and the spring's k (of k a^q); and the model's words
    #: that choose it (normal and its material, tangential, mindlin_kt, limit_damping): the deck writes those.
    shape: tuple = ()
    words: tuple = ()

    def __post_init__(self):
        checked(self, ("kn", "kt", "gamma_n", "gamma_t", "mu", "damping"))

    def law(self) -> dict:
        """kn, kt, gamma_n and gamma_t, as the uncapped references and the planar theory take them (the
        planar theory's force may pull: with limit_damping, :attr:`tensile` False, it has no matrix)."""
        return {"kn": self.kn, "kt": self.kt, "gamma_n": self.gamma_n, "gamma_t": self.gamma_t}

    @property
    def damped(self) -> bool:
        return self.gamma_n > 0.0 or self.gamma_t > 0.0

    @property
    def on_contact_radius(self) -> bool:
        """Whether its force, spring or dashpot grows with the contact radius (it has a shape; no closed
        planar theory)."""
        return bool(self.shape)

    @property
    def tensile(self) -> bool:
        """Whether the normal force may pull (False with LAMMPS's ``limit_damping``, one of its words)."""
        return not dict(self.words).get("limit_damping", False)

    def reference_law(self) -> dict:
        """What :func:`spinbounce.exact.pair_exact.solve` takes: :meth:`law` with the spring's k as kt
        and the law's shape."""
        shape = dict(self.shape)
        return self.law() | {"kt": shape.pop("k", self.kt)} | shape

    def solve(self, pair, planar: bool = False):
        """The outcome of ``pair`` (a :class:`.scene.Pair`) as LAMMPS integrates it (``planar``: with n held
        fixed), capped or not; solved once per law and pair (a step probe's runs share them)."""
        return _solve(self, pair, planar)


#: Outcomes kept: a probe runs the same pairs at up to five steps, each batch asking for their references.
SOLVED = 1 << 14


@functools.lru_cache(maxsize=SOLVED)
def _solve(contact: PairContact, pair, planar: bool):
    if not contact.mu:  # no cap, or a cap of zero: no tangential force (the capped solver divides by mu)
        law = contact.reference_law() | ({} if contact.mu is None else {"kt": 0.0, "gamma_t": 0.0})
        return pair_exact.solve(**pair.vectors(), **pair.properties(), **law, planar=planar, tensile=contact.tensile)
    return pair_capped.solve(**pair.vectors(), **pair.properties(), **contact.reference_law(), mu=contact.mu,
                             planar=planar, tensile=contact.tensile)
