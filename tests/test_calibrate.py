"""Calibration: targets (e, beta, t_c, mu) to (kn, kt, gamma_n, gamma_t), checked two ways.

Calibration: targets (e, beta, t_c, mu) -> (kn, kt, gamma_n, gamma_t), checked by the theory
it inverts and by LAMMPS.

LAMMPS tolerance 1e-3 (the acceptance line) on e, beta and t_c/target. The calibrated models
have different contact times, so no one step puts every contact's end mid-step and LAMMPS's
error is first order: measured over these 100 random targets at 2000 steps per half-period
(measure's default), largest 4.5e-4 in beta, 2.4e-4 in t_c, 1.1e-4 in e; at 1000 steps 9.9e-4 in
beta, at 4000 3.2e-4 (capped contacts: their sticking slip of 1e-3 mu |v_n| adds its own part).
"""

import argparse

import numpy as np
import pytest

from spinbounce import exact
from spinbounce.cli import calibrate as calibrate_cli
from spinbounce.cli.options import allow_negative_numbers
from spinbounce.studies.calibrate import (LIMIT_DAMPING_E_MIN, Targets, Unreachable, calibrate, fix_line, measure,
                                          tangential_range)


def random_targets(rng, count):
    """``count`` random targets over every branch (held gamma_t, held kt/kn, cap, limit_damping),
    with the targets the linear model cannot reach, and those it refuses, set aside."""
    reached, refused = [], []
    while len(reached) < count:
        held = rng.integers(3)
        limit = bool(rng.integers(2))
        t = Targets(e=rng.uniform(0.3, 1.0), contact_time=rng.uniform(0.5, 2.0), beta=rng.uniform(-0.95, 0.95),
                    mu=rng.uniform(0.1, 1.0) if limit and rng.random() < 0.5 else None, limit_damping=limit,
                    gamma_t=None if held == 2 else (0.0 if held == 0 else rng.uniform(0.0, 1.0)),
                    kt_over_kn=rng.uniform(0.05, 0.5) if held == 2 else None)
        try:
            reached.append(calibrate(t))
        except Unreachable:
            refused.append(t)
    return reached, refused


@pytest.mark.slow
def test_the_calibrated_model_meets_its_targets_in_the_exact_theory():
    # the inverse against the forward theory (linear.py): root finding to 1e-14, so 1e-9
    reached, refused = random_targets(np.random.default_rng(3), 120)
    for c in reached:
        got = c.achieved_theory()
        t = c.targets
        assert abs(got["e"] - t.e) < 1e-9 and abs(got["beta"] - t.beta) < 1e-9
        assert abs(got["contact_time"] / t.contact_time - 1.0) < 1e-9
    assert len(refused) > 0  # the random targets do reach past what the model allows


def test_limit_damping_cannot_go_below_exp_minus_2():
    assert exact.restitution(1.0, 1.0, 2.0 * (1 - 1e-9), tensile=False) == pytest.approx(LIMIT_DAMPING_E_MIN, 1e-6)
    with pytest.raises(Unreachable, match=r"\(0.135335, 1\]"):
        calibrate(Targets(e=0.1, contact_time=1.0, beta=0.5, limit_damping=True))
    calibrate(Targets(e=0.1, contact_time=1.0, beta=0.5))  # a normal force that may pull gets there


@pytest.mark.parametrize("held", [{"kt_over_kn": 0.2, "gamma_t": None}, {"gamma_t": 0.5}])
def test_the_reachable_range_named_on_refusal_is_the_real_one(held):
    base = Targets(e=0.8, contact_time=1.0, beta=0.0, **held)
    low, high, _ = tangential_range(base)
    for edge, inward in ((low, 1.0), (high, -1.0)):
        inside = Targets(**{**base.__dict__, "beta": edge + inward * 1e-6})
        assert abs(calibrate(inside).achieved_theory()["beta"] - inside.beta) < 1e-9
        outside = Targets(**{**base.__dict__, "beta": edge - inward * 1e-3})
        if -1.0 <= outside.beta <= 1.0:
            with pytest.raises(Unreachable, match="reaches beta in"):
                calibrate(outside)


def test_a_cap_with_a_pulling_normal_force_is_refused():
    # at F_n = 0 the cap wipes the spring's history: measured in LAMMPS and the oracle, beta
    # then misses the linear value by up to 0.25 however small the slip
    with pytest.raises(Unreachable, match="limit_damping"):
        calibrate(Targets(e=0.7, contact_time=1.0, beta=0.3, mu=0.5))
    calibrate(Targets(e=1.0, contact_time=1.0, beta=0.3, mu=0.5))  # undamped: F_n never pulls


@pytest.mark.slow
@pytest.mark.lammps
def test_lammps_reaches_100_random_targets_within_1e_3(tmp_path):
    reached, _ = random_targets(np.random.default_rng(11), 100)
    measured = measure(reached, tmp_path)
    assert len(list(tmp_path.glob("batch*"))) == 4  # 31 models a run
    errors = np.array([[m["e"] - c.targets.e, m["beta"] - c.targets.beta,
                        m["contact_time"] / c.targets.contact_time - 1.0] for c, m in zip(reached, measured)])
    assert np.abs(errors).max() < 1e-3
    # the wall line printed for the user is the one LAMMPS ran
    deck = (tmp_path / "batch1" / "in.lammps").read_text()
    assert fix_line(reached[0].model).split(" wall/gran ")[1].removesuffix(" zplane 0.0 NULL") in deck


def _cli(argv):
    parser = argparse.ArgumentParser(prog="spinbounce")
    calibrate_cli.register(parser.add_subparsers(dest="command"))
    allow_negative_numbers(parser)
    args = parser.parse_args(argv)
    return args.handler(args)


def test_the_command_prints_ready_lines(capsys):
    assert _cli(["calibrate", "--e", "0.9", "--contact-time", "2", "--Omega", "-1.5", "--no-run"]) == 0
    out = capsys.readouterr().out
    assert "fix wall all wall/gran granular hooke" in out and "pair_coeff * * hooke" in out
    with pytest.raises(Unreachable):
        _cli(["calibrate", "--e", "0.9", "--contact-time", "2", "--beta", "-0.9", "--kt-over-kn", "0.1", "--no-run"])


@pytest.mark.lammps
def test_the_command_reports_what_lammps_achieved(capsys):
    assert _cli(["calibrate", "--e", "0.8", "--contact-time", "1", "--beta", "0.4", "--mu", "0.5",
                 "--limit-damping"]) == 0
    rows = {line.split()[0]: line.split()[1:] for line in capsys.readouterr().out.splitlines() if line[:1] in "eb"}
    target, _, lammps = (float(x) for x in rows["beta"])
    assert abs(lammps - target) < 1e-3
