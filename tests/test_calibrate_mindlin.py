"""calibrate for Hertz-Mindlin: reachable targets met in LAMMPS, unreachable ones refused with the range.

Targets are drawn reachable by construction (a random material or k_t, its exact e and beta), then
calibrated from e and beta alone; LAMMPS, at the default step (1e-4 of the state), must meet both
targets within 1e-3, the acceptance bar.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from spinbounce.cli import main
from spinbounce.studies.calibrate import Unreachable
from spinbounce.studies.calibrate_mindlin import (MindlinTargets, _axis, achieved, beta_range, calibrate_mindlin,
                                                  measure_mindlin)

VARIANTS = ("mindlin", "mindlin/force", "mindlin_rescale", "mindlin_rescale/force")


def _reachable(rng) -> MindlinTargets:
    """A passive target some model reaches (-1 <= beta <= 1), drawn until one is."""
    while True:
        targets = _drawn(rng)
        if -1.0 <= targets.beta <= 1.0:
            return targets


def _drawn(rng) -> MindlinTargets:
    """A random e, variant and (nu, or nu and k_t), and the beta it reaches."""
    e, variant = float(rng.uniform(0.3, 0.95)), str(rng.choice(VARIANTS))
    if rng.random() < 0.5:  # beta through the NULL stiffness's Poisson's ratio
        nu = float(rng.uniform(-0.9, 0.5))
        beta = achieved(calibrate_mindlin(MindlinTargets(e=e, poisson_ratio=nu, tangential=variant)))["beta"]
        return MindlinTargets(e=e, beta=beta, tangential=variant)
    held = MindlinTargets(e=e, poisson_ratio=0.3, tangential=variant)
    model = calibrate_mindlin(held)
    ratio = float(10.0 ** rng.uniform(-2.5, 0.5))
    beta = achieved(model.replace(mindlin_kt=ratio * model.kn))["beta"]
    return MindlinTargets(e=e, beta=beta, poisson_ratio=0.3, tangential=variant)


def _meets_in_lammps(targets: MindlinTargets, tmp_path) -> None:
    model = calibrate_mindlin(targets)
    theory = achieved(model)
    assert theory["e"] == pytest.approx(targets.e, abs=1e-8) and theory["beta"] == pytest.approx(targets.beta, abs=1e-8)
    lammps = measure_mindlin(model, tmp_path)
    assert abs(lammps["e"] - targets.e) <= 1e-3 and abs(lammps["beta"] - targets.beta) <= 1e-3


@pytest.mark.lammps
@pytest.mark.parametrize("seed", range(3))
def test_a_reachable_target_is_met_in_lammps(seed, tmp_path):
    _meets_in_lammps(_reachable(np.random.default_rng(seed)), tmp_path)


@pytest.mark.slow
@pytest.mark.lammps
def test_thirty_random_reachable_targets_are_met_in_lammps(tmp_path):
    rng = np.random.default_rng(2026)
    for k in range(30):
        _meets_in_lammps(_reachable(rng), tmp_path / str(k))


#: Each variant once, each with another of (x_t, nu) (dashpot or not, the NULL stiffness's scan or k_t's), and
#: the case furthest from its single bounce (mindlin_rescale with a dashpot, on nu).
SCANS = [(v, x_t, nu) for v, (x_t, nu) in zip(VARIANTS, [(None, None), (0.4, None), (None, 0.3), (0.4, 0.3)])]


@pytest.mark.parametrize("variant, x_t, poisson_ratio", SCANS + [("mindlin_rescale", 0.4, None)])
def test_the_scan_s_one_integration_is_each_model_s_own_bounce(variant, x_t, poisson_ratio):
    # the scan reads each grid model's beta off one shared normal motion (each model's k_t/kn and x_t
    # on the first's, by the contact's self-similarity); it must be each model's own exact bounce to
    # the integrators' agreement: both are DOP853 at rtol 1e-12, and the single bounce itself is off by
    # up to 3e-10 (mindlin_rescale with x_t 0.4, against the same bounce at rtol 1e-14, which the
    # shared one meets to 4e-15); 1e-9 holds that, far below any target's 1e-3
    targets = MindlinTargets(e=0.45, beta=-0.5, tangential=variant, x_t=x_t, poisson_ratio=poisson_ratio)
    _, _, _, grid, betas = beta_range(targets)
    _, model_of, _ = _axis(targets)
    for k in [*range(grid.size // 6, grid.size, grid.size // 6), grid.size - 1]:  # not 0: the scan's own normal
        assert betas[k] == pytest.approx(achieved(model_of(grid[k]))["beta"], abs=1e-9)


def test_an_unreachable_beta_is_refused_with_the_reachable_range():
    targets = MindlinTargets(e=0.8, beta=0.2)  # the NULL stiffness of a solid sphere keeps most slip
    low, high, name, _, _ = beta_range(targets)
    with pytest.raises(Unreachable) as info:
        calibrate_mindlin(targets)
    assert info.value.parameter == "beta" and f"[{low:.6g}, {high:.6g}]" in str(info.value) and name in str(info.value)


def test_a_beta_of_an_energy_gaining_bounce_is_refused():
    with pytest.raises(Unreachable) as info:
        calibrate_mindlin(MindlinTargets(e=0.9, beta=-1.02))
    assert info.value.parameter == "beta" and "[-1, 1]" in str(info.value)


def test_e_is_the_restitution_at_every_speed():
    # coeff_restitution's Hertzian dashpot: e_n = e, and the contact is the same at every speed
    model = calibrate_mindlin(MindlinTargets(e=0.55, poisson_ratio=0.2))
    assert model.e_n == 0.55
    assert model.normal_law.restitutions(model, [-0.05, -0.7, -2.0]) == pytest.approx([0.55] * 3, abs=1e-9)


def test_the_cli_calibrates_and_refuses_the_linear_model_s_options(capsys):
    assert main(["calibrate", "--e", "0.7", "--beta", "-0.6", "--tangential", "mindlin", "--no-run", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["theory"]["e"] == pytest.approx(0.7, abs=1e-9)
    assert report["theory"]["beta"] == pytest.approx(-0.6, abs=1e-9)
    with pytest.raises(SystemExit):
        main(["calibrate", "--e", "0.7", "--beta", "-0.6", "--tangential", "mindlin", "--contact-time", "1"])
    assert "contact_time = 1.0" in capsys.readouterr().err
