"""The gases of the reproduction (the gas figure, the gas claims) against kinetic theory, by their records.

The session's reproduction (conftest.reproduction) runs them once: a dilute magic-ratio gas for the claims
(5,000 spheres, packing 0.01, kn = 1e4, 16 collisions per sphere at the starting rate) and the figure's
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
def dilute(reproduction):
    """The claims' gas's own record (its run folder under the reproduction's runs)."""
    made, _ = reproduction
    return json.loads((made.out.parent / "runs" / "claims" / "gas-magic" / "result.json").read_text())


@pytest.fixture(scope="module")
def figure(reproduction):
    made, _ = reproduction
    return {round(c["kt_over_kn"], 4): c for c in json.loads((made.out / "gas.json").read_text())["cases"]}


def test_the_dilute_magic_gas_reaches_equipartition_and_loses_what_its_collisions_lose(claims, dilute):
    """Equipartition within 0.01 (issue 29's line; the late ratio's own noise is about 1%). The energy: LAMMPS's
    drift within 0.2 percentage points and two standard errors of the exact pair references' (the claim's
    verdict: the paper's conservation is approximate, not unresolved), and both lose energy."""
    assert claims["gas-equipartition"]["lammps"] == pytest.approx(1.0, abs=0.01)
    assert claims["gas-equipartition"]["verdict"] == "reproduced"
    energy = claims["gas-energy"]
    assert energy["verdict"] == "approximate", energy["evidence"]
    error = dilute["accuracy"]["pair_level_drift_standard_error"]
    assert abs(energy["lammps"] - energy["exact"]) <= 0.002 + 2.0 * error
    assert energy["lammps"] < 0.0 and energy["exact"] < 0.0  # a pair's turning line of centres loses energy


def test_every_figure_gas_follows_its_pair_level_theory_to_its_noise(figure):
    """At 5,000 spheres the ratio is noisy to about 1.6% a sample, so the largest of 60 samples' differences
    reaches about three of those (0.05) from noise alone: 0.06 (measured: 0.047, 0.013, 0.019)."""
    for case in figure.values():
        assert case["theories"]["pairs"]["max_ratio_difference"] < 0.06, case


def test_a_denser_gas_loses_more_than_its_binary_collisions(dilute, figure):
    """The finding of docs/how-to/gas.md: LAMMPS's drift beyond the pair-level theory's, per collision, grows
    with the packing (a third sphere meets a touching pair in about 2 omega_E t_c of its contacts). Measured
    against LAMMPS's isolated pairs: about 0.9e-3 a collision at packing 0.05, 0.2e-3 to 0.3e-3 at 0.01; the
    test asks for twice, and at least 0.3e-3 (5,000 spheres' drifts are noisy to about 0.1 points)."""
    def excess(record) -> float:
        return ((record["lammps"]["energy_drift"] - record["theories"]["pairs"]["energy_drift"]["theory"])
                / record["lammps"]["collisions_per_sphere"])

    dense = excess(figure[round(2 / 7, 4)])
    assert dense < min(2.0 * excess(dilute), -3e-4)
