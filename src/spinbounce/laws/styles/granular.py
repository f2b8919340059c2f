"""``granular``: ``fix wall/gran granular`` assembled from sub-models, the paper's model.

The words after ``granular`` are the normal sub-model's (:mod:`spinbounce.laws.normal`), the
damping's (:mod:`spinbounce.laws.damping`: ``velocity``) and the tangential one's
(:mod:`spinbounce.laws.tangential`: ``linear_history``), as LAMMPS's GranularModel assembles
them; ``pair_coeff`` takes the same words after the atom types.
"""

from __future__ import annotations

from ..damping import DAMPING
from ..tangential import TANGENTIAL
from ..base import Style

__all__ = ["Granular", "STYLE"]


class Granular(Style):
    keyword = "granular"
    summary = "the paper's model, wall/gran granular"
    damping = DAMPING["velocity"]
    tangential = TANGENTIAL["linear_history"]

    def coefficient_terms(self, model, eta_n: float, x_t: float, damping: bool, mu: float) -> tuple:
        """The words after ``granular`` (``fix wall/gran``) or after the types (``pair_coeff``):
        the normal sub-model's, the damping's, the tangential one's with its cap, limit_damping."""
        return (*model.normal_law.deck_terms(model, eta_n), *self.damping.deck_terms(damping),
                *self.tangential.deck_terms(model, x_t, mu), *(("limit_damping",) if model.limit_damping else ()))

    def wall_terms(self, model) -> dict:
        eta_n, x_t, damping, notes = self.damping.dashpots(model)
        mu, cap_note = self.tangential.cap(model)
        terms = ("granular", *self.coefficient_terms(model, eta_n, x_t, damping, mu))
        return {"eta_n": eta_n, "x_t": x_t, "damping": damping, "mu": mu, "terms": terms,
                "comment": "; ".join([*notes, cap_note])}


STYLE = Granular()
