"""The 3-D Coulomb solver (exact.coulomb.bounce_3d) against the scipy oracle in 3-D.

Tolerance 1e-8 of the impact speed |v|, the acceptance line's. The solver reduces the
contact exactly to the plane of the first slip; the oracle integrates the 3-D equations
(a slide turning s towards the slip, exact.oracle's integrate) at rtol 1e-12. Measured
with studies.solver_speed.agreement: 1,000 random 3-D cases (seed 2026) worst 9.1e-12,
median 8.5e-16, none refused, 17 s; 3,000 more (seed 11) worst 9.1e-12, none refused.
Before the oracle integrated a 3-D slide by the angle of s and log |u'_perp| (it ran
LSODA on s), 6 of the first 60 of those cases were refused and 3 more took over 10 s
each; each is a named case below.
"""

import math
import warnings

import numpy as np
import pytest

from spinbounce.model.contact import ContactModel
from spinbounce.errors import PhysicsWarning
from spinbounce.studies.solver_speed import agreement
from spinbounce.exact import coulomb, oracle

ORACLE_TOLERANCE_3D = 1e-8


@pytest.mark.slow
def test_random_3d_models_and_states_agree_with_the_oracle():
    # random_cases_3d turns random_case's sample out of the plane: the tangential velocity
    # and the spin's axis along independent angles, a spin about the normal; 17 ms a case
    # on an idle core (32 ms on a shared one), so 600 fit in a CI budget of ~30 s
    row = agreement(600, 7, "3-D")
    assert row["refused"] == 0
    assert row["worst"] < ORACLE_TOLERANCE_3D, row["worst_case"]


#: name -> (the model's parameters, state (v_n, v_t, omega, v_s, omega_s, omega_n)): random
#: 3-D cases (seed 2026 of studies.solver_speed.random_cases_3d, the number in the name)
#: that the oracle refused when it ran LSODA on s, named by what made them hard
ORACLE_3D_REGRESSIONS = {
    # a slide from first touch, where the cap is zero and s turns at kt |u'_perp| / c
    # without bound: LSODA stopped ("Unexpected istate")
    "gross slip from a zero cap (5)": (
        {"kt": 20.0, "alpha": 0.4, "gamma_t": 4.966263042788571, "mu": 0.09104749109335224,
         "limit_damping": True},
        (-0.04571934735677615, 0.12565261057598132, 0.008446675044163875,
         -0.24321523767556785, -0.0028398310677707397, -0.1789486565097969)),
    "gross slip from a zero cap (16)": (
        {"kt": 5.0, "alpha": 0.4, "mu": 0.6235556030159868, "limit_damping": True},
        (-0.4685027661758996, -0.06686588341108268, -26.605799472013608,
         -0.5646630475268248, -8.365248904706649, 0.35807329991032016)),
    "gross slip from a zero cap (30)": (
        {"kt": 10.0, "alpha": 1.0, "gamma_t": 4.702704080288803, "mu": 0.0038467228550941503,
         "limit_damping": True},
        (-0.4802881734903074, 1.4199774656054918, 3.8198183567284225, -0.7993696371252487,
         9.347388503734976, 3.004342991042159)),
    "gross slip from a zero cap (59)": (
        {"kt": 10.0, "alpha": 0.25, "gamma_t": 5.454287499931187, "mu": 0.12960614231580567,
         "limit_damping": True},
        (-0.248850546903492, 0.5842590389705019, -22.619645251428096, 1.029172546123357,
         55.661335370280476, -0.9851344508403845)),
    "slides through a tensile turn (22)": (
        {"kt": 0.5, "alpha": 0.1, "gamma_n": 3.5656462120710968,
         "gamma_t": 0.31451735416752247, "mu": 0.059100924887822544},
        (-0.6200500468667598, 0.4639036226901188, 20.488422483179274, 0.17942124130964873,
         -25.33431297538334, 0.7315102079105871)),
    "slides through a tensile turn (58)": (
        {"kt": 5.0, "alpha": 1.0, "gamma_n": 4.986046246878101, "mu": 0.0021503503428409705},
        (-0.4598344553725026, 1.4532163047994242, 10.778637032750042, -0.6146876873812982,
         5.39813968608002, 2.3226986194945143)),
    # stiff slides LSODA crawled through (over 10 s each)
    "slow stiff slide (7)": (
        {"kt": 20.0, "alpha": 0.1, "mu": 0.04894191501963121},
        (-1.0153283192316251, -0.1338420712164228, 0.0, 0.06204696806298019, 0.0,
         -1.9992828340221807)),
    "slow stiff slide (9)": (
        {"kt": 10.0, "alpha": 0.4, "gamma_t": 5.505287904992001, "mu": 0.006435298697947706},
        (-0.3216948674971625, -0.6648309269324767, 0.0, -0.45100003551823153, 0.0,
         -0.6923362928835065)),
    "slow stiff slide (23)": (
        {"kt": 20.0, "alpha": 1.0, "gamma_n": 0.8651192535902648, "mu": 0.9288385532651169,
         "limit_damping": True},
        (-0.3023584443949087, -0.04534832577380835, 0.021836111213843056,
         0.10618551527412304, 0.009785110040013192, -0.10800885136653103)),
    # the two hard spots of the present formulation: a slide restarting from the zero cap
    # of a tensile turn (log |u'_perp| falls at kt p / c there) and a slip opposing s as the
    # cap shrinks (u'_perp grows there, held by TURN_FLOOR)
    "slide restarting at the tensile turn (45)": (
        {"kt": 20.0, "alpha": 2.0 / 3.0, "gamma_n": 5.1769008859616035,
         "gamma_t": 10.011275475145215, "mu": 0.035725183324104105},
        (-0.4376897229416676, -0.18358489163825187, 0.0, -0.2532381447817147, 0.0,
         0.7364252222676031)),
    "slip opposing s as the cap shrinks (295)": (
        {"kt": 10.0, "alpha": 2.0 / 3.0, "gamma_n": 0.0841661376188967,
         "gamma_t": 0.6210271112732579, "mu": 0.19504023228350922},
        (-1.1766777819235408, 0.10846676034543179, 1.3451634453878865, 0.8076308007897316,
         -0.6484772682840603, -0.7705084815179141)),
}


@pytest.mark.parametrize("name", list(ORACLE_3D_REGRESSIONS))
def test_3d_cases_the_oracle_once_refused(name):
    kw, state = ORACLE_3D_REGRESSIONS[name]
    with warnings.catch_warnings():  # alpha = 1 is a thin shell's inertia, on purpose
        warnings.simplefilter("ignore", PhysicsWarning)
        model = ContactModel(kn=10.0, **kw)
    v_n, v_t, omega, v_s, omega_s, omega_n = state
    slow = oracle.bounce(model, v_n, v_t, omega, v_s=v_s, omega_s=omega_s, omega_n=omega_n)
    fast = coulomb.bounce_3d(model, *state)[0]
    assert np.abs(fast - slow.final).max() / math.hypot(v_n, v_t, v_s) < ORACLE_TOLERANCE_3D


def test_3d_gross_slip_oracle_keeps_the_first_slip_direction():
    # a slide from first touch to exit with the slip along neither axis: the oracle's
    # integrated s must stay on the slip line, so its outcome is the rigid impulse
    # mu (1 + e) m |v_n| against the slip (e = 1: no normal damping)
    model = ContactModel(mu=0.02)
    v_n, v_t, omega, v_s, omega_s = -1.0, 0.5, -60.0, 2.0, 30.0
    slip = np.array([v_t + model.r * omega, v_s + model.r * omega_s])
    dv = -model.mu * 2.0 * abs(v_n) * slip / np.hypot(*slip)
    closed = [-v_n, v_t + dv[0], model.r * omega + dv[0] / model.alpha,
              v_s + dv[1], model.r * omega_s + dv[1] / model.alpha, 0.0]
    got = oracle.bounce(model, v_n, v_t, omega, v_s=v_s, omega_s=omega_s)
    assert got.pattern == "slip"
    assert np.abs(got.final - closed).max() < ORACLE_TOLERANCE_3D
