"""What a damping sub-model declares and answers: its coefficients and how they reach LAMMPS."""

from __future__ import annotations

from ...declaration import Parameter

__all__ = ["DampingLaw"]


class DampingLaw:
    """A damping sub-model: LAMMPS's keyword after ``damping``, its coefficients, and the
    dashpots it gives LAMMPS (the normal sub-model's damping coefficient, the tangential one's)."""

    keyword: str = ""
    coefficients: tuple[Parameter, ...] = ()

    def dashpots(self, model) -> tuple[float, float, bool, list[str]]:
        """(the normal coefficient, the tangential one, whether to write ``damping KEYWORD``, notes)."""
        raise NotImplementedError

    def deck_terms(self, written: bool) -> tuple:
        return ("damping", self.keyword) if written else ()
