"""The claims ledger: verdicts follow from the numbers, each checked by an independent route.

The claims ledger: verdicts follow from the numbers, every claim is measured, and the
numbers it quotes are checked here by an independent route (a dense grid, a hand derivation).
"""

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from spinbounce import exact
from spinbounce.studies.claims import CLAIMS, COLLISION_TOL, VERDICTS, markdown, verdict, write_claims
from spinbounce.studies.claims.damping import EQ23_STATE, eq22_error, eq22_worst, eq23_faults, printed_eq23
from spinbounce.studies.claims.energy import SPIN_STATE, best_reduction, loss_bracket
from spinbounce.studies.claims.ledger import checked, maximise

ALPHA = 0.4
COMMITTED = Path(__file__).resolve().parents[1] / "figures"


# ---------------------------------------------------------------------------
# No LAMMPS: the verdicts and the numbers behind them
# ---------------------------------------------------------------------------

def test_verdict_follows_the_numbers():
    # paper printed to 4 decimals, exact -1.28383856, LAMMPS 6e-6 away
    assert verdict(-1.2838, -1.2838446, -1.28383856, 5e-5, COLLISION_TOL) == "reproduced"
    assert verdict(-1.17, -1.2514, -1.2514, 5e-5, COLLISION_TOL, approx_tol=0.1) == "approximate"
    assert verdict(-1 / 7, -0.5714, -4 / 7, 1e-12, COLLISION_TOL) == "contradicted"
    # LAMMPS off from the exact theory: no verdict on the paper can be drawn
    assert verdict(-1.2838, -1.30, -1.28383856, 5e-5, COLLISION_TOL) == "unresolved"
    assert checked(False, "inconsistent") == "unresolved" and checked(True, "ill-posed") == "ill-posed"
    with pytest.raises(ValueError, match="unknown verdict"):
        checked(True, "wrong")


def test_maximise_finds_the_global_maximum_not_the_first_grid_point():
    # two maxima: 0.8 at x = 0.2 and 1.0 at x = 0.7231; Brent pins the better one to ~1e-8
    def fn(x):
        return 0.8 * math.exp(-((x - 0.2) / 0.05) ** 2) + math.exp(-((x - 0.7231) / 0.05) ** 2)

    x, value = maximise(fn, 0.0, 1.0, seeds=30)
    assert x == pytest.approx(0.7231, abs=1e-6) and value == pytest.approx(1.0, abs=1e-9)


def test_eq23_faults_match_a_hand_derivation():
    """Printed Eq. 23 with a = alpha/(1+alpha) = 2/7: both rows change by -a u'(0), so
    Delta v_t = r Delta omega; u'(inf) = (1 - 2a) u'(0) = 3/7 u'(0); at (v_t, r omega) = (-1, 2),
    u' = 1: v_t -> -9/7, r omega -> 12/7 and Delta E/m = (32/49 - 0.4 * 52/49)/2 = 4/35."""
    faults = eq23_faults(ALPHA)
    assert faults["vt_over_r_omega"] == pytest.approx(1.0, abs=1e-12)
    assert faults["slip_left"] == pytest.approx(3 / 7, abs=1e-12)
    assert faults["rolling_moved"] == pytest.approx(0.0, abs=1e-12)  # it does keep a rolling state
    assert EQ23_STATE[1:] == (-1.0, 2.0) and faults["energy_gain"] == pytest.approx(4 / 35, abs=1e-12)
    # and it is not Eq. 18 with Omega = -1, whose bottom row is (-1/(1+alpha), alpha/(1+alpha)) = (-5/7, 2/7)
    np.testing.assert_allclose(exact.rolling_matrix(ALPHA)[2, 1:], [-5 / 7, 2 / 7], atol=1e-12)
    np.testing.assert_allclose(printed_eq23(ALPHA)[2, 1:], [-2 / 7, 5 / 7], atol=1e-12)


def test_eq22_worst_error_is_a_true_maximum():
    """The optimiser's maximum beats a 10001-point grid, and the grid comes within its own
    resolution of it (|error| changes by < 2e-3 per unit gamma_t near the top: 1e-6 here)."""
    for ratio, where in ((0.1, 0.34), (0.02, 0.49)):
        gamma_t, worst = eq22_worst(ratio)
        grid = np.linspace(0.0, 5.0, 10001)
        on_grid = max(abs(eq22_error(x, ratio)) for x in grid)
        assert worst >= on_grid and worst - on_grid < 1e-6
        assert gamma_t == pytest.approx(where, abs=0.01)
    assert eq22_worst(0.1)[1] == pytest.approx(0.0852, abs=1e-4)  # not the 0.079 of gamma_t = 0.5
    assert eq22_worst(0.02)[1] == pytest.approx(0.3457, abs=1e-4)


def test_moderate_gamma_t_lowers_f_by_at_most_3_percent():
    """The optimiser's best drop in f against a coarse 2-D grid: never worse than any grid point,
    and the grid (step 0.002 in kt/kn, 0.01 in gamma_t) comes within 2e-4 of it."""
    ratio, gamma_t, fraction = best_reduction()
    grid = min((loss_bracket(g, x) / loss_bracket(0.0, x), x, g)
               for x in np.arange(0.06, 0.1001, 0.002) for g in np.arange(0.0, 1.0, 0.01))
    assert fraction <= grid[0] + 1e-9 and grid[0] - fraction < 2e-4
    assert abs(ratio - grid[1]) <= 0.002 and abs(gamma_t - grid[2]) <= 0.01  # one grid step
    assert (ratio, 1 - fraction) == pytest.approx((0.081, 0.032), abs=1e-3)
    # a very large gamma_t (the rolling limit) always dissipates more: the bracket is 1 at Omega = -1
    for x in (0.05, 0.1, 0.2, 0.5, 8 / 7):
        assert loss_bracket(40.0, x) >= loss_bracket(0.0, x)


def test_printed_eq23_dissipates_less_for_a_spinning_normal_impact():
    """(v_n, v_t, r omega) = (-1, 0, 1), E(0) = 0.7 m: printed Eq. 23 -> (1, -2/7, 5/7), f = 4/49;
    Eq. 18 gives f = alpha u'^2 [1 - (1+Omega)^2] / (2 (1+alpha) E(0)): 10/49 at Omega = -1."""
    state = np.array(SPIN_STATE)
    f_printed = exact.dissipation(state, printed_eq23(ALPHA) @ state, 1.0, ALPHA)
    assert f_printed == pytest.approx(4 / 49, abs=1e-12)
    f_rolling = exact.dissipation(state, exact.rolling_matrix(ALPHA) @ state, 1.0, ALPHA)
    assert f_rolling == pytest.approx(10 / 49, abs=1e-12)
    omega = exact.Omega(10.0, 1.0, ALPHA)
    f_tenth = exact.dissipation(state, exact.scattering_matrix(ALPHA, omega) @ state, 1.0, ALPHA)
    assert f_tenth == pytest.approx(10 / 49 * (1 - (1 + omega) ** 2), abs=1e-12)
    assert f_printed < f_tenth < f_rolling


# ---------------------------------------------------------------------------
# LAMMPS: the claims, judged once per session (conftest.reproduction)
# ---------------------------------------------------------------------------

@pytest.mark.lammps
def test_every_claim_is_measured_and_judged(claims_made):
    claims = claims_made
    assert len(claims) == len(CLAIMS) >= 20
    assert len({c.key for c in claims}) == len(claims)
    assert not [c.key for c in claims if c.verdict == "unresolved"]  # LAMMPS agreed with the exact theory
    assert {c.verdict for c in claims} <= set(VERDICTS)
    by_key = {c.key: c for c in claims}
    # The headline number: LAMMPS's fitted Omega within the collision tolerance of -1.28384
    assert abs(by_key["omega"].lammps - (-1.28383856)) < COLLISION_TOL
    # Where the paper's text and its own equations disagree, LAMMPS sides with the equations
    assert by_key["rough-vt"].verdict == "contradicted"
    assert abs(by_key["rough-vt"].lammps - (-4 / 7)) < COLLISION_TOL
    expected = {"eq23": "contradicted", "eq22": "approximate", "reflection-angle": "inconsistent",
                "hard-sphere": "ill-posed", "tau-gamma-n-longer": "reproduced", "tau-gamma-n-vn": "contradicted",
                "hertz-tau": "reproduced", "harmonics": "reproduced", "rolling-vs-rough": "contradicted",
                "friction-dissipation": "contradicted", "omega-sign": "reproduced"}
    assert {key: by_key[key].verdict for key in expected} == expected


@pytest.mark.lammps
def test_claims_quote_the_optimised_numbers(claims_made):
    by_key = {c.key: c for c in claims_made}
    gamma_t, worst = eq22_worst(0.1)
    eq22 = by_key["eq22"]
    assert eq22.paper == pytest.approx(exact.Omega_paper_damped(1.0, 10.0, 1.0, ALPHA, gamma_t), abs=1e-12)
    assert eq22.exact - eq22.paper == pytest.approx(-worst, abs=1e-12)
    assert f"{worst:.4f} at gamma_t = {gamma_t:.4f}" in eq22.evidence
    assert "would not even keep" not in by_key["eq23"].evidence
    assert f"{4 / 35:+.4f} m" in by_key["eq23"].evidence
    assert "at kt/kn = 1.142857" in by_key["omega-sign"].exact  # the true maximum, 0 at 8/7
    assert f"{1 - best_reduction()[2]:.2%}" in by_key["friction-dissipation"].evidence


@pytest.mark.lammps
def test_written_ledger_has_one_row_per_claim_and_its_provenance(claims_made, tmp_path):
    md, js = write_claims(claims_made, tmp_path)
    text = md.read_text()
    assert text.count("\n| ") - 1 == len(claims_made)  # one table row per claim, plus the header
    assert all(f"**{kind}**:" in text for kind in VERDICTS)  # every verdict kind is explained
    record = json.loads(js.read_text())
    assert sum(record["verdicts"].values()) == len(claims_made)
    assert record["lammps_version"] and record["python"] and record["created"]
    assert [c["key"] for c in record["claims"]] == [c.key for c in claims_made]


@pytest.mark.lammps
def test_committed_ledger_is_what_the_code_computes(claims_made):
    """figures/CLAIMS.md must be regenerated (`spinbounce claims`) whenever a claim changes."""
    committed = (COMMITTED / "CLAIMS.md").read_text()
    record = json.loads((COMMITTED / "claims.json").read_text())
    fresh = markdown(claims_made, {"lammps_version": record["lammps_version"]})
    assert committed == fresh, "figures/CLAIMS.md is stale: regenerate it with `spinbounce claims`"


@pytest.mark.lammps
def test_reproduce_writes_every_figure_and_the_claims(reproduction, monkeypatch, capsys):
    """The README's main job, end to end: six figures (PNG, PDF, JSON) and CLAIMS.md; the
    command prints the summary of that one session-wide run and fails on an unresolved claim."""
    from spinbounce.cli import main, reproduce as reproduce_cli

    made, _ = reproduction
    for n in range(2, 8):
        assert (made.out / f"fig{n}.png").read_bytes().startswith(b"\x89PNG")
        assert (made.out / f"fig{n}.pdf").read_bytes().startswith(b"%PDF")
        record = json.loads((made.out / f"fig{n}.json").read_text())
        assert 0 < record["max_deviation_exact"] < 1e-4  # the acceptance limit, measured per figure
    assert made.claims_md.read_text().count("**reproduced**") >= 1
    monkeypatch.setattr(reproduce_cli, "reproduce", lambda out, runs, only=None, workers=None: made)
    assert main(["reproduce", "--out", str(made.out)]) == 0
    printed = capsys.readouterr().out
    assert "0 unresolved" in printed and f"{len(made.claims)} claims" in printed
    # one claim that LAMMPS could not settle makes the command fail
    doubtful = [dataclasses.replace(made.claims[0], verdict="unresolved"), *made.claims[1:]]
    monkeypatch.setattr(reproduce_cli, "reproduce",
                        lambda out, runs, only=None, workers=None: dataclasses.replace(made, claims=doubtful))
    assert main(["reproduce", "--out", str(made.out)]) == 1
    assert "1 unresolved" in capsys.readouterr().out
