"""The pair as a scene kind: sphere a of the wall's scene against a free sphere b at rest.

A pair scene is the wall's scene with the wall replaced by sphere b (``scene = "pair"``,
with b's ``m_b``, ``r_b`` and ``alpha_b``; :data:`spinbounce.model.parameters.SCENE`).
Sphere a keeps the model's m, r and alpha and the wall scene's initial state, in the same
frame: the line of centres is LAMMPS's z (b below a), so a's (v_n, v_t, r omega, v_s,
r omega_s, r omega_n) are the wall's columns; b starts at rest without spin, or in its own
state of the same six columns (one collision's: :data:`~spinbounce.model.parameters.STATE_B`). The
contact law is the model's: its sub-models and coefficients (a force, spring or dashpot on the
contact radius with a = sqrt(R_eff delta), R_eff = r r_b/(r + r_b)) and mu; what the pair's references
cannot take is refused here with the reason (:func:`pair_contact`).
"""

from __future__ import annotations

import numpy as np

from ...lammps.decks import lammps_vectors, wall_frame
from ...model.contact import ContactModel
from ...model.parameters import PAIR_ONLY, PAIR_SPHERE, STATE_B, SceneError, by_name
from ...exact import pair as planar
from ...exact.wall_law import Law
from .pairs import along_z
from .scene import Pair, PairContact, Sphere

__all__ = ["pair_contact", "sphere_b", "state_b", "pairs_from_states", "wall_frame", "planar_matrix", "planar_Omega",
           "theory_kind", "THEORIES", "scene_of", "no_planar_matrix", "CAPPED_NO_MATRIX", "RADIAL_NO_MATRIX", "LIMITED_NO_MATRIX"]

#: Why a pair with a Coulomb cap has no scattering matrix (theory, the API and fit say it).
CAPPED_NO_MATRIX = "a capped pair has no matrix: the slides make the outcome depend on the state"
#: Why a pair whose normal force limit_damping cuts has none here.
LIMITED_NO_MATRIX = ("limit_damping cuts the pair's normal force at its turn, which the closed planar theory "
                     "does not: give a state for its exact reference")
#: Why a pair whose force, spring or dashpot grows with the contact radius has none here.
RADIAL_NO_MATRIX = ("a pair whose force, spring or dashpot grows with the contact radius has no closed planar "
                    "theory here: give a state for its exact reference")


#: The names a pair's reference goes by in a sweep's ``theory`` label, a fit's report and ``pair --json``'s
#: ``theory_kind`` (its module in spinbounce.exact), and in words.
THEORIES = {"pair_exact": "the exact pair reference: what LAMMPS integrates, as dt -> 0",
            "pair_capped": "the exact capped pair reference: what LAMMPS integrates under its cap, as dt -> 0"}


def theory_kind(model: ContactModel) -> str:
    """The reference a pair of this model is checked against: the capped one with a cap, else the uncapped."""
    return "pair_exact" if model.mu is None else "pair_capped"


def scene_of(values: dict) -> str:
    """The scene kind of a set of declared values; b's parameters without ``scene = pair`` are refused."""
    scene = by_name("scene").check(values.get("scene") or "wall")
    given = [name for name in PAIR_ONLY if values.get(name) is not None]
    if scene == "wall" and given:
        raise SceneError(given[0], values[given[0]], "is sphere b's: give scene = pair (the wall has no sphere b)")
    return scene


#: The model's words that choose a pair's law beyond the damping (the deck writes them again).
LAW_WORDS = ("normal", "youngs_modulus", "poisson_ratio", "tangential", "mindlin_kt", "limit_damping")


def equal_pair(model: ContactModel) -> tuple[Sphere, PairContact]:
    """Two equal spheres of the model (its m, r and alpha) and their contact under its law (a gas's pairs)."""
    sphere = Sphere(model.m, model.r, model.alpha)
    return sphere, pair_contact(model, sphere)


def pair_contact(model: ContactModel, b: Sphere) -> PairContact:
    """The pair deck's contact law from a contact model against sphere ``b``, or why the pair
    cannot run it. Its dashpots are the damping's in the pair's effective mass m b/(m + b); a force,
    spring or dashpot on the contact radius takes a = sqrt(R_eff delta) (the uncapped reference,
    :mod:`spinbounce.exact.pair_exact`)."""
    shape = _shape(model)
    if not model.style.pairs:
        raise SceneError("wall", model.wall, "must be granular with scene = pair (there is no wall; the classic "
                                             "pair style is not covered by the pair's references)")
    damping = model.damping_law
    gamma_n, gamma_t = damping.contact_dashpots(model, model.m * b.m / (model.m + b.m))
    own = tuple((p.name, getattr(model, p.name)) for p in damping.coefficients) if damping.derived else ()
    words = tuple((name, getattr(model, name)) for name in LAW_WORDS if getattr(model, name) != by_name(name).default)
    return PairContact(model.kn, model.kt, gamma_n, gamma_t, model.mu, model.damping, own, shape, words)


def _shape(model: ContactModel) -> tuple:
    """The law's shape beyond Hooke and linear_history as :attr:`PairContact.shape` ((name, value)
    pairs), or () for the Hookean law."""
    law, projected = Law.of(model), model.tangential_law.turns_history
    if not law.on_contact_radius and not projected:
        return ()
    return (("power", law.power), ("spring_power", law.spring_power), ("force_history", law.force_history),
            ("rescale", law.rescale), ("damping_power", law.damping_power), ("k", law.k), ("projected", projected)) + (
        (("classic_cap", True),) if law.classic_cap else ())  # a cap reset by k alone (exact.pair_capped_phases)


def no_planar_matrix(model: ContactModel) -> str | None:
    """Why the planar theory gives a's state no matrix with this law (a cap; limit_damping with a normal
    dashpot; a law on the contact radius), or None."""
    if model.mu is not None:
        return CAPPED_NO_MATRIX
    if model.limit_damping and model.gamma_n > 0.0:
        return LIMITED_NO_MATRIX
    return RADIAL_NO_MATRIX if _shape(model) else None


def sphere_b(m_b=1.0, r_b=0.5, alpha_b=0.4) -> Sphere:
    """Sphere b from its declared parameters (each checked against its declaration, named)."""
    return Sphere(*(by_name(name).check(value) for name, value in zip(PAIR_SPHERE, (m_b, r_b, alpha_b), strict=True)))


def state_b(values: dict) -> np.ndarray:
    """Sphere b's state (v_n_b, v_t_b, omega_b, v_s_b, omega_s_b, omega_n_b) from declared values
    (each checked; missing or None: at rest)."""
    return np.array([by_name(p.name).check(values[p.name]) if values.get(p.name) is not None else 0.0
                     for p in STATE_B])


def pairs_from_states(model: ContactModel, b: Sphere, states: np.ndarray, b_state=None) -> list[Pair]:
    """One pair per row of (v_n, v_t, omega[, v_s, omega_s, omega_n]): a as the wall's sphere, b
    below it along the line of centres, at rest or in ``b_state`` (the same six, a's frame and
    sign), in LAMMPS's frame as the wall's (:func:`~spinbounce.lammps.decks.lammps_vectors`)."""
    a = Sphere(model.m, model.r, model.alpha)
    states = np.atleast_2d(np.asarray(states, dtype=float))
    full = np.zeros((len(states), 6))
    full[:, : states.shape[1]] = states
    b_state = np.zeros(6) if b_state is None else np.asarray(b_state, dtype=float)
    leaving = np.flatnonzero(full[:, 0] - b_state[0] >= 0.0)
    if leaving.size:
        k = int(leaving[0])
        raise SceneError("v_n - v_n_b", float(full[k, 0] - b_state[0]), "must be < 0: the spheres approach at first "
                                                                       "touch" + (f" (row {k})" if len(full) > 1 else ""))
    return along_z(a, b, *lammps_vectors(*full.T), *lammps_vectors(*b_state))


def planar_matrix(model: ContactModel, b: Sphere, three_d: bool = False) -> np.ndarray:
    """The planar theory's map of a's state (b at rest), 3x3 (6x6 in 3-D): final = M @ initial.

    :func:`spinbounce.exact.pair.predict` is linear in a's state when b starts at rest, so
    its columns are its outcomes for the unit states.
    """
    size = 6 if three_d else 3
    states = np.eye(size)
    states[:, 0] = -1.0  # row 0: v_n = -1 alone; row k: v_n = -1 and unit component k
    spins = [2, 4, 5] if three_d else [2]
    states[:, spins] /= model.r  # the matrix acts on r omega: a unit r omega is omega = 1/r
    pairs = pairs_from_states(model, b, states)
    vectors = {k: np.array([p.vectors()[k] for p in pairs]) for k in ("n", "v_a", "v_b", "w_a", "w_b")}
    v_a, _, w_a, _ = planar.predict(**vectors, **pairs[0].properties(), **pair_contact(model, b).law())
    outcome = wall_frame(v_a, w_a, model.r)[:, :size]
    return np.column_stack([-outcome[0], *(outcome[k] - outcome[0] for k in range(1, size))]) + 0.0


def planar_Omega(model: ContactModel, b: Sphere) -> float:
    """The pair's Omega (the planar theory's; the wall's for equal alpha)."""
    law = pair_contact(model, b).law()
    return float(planar.Omega(model.m, model.alpha, b.m, b.alpha, law["kn"], law["kt"], law["gamma_t"],
                              law["gamma_n"]))
