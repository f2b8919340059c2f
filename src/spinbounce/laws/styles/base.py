"""What a wall style declares and answers: its flags, its checks and its part of the deck."""

from __future__ import annotations

__all__ = ["Style"]


class Style:
    """A wall command's style. Subclasses set the flags and build the deck's terms."""

    #: The ``wall`` parameter's value.
    keyword: str = ""
    #: One line for the ``wall`` parameter's help.
    summary: str = ""
    #: The tangential spring grows with the contact radius (kt sqrt(r delta)), so its exact theory
    #: is :mod:`spinbounce.exact.classic`, and Omega depends on v_n.
    tangential_contact_radius: bool = False
    #: Its exact theory holds in the paper's plane only (no v_s, omega_s, omega_n).
    planar_only: bool = False
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
