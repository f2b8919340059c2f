"""Published sphere-wall DEM benchmarks as named scenes, run in LAMMPS and set beside the
Coulomb oracle, rigid-body theory and measured data.

Four benchmarks (:data:`BENCHMARKS`):

* ``chung-ooi-4``: Chung & Ooi (2011) Test 4, an alumina sphere hitting a wall at a
  constant speed of 3.9 m/s over incidence angles 5-85 deg, with Kharaz, Gorham & Salman's
  (2001) measured points as digitised by Lethe and Kratos;
* ``chung-ooi-5``: Test 5, constant normal speed 5 m/s over tangential speeds (elastic);
* ``chung-ooi-6``: Test 6, a spinning sphere dropped at 0.2 m/s with no tangential speed;
* ``thornton-linear``: the linear-law oblique sweep over four restitutions that Kratos
  ships as its Benchmark 10, with its digitised data.

Each benchmark is data: a :class:`Benchmark` names its sources, its contact model(s)
(:class:`Series`), the initial states and what its figure plots. Every state gets
three expectations: the rigid-body theory (:func:`walton`), the Coulomb oracle
(:mod:`oracle`, exact for the Hookean model) and, where they exist, measured values.
:func:`run_benchmark` runs each series in one LAMMPS batch at a refined step, and once at
twice that refinement for a convergence estimate, and tabulates everything.

Units: SI (kg, m, s, N/m). LAMMPS's lj units are scale-free, so SI numbers pass through.
Sign conventions are the package's: v_n < 0 towards the wall, omega anticlockwise, the
contact point's tangential velocity (the slip rate) is v_t + r omega.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import pandas as pd

from ..theory import oracle
from .. import theory
from ..pipeline import run_collision
from ..model.scenes import Collision, ContactModel

__all__ = [
    "ACCEPTANCE",
    "BENCHMARKS",
    "QUANTITIES",
    "Benchmark",
    "BenchmarkRun",
    "Material",
    "Measured",
    "Series",
    "gamma_n_for_restitution_cut",
    "hertz_contact_time",
    "hookean_matching_hertz",
    "first_touch_stick",
    "impact_speed",
    "mindlin_ratio",
    "names",
    "refined_dt",
    "run_benchmark",
    "select",
    "walton",
]

#: Largest |LAMMPS - oracle| allowed, as a fraction of the impact speed (:func:`impact_speed`).
ACCEPTANCE = 1e-4
#: A solid sphere: I = (2/5) m r^2.
SOLID = 0.4


# ---------------------------------------------------------------------------
# Stiffness and damping from material constants
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class Material:
    """Elastic constants and density of a sphere (SI), with where they come from."""

    name: str
    E: float
    nu: float
    rho: float
    source: str

    def mass(self, r: float) -> float:
        return self.rho * 4.0 / 3.0 * math.pi * r**3

    def effective_modulus(self, wall: Material | None = None) -> float:
        """E* of Hertz's law: 1/E* = (1 - nu^2)/E + (1 - nu_w^2)/E_w (rigid wall: no second term)."""
        inverse = (1.0 - self.nu**2) / self.E
        if wall is not None:
            inverse += (1.0 - wall.nu**2) / wall.E
        return 1.0 / inverse


def hertz_contact_time(m: float, r: float, e_star: float, v: float) -> float:
    """Duration of an elastic Hertzian impact of a sphere (mass m, radius r) on a flat wall.

    With F = (4/3) E* sqrt(r) delta^(3/2), energy conservation gives the largest overlap
    delta_max = (15 m v^2 / (16 E* sqrt(r)))^(2/5), and integrating dt = d delta / delta'
    over the approach and the (symmetric) rebound gives

        t_H = 2 (delta_max / v) integral_0^1 dx / sqrt(1 - x^(5/2))
            = (4/5) B(2/5, 1/2) delta_max / v  (about 2.943 delta_max / v),

    with B the beta function (substitute u = x^(5/2)).
    """
    delta_max = (15.0 * m * v * v / (16.0 * e_star * math.sqrt(r))) ** 0.4
    beta = math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)
    return 0.8 * beta * delta_max / v


def mindlin_ratio(nu: float) -> float:
    """kt/kn of Mindlin's no-slip tangential stiffness over Hertz's tangent normal stiffness
    for like elastic bodies (or one on a rigid wall): 8 G* a / (2 E* a) = 2 (1 - nu)/(2 - nu)."""
    return 2.0 * (1.0 - nu) / (2.0 - nu)


def hookean_matching_hertz(material: Material, r: float, v_n: float,
                           wall: Material | None = None) -> tuple[float, float, float]:
    """(m, kn, kt): a Hookean spring with the Hertz contact time at normal speed |v_n|.

    kn = m (pi / t_H)^2 makes the undamped Hookean contact time pi sqrt(m/kn) equal to
    :func:`hertz_contact_time`; kt = kn * :func:`mindlin_ratio` (nu).
    """
    m = material.mass(r)
    t_h = hertz_contact_time(m, r, material.effective_modulus(wall), abs(v_n))
    kn = m * (math.pi / t_h) ** 2
    return m, kn, kn * mindlin_ratio(material.nu)


def gamma_n_for_restitution_cut(e: float, m: float, kn: float) -> float:
    """gamma_n giving restitution ``e`` when the normal force is never tensile (limit_damping).

    :func:`theory.restitution` with ``tensile=False`` rises monotonically as gamma_n falls,
    so bisection between 0 (e = 1) and critical damping finds it to round-off.
    """
    if not 0.0 < e <= 1.0:
        raise ValueError(f"e = {e!r}: must lie in (0, 1]")
    if e == 1.0:
        return 0.0
    lo, hi = 0.0, 2.0 * math.sqrt(m * kn) * (1.0 - 1e-12)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if theory.restitution(m, kn, mid, tensile=False) > e:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * hi:
            break
    return 0.5 * (lo + hi)


# ---------------------------------------------------------------------------
# Rigid-body theory
# ---------------------------------------------------------------------------

def walton(model: ContactModel, states: np.ndarray, e: float, beta0: float) -> tuple[np.ndarray, list[str]]:
    """Walton's rigid-body impact law: final (v_n, v_t, r omega) and the regime of each state.

    The normal impulse is m (1 + e) |v_n|. The contact point's tangential velocity
    s = v_t + r omega would reverse to -beta0 s under the impulse
    J* = m alpha/(1 + alpha) (1 + beta0) s (the reduced mass of the slip); the impulse
    taken is J = sign(s) min(|J*|, mu m (1 + e) |v_n|). Sliding (the Coulomb bound reached)
    when alpha/(1 + alpha) (1 + beta0) |s| >= mu (1 + e) |v_n|. Then
    Delta v_t = -J/m and Delta(r omega) = -J/(alpha m). For a solid sphere
    alpha/(1 + alpha) = 2/7, the 3.5 mu (1 + e) |v_n| threshold of the literature.
    """
    states = np.asarray(states, dtype=float)
    v_n, v_t, w = states.T
    a = model.alpha
    s = v_t + w
    bound = model.mu * (1.0 + e) * np.abs(v_n)
    wanted = a / (1.0 + a) * (1.0 + beta0) * s
    sliding = np.abs(wanted) >= bound
    impulse = np.where(sliding, np.sign(s) * bound, wanted)
    final = np.column_stack([-e * v_n, v_t - impulse, w - impulse / a])
    return final, ["sliding" if k else "sticking" for k in sliding]


def first_touch_stick(model: ContactModel, states: np.ndarray) -> np.ndarray:
    """Estimated shortfall in r omega of a damped sliding contact from the rigid-body outcome.

    With gamma_n > 0 the cap starts at c0 = mu gamma_n |v_n| > 0, so a contact that slides
    for the rest of the impact first sticks while the spring force kt |u'| t grows to the
    cap, for about t0 = c0/(kt |u'|); the friction impulse falls short of mu times the
    normal impulse by about c0 t0/2, and r omega (which takes 1/alpha of it per unit mass)
    by c0^2/(2 kt |u'| alpha m). Zero without damping."""
    states = np.asarray(states, dtype=float)
    c0 = model.mu * model.gamma_n * np.abs(states[:, 0])
    slip = np.abs(states[:, 1] + states[:, 2])
    with np.errstate(divide="ignore"):
        return np.where(slip > 0.0, c0**2 / (2.0 * model.kt * slip * model.alpha * model.m), np.inf)


def impact_speed(states: np.ndarray) -> np.ndarray:
    """The contact point's speed at first touch, sqrt(v_n^2 + (v_t + r omega)^2).

    Deviations are quoted relative to it: it sets the size of every outgoing component
    (for a pure spin drop it is the spin's surface speed, for an oblique impact |v|)."""
    states = np.asarray(states, dtype=float)
    return np.hypot(states[:, 0], states[:, 1] + states[:, 2])


# ---------------------------------------------------------------------------
# What the benchmarks plot: the literature's normalised quantities
# ---------------------------------------------------------------------------

def _e(model):
    return model.restitution


def _q(label: str, unit: str, f: Callable) -> dict:
    return {"label": label, "unit": unit, "f": f}


#: name -> label, unit and f(initial (n, 3), final (n, 3), model) -> values.
#: Rows are (v_n, v_t, r omega); ' marks the rebound.
QUANTITIES: dict[str, dict] = {
    "theta": _q(r"incidence angle $\theta$ (deg)", "deg",
                lambda i, f, m: np.degrees(np.arctan2(i[:, 1], -i[:, 0]))),
    "e_t": _q(r"$e_t = v_t'/v_t$", "", lambda i, f, m: f[:, 1] / i[:, 1]),
    "omega_out": _q(r"$\omega'$ (rad/s)", "rad/s", lambda i, f, m: f[:, 2] / m.r),
    "rebound_contact": _q(r"contact-point rebound angle (deg)", "deg",
                          lambda i, f, m: np.degrees(np.arctan((f[:, 1] + f[:, 2]) / f[:, 0]))),
    "rebound_centre": _q(r"centre-of-mass rebound angle (deg)", "deg",
                         lambda i, f, m: np.degrees(np.arctan(f[:, 1] / f[:, 0]))),
    "psi1": _q(r"$\Psi_1 = 2 v_t/(\mu(1+e)|v_n|)$", "",
               lambda i, f, m: 2.0 * (i[:, 1] + i[:, 2]) / (m.mu * (1.0 + _e(m)) * np.abs(i[:, 0]))),
    "psi2": _q(r"$\Psi_2 = 2(v_t'+r\omega')/(\mu(1+e)|v_n|)$", "",
               lambda i, f, m: 2.0 * (f[:, 1] + f[:, 2]) / (m.mu * (1.0 + _e(m)) * np.abs(i[:, 0]))),
    "spin_thornton": _q(r"$2r\omega'/(\mu(1+e)|v_n|)$", "",
                        lambda i, f, m: 2.0 * f[:, 2] / (m.mu * (1.0 + _e(m)) * np.abs(i[:, 0]))),
    "incident_co5": _q(r"$V_{st}/(\mu V_{cn})$", "",
                       lambda i, f, m: (i[:, 1] + i[:, 2]) / (m.mu * np.abs(i[:, 0]))),
    "recoil_co5": _q(r"$V'_{st}/(\mu V'_{cn})$", "", lambda i, f, m: (f[:, 1] + f[:, 2]) / (m.mu * f[:, 0])),
    "spin_co5": _q(r"$r\omega'/(\mu V_{cn})$", "", lambda i, f, m: f[:, 2] / (m.mu * np.abs(i[:, 0]))),
    "x_co6": _q(r"$3.5\mu(1+e)V_{cn}/V_{st}$", "",
                lambda i, f, m: 3.5 * m.mu * (1.0 + _e(m)) * np.abs(i[:, 0]) / (i[:, 1] + i[:, 2])),
    "beta_co6": _q(r"$\beta = -V'_{st}/V_{st}$", "", lambda i, f, m: -(f[:, 1] + f[:, 2]) / (i[:, 1] + i[:, 2])),
    "tan_incident": _q(r"$V_{st}/V_{cn}$", "", lambda i, f, m: (i[:, 1] + i[:, 2]) / np.abs(i[:, 0])),
    "tan_recoil": _q(r"$V'_{st}/V'_{cn}$", "", lambda i, f, m: (f[:, 1] + f[:, 2]) / f[:, 0]),
}


def quantity(name: str, initial, final, model: ContactModel) -> np.ndarray:
    return np.asarray(QUANTITIES[name]["f"](np.atleast_2d(initial), np.atleast_2d(final), model), dtype=float)


# ---------------------------------------------------------------------------
# Benchmarks as data
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class Measured:
    """Published points of one quantity against the benchmark's x quantity (digitised)."""

    quantity: str
    x: tuple[float, ...]
    values: tuple[float, ...]
    source: str
    label: str


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
    :func:`refined_dt`), with ``refine_why`` the measurement behind it.
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
    notes: tuple[str, ...] = field(default=())


KRATOS = "KratosMultiphysics/Kratos"
LETHE = "chaos-polymtl/lethe"
LETHE_KHARAZ = f"{LETHE} examples/dem/3d-oblique-wall-impact/oblique_wall_impact_postprocessing.py"
KRATOS_CHUNG_OOI = f"{KRATOS} applications/DEMApplication/python_scripts/Chung_Ooi_class.py"
KRATOS_BENCHMARKS = f"{KRATOS} applications/DEMApplication/python_scripts/DEM_benchmarks_class.py"
KRATOS_G2 = f"{KRATOS} applications/DEM_application/test_examples/basic_benchmarks/paper_data/benchmark4_graph2.dat"
KRATOS_G3 = (f"{KRATOS} applications/DEMApplication/tests/DEM3D_chung_ooi_tests/test4_data/paper_data/"
             "benchmark4_graph3.dat")
KRATOS_T10 = f"{KRATOS} applications/DEM_application/test_examples/basic_benchmarks/paper_data/"
MFIX_DEM05 = "MFIX VVUQ manual, DEM05 (https://mfix.netl.doe.gov/doc/vvuq-manual/main/html/dem/dem-05.html)"
YADE_T2 = "Yade Chung-Ooi Test2.py (Angelidakis, Chareyre & Caulk 2023; repository path not resolved)"

#: Chung & Ooi Test 2's aluminium alloy, the one Test-6 material whose constants were found.
AL_ALLOY = Material("aluminium alloy", 70e9, 0.30, 2699.0, YADE_T2)
#: Test 4's sphere (alumina) and wall (aluminium alloy).
ALUMINA = Material("alumina", 380e9, 0.23, 4000.0, f"{KRATOS} test4_data/Materials4.json; Yade Test4.py")
AL_WALL_T4 = Material("aluminium alloy (wall)", 70e9, 0.33, 2700.0, f"{KRATOS} test4_data/Materials4.json")
STEEL = Material("steel", 208e9, 0.30, 7850.0, "PySPH Chung-Ooi Test 5 input (repository path not resolved)")


def _angles(n: int) -> np.ndarray:
    """Kratos's sweep: theta_i = 90 i/(n + 1) deg, i = 1..n (Chung_Ooi_class.py)."""
    return np.radians(90.0 * np.arange(1, n + 1) / (n + 1))


def _oblique(speed: float) -> Callable:
    def to_state(model, theta_deg):
        t = math.radians(theta_deg)
        return (-speed * math.cos(t), speed * math.sin(t), 0.0)

    return to_state


def _normal_fixed(v_n: float, x_name: str) -> Callable:
    """States at fixed |v_n| from a tangential x quantity (psi1 or V_st/(mu V_cn))."""

    def to_state(model, x):
        if x_name == "psi1":
            v_t = x * model.mu * (1.0 + model.restitution) * v_n / 2.0
        else:
            v_t = x * model.mu * v_n
        return (-v_n, v_t, 0.0)

    return to_state


def _chung_ooi_4() -> Benchmark:
    r, speed, mu, e = 2.5e-3, 3.9, 0.092, 0.98
    m = ALUMINA.mass(r)
    kn, kt = 1.72e7, 1.48e7  # MFIX DEM05's linear spring-dashpot run
    model = ContactModel(m=m, r=r, alpha=SOLID, kn=kn, kt=kt, gamma_n=gamma_n_for_restitution_cut(e, m, kn),
                         mu=mu, limit_damping=True)
    theta = _angles(17)
    states = tuple((-speed * math.cos(t), speed * math.sin(t), 0.0) for t in theta)
    _, kn_hertz, kt_hertz = hookean_matching_hertz(ALUMINA, r, speed * math.cos(math.radians(45.0)), AL_WALL_T4)
    measured = (
        Measured("e_t", (1.84, 3.703, 9.496, 20.012, 30.127, 39.382, 49.694, 60.02),
                 (0.79344, 0.74533, 0.67257, 0.59691, 0.68756, 0.77148, 0.84761, 0.90142),
                 LETHE_KHARAZ, "Kharaz et al. 2001 (Lethe)"),
        Measured("omega_out", (5.897435897435898, 10.867850098619328, 21.12426035502959, 31.1439842209073,
                               38.95463510848126, 50.23668639053254, 60.098619329388555, 69.96055226824458,
                               78.56015779092702, 84.31952662721893),
                 (-134.86238532110102, -261.16207951070345, -573.7003058103976, -612.2324159021407,
                  -595.1070336391438, -449.54128440366975, -375.68807339449546, -242.9663608562692,
                  -142.35474006116218, -70.6422018348625),
                 f"{KRATOS_G2} ('#Experiment' block)", "Kharaz et al. 2001 (Kratos)"),
        Measured("rebound_contact", (2.0997281572207847, 3.9434155319702846, 9.717622556290827, 20.309682809728216,
                                     30.160683905575503, 39.120476602752326, 49.51201496648886, 59.9037955064207,
                                     70.46025585915032, 78.85965284042405, 84.78158734387202),
                 (0.7703927492447065, 0.7703927492447065, -1.0574018126888234, -8.53474320241692,
                  -2.5528700906344426, 9.909365558912384, 30.015105740181262, 49.95468277945619,
                  66.90332326283988, 78.86706948640483, 85.6797583081571),
                 f"{KRATOS_G3} ('#Experiment' block)", "Kharaz et al. 2001 (Kratos)"),
        Measured("rebound_centre", (0.016, 2.15, 4.096, 9.826, 20.567, 30.29, 39.535, 49.747, 60.208),
                 (0.074, 1.733, 2.962, 6.518, 12.208, 21.67, 32.613, 45.125, 57.474),
                 LETHE_KHARAZ, "Kharaz et al. 2001 (Lethe)"),
    )
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
            *((f"measured {QUANTITIES[p.quantity]['label']}", p.source) for p in measured),
        ),
        stiffness=(f"kn = 1.72e7 N/m and kt = 1.48e7 N/m, MFIX DEM05's published linear-spring setup for this "
                   f"impact (kt/kn = {kt / kn:.3f}, close to Mindlin's 2(1 - nu)/(2 - nu) = "
                   f"{mindlin_ratio(ALUMINA.nu):.3f} for nu = 0.23). For comparison, the Hookean spring with the "
                   f"Hertz contact time of alumina on the aluminium-alloy wall at the 45-deg normal speed "
                   f"would be kn = {kn_hertz:.3g} N/m, kt = {kt_hertz:.3g} N/m. Only kt/kn shapes the normalised "
                   "outcome of a linear contact; kn sets its duration."),
        series=(Series("e = 0.98", model, states, measured),),
        x="theta",
        panels=("e_t", "omega_out", "rebound_contact", "rebound_centre"),
        to_state=_oblique(speed),
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
    states = tuple((-v_n, v_n * math.tan(t), 0.0) for t in _angles(17))
    return Benchmark(
        name="chung-ooi-5",
        title="Chung & Ooi Test 5: steel sphere, v_n = 5 m/s across tangential speeds, elastic",
        citation="Chung & Ooi (2011), Granular Matter 13:643, Test 5 (paper not read; parameters from code).",
        sources=(
            ("v_n = 5 m/s, r = 10 um, mu = 0.3, e = 1", f"{KRATOS_CHUNG_OOI} (Benchmark5); PySPH Test 5 input "
             "(repository path not resolved)"),
            ("v_t = v_n tan(theta_i), theta_i = 90 i/18 deg, i = 1..17", KRATOS_CHUNG_OOI),
            ("steel: E = 208 GPa, nu = 0.3, rho = 7850 kg/m^3; rigid wall", STEEL.source),
        ),
        stiffness=(f"Hookean kn = {kn:.4g} N/m gives steel's Hertz contact time on a rigid wall at "
                   f"v_n = 5 m/s ({math.pi * math.sqrt(m / kn):.4g} s); kt = kn 2(1 - nu)/(2 - nu) = "
                   f"{kt:.4g} N/m (Mindlin, nu = 0.3). The test's second material (polyethylene, nu = 0.4) "
                   f"would give kt/kn = {mindlin_ratio(0.4):.3f} and the same sliding branch."),
        series=(Series("steel, e = 1", model, states),),
        x="incident_co5",
        panels=("recoil_co5", "spin_co5"),
        to_state=_normal_fixed(v_n, "incident_co5"),
        refine=1,
        refine_why=("undamped, so second order: measured max |LAMMPS - oracle|/U 6.8e-6 at the default step, "
                    "2.2e-6 at refine 2, 4.3e-7 at 4; the default step is already 15 times below the bar"),
    )


def _chung_ooi_6() -> Benchmark:
    r, v_n, mu, e = 0.1, 0.2, 0.4, 0.5
    m, kn, kt = hookean_matching_hertz(AL_ALLOY, r, v_n)
    model = ContactModel(m=m, r=r, alpha=SOLID, kn=kn, kt=kt, gamma_n=gamma_n_for_restitution_cut(e, m, kn),
                         mu=mu, limit_damping=True)
    states = tuple((-v_n, 0.0, v_n * math.tan(t) / r) for t in _angles(17))

    def to_state(model, x):  # x = 3.5 mu (1 + e) v_n / V_st with V_st = r omega
        return (-v_n, 0.0, 3.5 * model.mu * (1.0 + model.restitution) * v_n / x / model.r)

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
                   f"{mindlin_ratio(AL_ALLOY.nu):.3f}). The sliding branch (x <= 1) does not depend on them."),
        series=(Series("Al alloy, e = 0.5", model, states),),
        x="x_co6",
        panels=("beta_co6", "tan_recoil"),
        to_state=to_state,
        refine=32,
        refine_why=("measured max |LAMMPS - oracle|/U: 1.3e-3 at the default step, 3.3e-4 at refine 4, 8.2e-5 at "
                    "16, 4.1e-5 at 32, 2.0e-5 at 64 (first order: e = 0.5 is strong normal damping); refine 32 "
                    "is the coarsest below half the 1e-4 bar"),
        notes=("Kratos's digitised curves for this test (benchmark6_graph1/2) were not found: no literature "
               "data are compared.",),
    )


def _thornton_linear() -> Benchmark:
    r, v_n, mu = 0.025, 5.0, 0.1
    m, kn, kt = hookean_matching_hertz(AL_ALLOY, r, v_n)
    theta = np.radians([1.0, *(50.0 * (i - 1) / 10 for i in range(2, 11))])
    spin = {  # benchmark10_graph2.dat: (psi1, normalised spin) per e
        0.9: ((0.16300940438871503, 0.8840125391849534, 1.8181818181818188, 2.7836990595611284, 3.793103448275861,
               4.8652037617554855, 6.025078369905956, 7.322884012539186, 8.777429467084641, 10.476489028213166),
              (-0.06130814369707083, -0.4175997846310108, -1.2755451313204982, -2.493422472165073,
               -3.550494968579161, -4.427622901931376, -4.941022448273289, -4.97583814860403, -4.98006493649387,
               -4.980529625953563)),
        0.75: ((0.15047021943573702, 0.9655172413793107, 1.981191222570533, 3.03448275862069, 4.137931034482759,
                5.304075235109718, 6.06896551724138, 6.570532915360502, 7.974921630094043, 9.55485893416928,
                11.398119122257054),
               (-0.09959443984486377, -0.5669520058094758, -1.3866299182849589, -2.5892153749909617,
                -3.6539715373419135, -4.550270054308079, -4.918060615967884, -4.956487519258462,
                -4.979845452173423, -4.980277561929301, -4.976952717418795)),
        0.5: ((0.2257053291536053, 1.1661442006269596, 2.357366771159875, 3.5736677115987465, 4.852664576802508,
               6.394984326018809, 7.7115987460815045, 9.341692789968652, 11.197492163009404, 13.35423197492163),
              (-0.16853652256244545, -0.8273770109036269, -1.7160244416367472, -2.872706810386981,
               -3.96814276540527, -4.933465671709185, -5.002747269234956, -4.995535151642803, -4.996042709133834,
               -4.996632573245033)),
        0.25: ((0.27586206896551746, 1.3918495297805644, 2.808777429467085, 4.26332288401254, 5.793103448275863,
                6.6583072100313485, 7.410658307210031, 9.191222570532917, 11.134796238244514, 13.347962382445141),
               (-0.1762081854505333, -0.995913533466072, -2.1985984440047774, -3.3017403563362233,
                -4.374271064850472, -4.891418991852501, -4.972033182142549, -4.9725201629785385,
                -4.9807096716851795, -4.981314968287659)),
    }
    psi2_linear = ((0.20444444444444465, 1.1422222222222222, 2.3244444444444454, 3.551111111111113, 4.831111111111112,
                    5.760000000000003, 6.1911111111111135, 6.3688888888888915, 7.675555555555557, 9.320000000000002),
                   (0.015048978449481165, -0.013583823117829574, -0.2595479988804943, -0.6786999720123159,
                    -0.8176420375034992, -0.7644080604534023, -0.6385992163448102, -0.5945745871816421,
                    0.7211349006437153, 2.3515994962216618))
    series = []
    for e in (0.25, 0.5, 0.75, 0.9):
        model = ContactModel(m=m, r=r, alpha=SOLID, kn=kn, kt=kt, gamma_n=gamma_n_for_restitution_cut(e, m, kn),
                             mu=mu, limit_damping=True)
        states = tuple((-v_n, v_n * math.tan(t), 0.0) for t in theta)
        measured = [Measured("spin_thornton", *spin[e], f"{KRATOS_T10}benchmark10_graph2.dat ('# e = {e:.2f}')",
                             "Thornton (Kratos)")]
        if e == 0.5:
            measured.append(Measured("psi2", *psi2_linear,
                                     f"{KRATOS_T10}bench_10_norm_reb_tang_e_050.dat ('#Linear, e = 0.50')",
                                     "Thornton, linear (Kratos)"))
        series.append(Series(f"e = {e:g}", model, states, tuple(measured)))
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
        to_state=_normal_fixed(v_n, "psi1"),
        refine=16,
        refine_why=("measured max |LAMMPS - oracle|/U over all four e: 6.6e-4 at the default step, 1.7e-4 at "
                    "refine 4, 4.1e-5 at 16, 2.1e-5 at 32, 1.0e-5 at 64 (first order, worst at e = 0.25); "
                    "refine 16 is the coarsest below half the 1e-4 bar"),
    )


def _all() -> dict[str, Benchmark]:
    return {b.name: b for b in (_chung_ooi_4(), _chung_ooi_5(), _chung_ooi_6(), _thornton_linear())}


BENCHMARKS: dict[str, Benchmark] = _all()


def names() -> list[str]:
    return list(BENCHMARKS)


def select(only: list[str] | None) -> list[Benchmark]:
    """The named benchmarks in the order given (all when ``only`` is empty or None)."""
    if not only:
        return list(BENCHMARKS.values())
    unknown = [n for n in only if n not in BENCHMARKS]
    if unknown:
        raise KeyError(f"unknown benchmark(s) {', '.join(unknown)}; known: {', '.join(BENCHMARKS)}")
    return [BENCHMARKS[n] for n in dict.fromkeys(only)]


# ---------------------------------------------------------------------------
# Running
# ---------------------------------------------------------------------------

def refined_dt(model: ContactModel, refine: int) -> float:
    """The scene's default step made ``refine`` times finer, keeping its form
    tau/(N + 1/2): the normal force's end stays mid-step (:class:`scenes.Collision`)."""
    probe = Collision(model, v_n=-1.0, v_t=0.0, omega=0.0)
    per_tau = round(model.tau / probe.dt - 0.5)
    return model.tau / (refine * per_tau + 0.5)


@dataclass(frozen=True)
class _OracleBatch(Collision):
    """A collision batch whose theory columns are oracle finals computed once beforehand
    (NaN where the oracle failed), so the two refinements share one oracle pass."""

    oracle_final: tuple = ()

    def predicted(self) -> np.ndarray:
        return np.asarray(self.oracle_final, dtype=float).reshape(self.n, 3)


@dataclass(frozen=True)
class BenchmarkRun:
    """A benchmark's results: one row per state (:attr:`table`), measured comparisons,
    and the runs' provenance."""

    benchmark: Benchmark
    table: pd.DataFrame
    measured: pd.DataFrame
    runs: list[dict]

    def summary(self) -> dict:
        t = self.table
        ok = t[t["oracle_ok"]]
        worst = ok.loc[ok["dev_lammps_oracle_rel"].idxmax()]
        sliding = ok[ok["regime_rigid"] == "sliding"]
        out = {
            "benchmark": self.benchmark.name,
            "states": int(len(t)),
            "oracle_failures": int((~t["oracle_ok"]).sum()),
            "max_dev_lammps_oracle_rel": float(worst["dev_lammps_oracle_rel"]),
            "max_dev_lammps_oracle_state": str(worst["state"]),
            "max_dev_lammps_oracle_rel_2f": float(ok["dev_lammps_oracle_rel_2f"].max()),
            "max_dev_lammps_self_rel": float(ok["dev_lammps_self_rel"].max()),
            "passes": bool(worst["dev_lammps_oracle_rel"] < ACCEPTANCE),
            "max_dev_oracle_rigid_rel": float(ok["dev_oracle_rigid_rel"].max()),
            "max_dev_oracle_rigid_rel_sliding": (float(sliding["dev_oracle_rigid_rel"].max())
                                                 if len(sliding) else None),
            "refine": self.benchmark.refine,
        }
        m = self.measured
        out["measured"] = {
            q: {"points": int(len(g)), "max_abs_model_minus_measured": float(g["model_minus_measured"].abs().max()),
                "max_abs_rigid_minus_measured": float(g["rigid_minus_measured"].abs().max()),
                "unit": QUANTITIES[q]["unit"]}
            for q, g in m.groupby("quantity", sort=False)
        } if len(m) else {}
        return out


def _oracle(model: ContactModel, states) -> tuple[np.ndarray, list[str], list[str]]:
    finals, patterns, errors = [], [], []
    for v_n, v_t, omega in states:
        try:
            got = oracle.bounce(model, v_n, v_t, omega)
        except RuntimeError as exc:  # recorded and reported, never hidden
            finals.append([np.nan] * 3)
            patterns.append("failed")
            errors.append(str(exc))
        else:
            finals.append(got.final[:3])
            patterns.append(got.pattern)
            errors.append("")
    return np.array(finals), patterns, errors


def _run_lammps(model, states, oracle_final, refine: int, folder: Path) -> tuple[np.ndarray, dict]:
    s = np.asarray(states, dtype=float)
    scene = _OracleBatch(model, v_n=s[:, 0], v_t=s[:, 1], omega=s[:, 2], dt=refined_dt(model, refine),
                         oracle_final=tuple(np.asarray(oracle_final).ravel()))
    result = run_collision(scene, folder, atoms="library", record=True)
    t = result.table
    final = np.column_stack([t.vn_final, t.vt_final, t.r_omega_final])
    run = {"refine": refine, "dt": scene.dt, "nsteps": scene.nsteps, "tau": model.tau, "run_dir": str(folder),
           "lammps_wall_seconds": result.info.wall_seconds, "warnings": list(result.warnings)}
    return final, run


def run_benchmark(bench: Benchmark, root: Path, refine: int | None = None, log=print) -> BenchmarkRun:
    """Run every series of ``bench`` at ``refine`` (default: the benchmark's) and twice that.

    Rows: the benchmark's grid states, then one per measured point at its digitised input.
    Deviations are the largest over (v_n, v_t, r omega), relative to :func:`impact_speed`.
    """
    refine = bench.refine if refine is None else refine
    rows, measured_rows, runs = [], [], []
    for k, series in enumerate(bench.series):
        model = series.model
        states = [tuple(s) for s in series.states]
        labels = [f"grid {i + 1}" for i in range(len(states))]
        origin = []  # (row index, Measured, point index) of each measured point's own state
        for p in series.measured:
            for j, x in enumerate(p.x):
                origin.append((len(states), p, j))
                states.append(tuple(bench.to_state(model, x)))
                labels.append(f"{p.quantity} @ {x:.4g}")
        initial = np.array([(v_n, v_t, model.r * w) for v_n, v_t, w in states])
        oracle_final, patterns, errors = _oracle(model, states)
        folder = Path(root) / bench.name / f"series_{k}"
        lammps, run = _run_lammps(model, states, oracle_final, refine, folder / f"refine_{refine}")
        lammps2, run2 = _run_lammps(model, states, oracle_final, 2 * refine, folder / f"refine_{2 * refine}")
        runs += [{"series": series.label, **run}, {"series": series.label, **run2}]
        rigid, regimes = walton(model, initial, model.restitution, bench.beta0)
        speed = impact_speed(initial)
        dev = np.abs(lammps - oracle_final).max(axis=1) / speed
        dev2 = np.abs(lammps2 - oracle_final).max(axis=1) / speed
        log(f"{bench.name} [{series.label}]: {len(states)} states, refine {refine} and {2 * refine}: "
            f"max |LAMMPS - oracle|/U = {np.nanmax(dev):.3g}, {np.nanmax(dev2):.3g}")
        table = {
            "series": series.label, "state": labels, "v_n": initial[:, 0], "v_t": initial[:, 1],
            "omega": initial[:, 2] / model.r, "impact_speed": speed, "x": quantity(bench.x, initial, initial, model),
            "regime_rigid": regimes, "oracle_pattern": patterns, "oracle_error": errors,
            "oracle_ok": ~np.isnan(oracle_final).any(axis=1),
            "dev_lammps_oracle_rel": dev, "dev_lammps_oracle_abs": dev * speed, "dev_lammps_oracle_rel_2f": dev2,
            "dev_lammps_self_rel": np.abs(lammps - lammps2).max(axis=1) / speed,
            "dev_oracle_rigid_rel": np.abs(oracle_final - rigid).max(axis=1) / speed,
            "first_touch_stick_rel": first_touch_stick(model, initial) / speed,
        }
        for name, arr in (("lammps", lammps), ("lammps_2f", lammps2), ("oracle", oracle_final), ("rigid", rigid)):
            for c, comp in enumerate(("vn", "vt", "r_omega")):
                table[f"{comp}_{name}"] = arr[:, c]
            for q in bench.panels:
                table[f"{q}_{name}"] = quantity(q, initial, arr, model)
        frame = pd.DataFrame(table)
        rows.append(frame)
        for idx, p, j in origin:
            model_value = frame[f"{p.quantity}_oracle"].iloc[idx]
            rigid_value = frame[f"{p.quantity}_rigid"].iloc[idx]
            measured_rows.append({
                "series": series.label, "quantity": p.quantity, "x": p.x[j], "measured": p.values[j],
                "lammps": frame[f"{p.quantity}_lammps"].iloc[idx], "model": model_value, "rigid": rigid_value,
                "model_minus_measured": model_value - p.values[j], "rigid_minus_measured": rigid_value - p.values[j],
                "regime_rigid": regimes[idx], "oracle_pattern": patterns[idx], "source": p.source,
            })
    return BenchmarkRun(bench, pd.concat(rows, ignore_index=True), pd.DataFrame(measured_rows), runs)


def with_states(bench: Benchmark, keep: Callable[[int], bool] | list[int]) -> Benchmark:
    """The benchmark with a subset of each series' grid states and no measured points (for tests)."""
    pick = (lambda i: i in keep) if not callable(keep) else keep
    return replace(bench, series=tuple(
        replace(s, states=tuple(st for i, st in enumerate(s.states) if pick(i)), measured=()) for s in bench.series))
