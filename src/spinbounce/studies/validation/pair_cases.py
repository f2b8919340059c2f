"""Published sphere-sphere benchmarks as named pair scenes, run in LAMMPS beside the pair's theories.

Chung & Ooi (2011), Granular Matter 13:643, number their two-sphere tests 1, 7 and 8; each
:class:`PairBenchmark` says what its source publishes (test 7 as Kratos reads it: a rolling
contact, no slip so no tangential force; test 8 only its statement, the wall limit, not its
curves) and how close LAMMPS must come. Each scene's pairs run in one LAMMPS batch, every pair
also checked against the exact reference of what LAMMPS integrates (within the default
accuracy, 1e-4 of the pair's speed; with the Coulomb cap of tests 7 and 8, mu = 0.4,
:mod:`spinbounce.exact.pair_capped`) and set beside the planar theory. Thornton's oblique
sphere-sphere results: no source giving their parameters was found.

Units: SI (kg, m, s, N/m), passed through LAMMPS's scale-free lj units.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ...model.contact import ContactModel
from ...model.timestep import ACCURACY
from ...exact import choose
from ...exact import pair as planar
from ...pipeline import run_scene
from ...scenes.pair import Pair, PairBatch, PairContact, Sphere
from ...scenes.pair.kind import wall_frame
from .cases import kratos_angles
from .materials import AL_ALLOY, SOLID, Material, bisect_damping, matched_pair_contact
from .digitised import KRATOS_BENCHMARKS, PYSPH_T8, YADE_T1

__all__ = ["PairBenchmark", "PAIR_BENCHMARKS", "GLASS", "LIMESTONE", "run_pair_benchmark", "matched_pair_contact"]

GLASS = Material("glass", 4.8e10, 0.20, 2800.0, YADE_T1)
LIMESTONE = Material("limestone", 2.0e10, 0.25, 2500.0, YADE_T1)


@dataclass(frozen=True)
class PairBenchmark:
    """A named sphere-sphere benchmark: its sources, pairs and contact, and the published expectation.

    ``published(batch, table)`` returns (quantity, LAMMPS values, published values, tolerance):
    what the benchmark's source says each pair's outcome is, and how close LAMMPS must come.
    """

    name: str
    title: str
    citation: str
    sources: tuple[tuple[str, str], ...]
    stiffness: str
    make: Callable[[], object]
    published: Callable[[object, pd.DataFrame], tuple[str, np.ndarray, np.ndarray, float]]
    expectation: str


def _test_1(material: Material):
    r, v = 0.010, 10.0
    sphere = Sphere(material.mass(r), r, SOLID)
    kn, kt = matched_pair_contact(material, r, r, sphere.m, sphere.m, 2 * v)
    return PairBatch([Pair(a=sphere, b=sphere, v_a=(0.0, 0.0, -v), v_b=(0.0, 0.0, v))], PairContact(kn, kt))


def _elastic_rebound(batch, table):
    lammps = table[["a_vz", "b_vz"]].to_numpy().ravel()
    published = -np.array([[p.v_a[2], p.v_b[2]] for p in batch.pairs]).ravel()
    return "final normal velocities (m/s)", lammps, published, ACCURACY * float(table["speed"].max())


def _test_7():
    r, v_n = 0.1, 0.2
    sphere = Sphere(AL_ALLOY.mass(r), r, SOLID)
    kn, kt = matched_pair_contact(AL_ALLOY, r, r, sphere.m, sphere.m, 2 * v_n)
    spins = v_n * np.tan(kratos_angles()) / r
    pairs = [Pair(a=sphere, b=sphere, v_a=(0.0, 0.0, -v_n), v_b=(0.0, 0.0, v_n), w_a=(0.0, w, 0.0),
                  w_b=(0.0, -w, 0.0)) for w in spins]
    return PairBatch(pairs, PairContact(kn, kt, mu=CHUNG_OOI_MU))


def _rolling_contact(batch, table):
    """No slip: tangential velocities stay 0 and spins unchanged, in units of r omega (scale: the speed)."""
    r = batch.pairs[0].a.r
    lammps = np.concatenate([table["a_vx"], table["b_vx"], r * table["a_wy"], r * table["b_wy"]])
    published = np.concatenate([np.zeros(2 * batch.n), [r * p.w_a[1] for p in batch.pairs],
                                [r * p.w_b[1] for p in batch.pairs]])
    return "v_t' of a and b, r omega' of a and b (m/s)", lammps, published, ACCURACY * float(table["speed"].max())


#: Tests 7 and 8's friction coefficient (aluminium alloy on itself).
CHUNG_OOI_MU = 0.4
#: Test 8's restitution, and the second sphere's size and density over the first's.
T8_RESTITUTION, T8_SIZE, T8_DENSITY = 0.5, 5.0, 1000.0
#: How much finer than the pair's default step test 8 runs (its normal damping makes LAMMPS first order).
T8_REFINE = 4


def _test_8():
    r, v_n = 0.1, 0.2
    a = Sphere(AL_ALLOY.mass(r), r, SOLID)
    heavy = Material("aluminium alloy x1000", AL_ALLOY.E, AL_ALLOY.nu, AL_ALLOY.rho * T8_DENSITY, AL_ALLOY.source)
    b = Sphere(heavy.mass(T8_SIZE * r), T8_SIZE * r, SOLID)
    kn, kt = matched_pair_contact(AL_ALLOY, a.r, b.r, a.m, b.m, v_n)
    # the pair's (tensile) restitution falls as gamma_n grows
    gamma_n = bisect_damping(lambda g: planar.restitution(a.m, b.m, kn, g), T8_RESTITUTION,
                             2.0 * math.sqrt(planar.reduced_mass(a.m, b.m) * kn) * (1.0 - 1e-9), 0.0)
    spins = v_n * np.tan(kratos_angles()) / a.r
    pairs = [Pair(a=a, b=b, v_a=(0.0, 0.0, -v_n), w_a=(0.0, -w, 0.0)) for w in spins]
    contact = PairContact(kn, kt, gamma_n, mu=CHUNG_OOI_MU)
    # damped, so first order in dt: measured 1.8e-4 of the speed at the default step, 3.7e-5 at a quarter
    return PairBatch(pairs, contact, PairBatch(pairs, contact).dt / T8_REFINE)


def _wall_limit(batch, table):
    """a's (v_n, v_t, r omega) against the wall's exact theory for the same sphere and contact (and cap)."""
    a, law = batch.pairs[0].a, batch.contact.law()
    model = ContactModel(m=a.m, r=a.r, alpha=a.alpha, kn=law["kn"], kt=law["kt"], gamma_n=law["gamma_n"],
                         mu=batch.contact.mu)
    lammps = wall_frame(table[["a_vx", "a_vy", "a_vz"]].to_numpy(), table[["a_wx", "a_wy", "a_wz"]].to_numpy(),
                        a.r)[:, :3]
    published = []
    for p in batch.pairs:
        _, final = choose.outcome(model, p.v_a[2], p.v_a[0], -p.w_a[1])
        published.append([final["v_n"], final["v_t"], final["r_omega"]])
    # The heavy b is still curved: the line of centres turns (table's turn) and a's outcome leaves the
    # wall's by the planar theory's model error (b's recoil, O(m_a/m_b) = 8e-6, is far smaller); the
    # wall must be reached within that error plus the run's accuracy.
    tolerance = (ACCURACY + float(table["planar_error"].max())) * float(table["speed"].max())
    return "a's v_n', v_t', r omega' (m/s)", lammps.ravel(), np.array(published).ravel(), tolerance


_CHUNG = "Chung & Ooi (2011), Granular Matter 13:643"
PAIR_BENCHMARKS: dict[str, PairBenchmark] = {b.name: b for b in (
    PairBenchmark(
        "chung-ooi-1", "Chung & Ooi Test 1: elastic normal impact of two identical glass spheres, 10 m/s each",
        f"{_CHUNG}, Test 1 (paper not read; parameters from code)",
        (("r = 10 mm, v = +-10 m/s, glass E = 48 GPa, nu = 0.20, rho = 2800 kg/m^3 (or limestone 20 GPa, "
          "0.25, 2500)", YADE_T1),),
        "kn gives the Hertz contact time of the two spheres at 20 m/s (reduced mass, r* = r/2, E* of two "
        "glass spheres); kt from Mindlin's ratio (no tangential motion here)",
        lambda: _test_1(GLASS), _elastic_rebound, "elastic: each sphere's velocity reversed"),
    PairBenchmark(
        "chung-ooi-1-limestone", "Chung & Ooi Test 1, limestone: elastic normal impact of two identical spheres",
        f"{_CHUNG}, Test 1 (paper not read; parameters from code)",
        (("r = 10 mm, v = +-10 m/s, limestone E = 20 GPa, nu = 0.25, rho = 2500 kg/m^3", YADE_T1),),
        "as chung-ooi-1, limestone's constants", lambda: _test_1(LIMESTONE), _elastic_rebound,
        "elastic: each sphere's velocity reversed"),
    PairBenchmark(
        "chung-ooi-7", "Chung & Ooi Test 7: identical spheres, 0.2 m/s each way, equal and opposite spins",
        f"{_CHUNG}, Test 7 (paper not read; parameters from code)",
        (("r = 0.1 m, v_n = +-0.2 m/s, omega = +-v_n tan(theta_i)/r, theta_i = 90 i/18 deg, i = 1..17",
          f"{KRATOS_BENCHMARKS} (Benchmark7)"),
         ("aluminium alloy E = 70 GPa, nu = 0.30, rho = 2699 kg/m^3", AL_ALLOY.source)),
        "kn gives the Hertz contact time of the two spheres at 0.4 m/s; mu = 0.4 (no slip occurs, so the cap "
        "is never reached)", _test_7, _rolling_contact,
        "by symmetry the tangential velocities stay 0 and the spins unchanged"),
    PairBenchmark(
        "chung-ooi-8", "Chung & Ooi Test 8: a spinning sphere against one 5x larger and 1000x denser, at rest",
        f"{_CHUNG}, Test 8 (paper not read; parameters from code)",
        (("r = 0.1 m and 0.5 m, densities 2700 and 2.7e6 kg/m^3, v_n = 0.2 m/s, e = 0.5, mu = 0.4", PYSPH_T8),
         ("omega = v_n tan(theta_i)/r, theta_i = 90 i/18 deg, i = 1..17; 'the bigger and/or denser the second "
          "sphere is, the more this test resembles the sphere versus wall simulation'",
          f"{KRATOS_BENCHMARKS} (Benchmark8) and Kratos's DEM benchmark documentation")),
        "kn gives the Hertz contact time at 0.2 m/s; gamma_n the restitution 0.5 (tensile, no limit_damping); "
        "mu = 0.4, so the faster spins slide",
        _test_8, _wall_limit, "a's outcome is the wall's exact outcome for the same sphere and contact, within "
        "the curvature's model error (the planar theory's, from the exact reference)"),
)}


def run_pair_benchmark(bench: PairBenchmark, out: Path) -> dict:
    """Run a benchmark's pairs in one LAMMPS batch; its record (JSON-ready) with every check's numbers."""
    result = run_scene(bench.make(), Path(out) / bench.name, record=False)
    quantity, lammps, published, tolerance = bench.published(result.scene, result.table)
    off = float(np.abs(lammps - published).max())
    return {"name": bench.name, "title": bench.title, "citation": bench.citation,
            "sources": [list(s) for s in bench.sources], "stiffness": bench.stiffness,
            "pairs": result.scene.n, "dt": result.scene.dt, "steps": result.scene.nsteps,
            "lammps_vs_exact": result.max_error, "planar_vs_exact": result.table["planar_error"].max(),
            "published": bench.expectation, "quantity": quantity, "lammps_vs_published": off,
            "tolerance": tolerance, "agrees": bool(off <= tolerance and result.max_error <= ACCURACY)}
