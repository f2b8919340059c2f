"""The frozen contact under a constant Coulomb cap: its stick-slip theory, LAMMPS and --tolerance.

The theory is held to closed forms, an independent step-by-step integrator and LAMMPS at the
default step; a tolerance is met by measuring the error at halving steps."""

import math

import numpy as np
import pytest

from spinbounce import api
from spinbounce.exact.frozen_capped import frozen_velocities, slip
from spinbounce.model.contact import ContactModel
from spinbounce.model.timestep import FROZEN_ACCURACY
from spinbounce.pipeline import run_series
from spinbounce.scenes.frozen import Frozen

KT, M, ALPHA = 1.0, 1.0, 0.4
K = (1.0 + ALPHA) / (ALPHA * M)


def _undamped(t, u0, cap):
    """The undamped spring under a cap by hand: stick (u0 cos wt) until kt |xi| = cap, slip at the
    constant rate K cap until u = 0, then an oscillation of amplitude cap/kt that never slips."""
    w = math.sqrt(KT * K)
    if KT * abs(u0) / w <= cap:
        return u0 * np.cos(w * t)
    t1 = math.asin(cap * w / (KT * abs(u0))) / w
    u1 = u0 * math.cos(w * t1)
    t2 = t1 + abs(u1) / (K * cap)
    s = math.copysign(1.0, u0)
    return np.where(t < t1, u0 * np.cos(w * t),
                    np.where(t < t2, u1 - s * K * cap * (t - t1), -s * cap / KT * w * np.sin(w * (t - t2))))


def _stepped(t_end, dt, u0, gamma_t, cap):
    """LAMMPS's rule step by step (history += u dt, then the force, then the cap resets the history):
    first order in dt, an integrator that shares no code with the theory."""
    xi, u = 0.0, u0
    for _ in range(round(t_end / dt)):
        xi += u * dt
        force = -(KT * xi + gamma_t * u)
        if abs(force) > cap:
            force = math.copysign(cap, force)
            xi = -(force + gamma_t * u) / KT
        u += K * force * dt
    return u


@pytest.mark.parametrize("u0, cap", [(1.1, 0.15), (-1.1, 0.15), (0.3, 0.5), (2.0, 0.01)])
def test_the_undamped_stick_slip_is_the_closed_form(u0, cap):
    t = np.linspace(0.0, 12.0, 2001)
    # rtol 1e-12 in the stick phases and exact slip phases: 1e-9 of the slip leaves room for the events' roots
    assert np.abs(slip(t, u0, KT, K, 0.0, cap) - _undamped(t, u0, cap)).max() < 1e-9


@pytest.mark.parametrize("u0, gamma_t, cap", [(1.1, 0.5, 0.15), (1.1, 3.0, 0.15), (-2.0, 1.0, 0.3), (0.5, 0.2, 2.0)])
def test_the_damped_stick_slip_is_what_the_steps_converge_to(u0, gamma_t, cap):
    # first order in dt: two step sizes extrapolated leave ~dt^2; 1e-6 is far above that and far below
    # any mistake in the switching rules (a slip ending at u = 0 instead of gamma_t K cap/kt moves u by 1e-2)
    coarse, fine = (_stepped(7.3, dt, u0, gamma_t, cap) for dt in (2e-5, 1e-5))
    assert abs((2.0 * fine - coarse) - slip(np.array([7.3]), u0, KT, K, gamma_t, cap)[0]) < 1e-6


def test_forces_move_v_t_and_r_omega_as_alpha_to_one():
    t = np.linspace(0.0, 5.0, 50)
    v_t, r_omega = frozen_velocities(t, 0.8, 0.3, KT, M, ALPHA, 0.5, 0.15)
    np.testing.assert_allclose(v_t - 0.8, ALPHA * (r_omega - 0.3), atol=1e-12)


@pytest.mark.lammps
@pytest.mark.parametrize("mu, z, v_t, omega, gamma_t", [(0.05, 0.15, 0.8, 0.6, 0.0), (0.5, 0.15, 0.8, 0.6, 0.0),
                                                         (0.05, 0.15, 0.8, 0.6, 1.0), (0.01, 0.45, -2.0, 3.0, 0.0)])
def test_lammps_meets_the_capped_theory_at_the_default_step(mu, z, v_t, omega, gamma_t, tmp_path):
    result = run_series(Frozen(ContactModel(mu=mu, gamma_t=gamma_t), z=z, v_t=v_t, omega=omega, t_end=10.0), tmp_path)
    assert result.max_abs_error <= FROZEN_ACCURACY


@pytest.mark.lammps
def test_a_tolerance_is_met_by_measurement(tmp_path):
    report = api.frozen(0.15, 0.8, 0.6, 5.0, mu=0.05, tolerance=2e-7, out=tmp_path / "f")
    table, record = report.table, report.record
    error = max((table["v_t"] - table["v_t_theory"]).abs().max(), (table["r_omega"] - table["r_omega_theory"]).abs().max())
    assert record["method"].startswith("measured") and error <= record["estimate"] <= 2e-7


def test_the_classic_wall_is_refused_with_its_reason():
    from spinbounce.errors import SceneError

    with pytest.raises(SceneError, match="resets the history to the capped force over kt alone"):
        Frozen(ContactModel(mu=0.3, wall="classic"), z=0.3)
