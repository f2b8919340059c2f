"""The claims table: verdicts follow from the numbers, and every claim is measured."""

import json

import pytest

from spinbounce.studies.claims import CLAIMS, COLLISION_TOL, evaluate_claims, verdict, write_claims


def test_verdict_follows_the_numbers():
    # paper printed to 4 decimals, exact -1.28383856, LAMMPS 6e-6 away
    assert verdict(-1.2838, -1.2838446, -1.28383856, 5e-5, COLLISION_TOL) == "reproduced"
    assert verdict(-1.17, -1.2514, -1.2514, 5e-5, COLLISION_TOL, approx_tol=0.1) == "approximate"
    assert verdict(-1 / 7, -0.5714, -4 / 7, 1e-12, COLLISION_TOL) == "contradicted"
    # LAMMPS off from the exact theory: no verdict on the paper can be drawn
    assert verdict(-1.2838, -1.30, -1.28383856, 5e-5, COLLISION_TOL) == "unresolved"


@pytest.mark.lammps
def test_every_claim_is_measured_and_judged(tmp_path):
    claims = evaluate_claims(tmp_path / "runs", log=lambda *_: None)
    assert len(claims) == len(CLAIMS) >= 12
    by_key = {c.key: c for c in claims}
    assert not [c.key for c in claims if c.verdict == "unresolved"]  # LAMMPS agreed with the exact theory
    # The headline number: LAMMPS's fitted Omega within the collision tolerance of -1.28384
    assert abs(by_key["omega"].lammps - (-1.28383856)) < COLLISION_TOL
    # Where the paper's text and its own equations disagree, LAMMPS sides with the equations
    assert by_key["rough-vt"].verdict == "contradicted"
    assert abs(by_key["rough-vt"].lammps - (-4 / 7)) < COLLISION_TOL
    assert by_key["eq23"].verdict == "contradicted"
    # Eq. 22 is an approximation, and the table says by how much
    assert by_key["eq22"].verdict == "approximate" and "off by" in by_key["eq22"].evidence
    md, js = write_claims(claims, tmp_path / "out")
    text = md.read_text()
    assert text.count("\n| ") - 1 == len(claims)  # one table row per claim, plus the header
    record = json.loads(js.read_text())
    assert sum(record["verdicts"].values()) == len(claims)


@pytest.mark.lammps
def test_reproduce_writes_every_figure_and_the_claims(tmp_path, capsys):
    """The README's main job, end to end: six figures (PNG, PDF, JSON) and CLAIMS.md."""
    from spinbounce.cli import main

    out = tmp_path / "figures"
    assert main(["reproduce", "--out", str(out), "--run-dir", str(tmp_path / "runs")]) == 0
    for n in range(2, 8):
        assert (out / f"fig{n}.png").read_bytes().startswith(b"\x89PNG")
        assert (out / f"fig{n}.pdf").read_bytes().startswith(b"%PDF")
        record = json.loads((out / f"fig{n}.json").read_text())
        assert 0 < record["max_deviation_exact"] < 1e-4  # the acceptance limit, measured per figure
    assert (out / "CLAIMS.md").read_text().count("**reproduced**") >= 1
    assert "0 unresolved" in capsys.readouterr().out
