"""The Python API: the commands' work, callable from a script or a notebook.

Keywords are the declared parameter names (:data:`spinbounce.model.parameters.MODEL` and
``STATE``), with the declared defaults, as on the command line (``gamma_n`` is
``--gamma-n`` there). Results are plain objects and pandas DataFrames::

    import spinbounce
    result = spinbounce.collide(v_n=-1.0, v_t=1.0, omega=0.0, mu=0.3)
    print(result)                    # LAMMPS beside the theory, with the error
    spinbounce.theory(gamma_t=0.5)   # the scattering matrix that applies
    rows = spinbounce.sweep(n=2000, out="my-sweep", mu=[None, 0.3])
    spinbounce.fit("my-sweep")       # one row per model group
    spinbounce.collide(scene="pair", m_b=3.0, r_b=0.8)   # sphere a against a free sphere b at rest
    spinbounce.sweep(n=100, out="pairs", scene="pair", m_b=[1.0, 3.0])

A script needs no ``if __name__ == "__main__"`` guard: a sweep runs in this process by
default (``workers=1``); with more workers it forks them while LAMMPS is not loaded here,
and spawns them (which does need the guard) once it is.
"""

from .collisions import CollisionReport, PairReport, ToleranceReport, collide, model, theory
from .gases import gas
from .series import FrozenReport, frozen
from .sweeping import SweepReport, fit, fit_groups, run_sweep, sweep

__all__ = ["collide", "theory", "frozen", "gas", "sweep", "run_sweep", "fit", "fit_groups", "model", "CollisionReport",
           "PairReport", "ToleranceReport", "FrozenReport", "SweepReport"]
