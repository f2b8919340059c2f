"""Sphere-sphere collisions: the planar theory, the exact reference, and LAMMPS's pair granular."""

from __future__ import annotations

import json

import numpy as np
import pytest

from spinbounce import exact
from spinbounce.model.parameters import SceneError
from spinbounce.scenes.pair import Pair, PairBatch, PairContact, QUANTITIES, Sphere
from spinbounce.pipeline import run_scene
from spinbounce.scenes.pair.scene import SCALE_CLASSES, time_scaled
from spinbounce.studies.pairs import cases
from spinbounce.exact import pair as planar
from spinbounce.exact import pair_exact

LAW = {"kn": 10.0, "kt": 1.0}
OBLIQUE = Pair(a=Sphere(1.0, 0.5, 0.25), b=Sphere(2.5, 0.8, 0.4), normal=(0.2, 0.3, 1.0), v_a=(0.3, 0.1, -1.0),
               v_b=(0.0, 0.2, 0.1), w_a=(0.5, -1.0, 0.3), w_b=(0.2, 0.4, -0.7))


def _planar(pair: Pair, **law):
    vectors = {k: np.asarray(v)[None] for k, v in pair.vectors().items()}
    return [x[0] for x in planar.predict(**vectors, **pair.properties(), **(law or LAW))]


def _exact(pair: Pair, **options):
    o = pair_exact.solve(**pair.vectors(), **pair.properties(), **LAW, **options)
    return [o.v_a, o.v_b, o.w_a, o.w_b]


def test_exact_solve_with_frozen_line_of_centres_is_the_planar_closed_form():
    # Two independent routes to the planar theory (closed form, and the ODE with n and the
    # lever arms frozen); rtol 1e-12 integration: agreement to 1e-10 of unit speeds.
    for pair in (OBLIQUE, *cases()[::5]):
        for got, want in zip(_exact(pair, planar=True), _planar(pair), strict=True):
            assert np.max(np.abs(got - want)) < 1e-10


def test_exact_reference_is_converged_to_1e_9():
    # The reference must be accurate well beyond the 1e-4 it judges LAMMPS at: a 10x
    # tighter tolerance (near scipy's floor of 2.2e-14) moves it by less than 1e-9.
    for pair in (OBLIQUE, cases()[11], cases()[23]):
        for loose, tight in zip(_exact(pair), _exact(pair, rtol=1e-13), strict=True):
            assert np.max(np.abs(loose - tight)) < 1e-9


def test_planar_theory_conserves_momentum_and_each_spheres_angular_momentum_about_the_contact():
    pair = OBLIQUE
    n = np.asarray(pair.normal)
    v_a, v_b, w_a, w_b = _planar(pair)
    a, b = pair.a, pair.b
    momentum = a.m * np.asarray(pair.v_a) + b.m * np.asarray(pair.v_b)
    assert np.allclose(a.m * v_a + b.m * v_b, momentum, atol=1e-14)
    for side, sphere, (v0, w0), (v1, w1) in ((1, a, (pair.v_a, pair.w_a), (v_a, w_a)),
                                             (-1, b, (pair.v_b, pair.w_b), (v_b, w_b))):
        before = planar.angular_momentum_about_contact(n, v0, w0, sphere.m, sphere.r, sphere.alpha, side)
        after = planar.angular_momentum_about_contact(n, v1, w1, sphere.m, sphere.r, sphere.alpha, side)
        assert np.allclose(before, after, atol=1e-14)


def test_planar_theory_slip_rate_is_scaled_by_one_plus_Omega():
    pair = OBLIQUE
    n = np.asarray(pair.normal)
    u0 = planar.slip_rate(n, pair.v_a, pair.v_b, pair.w_a, pair.w_b, pair.a.r, pair.b.r)
    v_a, v_b, w_a, w_b = _planar(pair)
    u1 = planar.slip_rate(n, v_a, v_b, w_a, w_b, pair.a.r, pair.b.r)
    omega = planar.Omega(pair.a.m, pair.a.alpha, pair.b.m, pair.b.alpha, **LAW)
    m_star = planar.reduced_mass(pair.a.m, pair.b.m)
    K = planar.slip_mobility(**pair.properties())
    # the closed form the brief states: cos(pi sqrt((kt/kn) m* K)) - 1
    assert omega == pytest.approx(np.cos(np.pi * np.sqrt(LAW["kt"] / LAW["kn"] * m_star * K)) - 1, abs=1e-14)
    assert np.allclose(u1, (1 + omega) * u0, atol=1e-14)


@pytest.mark.parametrize("m_b", [1e6, 1e9, 1e14])
def test_a_heavy_sphere_b_at_rest_is_the_wall(m_b):
    # Eq. 18 in 3-D for sphere a; the pair's correction is O(m_a/m_b), so 1e-12 needs m_b >= 1e14
    # and the smaller masses bound the approach (error below 10 m_a/m_b).
    a = Sphere(1.0, 0.5, 0.3)
    pair = Pair(a=a, b=Sphere(m_b, 0.7, 0.4), v_a=(0.4, -0.3, -1.0), w_a=(0.6, -0.8, 0.5))
    v_a, v_b, w_a, _ = _planar(pair)
    wall = exact.block_matrix(a.alpha, exact.Omega(LAW["kn"], LAW["kt"], a.alpha))
    # (v_n, v_t, r omega, v_s, r omega_s, r omega_n) with omega = -omega_y, omega_s = omega_x
    state = np.array([pair.v_a[2], pair.v_a[0], -a.r * pair.w_a[1], pair.v_a[1], a.r * pair.w_a[0], a.r * pair.w_a[2]])
    want = wall @ state
    got = np.array([v_a[2], v_a[0], -a.r * w_a[1], v_a[1], a.r * w_a[0], a.r * w_a[2]])
    assert np.max(np.abs(got - want)) < max(1e-12, 10 * a.m / m_b)
    assert np.max(np.abs(v_b)) < 10 * a.m / m_b


@pytest.mark.parametrize("masses,radii", [((1.0, 1.0), (0.5, 0.5)), ((0.3, 5.0), (0.2, 1.1)),
                                          ((4.0, 0.7), (0.9, 0.3)), ((1.0, 100.0), (0.5, 2.0))])
def test_equal_alpha_pairs_have_the_walls_Omega(masses, radii):
    for alpha in (0.1, 0.4, 2.0 / 3.0):
        assert planar.equivalent_alpha(masses[0], alpha, masses[1], alpha) == pytest.approx(alpha, rel=1e-14)
        omega = planar.Omega(masses[0], alpha, masses[1], alpha, **LAW)
        assert omega == pytest.approx(exact.Omega(LAW["kn"], LAW["kt"], alpha), abs=1e-14)


def test_scene_refuses_bad_input_before_lammps():
    with pytest.raises(SceneError, match="alpha"):
        Sphere(alpha=1.5)
    with pytest.raises(SceneError, match="approach"):
        Pair(v_a=(0.0, 0.0, 1.0))
    with pytest.raises(SceneError, match="kn"):
        PairContact(kn=-1.0)
    with pytest.raises(SceneError, match="overlap"):
        PairBatch([Pair(v_a=(0.0, 0.0, -5.0))])


@pytest.mark.lammps
def test_lammps_matches_the_exact_reference_on_24_cases(tmp_path):
    # Default step; the bound is the default accuracy (1e-4 of the speed, the larger of
    # |v_a - v_b| and |u'(0)|). The line of centres turns by up to 3.9 rad, which leaves
    # LAMMPS first order in dt even with every contact ending mid-step (aligned time
    # scales); the probe sees that order and takes the steps it needs, fewer than the fine
    # rule's (measured: 3,701 against 10,865, every row within 4.8e-5).
    result = run_scene(PairBatch(cases()), tmp_path)
    assert result.step.method == "probe" and result.step.observed_order < 1.5
    assert result.scene.nsteps < PairBatch(cases()).nsteps
    table = result.table
    assert len(table) == 24 and (table["eps"] > 3.0).any() and (table["r_a"] != table["r_b"]).any()
    assert result.max_error < 1e-4
    # the planar theory is a model error, far above the run's: the exact reference is needed
    assert result.table["planar_error"].max() > 0.1
    assert json.loads((tmp_path / "result.json").read_text())["step"]["method"] == "probe"


def test_a_time_scaled_pair_is_the_same_collision_slower():
    # scenes.pair.scene.time_scaled: masses x s^2, velocities and spins / s. The exact reference of
    # the scaled pair must be the original's over s, lasting s times longer: to its own
    # tolerance (1e-9 of unit speeds), for an oblique pair whose line of centres turns.
    for pair in (OBLIQUE, cases()[5]):
        for s in (0.9, 1.003, 2.0):
            scaled = time_scaled(pair, s)
            original = pair_exact.solve(**pair.vectors(), **pair.properties(), **LAW)
            slower = pair_exact.solve(**scaled.vectors(), **scaled.properties(), **LAW)
            assert slower.contact_time == pytest.approx(s * original.contact_time, rel=1e-9)
            for q in ("v_a", "v_b", "w_a", "w_b"):
                assert np.max(np.abs(s * np.asarray(getattr(slower, q)) - getattr(original, q))) < 1e-9


def test_an_aligned_batch_ends_every_contact_mid_step():
    # Each pair's contact lasts a whole number of steps and a half in the deck, touching a
    # quarter step after a step (PairBatch.lead with g = 1/2), at a time scale within half a
    # step per contact of 1.
    batch = PairBatch(cases(), dt=0.013, aligned=True)
    ends = batch.deck_contact_times / batch.dt
    assert np.allclose(ends % 1, 0.5, atol=1e-9) and np.allclose(batch.lead, 0.25 * batch.dt)
    contact_steps = np.array([o.contact_time for o in batch.exact]) / batch.dt
    assert np.all(np.abs(batch.time_scales - 1) <= 0.5 / contact_steps + 1e-12)
    assert len(set(batch.time_scales)) > 1
    # A damped batch's pairs share SCALE_CLASSES scales (its damping scales per atom type): each
    # contact then ends within 1/(2K) of mid-step, times its length over the shortest's.
    damped = PairBatch(cases(), PairContact(gamma_n=0.5), dt=0.013, aligned=True)
    index, values = damped.scale_classes
    assert 1 < len(values) <= SCALE_CLASSES and np.array_equal(damped.time_scales, values[index])
    ends = damped.contact_times / damped.dt
    off = np.abs(damped.deck_contact_times / damped.dt % 1 - 0.5)
    assert np.all(off <= 0.5 / SCALE_CLASSES * ends / ends.min() + 1e-9)


def _sweep_pairs(r: float, n: int = 24) -> list[Pair]:
    rng = np.random.default_rng(5)
    sphere = Sphere(1.0, r, 0.4)
    return [Pair(a=sphere, b=sphere, v_a=(rng.uniform(-1, 1), 0.0, -rng.uniform(0.5, 1.5)),
                 w_a=(0.0, rng.uniform(-1, 1) / r, 0.0)) for _ in range(n)]


@pytest.mark.lammps
def test_a_small_eps_batch_is_probed_to_far_fewer_steps_within_the_accuracy(tmp_path):
    # Radii 5e3: the line of centres turns by eps < 1e-4, every contact lasts the same time,
    # and with that time mid-step LAMMPS converges at about second order (measured 1.6e-5 at
    # 100 steps per contact, where the fine rule takes 8000). The probe must find a step at
    # least ten times coarser than the fine rule's, and every row must still be within the
    # default accuracy of the exact reference.
    batch = PairBatch(_sweep_pairs(5e3))
    result = run_scene(batch, tmp_path)
    assert result.step.method == "probe" and len(result.step.probe_errors) >= 2
    assert result.scene.nsteps * 10 < batch.nsteps
    assert result.max_error < 1e-4
    assert result.table["eps"].max() < 1e-4
    recorded = json.loads((tmp_path / "result.json").read_text())
    assert recorded["step"]["dt"] == result.scene.dt == recorded["parameters"]["dt"]


@pytest.mark.lammps
def test_a_given_step_is_kept_and_recorded_as_given(tmp_path):
    batch = PairBatch(_sweep_pairs(5e3, 3), dt=1e-3)
    result = run_scene(batch, tmp_path, record=False)
    assert result.scene is batch and result.step.method == "given" and not result.step.probe_errors


def test_contacts_are_placed_where_the_first_order_errors_cancel_best():
    # PairBatch.lead: touch at a fraction phi = (1 - g)/2 of a step, g = frac(T/dt), so that
    # touch and release fall in one step's count (phi + g < 1) and release is at (1 + g)/2.
    batch = PairBatch(cases()[:6], dt=0.013)
    ends = np.array([o.contact_time for o in batch.exact]) / batch.dt
    phi = batch.lead / batch.dt
    assert np.all((phi >= 0) & (phi + ends % 1 < 1))
    assert np.allclose((phi + ends) % 1, (1 + ends % 1) / 2, atol=1e-9)


@pytest.mark.lammps
def test_a_batch_equals_isolated_runs(tmp_path):
    # Pairs in their own cells never interact: the batch reproduces each pair run alone
    # (same dt, same lead, same time scale) to rounding, 1e-11.
    chosen = [cases()[i] for i in (3, 9, 16, 23)]
    batch = PairBatch(chosen, dt=PairBatch(chosen).dt, aligned=True)
    together = run_scene(batch, tmp_path / "batch", record=False).table
    assert len(set(together["time_scale"])) == len(chosen)
    for k, pair in enumerate(chosen):
        alone = run_scene(PairBatch([pair], dt=batch.dt, aligned=True), tmp_path / f"alone{k}", record=False).table
        assert alone["contact_time"][0] == together["contact_time"][k]
        for q in QUANTITIES:
            assert abs(alone[q][0] - together[q][k]) < 1e-11, q


@pytest.mark.lammps
def test_lammps_gives_equal_alpha_pairs_the_walls_Omega(tmp_path):
    # Head-on, spinning: the slip ratio u'(end)/u'(0) - 1 is Omega. The tangential force
    # turns the line of centres by about u'(0) tau/(r_a + r_b), an O(1) relative error at
    # r ~ 1; radii of order 1e4 make it 1e-4 smaller. Three mass and radius ratios, alpha
    # 2/5 and 0.2 (rigid bodies). The slip adds four quantities each within the default
    # accuracy (1e-4 of the speed): 2e-4 of it bounds their sum in practice.
    pairs = []
    for alpha in (0.4, 0.2):
        for (m_a, m_b), (r_a, r_b) in (((1.0, 1.0), (5e3, 5e3)), ((0.3, 5.0), (2e3, 1.1e4)), ((4.0, 0.7), (9e3, 3e3))):
            pairs.append(Pair(a=Sphere(m_a, r_a, alpha), b=Sphere(m_b, r_b, alpha), v_a=(0.0, 0.0, -1.0),
                              w_a=(0.0, 1.0 / r_a, 0.0), w_b=(0.0, 0.5 / r_b, 0.0)))
    table = run_scene(PairBatch(pairs), tmp_path, record=False).table
    for k, pair in enumerate(pairs):
        row = table.iloc[k]
        n = np.array([0.0, 0.0, 1.0])
        u0 = planar.slip_rate(n, pair.v_a, pair.v_b, pair.w_a, pair.w_b, pair.a.r, pair.b.r)
        vectors = [np.array([row[f"{s}_{q}{x}"] for x in "xyz"]) for s, q in (("a", "v"), ("b", "v"), ("a", "w"),
                                                                                 ("b", "w"))]
        u1 = planar.slip_rate(n, *vectors, pair.a.r, pair.b.r)
        wall = exact.Omega(LAW["kn"], LAW["kt"], pair.a.alpha)
        assert u1[0] / u0[0] - 1 == pytest.approx(wall, abs=2e-4 / abs(u0[0]))


@pytest.mark.lammps
def test_lammps_dense_second_sphere_is_the_wall(tmp_path):
    # m_b = 1e8: the pair's own correction is 1e-8, so LAMMPS must give Eq. 18 (3-D) to its
    # default accuracy, 1e-4. Head-on, with radii 5e3 so that the slip hardly turns the line
    # of centres (see the equal-alpha test); Eq. 18 in r omega does not depend on r.
    a = Sphere(1.0, 5e3, 0.4)
    pair = Pair(a=a, b=Sphere(1e8, 5e3, 0.4), v_a=(0.0, 0.0, -1.0), w_a=(0.6 / a.r, -1.2 / a.r, 0.5 / a.r))
    row = run_scene(PairBatch([pair]), tmp_path, record=False).table.iloc[0]
    state = np.array([-1.0, 0.0, -a.r * pair.w_a[1], 0.0, a.r * pair.w_a[0], a.r * pair.w_a[2]])
    want = exact.block_matrix(a.alpha, exact.Omega(LAW["kn"], LAW["kt"], a.alpha)) @ state
    got = np.array([row.a_vz, row.a_vx, -a.r * row.a_wy, row.a_vy, a.r * row.a_wx, a.r * row.a_wz])
    assert np.max(np.abs(got - want)) < 1e-4


@pytest.mark.lammps
def test_pair_command_prints_lammps_beside_both_references(tmp_path, capsys):
    # `pair` is `collide --scene pair`: sphere a's state in the paper's frame and sign (LAMMPS's
    # angular velocity (0, 2, 1) is omega = -2, omega_n = 1)
    from spinbounce.cli import main

    assert main(["pair", "--alpha", "0.25", "--omega", "-2", "--omega-n", "1", "--out", str(tmp_path), "--json"]) == 0
    row = json.loads(capsys.readouterr().out)
    assert row["error_estimate"] < 1e-4 and row["alpha_a"] == 0.25
    assert row["planar_error"] > 100 * row["error_estimate"]  # eps = 0.66: the planar theory is far off
    assert row["initial"]["omega"] == -2.0 and row["initial"]["omega_n"] == 1.0  # the wall's keys, as typed


@pytest.mark.lammps
def test_a_damped_batch_is_probed_coarser_than_the_fine_rule_within_the_accuracy(tmp_path):
    # 30 damped pairs at the default radii (eps up to 0.7): with one shared step the probe
    # could not reach the accuracy below the fine rule (measured on 60 such pairs: 8,054
    # steps); with their time-scale classes it must, and every pair must stay within 1e-4.
    pairs = [Pair(v_a=(t, 0.0, -n), w_a=(0.0, w, 0.0)) for t, n, w in
             np.random.default_rng(4).uniform([-1.0, 0.5, -2.0], [1.0, 1.5, 2.0], (30, 3))]
    batch = PairBatch(pairs, PairContact(gamma_n=0.5))
    result = run_scene(batch, tmp_path, record=False)
    assert result.step.method == "probe" and result.scene.nsteps < batch.nsteps
    assert len(result.scene.scale_classes[1]) > 1 and result.max_error < 1e-4


def test_free_flight_parts_the_spheres_where_the_overlap_is_gone():
    # limit_damping's end of a contact: from the normal force's turn each centre moves on at its
    # velocity; the distance must grow by the overlap left (along n0 with the line held), to rounding
    rng = np.random.default_rng(31)
    for _ in range(50):
        n0 = rng.normal(size=3)
        n0 /= np.linalg.norm(n0)
        d = rng.uniform(0.5, 2.0) * n0 + rng.normal(scale=0.1, size=3)
        v_b = rng.normal(size=3)
        v_a = v_b + rng.uniform(0.1, 2.0) * d / np.linalg.norm(d) + rng.normal(scale=0.5, size=3)
        state, delta = np.concatenate([d, v_a, v_b, np.zeros(6)]), rng.uniform(1e-6, 0.1)
        if (v_a - v_b) @ n0 <= 0.0:
            continue
        end, t = pair_exact.free_flight(state, 1.0, n0, False, delta)
        assert np.linalg.norm(end[:3]) == pytest.approx(np.linalg.norm(d) + delta, rel=1e-13) and t > 1.0
        assert np.array_equal(end[3:], state[3:])  # velocities and spins kept
        held, _ = pair_exact.free_flight(state, 0.0, n0, True, delta)
        assert (held[:3] - d) @ n0 == pytest.approx(delta, rel=1e-12)
