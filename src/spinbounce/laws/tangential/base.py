"""What a tangential sub-model declares and answers: its coefficients and its words in a deck."""

from __future__ import annotations

from ...declaration import Parameter

__all__ = ["TangentialLaw"]


class TangentialLaw:
    """A tangential sub-model: LAMMPS's keyword after ``tangential``, its coefficients, and its
    words given the damping's tangential coefficient."""

    keyword: str = ""
    coefficients: tuple[Parameter, ...] = ()

    def deck_terms(self, model, x_t: float) -> tuple[tuple, list[str]]:
        """(its words, notes for the deck's comment)."""
        raise NotImplementedError
