"""The accuracy study: its arithmetic, its cases, and the quick study run end to end.

The LAMMPS tests run ``spinbounce accuracy --quick`` once (a few seconds) and check what
the study claims: the observed orders, errors that shrink along the ladder, the step
counts it reports for a target actually reaching it, and the files it writes.
"""

import argparse
import contextlib
import io
import itertools
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

from spinbounce.studies import accuracy
from spinbounce.studies.accuracy import (
    EDGE,
    FROZEN,
    MID,
    TARGETS,
    cases,
    collision_dt,
    fit_order,
    frozen_dt,
    steps_for,
)
from spinbounce.cli import accuracy as accuracy_cli
from spinbounce.model.scenes import Collision, ContactModel, Frozen

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def parse(argv):
    parser = argparse.ArgumentParser(prog="spinbounce")
    sub = parser.add_subparsers(dest="command", required=True)
    accuracy_cli.register(sub)
    return parser.parse_args(argv)


# ---------------------------------------------------------------------------
# No LAMMPS
# ---------------------------------------------------------------------------

def test_importing_loads_neither_matplotlib_nor_lammps():
    code = ("import sys, spinbounce.studies.accuracy, spinbounce.cli.accuracy; "
            "print('matplotlib' in sys.modules, 'lammps' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.split() == ["False", "False"]


def test_fit_recovers_a_power_law_and_ignores_the_coarse_levels_and_the_floor():
    dt = 0.1 / 2.0 ** np.arange(10)
    error = 3.0 * dt**2
    error[0] *= 5.0  # a pre-asymptotic coarse level: outside the finest four
    error[-1] = 1e-14  # round-off: below the floor
    fit = fit_order(dt, error)
    assert fit["order"] == pytest.approx(2.0, abs=1e-12)
    assert fit["prefactor"] == pytest.approx(3.0, rel=1e-10)
    assert fit["fit_dt"] == pytest.approx(dt[-5:-1])
    assert fit["local_orders"][0] == pytest.approx(2.0 + math.log2(5.0))


def test_fit_without_two_usable_levels_is_nan():
    assert math.isnan(fit_order([0.1, 0.05], [1e-13, 1e-14])["order"])


def test_steps_for_interpolates_inside_and_extrapolates_outside():
    dt = 1.0 / np.array([100.0, 200.0, 400.0, 800.0])
    error = 2.0 * dt
    steps = 1.0 / dt  # steps proportional to 1/dt, so log error is linear in log steps
    fit = fit_order(dt, error)
    inside, flagged = steps_for(steps, error, 4e-3, fit, lambda d: 1.0 / d)
    assert not flagged and inside == pytest.approx(500.0)
    outside, flagged = steps_for(steps, error, 1e-5, fit, lambda d: 1.0 / d)
    assert flagged and outside == pytest.approx(2e5)
    coarse, flagged = steps_for(steps, error, 0.1, fit, lambda d: 1.0 / d)
    assert flagged and coarse == pytest.approx(20.0)  # below the ladder: the fitted line, marked


def test_ladder_steps_match_the_scenes_defaults():
    m = ContactModel()
    assert collision_dt(m, 250, MID) == Collision(m).dt
    assert collision_dt(m, 250, EDGE) == pytest.approx(m.tau / 250)
    damped = ContactModel(gamma_t=1.0)
    assert frozen_dt(damped, 1000) == Frozen(damped, z=0.1, v_t=1.0, omega=0.0, t_end=10.0).dt
    with pytest.raises(ValueError, match="form"):
        collision_dt(m, 250, FROZEN)


def test_the_cases_cover_the_brief_and_are_valid_scenes():
    all_cases = cases()
    names = [c.name for c in all_cases]
    assert len(set(names)) == len(names)
    for name in ("defaults", "magic", "soft", "stiff", "damped_t", "damped_n", "alpha_small", "alpha_shell",
                 "grazing", "head_on", "head_on_spin", "high_spin", "frozen", "frozen_damped"):
        assert name in names
    for case in all_cases:
        assert case.why and case.limit and case.expected in (1.0, 2.0, 3.0)
        if case.kind == "collision":
            Collision(case.model, v_n=[s[0] for s in case.states], v_t=[s[1] for s in case.states],
                      omega=[s[2] / case.model.r for s in case.states])
            assert case.expected_edge in (1.0, 2.0, 3.0)
        else:
            assert len(case.states) == 1 and case.states[0][0] == 0.0
    by_name = {c.name: c for c in all_cases}
    assert by_name["magic"].model.kt / by_name["magic"].model.kn == pytest.approx(2.0 / 7.0)
    assert all(abs(s[0]) == 0.01 for s in by_name["grazing"].states)
    assert all(abs(s[2]) == pytest.approx(20 * abs(s[0])) for s in by_name["high_spin"].states)
    assert [c.name for c in all_cases if not c.exact] == ["coulomb"]


def test_cli_options():
    args = parse(["accuracy"])
    assert args.out == Path("figures") and not args.quick and args.runs is None
    args = parse(["accuracy", "--quick", "--out", "somewhere", "--json"])
    assert args.quick and args.out == Path("somewhere") and args.json


# ---------------------------------------------------------------------------
# LAMMPS: the quick study, once
# ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def quick():
    """``spinbounce accuracy --quick --json`` into a temporary folder: (report, out folder, study JSON)."""
    with tempfile.TemporaryDirectory(prefix="spinbounce-accuracy-test-") as tmp:
        out = Path(tmp) / "figures"
        args = parse(["accuracy", "--quick", "--json", "--out", str(out)])
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(io.StringIO()):
            assert args.handler(args) == 0
        report = json.loads(printed.getvalue())
        record = json.loads((out / "accuracy.json").read_text())
        yield report, out, record


def _summary(record, case, form):
    (row,) = [r for r in record["summary"] if r["case"] == case and r["form"] == form]
    return row


@pytest.mark.lammps
def test_observed_orders_are_the_integrators(quick):
    _, _, record = quick
    assert _summary(record, "defaults", MID)["observed_order"] == pytest.approx(2.0, abs=0.2)
    assert _summary(record, "defaults", EDGE)["observed_order"] == pytest.approx(1.0, abs=0.2)
    assert _summary(record, "frozen", FROZEN)["observed_order"] == pytest.approx(2.0, abs=0.2)
    assert _summary(record, "frozen_damped", FROZEN)["observed_order"] == pytest.approx(1.0, abs=0.2)
    # and every case lands on the order its explanation predicts
    off = [(r["case"], r["form"], r["observed_order"], r["expected_order"]) for r in record["summary"]
           if abs(r["observed_order"] - r["expected_order"]) > 0.2]
    assert not off


@pytest.mark.lammps
def test_errors_shrink_along_the_ladder(quick):
    _, _, record = quick
    runs = [r for r in record["runs_table"] if r["in_ladder"] and r["exact_theory"]]
    groups = {}
    for r in runs:
        groups.setdefault((r["case"], r["form"]), []).append(r)
    assert len(groups) == 26  # 12 collision cases in two forms, plus the two frozen contacts
    for key, rows in groups.items():
        rows.sort(key=lambda r: r["steps_per_half_period"])
        assert [r["steps_per_half_period"] for r in rows] == list(accuracy.QUICK_LADDER), key
        errors = [r["error"] for r in rows if r["error"] > accuracy.ERROR_FLOOR]
        assert len(errors) >= 4, key
        assert all(b < a for a, b in itertools.pairwise(errors)), (key, errors)


@pytest.mark.lammps
def test_default_error_is_the_normal_over_kick(quick):
    """At the defaults the largest error is v_n's, |v_n| (w_n dt)^2/8 with the end mid-step."""
    _, _, record = quick
    row = _summary(record, "defaults", MID)
    m = ContactModel()
    w_dt = math.sqrt(m.kn / m.m) * row["default_dt"]
    assert row["error_at_default_dt"] == pytest.approx(1.5 * w_dt**2 / 8.0, rel=1e-3)


@pytest.mark.lammps
def test_steps_reported_for_a_target_reach_it(quick):
    report, _, record = quick
    costs = record["default_costs"]
    assert [c["target"] for c in costs] == list(TARGETS)
    for c in costs:
        # interpolation on a curve that is a clean power law: on target to within a few percent
        assert c["error_reached"] <= 1.05 * c["target"], c
        assert c["error_reached"] >= 0.5 * c["target"], c  # and not far more steps than needed
        assert c["single_error"] <= 1.05 * c["target"] and c["batch_error"] <= 1.05 * c["target"]
        assert c["single_wall_seconds"] > 0 and c["per_collision_wall_seconds"] > 0
    assert [c["lammps_steps"] for c in costs] == sorted(c["lammps_steps"] for c in costs)
    assert report["default_costs"] == costs


@pytest.mark.lammps
def test_files_are_written_with_provenance(quick):
    report, out, record = quick
    assert set(report["files"]) == {"png", "pdf", "json", "markdown"}
    assert (out / "accuracy.png").read_bytes()[:8] == PNG_MAGIC
    assert (out / "accuracy.pdf").read_bytes()[:5] == b"%PDF-"
    assert record["quick"] is True and record["lammps_version"] and record["spinbounce_version"]
    assert record["parameters"]["ladder_steps_per_half_period"] == list(accuracy.QUICK_LADDER)
    assert record["files"] == {"png": "accuracy.png", "pdf": "accuracy.pdf"}
    assert {c["name"] for c in record["cases"]} == {c.name for c in cases()}
    md = (out / "ACCURACY.md").read_text()
    for case in cases():
        assert case.label.replace("|", r"\|") in md
    assert "## Cost at the paper's defaults" in md and "## What limits the order" in md
    assert not list(out.glob(".*.tmp"))


@pytest.mark.lammps
def test_corners_bound_the_error_over_the_box(tmp_path):
    """The study runs only the box's corners: with no cap the map is linear, so no state inside
    the box can have a larger error than the worst corner."""
    (case,) = [c for c in cases() if c.name == "defaults"]
    for form in (MID, EDGE):
        dt = collision_dt(case.model, 64, form)
        corners, _ = accuracy._run_collision(case, dt, tmp_path / form.replace(" ", "-") / "corners")
        inside, _ = accuracy._run_collision(case, dt, tmp_path / form.replace(" ", "-") / "inside",
                                            states=accuracy._box_sample(200, seed=7))
        for s in ("vn", "vt", "r_omega"):
            assert inside[f"error_{s}"] <= corners[f"error_{s}"] * (1 + 1e-9), (form, s)
