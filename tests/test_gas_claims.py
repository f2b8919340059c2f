"""The gases of the reproduction (the gas figure, the gas claims) against kinetic theory, by their records.

The session's reproduction (conftest.reproduction) runs them once: issue 29's magic-ratio gas for the claims
(20,000 spheres, packing 0.05, kn = 1e4, 16 collisions per sphere at the starting rate) and the figure's three
gases (5,000 spheres, packing 0.05, kn = 1e4, 60), whose kt/kn = 0.1 gas is the claims' second. Tolerances are
the runs' own noise: a temperature of N spheres is noisy to sqrt(2/(3N)) (1.2% at 5,000), a ratio of two to about
1.6%.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from spinbounce.scenes.gas.run import GASES

pytestmark = pytest.mark.lammps


@pytest.fixture(scope="module")
def claims(reproduction):
    """The judged claims by key."""
    made, _ = reproduction
    return {c["key"]: c for c in json.loads((made.out / "claims.json").read_text())["claims"]}


def run_record(made, claim: dict) -> dict:
    """The record of the gas a claim names (its folder among the reproduction's shared gases)."""
    (folder,) = claim["runs"]
    return json.loads((made.out.parent / "runs" / GASES / folder / "result.json").read_text())


@pytest.fixture(scope="module")
def claimed(reproduction, claims):
    """The claims' gas's own record (its run folder, as the claim names it from the claims' run folder)."""
    made, _ = reproduction
    return run_record(made, claims["gas-equipartition"])


@pytest.fixture(scope="module")
def figure(reproduction):
    made, _ = reproduction
    return {round(c["kt_over_kn"], 4): c for c in json.loads((made.out / "gas.json").read_text())["cases"]}


def test_the_magic_gas_reaches_equipartition_and_loses_what_its_pairs_and_overlaps_lose(claims, claimed):
    """Issue 29's gas. Equipartition within 0.01 (its line; the late ratio's own noise is about 0.5%). The energy:
    the claim's verdict is approximate (the paper's conservation does not hold; LAMMPS and the pair-level theory
    at the gas's step agree within 0.2 percentage points and two standard errors: three runs measured 0.19, 0.01
    and 0.08 apart), and both lose energy."""
    assert claims["gas-equipartition"]["lammps"] == pytest.approx(1.0, abs=0.01)
    assert claims["gas-equipartition"]["verdict"] == "reproduced"
    energy = claims["gas-energy"]
    assert energy["verdict"] == "approximate", energy["evidence"]
    error = claimed["accuracy"]["pair_level_drift_standard_error"]
    pairs = claimed["theories"]["pairs"]["energy_drift_boltzmann"]  # with the closure's error
    assert energy["lammps"] == claimed["lammps"]["energy_drift"]
    assert abs(energy["lammps"] - pairs) <= 0.002 + 2.0 * error
    assert energy["lammps"] < 0.0 and pairs < 0.0  # turning lines of centres and overlaps lose energy


def test_the_soft_gas_settles_where_the_pair_level_theory_without_its_closure_says(claims, reproduction):
    """kt/kn = 0.1 (issue 29's lines): the late ratio within 0.015 of the pair-level theory's over the same late
    samples, with the closure's error (5,000 spheres: the late ratio is noisy to about 0.004; measured 0.005
    apart), the relaxation time within 10% (measured 4%). The closure's error is the DSMC's, below its closed
    form by many of its own standard errors."""
    made, _ = reproduction
    record = run_record(made, claims["gas-steady-ratio"])
    figure = {round(c["kt_over_kn"], 4): c for c in json.loads((made.out / "gas.json").read_text())["cases"]}
    # one run for both products (whichever came first ran it, the other read it back): four gases for five
    gases = made.out.parent / "runs" / GASES
    assert Path(figure[0.1]["run"]).resolve() == (gases / claims["gas-steady-ratio"]["runs"][0]).resolve()
    assert len([p for p in gases.iterdir() if p.is_dir()]) == 4
    steady, relaxation = claims["gas-steady-ratio"], claims["gas-relaxation"]
    pairs = record["theories"]["pairs"]
    assert steady["lammps"] == record["lammps"]["late_ratio"]
    assert steady["exact"] == pytest.approx(pairs["late_ratio"] + record["closure"]["closure_error"], rel=1e-12)
    assert abs(steady["lammps"] - steady["exact"]) <= 0.015 and steady["verdict"] == "reproduced", steady["evidence"]
    assert record["closure"]["closure_error"] < -5.0 * record["closure"]["standard_error"]
    assert abs(relaxation["lammps"] / relaxation["exact"] - 1.0) <= 0.10, relaxation["evidence"]


def test_every_figure_gas_follows_its_pair_level_theory_to_its_noise(figure):
    """At 5,000 spheres the ratio is noisy to about 1.6% a sample, so the largest of 60 samples' differences
    reaches about three of those (0.05) from noise alone: 0.06 (measured: 0.047, 0.013, 0.019)."""
    for case in figure.values():
        assert case["theories"]["pairs"]["max_ratio_difference"] < 0.06, case


def test_the_overlapping_contacts_are_half_a_dense_magic_gas_s_loss(claimed, figure):
    """At packing 0.05 and kn = 1e4 a sphere meets a third while it touches a second in about 3% of its
    collisions, and at the magic ratio those overlaps lose more than the isolated pairs (docs/how-to/gas.md).
    Without them the pair-level theory would miss LAMMPS's drift by more than its tolerance: in the claims' gas
    (measured: share -0.99 points of -2.11) and in the figure's magic gas (5,000 spheres over 22 collisions,
    share -1.9 of -3.3), which with them is held within 0.5 points and two standard errors (its drift's noise
    is larger than 20,000 spheres')."""
    for record in (claimed, figure[round(2 / 7, 4)]):
        error = record["accuracy"]["pair_level_drift_standard_error"]
        lammps, theory = record["lammps"]["energy_drift"], record["theories"]["pairs"]["energy_drift"]["theory"]
        assert abs(lammps - (theory - record["overlaps"]["energy_drift"])) > 0.002 + 2 * error
    magic = figure[round(2 / 7, 4)]
    error = magic["accuracy"]["pair_level_drift_standard_error"]
    theory = magic["theories"]["pairs"]["energy_drift"]["theory"]
    assert abs(magic["lammps"]["energy_drift"] - theory) < 0.005 + 2 * error
