"""The wall command's styles, registered by keyword: one entry each in :data:`STYLES`.

LAMMPS's ``fix wall/gran`` takes either ``granular`` with sub-models chosen by keyword (the
paper's model: :class:`Granular`) or a classic style, a fixed assembly of sub-models
(``hooke/history``: :class:`Classic`). The ``wall`` parameter picks one; the rest of
spinbounce asks the style's flags, never its keyword.
"""

from __future__ import annotations

from ..declaration import Parameter
from ..errors import SceneError
from .base import Style, choice, lookup
from .damping import DAMPING
from .normal import NORMAL
from .tangential import TANGENTIAL

__all__ = ["STYLES", "Style", "Granular", "Classic", "style", "style_parameter", "MU_MAX", "VANISHING_GAMMA_N"]

#: The classic form refuses a larger MU ("Illegal classic gran model command"): no cap is this.
MU_MAX = 1.0e4

#: The classic form gives its tangential damping as GAMMA_T/GAMMA_N, so GAMMA_N = 0 is 0/0 (NaN
#: in this build): a vanishing one stands in, far below any force it could add.
VANISHING_GAMMA_N = 1.0e-100


class Granular(Style):
    """``granular``: ``fix wall/gran granular`` assembled from sub-models, the paper's model.

    The words after ``granular`` are the normal sub-model's (:mod:`spinbounce.laws.normal`), the
    model's damping's (:mod:`spinbounce.laws.damping`) and the tangential one's
    model's tangential one's (:mod:`spinbounce.laws.tangential`), as LAMMPS's GranularModel assembles
    them; ``pair_coeff`` takes the same words after the atom types.
    """

    keyword = "granular"
    summary = "the paper's model, wall/gran granular"

    def coefficient_terms(self, model, eta_n: float, x_t: float, damping: bool, mu: float) -> tuple:
        """The words after ``granular`` (``fix wall/gran``) or after the types (``pair_coeff``):
        the normal sub-model's, the damping's, the tangential one's with its cap, limit_damping."""
        return (*model.normal_law.deck_terms(model, eta_n), *model.damping_law.deck_terms(damping),
                *model.tangential_law.deck_terms(model, x_t, mu), *(("limit_damping",) if model.limit_damping else ()))

    def wall_terms(self, model) -> dict:
        eta_n, x_t, damping, notes = model.damping_law.dashpots(model)
        mu, cap_note = model.tangential_law.cap(model)
        terms = ("granular", *self.coefficient_terms(model, eta_n, x_t, damping, mu))
        return {"eta_n": eta_n, "x_t": x_t, "damping": damping, "mu": mu, "terms": terms,
                "comment": "; ".join([*notes, cap_note])}


class Classic(Style):
    """``classic``: ``fix wall/gran hooke/history``, LAMMPS's fixed assembly of a Hookean spring,
    ``mass_velocity`` dashpots and the classic tangential history.

    This build scales its tangential spring by the contact radius, kt sqrt(r delta) (measured; its
    exact theory is :mod:`spinbounce.exact.classic`), so Omega depends on v_n. Its dashpots are rates
    times the mass, so GAMMA = gamma/m; its cap is at most 1e4 ("Illegal classic gran model
    command" above it), and GAMMA_N = 0 divides by zero (NaN) in this build.
    """

    keyword = "classic"
    summary = "wall/gran hooke/history, whose tangential spring this LAMMPS build scales by the contact radius"
    tangential_contact_radius = True
    # measured: at tolerance 1e-6 the ladder's estimate was 1.0e-6 where the error was 2.1e-6;
    # its spring kt sqrt(r delta) has an infinite slope at contact
    smooth_in_dt = False
    pairs = False
    #: The one normal, damping and tangential sub-model of the assembly.
    normal = NORMAL["hooke"]
    damping = DAMPING["velocity"]
    tangential = TANGENTIAL["linear_history"]

    def check(self, model) -> None:
        if model.normal_law is not self.normal:
            raise SceneError("normal", model.normal, f"must be {self.normal.keyword} with wall = {self.keyword} "
                                                     "(hooke/history is Hookean)")
        if model.damping_law is not self.damping:
            raise SceneError("damping", model.damping, f"must be {self.damping.keyword} with wall = {self.keyword} "
                                                       "(hooke/history's dashpots are its own: give gamma_n, gamma_t)")
        if model.tangential_law is not self.tangential:
            raise SceneError("tangential", model.tangential, f"must be {self.tangential.keyword} with wall = "
                                                             f"{self.keyword} (hooke/history's spring is its own)")
        if model.limit_damping:
            raise SceneError("limit_damping", True, f"is not covered by the classic wall's theory: leave it out "
                                                     f"with wall = {self.keyword}")

    def coefficients(self, model) -> dict:
        """The command's own numbers, which its exact theory takes too: the dashpots as rates
        (GAMMA = gamma/m, ``mass_velocity``) and the cap (none: the largest, :data:`MU_MAX`). A cap
        above MU_MAX is the theory's; the deck writes MU_MAX (:meth:`wall_terms`), and each row's
        error, against the theory of the cap asked for, includes the difference."""
        return {"kn": model.kn, "kt": model.kt, "gamma_n": model.gamma_n / model.m,
                "gamma_t": model.gamma_t / model.m, "mu": MU_MAX if model.mu is None else model.mu}

    def wall_terms(self, model) -> dict:
        notes = ["classic wall: this build scales the tangential spring by the contact radius sqrt(r delta) "
                 "(theory: spinbounce.exact.classic)"]
        c = self.coefficients(model)
        gamma_n = c["gamma_n"]
        if gamma_n == 0.0:
            gamma_n = VANISHING_GAMMA_N
            notes.append(f"GAMMA_N = {gamma_n:g} stands in for 0, which the classic form divides by (0/0 = NaN)")
        mu = min(c["mu"], MU_MAX)
        if model.mu is None:
            notes.append(f"no cap asked for: MU = {mu:g}, the classic form's largest")
        elif model.mu > MU_MAX:
            notes.append(f"mu = {model.mu:g} asked for: MU = {mu:g}, the classic form's largest (LAMMPS refuses more); "
                         f"each row's error is against mu = {model.mu:g}'s theory")
        terms = ("hooke/history", float(c["kn"]), float(c["kt"]), gamma_n, float(c["gamma_t"]), float(mu), "1")
        return {"classic": True, "gamma_n": gamma_n, "gamma_t": c["gamma_t"], "mu": mu, "terms": terms,
                "comment": "; ".join(notes)}



#: Every wall style, by its keyword (the ``wall`` parameter's value).
STYLES: dict[str, Style] = {entry.keyword: entry for entry in (Granular(), Classic())}


def style(keyword: str) -> Style:
    """The style of ``keyword``, or a :class:`SceneError` listing the registered ones."""
    return lookup(STYLES, "wall", keyword)


def style_parameter() -> Parameter:
    """The ``wall`` choice: one of the registered styles."""
    return choice("wall", "the wall command", STYLES, "granular",
                  "wall/gran granular ... | wall/gran hooke/history KN KT GAMMA_N/m GAMMA_T/m MU 1")
