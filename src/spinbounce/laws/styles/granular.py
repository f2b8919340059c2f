"""``granular``: ``fix wall/gran granular`` assembled from sub-models, the paper's model.

The normal sub-model gives its words (:mod:`spinbounce.laws.normal`); the damping is LAMMPS's
``damping velocity`` (normal force -ETA_N v_n, tangential -(X_T ETA_N) u'); the tangential
spring is ``linear_history`` (Cundall-Strack) with a Coulomb cap.
"""

from __future__ import annotations

import math

from .base import Style

__all__ = ["Granular", "STYLE", "NO_CAP_MU", "VANISHING_ETA_N"]

#: LAMMPS always caps |F_t| <= mu F_n. The paper's model has no cap, so "no cap" is this
#: large mu; facts measured on this build: 1e4 leaves a 1e-4 error floor, 1e12 does not.
NO_CAP_MU = 1.0e12
#: With gamma_n = 0 but gamma_t > 0, LAMMPS's tangential damping is X_T * ETA_N, so ETA_N
#: must not be 0. This relative size (of critical normal damping) changes the normal
#: restitution by about 1e-12, far below any other error.
VANISHING_ETA_N = 1.0e-12


class Granular(Style):
    keyword = "granular"
    summary = "the paper's model, wall/gran granular"

    def dashpots(self, model) -> tuple[float, float, bool, list[str]]:
        """(ETA_N, X_T, whether to write ``damping velocity``, notes) for gamma_n and gamma_t."""
        if model.gamma_t == 0.0 and model.gamma_n == 0.0:
            return 0.0, 0.0, False, []
        if model.gamma_n > 0.0:
            return model.gamma_n, model.gamma_t / model.gamma_n, True, []
        eta_n = VANISHING_ETA_N * 2.0 * math.sqrt(model.m * model.kn)
        return eta_n, model.gamma_t / eta_n, True, [
            f"gamma_n = 0, gamma_t = {model.gamma_t!r}: ETA_N = {eta_n!r} is a vanishing normal damping so that "
            f"X_T * ETA_N = gamma_t"]

    def coefficient_terms(self, model, eta_n: float, x_t: float, damping: bool, mu: float) -> tuple:
        """The words after ``granular`` (``fix wall/gran``) or after the types (``pair_coeff``):
        the normal sub-model's, the damping, the tangential spring and its cap."""
        return (*model.normal_law.deck_terms(model, eta_n), *(("damping", "velocity") if damping else ()),
                "tangential", "linear_history", float(model.kt), float(x_t), float(mu),
                *(("limit_damping",) if model.limit_damping else ()))

    def wall_terms(self, model) -> dict:
        eta_n, x_t, damping, notes = self.dashpots(model)
        if model.mu is None:
            mu = NO_CAP_MU
            notes.append(f"the paper's model has no Coulomb limit; LAMMPS always applies one, so mu = {NO_CAP_MU:g}")
        else:
            mu = model.mu
            notes.append(f"Coulomb limit |F_t| <= {mu!r} F_n: not the paper's model")
        terms = ("granular", *self.coefficient_terms(model, eta_n, x_t, damping, mu))
        return {"eta_n": eta_n, "x_t": x_t, "damping": damping, "mu": mu, "terms": terms,
                "comment": "; ".join(notes)}


STYLE = Granular()
