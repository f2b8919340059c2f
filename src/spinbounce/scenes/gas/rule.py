"""The paper's planar rule for two of a gas's spheres: its restitutions, each drawn collision's outcome by it,
and its exact average over a Maxwellian gas's collisions (the rough-sphere closed form).

The pair-level theories take it as a control variate: a collision's outcome by LAMMPS or by the exact
references differs from the rule's by a little (the line of centres turns, the step errs), so the mean of
that difference, plus the rule's exact mean, has a far smaller variance than the outcomes' own mean.
"""

from __future__ import annotations

import numpy as np

from ...exact import kinetic
from ...exact import pair as planar
from ..pair.kind import equal_pair, no_planar_matrix

__all__ = ["restitutions", "has_rule", "outcomes", "mean_changes", "pair_law"]


def pair_law(model) -> dict:
    """The planar rule's keyword arguments for two of the gas's equal spheres (:func:`.pair.predict`)."""
    props = {"m_a": model.m, "r_a": model.r, "alpha_a": model.alpha, "m_b": model.m, "r_b": model.r,
             "alpha_b": model.alpha}
    return props | equal_pair(model)[1].law()


def has_rule(model) -> bool:
    """Whether the planar theory gives the law a rule (no cap, no law on the contact radius)."""
    return no_planar_matrix(model) is None


def outcomes(model, g: np.ndarray, spins: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each collision's relative velocity g' and spins (w_a', w_b') by the rule, from g = v_a - v_b ((count,
    3)) and the spins ((count, 6)), the line of centres n = +z."""
    n, zero = np.tile([0.0, 0.0, 1.0], (len(g), 1)), np.zeros_like(g)
    va, vb, wa, wb = planar.predict(n, g, zero, spins[:, :3], spins[:, 3:], **pair_law(model))
    return va - vb, np.hstack([wa, wb])


def restitutions(model) -> tuple[float, float]:
    """(e_n, beta) of the rule: a closing unit speed with a unit slip."""
    g, zero = np.array([[1.0, 0.0, -1.0]]), np.zeros((1, 3))
    g1, w1 = outcomes(model, g, np.zeros((1, 6)))
    u0 = planar.slip_rate(np.array([[0.0, 0.0, 1.0]]), g, zero, zero, zero, model.r, model.r)[0]
    u1 = planar.slip_rate(np.array([[0.0, 0.0, 1.0]]), g1, zero, w1[:, :3], w1[:, 3:], model.r, model.r)[0]
    return float(g1[0, 2]), float(-np.dot(u1, u0) / np.dot(u0, u0))  # e_n = -g'_n / g_n with g_n = -1


def mean_changes(model, t_tr: float) -> np.ndarray:
    """The rule's exact mean energy change of a collision at ``t_tr`` ((3, 2): rows translational, rotational and
    their sum; columns without spins and the spins' part at T_rot = T_tr): 3 T_tr times the closed form's L."""
    e_n, beta = restitutions(model)
    columns = 3.0 * t_tr * kinetic.rough_sphere_matrix(e_n, beta, model.alpha)
    return np.vstack([columns, columns.sum(axis=0)])
