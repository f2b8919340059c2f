"""Published sphere-wall DEM benchmarks as named scenes, run in LAMMPS and set beside the
Coulomb oracle, rigid-body theory and measured data (``spinbounce benchmarks``).

Each benchmark is data (:mod:`.cases`): a :class:`Benchmark` names its sources, its
contact model(s) (:class:`Series`, stiffness and damping from :mod:`.materials`), the
initial states and what its figure plots (:mod:`.quantities`); its published points are
in :mod:`.digitised`. Every state gets three expectations: the rigid-body theory
(:func:`walton`, :mod:`.quantities`), the Coulomb oracle (exact for the Hookean model) and,
where they exist, measured values. :func:`run_benchmark` (:mod:`.run`) runs each series in
one LAMMPS batch at a refined step, and once at twice that refinement for a convergence
estimate, and tabulates everything; :mod:`.report` writes BENCHMARKS.md, the JSON record
and the figure.

Units: SI (kg, m, s, N/m). LAMMPS's lj units are scale-free, so SI numbers pass through.
Sign conventions are the package's: v_n < 0 towards the wall, omega anticlockwise, the
contact point's tangential velocity (the slip rate) is v_t + r omega.
"""

from .cases import BENCHMARKS, Benchmark, Series, select, with_states
from .digitised import Measured
from .materials import (AL_ALLOY, ALUMINA, SOLID, STEEL, Material, gamma_n_for_restitution_cut,
                        hertz_contact_time, hookean_matching_hertz, mindlin_ratio)
from .quantities import QUANTITIES, first_touch_stick, impact_speed, quantity, walton
from .run import ACCEPTANCE, BenchmarkRun, refined_dt, run_benchmark

__all__ = [
    "ACCEPTANCE",
    "AL_ALLOY",
    "ALUMINA",
    "BENCHMARKS",
    "QUANTITIES",
    "SOLID",
    "STEEL",
    "Benchmark",
    "BenchmarkRun",
    "Material",
    "Measured",
    "Series",
    "first_touch_stick",
    "gamma_n_for_restitution_cut",
    "hertz_contact_time",
    "hookean_matching_hertz",
    "impact_speed",
    "mindlin_ratio",
    "quantity",
    "refined_dt",
    "run_benchmark",
    "select",
    "walton",
    "with_states",
]
