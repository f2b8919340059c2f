"""The contact law shared by every pair of a batch (:class:`PairContact`): what the deck writes and
what the pair references (:mod:`spinbounce.exact.pair_exact`, :mod:`spinbounce.exact.pair_capped`)
integrate."""

from __future__ import annotations

import itertools
import warnings
from collections import OrderedDict
from dataclasses import dataclass, fields

import numpy as np

from ...errors import NoLimit, PhysicsWarning, ResultError
from ...model.parameters import by_name
from .columns import pair_columns

__all__ = ["PairContact", "checked", "ONE_PAIR_SECONDS"]


def checked(owner, names: tuple[str, ...]) -> None:
    """Each of ``names`` of a frozen ``owner`` checked against its declaration (and set so)."""
    for name in names:
        object.__setattr__(owner, name, by_name(name).check(getattr(owner, name)))


#: Seconds one pair's exact references take when solved on their own (scipy on the compiled equations,
#: exact.pair_kernel; the exact reference and the planar theory, which the capped reference solves by events),
#: as a sweep's chunks and a gas's theories are estimated: the slower of the measurements on an idle core, with
#: room. A sweep's default ranges (v_n -0.8 to -0.1, 2-D and 3-D, 12 to 29 pairs): 25 ms uncapped
#: (Hertz-Mindlin); capped 20 to 150 ms (Hooke with limit_damping, the Mindlin springs and dashpots). A gas's
#: collisions (3-D, hot: 10 to 20 draws at T_tr = 0.5, hertz/material with E = 1e5 and linear_history or each
#: Mindlin spring): 10 to 30 ms uncapped, 41 to 48 ms capped (mu = 0.5), the classic spring capped 53 ms with
#: Hooke's force and 68 ms with Hertz's. In a sweep's slower impacts a capped Hertzian force on a spring that
#: does not grow with the contact radius (linear_history), or the classic spring's cap, takes far longer
#: ("capped stiff"): the cap closes on the stiff spring at both ends of the contact and a slide's direction turns
#: stiffly (the classic spring 0.8 to 0.9 s a pair; linear_history 36 ms in the plane and 1.9 s in 3-D, 0.3 to
#: 4.3 s a pair). A law whose references are solved together (:attr:`PairContact.batched`) costs none of these.
ONE_PAIR_SECONDS = {"uncapped": 0.06, "capped": 0.2, "capped stiff": 6.0}


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

    def __hash__(self) -> int:  # in every pair's reference key (solve_all): computed once, not per key
        if "_hash" not in self.__dict__:
            self.__dict__["_hash"] = hash(tuple(getattr(self, f.name) for f in fields(self)))
        return self.__dict__["_hash"]

    def __getstate__(self) -> dict:  # the hash stays behind: a string's differs from process to process
        return {k: v for k, v in self.__dict__.items() if k != "_hash"}

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
        return self.solve_all((pair,), planar)[0]

    def solve_all(self, pairs, planar: bool = False) -> tuple:
        """:meth:`solve` of each of ``pairs``: those not solved before together where the law allows
        (:attr:`batched`), else one at a time. A pair solved before is looked up once (a pair's hash is a Python
        call: a sweep's chunk asks for 25,000 several times)."""
        solved = _SOLVED.pop((self, planar), None) or {}
        _SOLVED[(self, planar)] = solved  # this law's outcomes now the newest
        found = [solved.get(pair) for pair in pairs]
        missing = list(dict.fromkeys(pair for pair, outcome in zip(pairs, found) if outcome is None))
        if missing:
            solved.update(zip(missing, self._solve_many(missing, planar), strict=True))
            found = [solved[pair] if outcome is None else outcome for pair, outcome in zip(pairs, found)]
        _forget_oldest()
        return tuple(found)

    @property
    def batched(self) -> bool:
        """Whether a batch's references are solved together: Hooke's force and linear_history, capped
        (:mod:`spinbounce.exact.pair_capped_batch`, the normal force never cut) or not
        (:mod:`spinbounce.exact.pair_batch`)."""
        from ...exact import pair_batch, pair_capped_batch

        solver = pair_capped_batch if self.mu else pair_batch
        return solver.solvable(self.reference_law(), self.tensile)

    def one_pair_seconds(self, slow_impacts: bool = True) -> float:
        """What one pair's references cost when solved on their own (:data:`ONE_PAIR_SECONDS`); none where a
        batch's are solved together (:attr:`batched`). ``slow_impacts``: the states reach a sweep's slower impacts,
        where a stiff law's cap closes slowly (a gas's hot collisions were measured at the capped figure)."""
        if self.batched:
            return 0.0
        if not self.mu:
            return ONE_PAIR_SECONDS["uncapped"]
        law = self.reference_law()  # a Hertzian force, a spring off the contact radius: the cap closes on it
        stiff = law.get("classic_cap", False) or (law.get("power", 1.0) != 1.0 and law.get("spring_power", 0.0) == 0.0)
        return ONE_PAIR_SECONDS["capped stiff" if stiff and slow_impacts else "capped"]

    def _solve_many(self, pairs: list, planar: bool) -> list:
        try:
            return self._references(pairs, planar)
        except RuntimeError as exc:  # a scipy reference's failure (a contact it cannot end, chattering)
            raise ResultError(f"the exact pair reference gives no outcome: {exc}") from None

    def _references(self, pairs: list, planar: bool) -> list:
        # the references (compiled, or scipy's) are loaded when a pair is solved: a wall's run never is
        from ...exact import pair_batch, pair_capped, pair_capped_batch, pair_exact

        capped = bool(self.mu)  # a cap of zero: no tangential force (the capped solver divides by mu)
        law = self.reference_law() | ({"kt": 0.0, "gamma_t": 0.0} if self.mu == 0.0 else {})
        cap = {"mu": self.mu} if capped else {}
        if self.batched:
            c = pair_columns(pairs)
            names = ("v_a", "v_b", "w_a", "w_b", "m_a", "r_a", "alpha_a", "m_b", "r_b", "alpha_b")
            columns = {"n": c["normal"]} | {k: c[k] for k in names}
            solver = pair_capped_batch if capped else pair_batch
            return solver.solve(**columns, **{k: law[k] for k in self.law()}, **cap, planar=planar)
        solver = pair_capped if capped else pair_exact
        limitless: list[str] = []
        out = [_solved(solver, k, p, law | cap, planar, self.tensile, limitless) for k, p in enumerate(pairs)]
        if limitless:
            held = "the held line of centres' reference (its _planar columns NaN)" if planar else \
                "no reference (status no_limit)"
            warnings.warn(f"{len(limitless)} of {len(pairs)} pair(s) have {held}, the first: {limitless[0]}",
                          PhysicsWarning, stacklevel=4)
        return out


def _solved(solver, k: int, pair, law: dict, planar: bool, tensile: bool, limitless: list):
    """Pair ``k`` of a batch by a scipy reference; its failure names the pair. A pair whose LAMMPS outcome has
    no dt -> 0 limit (:class:`.NoLimit`) gets NaN velocities and spins (its contact time and turn hold), its
    reason kept in ``limitless``."""
    try:
        return solver.solve(**pair.vectors(), **pair.properties(), **law, planar=planar, tensile=tensile)
    except NoLimit as exc:
        limitless.append(f"pair {k}: {exc}")
        nan = np.full(3, np.nan)
        return exc.outcome._replace(v_a=nan, v_b=nan, w_a=nan, w_b=nan)
    except RuntimeError as exc:
        raise RuntimeError(f"the batch's pair {k} (row {k} of those solved together): {exc}") from None


#: Outcomes kept (the laws used longest ago dropped first, then a law's first solved): a probe runs the same
#: pairs at up to five steps, each batch asking for their references; more than a sweep's chunk of pairs
#: (25,000), ~1 kB each.
SOLVED = 1 << 15
#: (law, held line of centres) -> {pair: outcome}: the law used last at the end, each law's pairs in the
#: order they were first solved.
_SOLVED: OrderedDict = OrderedDict()


def kept() -> int:
    """The outcomes kept, over every law."""
    return sum(map(len, _SOLVED.values()))


def _forget_oldest() -> None:
    """Drop the outcomes beyond SOLVED: the laws used longest ago first, then the newest law's first solved."""
    extra = kept() - SOLVED
    while extra > 0:
        law, solved = next(iter(_SOLVED.items()))
        if len(_SOLVED) > 1 and len(solved) <= extra:
            del _SOLVED[law]
            extra -= len(solved)
            continue
        for pair in list(itertools.islice(solved, extra)):
            del solved[pair]
        extra = 0
        if not solved:
            del _SOLVED[law]
