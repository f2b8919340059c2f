"""Published benchmarks: LAMMPS and the rigid-body law against the oracle, and the CLI's refusal.

Published benchmarks: LAMMPS against the oracle at each benchmark's refinement, the oracle
against the rigid-body law in gross sliding, the stiffness recipe, and the CLI's refusal.

Tolerances:
* LAMMPS vs oracle: 1e-4 of the impact speed U (the acceptance bar). Each benchmark's refine
  was chosen as the coarsest power of two with a measured worst case below 5e-5 U over its
  full state list (Benchmark.refine_why); the states here are a subset.
* oracle vs rigid body in gross sliding, undamped (chung-ooi-5): 1e-9 U. The friction
  impulse is exactly mu times the normal impulse; the oracle integrates at rtol 1e-12
  (measured 2.6e-14 U).
* damped (gamma_n > 0): the contact first sticks until the spring force reaches the
  cap mu gamma_n |v_n|, so the oracle falls short of the rigid-body outcome by about
  benchmarks.first_touch_stick. Measured ratio over every sliding state of the four
  benchmarks: 0.90 to 1.21; the test asks for 0.67 to 1.5 so it fails if the shortfall
  vanished or were of another origin.
"""

import math
from dataclasses import replace

import numpy as np
import pytest

from figure_bounds import texts_outside
from spinbounce.cli import main
from spinbounce.figures.core import STYLE
from spinbounce.studies import validation as B
from spinbounce.studies.validation.report import draw
from spinbounce.exact import choose, oracle

#: grid indices per benchmark: near-normal, mid (sticking or micro-slip), gross sliding;
#: chung-ooi-4's 30 deg and thornton's threshold states are avoided (oracle failures, see report)
REDUCED = {"chung-ooi-4": [1, 8, 16], "chung-ooi-5": [2, 8, 15], "chung-ooi-6": [2, 9, 15],
           "thornton-linear": [1, 3, 8], "thornton-hertz-mindlin": [1, 3, 8]}
#: the benchmarks with a Hookean series, which the rigid-body law's gross sliding is held to
HOOKEAN = [name for name in REDUCED if name != "thornton-hertz-mindlin"]


def _reduced(name):
    bench = B.with_states(B.BENCHMARKS[name], REDUCED[name])
    if name == "thornton-linear":  # the strongest damping (e = 0.25) is the hardest for LAMMPS
        bench = replace(bench, series=bench.series[:1])
    return bench


@pytest.mark.lammps
@pytest.mark.parametrize("name", list(REDUCED))
def test_lammps_matches_the_oracle_at_the_benchmark_refinement(tmp_path, name):
    run = B.run_benchmark(_reduced(name), tmp_path, log=lambda s: None)
    t = run.table
    assert t["oracle_ok"].all()
    assert t["dev_lammps_oracle_rel"].max() < B.ACCEPTANCE
    # the deviation is LAMMPS's own: it shrinks when the step does
    assert t["dev_lammps_oracle_rel_2f"].max() < t["dev_lammps_oracle_rel"].max()


@pytest.mark.parametrize("name", HOOKEAN)
def test_oracle_in_gross_sliding_is_the_rigid_body_law_up_to_the_first_touch_stick(name):
    bench = B.BENCHMARKS[name]
    checked = 0
    for series in bench.series:
        model = series.model
        if model.normal_law.contact_radius:  # a Hertz-Mindlin series: its dashpot pulls (below)
            continue
        states = np.array(series.states)
        initial = states * [1.0, 1.0, model.r]
        rigid, regimes = B.walton(model, initial, B.restitution(model, initial), bench.beta0)
        speed = B.impact_speed(initial)
        estimate = B.first_touch_stick(model, initial) / speed
        # the states furthest from the threshold, where the rigid law is meant to hold
        for i in [k for k, r in enumerate(regimes) if r == "sliding"][-2:]:
            got = (oracle.bounce(model, *states[i]).final[:3] if choose.which(model).kind == "coulomb"
                   else choose.predict(model, initial[i:i + 1])[0])  # a Mindlin contact's own reference
            dev = np.abs(got - rigid[i]).max() / speed[i]
            if model.gamma_n == 0.0:
                assert dev < 1e-9
            else:
                assert 0.67 * estimate[i] < dev < 1.5 * estimate[i]
            checked += 1
    assert checked >= 2


def test_hertz_contact_time_matches_an_integration_of_hertz_law():
    from scipy.integrate import solve_ivp

    steel = B.STEEL
    r, v = 1e-5, 5.0
    m, e_star = steel.mass(r), steel.effective_modulus()
    k = 4.0 / 3.0 * e_star * math.sqrt(r)

    def rhs(t, y):
        return [y[1], -k * max(y[0], 0.0) ** 1.5 / m]

    def out(t, y):
        return y[0]

    out.terminal, out.direction = True, -1.0
    t_h = B.hertz_contact_time(m, r, e_star, v)
    sol = solve_ivp(rhs, (0.0, 3 * t_h), [0.0, v], events=out, rtol=1e-11, atol=1e-20,
                    first_step=t_h * 1e-6)
    # the event is located to the integrator's accuracy, far below 1e-8 relative
    assert sol.t_events[0][0] == pytest.approx(t_h, rel=1e-8)


def test_hookean_springs_have_the_hertz_time_and_mindlin_ratio_and_the_damping_the_restitution():
    for name in ("chung-ooi-6", "thornton-linear"):
        for series in B.BENCHMARKS[name].series:
            mdl = series.model
            if mdl.normal_law.contact_radius:
                continue
            assert mdl.kt / mdl.kn == pytest.approx(B.mindlin_ratio(B.AL_ALLOY.nu), rel=1e-14)
            v_n = abs(series.states[0][0])
            t_h = B.hertz_contact_time(mdl.m, mdl.r, B.AL_ALLOY.effective_modulus(), v_n)
            assert math.pi * math.sqrt(mdl.m / mdl.kn) == pytest.approx(t_h, rel=1e-12)
    for name, e in (("chung-ooi-4", 0.98), ("chung-ooi-6", 0.5)):
        # bisection to 1e-15 in gamma_n: the restitution to ~1e-14
        assert B.BENCHMARKS[name].series[0].model.restitution == pytest.approx(e, abs=1e-12)


def test_the_hertz_mindlin_series_take_the_materials_and_the_restitution_at_every_speed():
    # kn = 4/3 E*, k_t = 8 G* of sphere and wall (Test 4: alumina on the alloy wall; Test 6: a
    # rigid wall), and coeff_restitution's e at every impact speed (1e-9: the integrated exit)
    for name, wall, e in (("chung-ooi-4", B.AL_WALL_T4, 0.98), ("chung-ooi-6", None, 0.5),
                          ("thornton-hertz-mindlin", None, 0.5)):
        series = B.BENCHMARKS[name].series[-1]
        mdl, material = series.model, (B.ALUMINA if wall else B.AL_ALLOY)
        assert mdl.kn == pytest.approx(4.0 / 3.0 * material.effective_modulus(wall), rel=1e-14)
        assert mdl.mindlin_kt == pytest.approx(8.0 * material.shear_modulus(wall), rel=1e-14)
        speeds = [-abs(s[0]) for s in series.states]
        assert mdl.normal_law.restitutions(mdl, speeds) == pytest.approx(e, abs=1e-9)


def test_hertz_mindlin_in_gross_sliding_takes_mu_times_the_whole_normal_force():
    # the rigid-body law's friction impulse is mu (1 + e) m |v_n|; LAMMPS's cap is mu |F_n|, and
    # a dashpot that pulls near the exit adds mu times that pull: with e = 0.98 the oracle's
    # sliding states stay within 1e-5 of the rigid law, with e = 0.5 they do not (1.6e-2 measured)
    near = {}
    for name in ("chung-ooi-4", "chung-ooi-6"):
        bench = B.BENCHMARKS[name]
        model = bench.series[1].model
        initial = np.array(bench.series[1].states) * [1.0, 1.0, model.r]
        rigid, regimes = B.walton(model, initial, B.restitution(model, initial), bench.beta0)
        i = [k for k, r in enumerate(regimes) if r == "sliding"][-1]
        near[name] = np.abs(choose.predict(model, initial[i:i + 1])[0] - rigid[i]).max() / B.impact_speed(initial)[i]
    assert near["chung-ooi-4"] < 1e-5 < 1e-3 < near["chung-ooi-6"]


@pytest.mark.lammps
def test_benchmark_figure_keeps_every_label_inside_the_figure(tmp_path):
    """The report's figure, drawn from every benchmark (a few states each, every series),
    leaves no text cut off at the figure's edge: its long y-labels used to run past the top."""
    import matplotlib.style

    runs = [B.run_benchmark(B.with_states(B.BENCHMARKS[name], REDUCED[name]), tmp_path, log=lambda s: None)
            for name in REDUCED]
    with matplotlib.style.context(STYLE):
        fig = draw(runs)
        assert texts_outside(fig) == []


def test_cli_refuses_an_unknown_benchmark(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["benchmarks", "--only", "chung-ooi-4,chung-ooi-9"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "unknown benchmark chung-ooi-9" in err
    for name in B.BENCHMARKS:
        assert name in err


def test_select_refuses_an_unknown_name():
    with pytest.raises(KeyError, match="known: chung-ooi-4, chung-ooi-5, chung-ooi-6, thornton-linear, "
                                       "thornton-hertz-mindlin"):
        B.select(["thornton"])


def test_the_cli_s_help_names_every_benchmark(capsys, monkeypatch):
    # the help is written out (the command starts without importing the benchmarks): it must not fall behind
    monkeypatch.setenv("COLUMNS", "1000")  # no name broken at its hyphen
    with pytest.raises(SystemExit):
        main(["benchmarks", "--help"])
    printed = " ".join(capsys.readouterr().out.split())
    for name in B.BENCHMARKS:
        assert name in printed
