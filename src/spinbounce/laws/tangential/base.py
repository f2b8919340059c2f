"""What a tangential sub-model declares and answers: its coefficients and its words in a deck."""

from __future__ import annotations

from ...declaration import Parameter

__all__ = ["TangentialLaw"]


class TangentialLaw:
    """A tangential sub-model: LAMMPS's keyword after ``tangential``, its coefficients, and its
    words given the damping's tangential coefficient."""

    keyword: str = ""
    coefficients: tuple[Parameter, ...] = ()

    def cap(self, model) -> tuple[float, str]:
        """The Coulomb cap a wall deck writes for the model, and a note saying why."""
        raise NotImplementedError

    def deck_terms(self, model, x_t: float, mu: float) -> tuple:
        """Its words, given the damping's tangential coefficient and the cap to write."""
        raise NotImplementedError
