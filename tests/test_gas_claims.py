"""The gases of the reproduction (the gas figure, the gas claims) against kinetic theory, by their records.

The session's reproduction (conftest.reproduction) runs them once: issue 29's magic-ratio gas for the claims
(20,000 spheres, packing 0.05, kn = 1e4, 16 collisions per sphere at the starting rate) and the figure's
three gases (5,000 spheres, packing 0.05, kn = 1e4, 30). Tolerances are the runs' own noise: a
temperature of N spheres is noisy to sqrt(2/(3N)) (1.2% at 5,000), a ratio of two to about 1.6%.
"""

from __future__ import annotations

import json

import pytest

pytestmark = pytest.mark.lammps


@pytest.fixture(scope="module")
def claims(reproduction):
    """The judged claims by key."""
    made, _ = reproduction
    return {c["key"]: c for c in json.loads((made.out / "claims.json").read_text())["claims"]}


@pytest.fixture(scope="module")
def claimed(reproduction):
    """The claims' gas's own record (its run folder under the reproduction's runs)."""
    made, _ = reproduction
    return json.loads((made.out.parent / "runs" / "claims" / "gas-magic" / "result.json").read_text())


@pytest.fixture(scope="module")
def figure(reproduction):
    made, _ = reproduction
    return {round(c["kt_over_kn"], 4): c for c in json.loads((made.out / "gas.json").read_text())["cases"]}


def test_the_magic_gas_reaches_equipartition_and_loses_what_its_pairs_and_overlaps_lose(claims, claimed):
    """Issue 29's gas. Equipartition within 0.01 (its line; the late ratio's own noise is about 0.5%). The energy:
    LAMMPS's drift within 0.2 percentage points and two standard errors of the pair-level theory's at the gas's
    step (the claim's verdict: the paper's conservation is approximate, not unresolved; two seeds measured 0.21
    and 0.07 points apart from it), and both lose energy."""
    assert claims["gas-equipartition"]["lammps"] == pytest.approx(1.0, abs=0.01)
    assert claims["gas-equipartition"]["verdict"] == "reproduced"
    energy = claims["gas-energy"]
    assert energy["verdict"] == "approximate", energy["evidence"]
    error = claimed["accuracy"]["pair_level_drift_standard_error"]
    assert abs(energy["lammps"] - energy["exact"]) <= 0.002 + 2.0 * error
    assert energy["lammps"] < 0.0 and energy["exact"] < 0.0  # a pair's turning line of centres loses energy


def test_every_figure_gas_follows_its_pair_level_theory_to_its_noise(figure):
    """At 5,000 spheres the ratio is noisy to about 1.6% a sample, so the largest of 60 samples' differences
    reaches about three of those (0.05) from noise alone: 0.06 (measured: 0.047, 0.013, 0.019)."""
    for case in figure.values():
        assert case["theories"]["pairs"]["max_ratio_difference"] < 0.06, case


def test_the_overlapping_contacts_are_half_a_dense_magic_gas_s_loss(claimed, figure):
    """At packing 0.05 and kn = 1e4 a sphere meets a third while it touches a second in about 3% of its
    collisions, and at the magic ratio those overlaps lose more than the isolated pairs (docs/how-to/gas.md):
    their own share of the pair-level drift is more than the tolerance the theory meets, so that without them it
    would miss. Both gases at packing 0.05: the claims' (measured share -1.0 points of -2.2) and the figure's
    magic one (5,000 spheres over 22 collisions: held within 0.5 points and two standard errors, its drift's
    noise being larger than 20,000 spheres')."""
    shares = [claimed["overlaps"]["energy_drift"], figure[round(2 / 7, 4)]["overlaps"]["energy_drift"]]
    assert shares[0] < -0.005 and shares[1] < -0.005
    magic = figure[round(2 / 7, 4)]
    error = magic["accuracy"]["pair_level_drift_standard_error"]
    theory = magic["theories"]["pairs"]["energy_drift"]["theory"]
    assert abs(magic["lammps"]["energy_drift"] - theory) < 0.005 + 2 * error
