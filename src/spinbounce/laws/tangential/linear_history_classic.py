"""``tangential linear_history_classic KT X_T MU``: the classic wall's tangential sub-model, as
the pinned LAMMPS build runs it inside ``granular``.

This build sets its ``contact_radius_flag``: the spring is kt a on the slip history with a =
sqrt(R delta), the equations of ``mindlin`` with k_t = kt (measured: LAMMPS's outcomes of the
two are bit-identical against a wall without a cap). Its cap differs: it resets the history by kt
alone, not kt a (``exact.classic``'s sawtooth and slide). So against a wall without a cap its
reference is :mod:`spinbounce.exact.mindlin`, with a cap :mod:`spinbounce.exact.classic` in the plane
with Hooke's force and constant dashpots, else the oracle with the classic cap
(:mod:`spinbounce.exact.oracle_classic`: 3-D, any force and dashpot, ``limit_damping``; a state whose
outcome has no dt -> 0 limit is refused there). ``--wall classic`` is the same sub-model in its fixed assembly
(``hooke/history``).

Between two spheres it differs from ``mindlin`` without a cap too: it projects its history onto the
tangent plane at every step (:attr:`turns_history`), where ``mindlin`` under the no-cap mu never
does, so the pair reference turns the history with the line of centres (measured: LAMMPS's pair at
kn = 20, whose line of centres turns 0.41 rad, stays 2.6e-3 from ``mindlin``'s reference at any step,
and comes within 8e-6, 3.7e-6 and 5e-7 of this one at dt = 1e-4, 2.5e-5 and 6.25e-6). With a cap
between two spheres it has the same reset (:mod:`spinbounce.exact.pair_capped_phases`).
"""

from __future__ import annotations

from .linear_history import KT, MU
from .mindlin import RadiusSpring

__all__ = ["LinearHistoryClassic", "LAW"]


class LinearHistoryClassic(RadiusSpring):
    keyword = "linear_history_classic"
    summary = "the classic wall's spring, kt a xi in this build, its cap reset by kt alone"
    coefficients = (KT, MU)
    classic_cap = True
    turns_history = True
    #: (force, rescale): a displacement history, never rescaled (mindlin's equations).
    variant = (False, False)

    def stiffness(self, model) -> float:
        return model.kt


LAW = LinearHistoryClassic()
