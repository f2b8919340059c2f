"""Published DEM benchmarks as named scenes, run in LAMMPS and set beside the Coulomb oracle,
rigid-body theory and measured data (``spinbounce benchmarks``; the sphere-sphere ones are in
:mod:`.pair_cases`).

Each benchmark is data (:mod:`.cases`): its sources, contact model(s) (:class:`Series`,
stiffness and damping from :mod:`.materials`), initial states and plotted quantities
(:mod:`.quantities`, with the rigid-body law); its published points are in :mod:`.digitised`.
:mod:`.run` runs and tabulates it, :mod:`.report` writes BENCHMARKS.md, the JSON record and
the figure. Units: SI (kg, m, s, N/m), passed through LAMMPS's scale-free lj units; signs are
the package's (:mod:`.quantities`).
"""

from .. import lazy_exports

#: Each module and the names it exports here, loaded on a name's first use (the command line
#: checks a benchmark's name without loading the runs).
_EXPORTS = {
    "cases": ("BENCHMARKS", "Benchmark", "Series", "select", "with_states"),
    "digitised": ("Measured",),
    "materials": ("AL_ALLOY", "AL_WALL_T4", "ALUMINA", "SOLID", "STEEL", "Material", "gamma_n_for_restitution_cut",
                  "hertz_contact_time", "hookean_matching_hertz", "mindlin_ratio"),
    "quantities": ("QUANTITIES", "first_touch_stick", "impact_speed", "quantity", "restitution", "walton"),
    "run": ("ACCEPTANCE", "BenchmarkRun", "refined_dt", "run_benchmark"),
}
__all__, __getattr__ = lazy_exports(__name__, _EXPORTS)
