"""The published sphere-wall benchmarks as data (:data:`BENCHMARKS`: Chung & Ooi (2011) Tests 4-6
and Kratos's Benchmark 10, Thornton's linear and Hertzian laws; each one's title says what it is): sources,
contact models, initial states (v_n, v_t, omega, SI units), plots."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from ...model.contact import ContactModel
from .digitised import (CHUNG_OOI_5, KHARAZ_2001, KRATOS, KRATOS_BENCHMARKS, KRATOS_CHUNG_OOI, KRATOS_T10, LETHE,
                        MFIX_DEM05, THORNTON_PSI2_HERTZIAN, THORNTON_PSI2_LINEAR, THORNTON_SPIN, Measured)
from .materials import (AL_ALLOY, AL_WALL_T4, ALUMINA, SOLID, STEEL, gamma_n_for_restitution_cut,
                        hertz_mindlin_rigid_wall, hookean_matching_hertz, mindlin_ratio)
from .quantities import QUANTITIES, restitution

__all__ = ["BENCHMARKS", "Benchmark", "Series", "select", "with_states"]


@dataclass(frozen=True)
class Series:
    """One contact model and its initial states (v_n, v_t, omega), one LAMMPS batch."""

    label: str
    model: ContactModel
    states: tuple[tuple[float, float, float], ...]
    measured: tuple[Measured, ...] = ()


@dataclass(frozen=True)
class Benchmark:
    """A named benchmark: its sources, model(s), states and plots.

    ``to_state(model, x)`` turns a value of the x quantity into an initial state, so each
    measured point is also run (in the same batch) at its own digitised input.
    ``refine``: how much finer than the scene's default step LAMMPS runs (see
    :func:`.run.refined_dt`), with ``refine_why`` the measurement behind it.
    """

    name: str
    title: str
    citation: str
    sources: tuple[tuple[str, str], ...]
    stiffness: str
    series: tuple[Series, ...]
    x: str
    panels: tuple[str, ...]
    to_state: Callable[[ContactModel, float], tuple[float, float, float]]
    refine: int
    refine_why: str
    beta0: float = 0.0
    notes: tuple[str, ...] = ()


def kratos_angles(n: int = 17) -> np.ndarray:
    """Kratos's sweep: theta_i = 90 i/(n + 1) deg, i = 1..n (Chung_Ooi_class.py, DEM_benchmarks_class.py)."""
    return np.radians(90.0 * np.arange(1, n + 1) / (n + 1))


def _hertz_mindlin(material, r: float, mu: float, e: float, wall=None) -> ContactModel:
    """The test's own Hertz-Mindlin law in LAMMPS's words: ``hertz`` kn = 4/3 E*, ``damping
    coeff_restitution`` e (its restitution at every speed, the normal force let pull), ``mindlin``
    k_t = 8 G* with no tangential dashpot, and the cap mu (:func:`hertz_mindlin_rigid_wall`)."""
    return ContactModel(m=material.mass(r), r=r, alpha=SOLID, mu=mu, damping="coeff_restitution", e_n=e,
                        **hertz_mindlin_rigid_wall(material, r, wall))


def _chung_ooi_4() -> Benchmark:
    r, speed, mu, e = 2.5e-3, 3.9, 0.092, 0.98
    m = ALUMINA.mass(r)
    kn, kt = 1.72e7, 1.48e7  # MFIX DEM05's linear spring-dashpot run
    model = ContactModel(m=m, r=r, alpha=SOLID, kn=kn, kt=kt, gamma_n=gamma_n_for_restitution_cut(e, m, kn),
                         mu=mu, limit_damping=True)
    states = tuple((-speed * math.cos(t), speed * math.sin(t), 0.0) for t in kratos_angles())
    _, kn_hertz, kt_hertz = hookean_matching_hertz(ALUMINA, r, speed * math.cos(math.radians(45.0)), AL_WALL_T4)
    return Benchmark(
        name="chung-ooi-4",
        title="Chung & Ooi Test 4: alumina sphere, |v| = 3.9 m/s, incidence 5-85 deg (Kharaz et al. 2001)",
        citation=("Chung & Ooi (2011), Granular Matter 13:643, Test 4, after Kharaz, Gorham & Salman (2001), "
                  "Powder Technol. 120:281. The papers were not read; every number comes from code that "
                  "implements or digitises them."),
        sources=(
            ("r = 2.5 mm, rho = 4000 kg/m^3, |v| = 3.9 m/s, mu = 0.092, e = 0.98", f"{KRATOS_CHUNG_OOI}; "
             f"{KRATOS} applications/DEMApplication/tests/DEM3D_chung_ooi_tests/test4_data/Materials4.json; "
             f"{LETHE} examples/dem/3d-oblique-wall-impact/oblique_wall_impact_template.tpl"),
            ("theta_i = 90 i/18 deg, i = 1..17", KRATOS_CHUNG_OOI),
            ("kn = 1.72e7 N/m, kt = 1.48e7 N/m (linear spring-dashpot)",
             f"{MFIX_DEM05}, its run script (repository path not resolved)"),
            *((f"measured {QUANTITIES[p.quantity]['label']}", p.source) for p in KHARAZ_2001),
        ),
        stiffness=(f"kn = 1.72e7 N/m and kt = 1.48e7 N/m, MFIX DEM05's published linear-spring setup for this "
                   f"impact (kt/kn = {kt / kn:.3f}, close to Mindlin's 2(1 - nu)/(2 - nu) = "
                   f"{mindlin_ratio(ALUMINA.nu):.3f} for nu = 0.23). For comparison, the Hookean spring with the "
                   f"Hertz contact time of alumina on the aluminium-alloy wall at the 45-deg normal speed "
                   f"would be kn = {kn_hertz:.3g} N/m, kt = {kt_hertz:.3g} N/m. Only kt/kn shapes the normalised "
                   "outcome of a linear contact; kn sets its duration. The second series is the test's own "
                   "Hertz-Mindlin law on the aluminium-alloy wall (E* and G* of the two materials; "
                   "coeff_restitution e = 0.98, the normal force let pull; no tangential dashpot; mu = 0.092), "
                   "held to the Coulomb oracle carried over to it (exact.oracle)."),
        series=(Series("e = 0.98", model, states, KHARAZ_2001),
                Series("Hertz-Mindlin, e = 0.98", _hertz_mindlin(ALUMINA, r, mu, e, AL_WALL_T4), states,
                       KHARAZ_2001)),
        x="theta",
        panels=("e_t", "omega_out", "rebound_contact", "rebound_centre"),
        to_state=lambda model, theta: (-speed * math.cos(math.radians(theta)),
                                       speed * math.sin(math.radians(theta)), 0.0),
        refine=2,
        refine_why=("measured max |LAMMPS - oracle|/U over the 17 grid states and 38 measured inputs: 5.2e-5 at "
                    "the default step, 2.4e-5 at refine 2, 1.2e-5 at 4, 2.9e-6 at 16 (first order, from the "
                    "normal dashpot); refine 2 is the coarsest below half the 1e-4 bar"),
    )


def _chung_ooi_5() -> Benchmark:
    r, v_n, mu = 1e-5, 5.0, 0.3
    m, kn, kt = hookean_matching_hertz(STEEL, r, v_n)
    # no damping, so the normal force kn delta is never tensile and limit_damping would change
    # nothing in LAMMPS; it is left off because the oracle mishandles limit_damping with
    # gamma_n = 0 (its cap rate is zero at first touch, so a sticking contact is started as
    # sliding and the spurious switch at delta = 0 is taken for the exit)
    model = ContactModel(m=m, r=r, alpha=SOLID, kn=kn, kt=kt, mu=mu, limit_damping=False)
    states = tuple((-v_n, v_n * math.tan(t), 0.0) for t in kratos_angles())
    hertz_mindlin = ContactModel(m=m, r=r, alpha=SOLID, mu=mu, **hertz_mindlin_rigid_wall(STEEL, r))
    return Benchmark(
        name="chung-ooi-5",
        title="Chung & Ooi Test 5: steel sphere, v_n = 5 m/s across tangential speeds, elastic",
        citation="Chung & Ooi (2011), Granular Matter 13:643, Test 5 (paper not read; parameters from code).",
        sources=(
            ("v_n = 5 m/s, r = 10 um, mu = 0.3, e = 1", f"{KRATOS_CHUNG_OOI} (Benchmark5); PySPH Test 5 input "
             "(repository path not resolved)"),
            ("v_t = v_n tan(theta_i), theta_i = 90 i/18 deg, i = 1..17", KRATOS_CHUNG_OOI),
            ("steel: E = 208 GPa, nu = 0.3, rho = 7850 kg/m^3; rigid wall", STEEL.source),
            *((f"published {QUANTITIES[p.quantity]['label']}: {p.label}", p.source) for p in CHUNG_OOI_5),
        ),
        stiffness=(f"Hookean kn = {kn:.4g} N/m gives steel's Hertz contact time on a rigid wall at "
                   f"v_n = 5 m/s ({math.pi * math.sqrt(m / kn):.4g} s); kt = kn 2(1 - nu)/(2 - nu) = "
                   f"{kt:.4g} N/m (Mindlin, nu = 0.3). The test's second material (polyethylene, nu = 0.4) "
                   f"would give kt/kn = {mindlin_ratio(0.4):.3f} and the same sliding branch. The second series "
                   f"is the test's own Hertz-Mindlin law, LAMMPS's hertz with kn = 4/3 E/(1 - nu^2) (a rigid "
                   f"wall: E* = E/(1 - nu^2)) and tangential mindlin with k_t = 8 G/(2 - nu), G = E/(2 (1 + nu)), "
                   f"the rigid wall's 8 G* (hertz/material would mix the wall as steel)."),
        series=(Series("steel, e = 1", model, states),
                Series("steel, Hertz-Mindlin", hertz_mindlin, states, CHUNG_OOI_5)),
        x="incident_co5",
        panels=("recoil_co5", "spin_co5"),
        to_state=lambda model, x: (-v_n, x * model.mu * v_n, 0.0),
        refine=1,
        refine_why=("undamped, so second order: measured max |LAMMPS - oracle|/U 6.8e-6 at the default step, "
                    "2.2e-6 at refine 2, 4.3e-7 at 4; the default step is already 15 times below the bar"),
    )


def _chung_ooi_6() -> Benchmark:
    r, v_n, mu, e = 0.1, 0.2, 0.4, 0.5
    m, kn, kt = hookean_matching_hertz(AL_ALLOY, r, v_n)
    model = ContactModel(m=m, r=r, alpha=SOLID, kn=kn, kt=kt, gamma_n=gamma_n_for_restitution_cut(e, m, kn),
                         mu=mu, limit_damping=True)
    states = tuple((-v_n, 0.0, v_n * math.tan(t) / r) for t in kratos_angles())
    return Benchmark(
        name="chung-ooi-6",
        title="Chung & Ooi Test 6: pure spin, v_n = 0.2 m/s, r = 0.1 m, mu = 0.4, e = 0.5",
        citation="Chung & Ooi (2011), Granular Matter 13:643, Test 6 (paper not read; parameters from code).",
        sources=(
            ("v_n = 0.2 m/s, r = 0.1 m, mu = 0.4, e = 0.5, no tangential speed", f"{KRATOS_CHUNG_OOI} (Benchmark6)"),
            ("omega_i = v_n tan(theta_i)/r, theta_i = 90 i/18 deg, i = 1..17 (0.175 to 22.9 rad/s)",
             f"{KRATOS_CHUNG_OOI}; a 'Cf. Test No.6 by Chung and Ooi' input header found in code search gives "
             "0.175 to 21 rad/s (repository not resolved)"),
            ("aluminium alloy: E = 70 GPa, nu = 0.30, rho = 2699 kg/m^3 (Test 2's constants: Test 6's own were "
             "not found)", AL_ALLOY.source),
        ),
        stiffness=(f"Test 6's material constants were not found; the aluminium alloy of Test 2 (same r and v_n) "
                   f"stands in. kn = {kn:.4g} N/m gives its Hertz contact time on a rigid wall at 0.2 m/s "
                   f"({math.pi * math.sqrt(m / kn):.4g} s), kt = {kt:.4g} N/m (Mindlin ratio "
                   f"{mindlin_ratio(AL_ALLOY.nu):.3f}). The sliding branch (x <= 1) does not depend on them. The "
                   "second series is Hertz-Mindlin on a rigid wall with the same alloy (coeff_restitution e = 0.5, "
                   "no tangential dashpot), held to the Coulomb oracle carried over to it (exact.oracle)."),
        series=(Series("Al alloy, e = 0.5", model, states),
                Series("Hertz-Mindlin, e = 0.5", _hertz_mindlin(AL_ALLOY, r, mu, e), states)),
        x="x_co6",
        panels=("beta_co6", "tan_recoil"),
        to_state=lambda model, x: (-v_n, 0.0, 3.5 * model.mu * (1.0 + float(restitution(model, [(-v_n, 0.0, 0.0)])[0])) * v_n / x / model.r),
        refine=32,
        refine_why=("measured max |LAMMPS - oracle|/U: 1.3e-3 at the default step, 3.3e-4 at refine 4, 8.2e-5 at "
                    "16, 4.1e-5 at 32, 2.0e-5 at 64 (first order: e = 0.5 is strong normal damping); refine 32 "
                    "is the coarsest below half the 1e-4 bar"),
        notes=("Kratos's digitised curves for this test (benchmark6_graph1/2) were not found: no literature "
               "data are compared.",),
    )


def _thornton_states(v_n: float) -> tuple:
    """Thornton's impact angles (1 deg, then 50 (i - 1)/10 deg for i = 2..10) at the normal speed ``v_n``, unspun."""
    theta = np.radians([1.0, *(50.0 * (i - 1) / 10 for i in range(2, 11))])
    return tuple((-v_n, v_n * math.tan(t), 0.0) for t in theta)


def _thornton_linear() -> Benchmark:
    r, v_n, mu = 0.025, 5.0, 0.1
    m, kn, kt = hookean_matching_hertz(AL_ALLOY, r, v_n)
    states = _thornton_states(v_n)
    series = []
    for e in (0.25, 0.5, 0.75, 0.9):
        model = ContactModel(m=m, r=r, alpha=SOLID, kn=kn, kt=kt, gamma_n=gamma_n_for_restitution_cut(e, m, kn),
                             mu=mu, limit_damping=True)
        measured = (THORNTON_SPIN[e], THORNTON_PSI2_LINEAR) if e == 0.5 else (THORNTON_SPIN[e],)
        series.append(Series(f"e = {e:g}", model, states, measured))
    return Benchmark(
        name="thornton-linear",
        title="Thornton's oblique impacts, linear law: v_n = 5 m/s, r = 25 mm, mu = 0.1, e = 0.25-0.9",
        citation=("The linear-law oblique-impact sweep of Kratos's Benchmark 10, whose code says only "
                  "'THORNTON' (the paper was not identified with certainty)."),
        sources=(
            ("v_n = 5 m/s, r = 0.025 m, mu = 0.1, e in {0.25, 0.5, 0.75, 0.9}; theta = 1 deg, then 50 (i - 1)/10 "
             "deg, i = 2..10; Psi1, Psi2 and the normalised spin", KRATOS_BENCHMARKS + " (Benchmark10)"),
            ("normalised spin against Psi1, each e", f"{KRATOS_T10}benchmark10_graph2.dat"),
            ("Psi2 against Psi1, e = 0.5, linear law", f"{KRATOS_T10}bench_10_norm_reb_tang_e_050.dat"),
            ("aluminium alloy E = 70 GPa, nu = 0.30, rho = 2699 kg/m^3 (stand-in: the benchmark's own "
             "material was not found)", AL_ALLOY.source),
        ),
        stiffness=(f"The benchmark's material constants were not found; Chung & Ooi's aluminium alloy stands in. "
                   f"kn = {kn:.4g} N/m gives its Hertz contact time on a rigid wall at 5 m/s; "
                   f"kt = {kt:.4g} N/m (Mindlin ratio {mindlin_ratio(AL_ALLOY.nu):.3f}). In these axes a linear "
                   "contact's outcome depends on kt/kn, e, mu and alpha only, so the stand-in's E and rho do not "
                   "matter, but its nu (through kt/kn) shapes the sticking branch."),
        series=tuple(series),
        x="psi1",
        panels=("psi2", "spin_thornton"),
        to_state=lambda model, x: (-v_n, x * model.mu * (1.0 + model.restitution) * v_n / 2.0, 0.0),
        refine=16,
        refine_why=("measured max |LAMMPS - oracle|/U over all four e: 6.6e-4 at the default step, 1.7e-4 at "
                    "refine 4, 4.1e-5 at 16, 2.1e-5 at 32, 1.0e-5 at 64 (first order, worst at e = 0.25); "
                    "refine 16 is the coarsest below half the 1e-4 bar"),
    )


def _thornton_hertz_mindlin() -> Benchmark:
    r, v_n, mu, e = 0.025, 5.0, 0.1, 0.5
    model = _hertz_mindlin(AL_ALLOY, r, mu, e)
    states = _thornton_states(v_n)
    return Benchmark(
        name="thornton-hertz-mindlin",
        title="Thornton's oblique impacts, Hertzian law: v_n = 5 m/s, r = 25 mm, mu = 0.1, e = 0.5",
        citation=("The Hertzian oblique-impact sweep of Kratos's Benchmark 10 (its code says only 'THORNTON'; the "
                  "paper was not identified with certainty), the presentation of Maw, Barber and Fawcett's "
                  "normalised tangential response in Psi1 and Psi2."),
        sources=(
            ("v_n = 5 m/s, r = 0.025 m, mu = 0.1, e = 0.5; theta = 1 deg, then 50 (i - 1)/10 deg, i = 2..10",
             KRATOS_BENCHMARKS + " (Benchmark10)"),
            ("Psi2 against Psi1, e = 0.5, Hertzian law", THORNTON_PSI2_HERTZIAN.source),
            ("aluminium alloy E = 70 GPa, nu = 0.30, rho = 2699 kg/m^3 (stand-in: the benchmark's own "
             "material was not found)", AL_ALLOY.source),
        ),
        stiffness=("The benchmark's material constants were not found; Chung & Ooi's aluminium alloy stands in, on a "
                   "rigid wall: LAMMPS's `hertz` with kn = 4/3 E*, `damping coeff_restitution` e = 0.5 (the normal "
                   "force let pull), `tangential mindlin` with k_t = 8 G* and no tangential dashpot. With Hertz and "
                   "Mindlin both on the contact radius the normalised outcome depends on nu, e, mu and alpha, not on "
                   "E or rho; the stand-in's nu = 0.3 sets it. In gross sliding the published points follow the "
                   "rigid-body law, and this law falls below it: its dashpot pulls near the exit, and the cap "
                   "mu |F_n| adds that pull's friction (as in chung-ooi-6)."),
        series=(Series(f"Hertz-Mindlin, e = {e:g}", model, states, (THORNTON_PSI2_HERTZIAN,)),),
        x="psi1",
        panels=("psi2", "spin_thornton"),
        to_state=lambda model, x: (-v_n, x * model.mu * (1.0 + restitution(model, [(-v_n, 0.0, 0.0)])[0]) * v_n / 2.0,
                                   0.0),
        refine=4,
        refine_why=("measured max |LAMMPS - oracle|/U over the 10 grid states and 10 measured inputs: 1.7e-4 at the "
                    "default step, 8.5e-5 at refine 2, 4.3e-5 at 4, 2.2e-5 at 8 (first order, from the normal "
                    "dashpot); refine 4 is the coarsest below half the 1e-4 bar"),
    )


BENCHMARKS: dict[str, Benchmark] = {b.name: b for b in (_chung_ooi_4(), _chung_ooi_5(), _chung_ooi_6(),
                                                          _thornton_linear(), _thornton_hertz_mindlin())}


def select(only: list[str] | None) -> list[Benchmark]:
    """The named benchmarks in the order given (all when ``only`` is empty or None)."""
    if not only:
        return list(BENCHMARKS.values())
    unknown = [n for n in only if n not in BENCHMARKS]
    if unknown:
        raise KeyError(f"unknown benchmark(s) {', '.join(unknown)}; known: {', '.join(BENCHMARKS)}")
    return [BENCHMARKS[n] for n in dict.fromkeys(only)]


def with_states(bench: Benchmark, keep: Callable[[int], bool] | list[int]) -> Benchmark:
    """The benchmark with a subset of each series' grid states and no measured points (for tests)."""
    pick = (lambda i: i in keep) if not callable(keep) else keep
    return replace(bench, series=tuple(
        replace(s, states=tuple(st for i, st in enumerate(s.states) if pick(i)), measured=()) for s in bench.series))
