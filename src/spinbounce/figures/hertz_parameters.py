"""The Hertz measurement's grid and contact (:mod:`.hertz`), importing nothing heavy: the
``hertz`` command shows these defaults in its ``--help``."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..errors import SceneError

if TYPE_CHECKING:
    import numpy as np

    from ..model.contact import ContactModel

__all__ = ["HertzParameters", "V_T", "OMEGA"]

#: The most speeds the grid takes (each is two LAMMPS runs, about a third of a second: 1,000 take minutes).
MAX_POINTS = 1000
#: Initial tangential state of every run: v_t = 1, no spin (so u'(0) = 1).
V_T, OMEGA = 1.0, 0.0


@dataclass(frozen=True)
class HertzParameters:
    """The measurement's grid and contact. kn = 1000 keeps the overlap at |v_n| = 1.5 at
    0.22 r (kn = 10, r = 0.5 would tunnel above |v_n| = 1)."""

    v_min: float = 0.05
    v_max: float = 1.5
    points: int = 12
    v_ref: float = 0.5
    m: float = 1.0
    r: float = 0.5
    alpha: float = 0.4
    kn: float = 1000.0

    def speeds(self) -> np.ndarray:
        import numpy as np

        return np.geomspace(self.v_min, self.v_max, self.points)

    def model(self, kt: float) -> ContactModel:
        from ..model.contact import ContactModel

        return ContactModel(m=self.m, r=self.r, alpha=self.alpha, kn=self.kn, kt=kt, normal="hertz")

    def kt_star(self, v) -> np.ndarray:
        from ..exact import hertz

        return hertz.energy_conserving_kt(v, self.m, self.kn, self.r, self.alpha)

    def check(self) -> None:
        """Refuse a bad grid before LAMMPS starts (the scenes refuse the rest: tunnelling, dt)."""
        if not isinstance(self.points, int) or self.points < 2:
            raise SceneError("points", self.points, "must be a whole number >= 2")
        if self.points > MAX_POINTS:
            raise SceneError("points", self.points, f"must be at most {MAX_POINTS}: each speed is two LAMMPS runs and "
                             "a row of the figure and its table")
        for name in ("v_min", "v_max", "v_ref"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise SceneError(name, value, "must be a speed > 0")
        if self.v_min >= self.v_max:
            raise SceneError("v_min", self.v_min, f"must be below v_max = {self.v_max!r}")
        from ..scenes.collision import Collision

        # the fastest sphere overlaps deepest: refused here, by name, if it would tunnel
        Collision(self.model(float(self.kt_star(self.v_max))), v_n=-self.v_max, v_t=V_T, omega=OMEGA)
