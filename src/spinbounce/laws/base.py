"""What each kind of sub-model declares and answers (normal, damping, tangential, the wall's
style), and the registry every kind keeps: its ``__init__`` names its modules, each module
defines its entry, and a keyword finds it (or is refused with the registered ones).

A sub-model is asked, never named: its coefficients, its flags (``contact_radius``: the
force grows with the contact radius a = sqrt(R delta), LAMMPS's ``contact_radius_flag``;
``power``: F = kn r^(p - 1) delta^p), the words it adds to a
deck, and the contact's normal motion for the exact reference and the step rule.
"""

from __future__ import annotations

import importlib

import numpy as np

from ..declaration import Parameter
from ..errors import SceneError

__all__ = ["NormalLaw", "DampingLaw", "TangentialLaw", "Style", "Kind", "STIFFNESS", "NO_CAP_MU", "registry", "lookup",
           "refuse_foreign", "coefficients", "choice"]

#: LAMMPS always caps |F_t| <= mu F_n: "no cap" is this large mu (measured on this build: mu = 1e4
#: leaves a 1e-4 error floor, 1e12 does not).
NO_CAP_MU = 1.0e12

#: The stiffness of ``hooke`` (F = kn delta) and ``hertz`` (F = kn a delta, LAMMPS's K).
STIFFNESS = Parameter(
    "kn", "normal spring constant (Hertz: LAMMPS's K, F = kn sqrt(r) delta^(3/2))", "force/length", 10.0,
    low=0.0, low_open=True, why="a positive stiffness keeps the sphere out of the wall",
    deck="wall/gran granular hooke|hertz KN")


def registry(package: str, modules: tuple[str, ...], entry: str) -> dict:
    """``{keyword: entry}`` of every module of ``package`` named in ``modules``, in their order."""
    found = (getattr(importlib.import_module(f".{name}", package), entry) for name in modules)
    return {item.keyword: item for item in found}


def refuse_foreign(kind: str, law, values: dict, foreign: tuple[Parameter, ...]) -> None:
    """Refuse a value given for a coefficient of another ``kind`` sub-model than ``law`` (the
    coefficients without a default: a law's own, given only with it)."""
    for parameter in foreign:
        if parameter not in law.coefficients and values.get(parameter.name) is not None \
                and parameter.default is None:
            raise SceneError(parameter.name, values[parameter.name],
                             f"is not a coefficient of {kind} = {law.keyword} (it takes "
                             f"{', '.join(p.name for p in law.coefficients)})")


def coefficients(entries: dict) -> tuple[Parameter, ...]:
    """Every coefficient of the sub-models in ``entries`` (a registry), each once, in its order."""
    return tuple(dict.fromkeys(p for law in entries.values() for p in law.coefficients))


def choice(name: str, meaning: str, entries: dict, default: str, deck: str) -> Parameter:
    """The parameter that picks one of ``entries`` (a registry) by keyword, each summarised."""
    laws = "; ".join(f"{law.keyword}: {law.summary}" for law in entries.values())
    return Parameter(name, f"{meaning} ({laws})", "-", default, kind="choice", choices=tuple(entries), deck=deck)


class Kind:
    """One kind of sub-model (normal, damping, tangential): the parameter that picks one, what it
    means, the registry, the default keyword and the deck's words; it finds a sub-model by keyword,
    lists every sub-model's coefficients and makes the choice parameter."""

    def __init__(self, name: str, meaning: str, entries: dict, default: str, deck: str):
        self.name, self.meaning, self.entries, self.default, self.deck = name, meaning, entries, default, deck

    def law(self, keyword: str):
        """The sub-model of ``keyword``, or a :class:`SceneError` listing the registered ones."""
        return lookup(self.entries, self.name, keyword)

    def coefficients(self) -> tuple[Parameter, ...]:
        """Every sub-model's coefficients, each once, in registry order."""
        return coefficients(self.entries)

    def parameter(self) -> Parameter:
        """The choice of one of the registered keywords."""
        return choice(self.name, self.meaning, self.entries, self.default, self.deck)


def lookup(entries: dict, parameter: str, keyword):
    """The entry of ``keyword``, or a :class:`SceneError` naming ``parameter`` and the choices."""
    try:
        return entries[keyword]
    except (KeyError, TypeError):
        raise SceneError(parameter, keyword, f"must be one of {', '.join(entries)}") from None


class NormalLaw:
    """A normal sub-model. Subclasses set the class attributes and the normal motion."""

    #: LAMMPS's keyword, after ``granular`` in ``fix wall/gran`` or in ``pair_coeff``.
    keyword: str = ""
    #: The sub-model a model without a ``normal`` has (the paper's).
    default_keyword = "hooke"
    #: The model's values it computes from its coefficients (reset when a model is copied).
    derived: tuple[str, ...] = ()
    #: One line for the ``normal`` parameter's help.
    summary: str = ""
    #: The coefficients it takes, besides the spheres' (declared once each).
    coefficients: tuple[Parameter, ...] = (STIFFNESS,)
    #: The force grows with the contact radius a = sqrt(R delta): the contact time, and with it
    #: Omega, depends on the impact speed (Hertzian: F = kn a delta).
    contact_radius: bool = False
    #: The force's power of the overlap, F = kn r^(power - 1) delta^power (LAMMPS's, against a wall).
    power: float = 1.0
    #: It is made from a material (E, nu), so a Mindlin stiffness can be too (LAMMPS's NULL k_t).
    material: bool = False

    def settle(self, values: dict, foreign: tuple[Parameter, ...]) -> dict:
        """The model's values this law fixes (derived coefficients), after refusing a value
        given for another law's coefficient (``foreign``: every other sub-model's)."""
        refuse_foreign("normal", self, values, foreign)
        return {}

    def wall_constant(self, model) -> float:
        """K of the wall's force K delta^power: kn r^(power - 1) (Hooke: kn; Hertz: kn sqrt(r))."""
        return model.kn * model.r ** (self.power - 1.0)

    def shear_stiffness(self, model) -> float:
        """LAMMPS's NULL Mindlin stiffness 8 G* of its material (only a ``material`` law has one)."""
        raise NotImplementedError(f"normal = {self.keyword} has no material")

    #: Its coefficients in LAMMPS's order after its keyword (``eta_n``: the damping's ETA_N): the
    #: deck writes them and ``--contact`` reads them (:mod:`spinbounce.laws.words`).
    lammps_coefficients: tuple[str, ...] = ("kn", "eta_n")

    def deck_terms(self, model, eta_n: float) -> tuple:
        """Its part of a deck, as LAMMPS reads it after ``granular``: the keyword (a word from
        the registry), then its coefficients as numbers (the deck formats them)."""
        return (self.keyword, *(float(eta_n if name == "eta_n" else getattr(model, name))
                                for name in self.lammps_coefficients))

    # -- the normal motion (exact) --------------------------------------------------
    def contact_times(self, model, v_n) -> np.ndarray:
        """Each sphere's time until it is out of the overlap."""
        raise NotImplementedError

    def restitutions(self, model, v_n) -> np.ndarray:
        """Each sphere's normal restitution -v_n(out)/v_n(0)."""
        raise NotImplementedError

    def integrated(self, model) -> bool:
        """Whether its damped contact has no closed form here: a dashpot, and a force or a dashpot
        that grows with the contact radius (its exits are then :meth:`integrated_exits`)."""
        return model.gamma_n > 0.0 and (self.contact_radius or model.damping_law.radius_power(self) > 0.0)

    def integrated_exits(self, model, v_n) -> np.ndarray:
        """(n, 3) restitution, contact time and the force's end of each contact, the normal motion
        integrated in time (spinbounce.exact.contact_phases; scipy is loaded here, when one is asked)."""
        from ..exact import contact_phases

        law = contact_phases.Law.of(model, normal_only=True)
        return np.array([contact_phases.normal_exit(law, abs(float(v))) for v in np.atleast_1d(v_n)])

    def dashpot_rate(self, model, speed: float) -> float:
        """The normal dashpot over the mass at the deepest overlap of |v_n| = ``speed`` (undamped,
        an upper bound): gamma_n a^s/m."""
        s = model.damping_law.radius_power(self)
        a_max = float(np.sqrt(model.r * self.max_overlap(model, speed))) if s else 1.0
        return model.gamma_n * a_max**s / model.m

    def force_times(self, model, v_n) -> np.ndarray:
        """Each sphere's time until the contact force ends (at or before it leaves the overlap: with
        limit_damping where the force turns)."""
        if self.integrated(model):
            return self.integrated_exits(model, v_n)[:, 2]
        return self.contact_times(model, v_n)

    def tunnelling_speed(self, model) -> float:
        """The |v_n| at which the largest overlap reaches the radius (the centre would cross the wall)."""
        raise NotImplementedError

    def max_overlap(self, model, speed) -> np.ndarray:
        """The largest overlap of a contact that starts touching at |v_n| = ``speed``."""
        raise NotImplementedError

    def normal_mode(self, model, speed: float | None) -> tuple[float, float]:
        """(w, c) of the normal motion as x'' + c x' + w^2 x = 0 (the step rule's mode); a
        nonlinear force is represented by its stiffest point, at the fastest ``speed``."""
        raise NotImplementedError


class DampingLaw:
    """A damping sub-model: LAMMPS's keyword after ``damping``, its coefficients, the dashpots
    it gives LAMMPS (the normal sub-model's damping coefficient ETA_N, the tangential one's X_T)
    and the viscous dashpots they make in a contact of effective mass ``m_eff``: the normal
    -gamma_n v_n and the tangential -gamma_t u' that every exact reference takes."""

    keyword: str = ""
    #: The sub-model a model without a ``damping`` has (the paper's viscous dashpots).
    default_keyword = "velocity"
    #: The sub-model LAMMPS constructs for a granular line that names none (its granular model's, fix wall/gran's
    #: and pair granular's "default damping sub model if unspecified"): how ``--contact`` reads such a line.
    lammps_default_keyword = "viscoelastic"
    #: One line for the ``damping`` parameter's help.
    summary: str = ""
    coefficients: tuple[Parameter, ...] = ()
    #: The model's values it computes from its coefficients (reset when a model is copied).
    derived: tuple[str, ...] = ()

    def settle(self, values: dict, foreign: tuple[Parameter, ...]) -> dict:
        """The model's values this law fixes (its dashpots against a wall, whose effective mass
        is the sphere's), after refusing another damping sub-model's coefficients."""
        refuse_foreign("damping", self, values, foreign)
        return {}

    #: How LAMMPS's ETA_N follows a contact run in time units s times longer (masses s^2, speeds
    #: 1/s; the dashpot gamma_n must become s gamma_n): ETA_N times s to this power.
    eta_time_power: int = 1

    def radius_power(self, normal) -> float:
        """s of its dashpots c = gamma a^s with the ``normal`` sub-model (LAMMPS's prefactor: 0 for
        a constant one; 1/2 for sqrt(m_eff F/delta) with the Hertzian force, F/delta = kn a)."""
        return 0.0

    @property
    def normal_coefficient(self) -> str:
        """The coefficient a user gives for the normal dashpot (named when it is refused)."""
        return "gamma_n"

    def contact_dashpots(self, model, m_eff: float) -> tuple[float, float]:
        """(gamma_n, gamma_t) in a contact of effective mass ``m_eff`` (a pair's)."""
        return model.gamma_n, model.gamma_t

    def dashpots(self, model) -> tuple[float, float, bool, list[str]]:
        """(ETA_N, X_T, whether to write ``damping KEYWORD``, notes) for a deck."""
        raise NotImplementedError

    def deck_terms(self, written: bool) -> tuple:
        return ("damping", self.keyword) if written else ()

    def from_lammps(self, eta_n: float, x_t: float) -> dict:
        """The model's values of a deck's ETA_N and X_T under this damping (``--contact``)."""
        raise NotImplementedError


class TangentialLaw:
    """A tangential sub-model: LAMMPS's keyword after ``tangential``, its coefficients, its flags,
    its words given the damping's tangential coefficient, and its spring's stiffness (the step
    rule's slip mode; the frozen contact's spring)."""

    keyword: str = ""
    #: The sub-model a model without a ``tangential`` has (the paper's Cundall-Strack spring).
    default_keyword = "linear_history"
    #: One line for the ``tangential`` parameter's help.
    summary: str = ""
    coefficients: tuple[Parameter, ...] = ()
    #: The model's values it computes from its coefficients (reset when a model is copied).
    derived: tuple[str, ...] = ()
    #: Its stiffness grows with the contact radius a = sqrt(R delta) (LAMMPS's contact_radius_flag):
    #: its exact reference is :mod:`spinbounce.exact.mindlin`.
    contact_radius: bool = False
    #: Its cap resets the history by kt alone (this build's classic spring): with a cap its
    #: reference is :mod:`spinbounce.exact.classic`.
    classic_cap: bool = False
    #: LAMMPS projects its history onto the tangent plane at every step, capped or not (this build's
    #: classic spring); the others turn it only near the cap (|xi.n| k > 1e-10 mu F_n), which the no-cap
    #: mu never is. Between two spheres the line of centres turns, so their references differ.
    turns_history: bool = False
    #: (force, rescale): its history is the elastic force (``/force``), not a displacement; it is
    #: rescaled by a_new/a_old while the contact radius shrinks (``_rescale``).
    variant: tuple[bool, bool] = (False, False)

    def stiffness(self, model) -> float:
        """k of its spring k a^q (q = 1 on the contact radius, else 0): linear_history's kt."""
        return model.kt

    def settle(self, values: dict, foreign: tuple[Parameter, ...]) -> dict:
        """The model's values this law fixes, after refusing another tangential sub-model's
        coefficients (and what it cannot be checked with)."""
        refuse_foreign("tangential", self, values, foreign)
        return {}

    def cap(self, model) -> tuple[float, str]:
        """The Coulomb cap a deck writes for the model, and why: the model's, or :data:`NO_CAP_MU`
        for none (LAMMPS always applies one)."""
        if model.mu is None:
            return NO_CAP_MU, ("the paper's model has no Coulomb limit; LAMMPS always applies one, so mu = "
                               f"{NO_CAP_MU:g}")
        return model.mu, f"Coulomb limit |F_t| <= {model.mu!r} F_n: not the paper's model"

    #: Its coefficients in LAMMPS's order after its keyword (``x_t``: the damping's X_T; ``mu``:
    #: the cap): the deck writes them, ``--contact`` reads them. A value of none is written NULL.
    lammps_coefficients: tuple[str, ...] = ("kt", "x_t", "mu")

    def deck_terms(self, model, x_t: float, mu: float) -> tuple:
        """Its words, given the damping's tangential coefficient and the cap to write."""
        given = {"x_t": x_t, "mu": mu}
        values = (given[name] if name in given else getattr(model, name) for name in self.lammps_coefficients)
        return ("tangential", self.keyword, *("NULL" if v is None else float(v) for v in values))

    def slip_stiffness(self, model, speed: float | None) -> float:
        """The slip spring's stiffness at its stiffest, for a contact at |v_n| = ``speed``."""
        raise NotImplementedError

    def frozen_stiffness(self, model, overlap: float | None) -> float:
        """The slip spring's stiffness at a fixed ``overlap`` (the frozen contact)."""
        raise NotImplementedError


class Style:
    """A wall command's style. Subclasses set the flags and build the deck's terms."""

    #: The ``wall`` parameter's value.
    keyword: str = ""
    #: One line for the ``wall`` parameter's help.
    summary: str = ""
    #: The tangential spring grows with the contact radius (kt sqrt(r delta)), so its exact theory
    #: is :mod:`spinbounce.exact.classic`, and Omega depends on v_n.
    tangential_contact_radius: bool = False
    #: Without a cap, a collision's error is smooth in dt, so Richardson extrapolation applies.
    smooth_in_dt: bool = True
    #: Two free spheres can run this law against the pair references.
    pairs: bool = True

    def check(self, model) -> None:
        """Refuse what this style cannot express, or its theory does not cover."""

    def coefficient_terms(self, model, eta_n: float, x_t: float, damping: bool, mu: float) -> tuple:
        """The coefficients ``pair_coeff`` takes for this law (a style without pairs has none)."""
        raise NotImplementedError(f"the {self.keyword} style has no pair coefficients here")

    def wall_terms(self, model) -> dict:
        """The deck's view of the wall: ``terms``, the words and numbers after ``wall/gran``
        (a word from a registry, or a number the deck formats), ``comment``, and the numbers
        the templates also use."""
        raise NotImplementedError
