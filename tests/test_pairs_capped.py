"""Two spheres with a Coulomb cap: the capped reference against the wall's exact solver, and LAMMPS against it.

* The capped reference with its line of centres held fixed is the wall's capped problem of the
  equivalent sphere (reduced mass, alpha_eq: exact/pair.py), which the wall's exact stick-slip
  solver (exact.choose) solves independently, in the plane and in 3-D, with dashpots: 1e-9 of
  the speeds, the references' own accuracy (measured worst 1.9e-11 over 200 random cases).
* Turning, it conserves the pair's momentum and angular momentum (the contact force passes
  between the centres at the lever arms' split), to its integration's accuracy.
* LAMMPS converges to the turning reference at first order in dt (second where a contact
  slides throughout), down to 1e-9 of the speed: that the limit is the reference shows both
  the capped history rule (turned with the line of centres, rescaled onto the cap) and the
  reference's accuracy. At the default step every pair must be within the default accuracy.
"""

from __future__ import annotations

import numpy as np
import pytest

from spinbounce.cli import main
from spinbounce.model.parameters import SceneError
from spinbounce.scenes.pair import Pair, PairBatch, PairContact, Sphere
from spinbounce.pipeline import run_scene
from spinbounce.exact import choose, pair_exact

SOLVER_AGREEMENT = 1e-9


def _random_pair(rng, planar: bool = True) -> tuple[Pair, float, float]:
    """A pair moving in the x-z plane (spins along y), or in 3-D, with a random contact law (kt, mu)."""
    a, b = (Sphere(rng.uniform(0.3, 3.0), rng.uniform(0.2, 1.0), rng.choice([0.4, 0.25, 0.6])) for _ in range(2))
    angle = rng.uniform(0.0, 2.0 * np.pi)
    n, t = np.array([np.sin(angle), 0.0, np.cos(angle)]), np.array([np.cos(angle), 0.0, -np.sin(angle)])
    v_b = np.array([rng.uniform(-1, 1), 0.0, rng.uniform(-1, 1)])
    v_a = v_b - rng.uniform(0.2, 2.0) * n + rng.uniform(-3, 3) * t
    w_a, w_b = np.array([0.0, rng.uniform(-2, 2), 0.0]), np.array([0.0, rng.uniform(-2, 2), 0.0])
    if not planar:  # velocities across the x-z plane (n lies in it), spins in every direction
        v_a, v_b = (v + (0.0, rng.uniform(-2, 2), 0.0) for v in (v_a, v_b))
        w_a, w_b = (w + (rng.uniform(-2, 2), 0.0, rng.uniform(-2, 2)) for w in (w_a, w_b))
    return Pair(a=a, b=b, normal=n, v_a=v_a, v_b=v_b, w_a=w_a, w_b=w_b), rng.uniform(0.5, 9.0), 10 ** rng.uniform(-2, 1)


def _wall_columns(pair: Pair, v_a, v_b, w_a, w_b) -> np.ndarray:
    """The equivalent wall's (v_n, v_t, r omega, v_s, r omega_s) of the relative motion: the relative
    velocity along n, t and s = n x t (t in the x-z plane), and r omega = u' - v along t and s."""
    n = np.asarray(pair.normal)
    t = np.cross((0.0, 1.0, 0.0), n)
    s = np.cross(n, t)
    v = np.asarray(v_a) - np.asarray(v_b)
    slip = v - (v @ n) * n - np.cross(pair.a.r * np.asarray(w_a) + pair.b.r * np.asarray(w_b), n)
    return np.array([v @ n, v @ t, (slip - v) @ t, v @ s, (slip - v) @ s])


@pytest.mark.parametrize("planar", [True, False], ids=["planar", "3-D"])
def test_the_capped_reference_with_n_held_is_the_walls_exact_stick_slip_solution(planar):
    # with dashpots (gamma_n, gamma_t: the wall's exact damped stick-slip solver) half the time
    rng = np.random.default_rng(11 if planar else 14)
    for _ in range(100 if planar else 40):  # a 3-D case takes ~0.5 s (a slide's turn is stiff as the cap closes)
        pair, kt, mu = _random_pair(rng, planar)
        gamma_n, gamma_t = (rng.choice([0.0, rng.uniform(0.0, 2.0)]) for _ in range(2))
        held = PairContact(10.0, kt, gamma_n, gamma_t, mu=mu).solve(pair, planar=True)
        wall = pair.equivalent_wall(PairContact(10.0, kt, gamma_n, gamma_t)).replace(mu=mu)
        v_n, v_t, r_omega, v_s, r_omega_s = _wall_columns(pair, pair.v_a, pair.v_b, pair.w_a, pair.w_b)
        _, final = choose.outcome(wall, v_n, v_t, r_omega / wall.r, v_s, r_omega_s / wall.r)
        want = np.array([final[k] for k in ("v_n", "v_t", "r_omega")] + ([] if planar else [final["v_s"],
                                                                                          final["r_omega_s"]]))
        got = _wall_columns(pair, held.v_a, held.v_b, held.w_a, held.w_b)[: want.size]
        assert np.abs(got - want).max() < SOLVER_AGREEMENT * pair.speed()


@pytest.mark.parametrize("planar", [True, False], ids=["planar", "3-D"])
def test_a_batchs_planar_columns_are_the_held_pair_reference(planar):
    """The table's planar theory of a capped batch (its equivalent walls' exact stick-slip solutions, turned back
    into both spheres' states: exact/pair.from_wall) is the pair reference with its line held, to the references'
    own accuracy: unequal spheres, dashpots, 3-D (kn = 100: a batch refuses overlaps beyond the smaller radius)."""
    from spinbounce.scenes.pair.table import pair_table

    rng = np.random.default_rng(21 if planar else 22)
    for _ in range(6):
        pairs = [_random_pair(rng, planar)[0] for _ in range(5)]
        contact = PairContact(100.0, rng.uniform(5.0, 90.0), rng.choice([0.0, 2.0]), rng.choice([0.0, 4.0]),
                              mu=10 ** rng.uniform(-2, 1))
        table = pair_table(PairBatch(tuple(pairs), contact), None)
        for k, pair in enumerate(pairs):
            held = contact.solve(pair, planar=True)
            for side, r in (("a", pair.a.r), ("b", pair.b.r)):
                got = [table[[f"{side}_{q}{x}_planar" for x in "xyz"]].to_numpy()[k] for q in "vw"]
                want = (getattr(held, f"v_{side}"), getattr(held, f"w_{side}"))
                worst = max(np.abs(got[0] - want[0]).max(), r * np.abs(got[1] - want[1]).max())
                assert worst < SOLVER_AGREEMENT * pair.speed()


def test_a_cap_never_reached_with_n_held_is_the_uncapped_reference():
    # mu = 1e12: the contact sticks but for its last 1e-13 of overlap, where the vanishing cap
    # always wins (at mu = 1e6 that end slide moves the outcome by 2.5e-9, which the reference
    # resolves); with n fixed the history's rotation is moot.
    pair = Pair(a=Sphere(1.0, 0.5, 0.4), b=Sphere(2.0, 0.7, 0.25), normal=(0.6, 0.0, 0.8), v_a=(0.5, 0.0, -1.0),
                v_b=(0.0, 0.0, 0.2), w_a=(0.0, 1.0, 0.0), w_b=(0.0, -0.5, 0.0))
    capped = PairContact(10.0, 3.0, mu=1e12).solve(pair, planar=True)
    uncapped = pair_exact.solve(**pair.vectors(), **pair.properties(), kn=10.0, kt=3.0, planar=True)
    for q in ("v_a", "v_b", "w_a", "w_b"):
        assert np.abs(np.asarray(getattr(capped, q)) - getattr(uncapped, q)).max() < SOLVER_AGREEMENT


@pytest.mark.parametrize("planar", [True, False], ids=["planar", "3-D"])
def test_the_turning_capped_reference_conserves_momentum_and_angular_momentum(planar):
    # b feels minus a's force, and the torques -(r - delta/2) n x F_t on each add up to -|d| n x F_t,
    # the moment of a's force about b's centre: both are conserved to the integration's accuracy
    rng = np.random.default_rng(12)
    for _ in range(20 if planar else 8):
        pair, kt, mu = _random_pair(rng, planar)
        o = PairContact(10.0, kt, rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), mu=mu).solve(pair)
        a, b = pair.a, pair.b
        before = a.m * np.asarray(pair.v_a) + b.m * np.asarray(pair.v_b)
        after = a.m * o.v_a + b.m * o.v_b
        assert np.abs(after - before).max() < SOLVER_AGREEMENT * pair.speed() * (a.m + b.m)
        # about the centre of mass: m* d x (v_a - v_b) + I_a w_a + I_b w_b, d = a's centre less b's
        def angular_momentum(d, v_a, v_b, w_a, w_b):
            spins = a.alpha * a.m * a.r**2 * np.asarray(w_a) + b.alpha * b.m * b.r**2 * np.asarray(w_b)
            return a.m * b.m / (a.m + b.m) * np.cross(d, np.subtract(v_a, v_b)) + spins

        l_before = angular_momentum((a.r + b.r) * np.asarray(pair.normal), pair.v_a, pair.v_b, pair.w_a, pair.w_b)
        l_after = angular_momentum(o.d_end, o.v_a, o.v_b, o.w_a, o.w_b)
        assert np.abs(l_after - l_before).max() < SOLVER_AGREEMENT * pair.speed() * (a.m + b.m) * (a.r + b.r)


def _capped_cases(three_d: bool = False) -> list[Pair]:
    """12 pairs: unequal spheres (alpha 2/5 and rigid bodies), oblique, spinning, b moving; planar, or
    (``three_d``) with velocities across the plane and spins in it."""
    rng = np.random.default_rng(13)
    out = []
    for a, b in ((Sphere(1.0, 0.5, 0.4), Sphere(1.0, 0.5, 0.4)), (Sphere(1.0, 0.5, 0.25), Sphere(3.0, 0.8, 0.4)),
                 (Sphere(0.5, 0.3, 0.4), Sphere(2.0, 0.7, 0.6))):
        for ratio in (0.0, 0.5, 1.5, 4.0):
            angle = rng.uniform(0.0, 2.0 * np.pi)
            n, t = np.array([np.sin(angle), 0.0, np.cos(angle)]), np.array([np.cos(angle), 0.0, -np.sin(angle)])
            v_b = np.array([rng.uniform(-0.5, 0.5), 0.0, rng.uniform(-0.5, 0.5)])
            across = rng.uniform(-0.6, 0.6, 4) if three_d else np.zeros(4)
            out.append(Pair(a=a, b=b, normal=n, v_a=v_b - 0.6 * n + 0.6 * ratio * t + (0.0, across[0], 0.0),
                            v_b=v_b, w_a=(across[1] / a.r, rng.uniform(-1, 1) / a.r, across[2] / a.r),
                            w_b=(across[3] / b.r, rng.uniform(-1, 1) / b.r, 0.0)))
    return out


@pytest.mark.lammps
@pytest.mark.parametrize("contact, three_d", [(PairContact(mu=0.3), False),
                                             (PairContact(kt=2.0, gamma_n=0.8, mu=0.1), False),
                                             (PairContact(mu=0.3), True),
                                             (PairContact(kt=2.0, gamma_n=0.8, gamma_t=0.4, mu=0.1), True)],
                         ids=["undamped", "damped", "3-D", "3-D, both dashpots"])
def test_lammps_capped_pairs_are_within_the_default_accuracy(tmp_path, contact, three_d):
    result = run_scene(PairBatch(_capped_cases(three_d), contact), tmp_path, record=False)
    assert result.max_error < 1e-4
    assert result.table["eps"].max() > 0.5  # the line of centres turns: the planar model would not do
    assert result.table["planar_error"].max() > 10 * result.max_error


@pytest.mark.lammps
def test_lammps_converges_to_the_capped_reference(tmp_path):
    # Sliding throughout (gross slip), a turning line of centres: LAMMPS is second order here
    # (measured 3.2e-7, 8.0e-8, 2.0e-8 at 200, 400, 800 steps per contact); the error must
    # shrink by at least 3.5 per halving and reach 1e-7, far below what a wrong history rule
    # or an inaccurate reference would leave.
    pair = Pair(v_a=(2.0, 0.0, -1.0), w_a=(0.0, -3.0, 0.0))
    contact = PairContact(mu=0.3)
    time = PairBatch([pair], contact).exact[0].contact_time
    errors = [run_scene(PairBatch([pair], contact, time / (steps + 0.5), aligned=True), tmp_path / str(steps),
                        record=False).max_error for steps in (200, 400)]
    assert errors[0] / errors[1] > 3.5 and errors[1] < 1e-7


@pytest.mark.lammps
def test_a_capped_pair_sweep_runs_and_its_fit_claims_no_matrix(tmp_path, capsys):
    out = tmp_path / "sweep"
    assert main(["sweep", "--scene", "pair", "--mu", "0.3", "--n", "8", "--vn", "-1.5", "-0.5", "--vt", "-1", "1",
                 "--r-omega", "-1", "1", "--out", str(out)]) == 0
    assert "8 ok" in capsys.readouterr().out
    assert main(["fit", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "theory: pair_capped" in printed and "Coulomb cap: a capped pair has no matrix" in printed


def test_a_grazing_pair_separates_in_both_references():
    # Found by a random search (1,500 planar pairs): |v_t|/|v_n| = 14, the spheres touch for
    # 0.006 s against tau = 0.5 s, and the integrator's first step carried the capped pair
    # from touch past separation unseen; pair_exact.longest_step now bounds every step by the
    # free-flight overlap time.
    a = Sphere(0.7650724981471964, 0.12315175973341227, 0.4)
    b = Sphere(0.9041708007029703, 0.11267693379258904, 0.25)
    pair = Pair(a=a, b=b, normal=(0.9337084177010475, 0.0, -0.35803434292565584),
                v_a=(-2.7390242701789482, 0.0, -4.379458960909444), v_b=(-0.40258479121281043, 0.0, 0.6129321291679928),
                w_a=(0.0, 4.174294737346495, 0.0), w_b=(0.0, -3.0660568975684854, 0.0))
    tau = np.pi * np.sqrt(a.m * b.m / (a.m + b.m) / 10.0)
    for contact in (PairContact(10.0, 1.2365760546884639), PairContact(10.0, 1.2365760546884639, mu=1.1094679509042449)):
        assert 0.0 < contact.solve(pair).contact_time < 0.05 * tau


def test_the_api_gives_a_capped_pair_no_matrix_but_its_outcome():
    import spinbounce

    report = spinbounce.theory(scene="pair", mu=0.3)
    assert report["matrix"] is None and "a capped pair has no matrix" in report["why_no_matrix"]
    outcome = spinbounce.theory(v_n=-1.0, v_t=1.0, scene="pair", mu=0.3)
    exact = PairContact(mu=0.3).solve(Pair(v_a=(1.0, 0.0, -1.0)))
    assert outcome["theory"]["v_t"] == pytest.approx(exact.v_a[0], abs=1e-12)  # LAMMPS's x: the paper's v_t


def test_the_normal_forces_zero_is_passed_once():
    # Found by a review's random search: F_n falls through 0 at -883 per unit time, and the
    # event's root left F_n = +6e-16, above the rounding threshold, so the phase restarted on
    # the positive side and found the same zero again (200 restarts). After F_n's zero the
    # contact now takes the side F_n moves to.
    pair = Pair(a=Sphere(0.4967322894019039, 0.1534741768365512, 0.6), b=Sphere(4.875044127070722, 0.16361539765824082, 0.9),
                normal=(0.9580500255033809, 0.0, 0.28660102692239464), v_a=(-8.368075443085203, 0.0, 27.47122753775543),
                v_b=(-0.2279042708821113, 0.0, 0.4894397791841172), w_a=(0.0, -3.4843990815954435, 0.0),
                w_b=(0.0, 14.181967702278126, 0.0))
    contact = PairContact(0.6694303158308653, 0.04412180984692765, 0.35247138755000235, mu=195.85450923469128)
    outcome = contact.solve(pair)
    before = pair.a.m * np.asarray(pair.v_a) + pair.b.m * np.asarray(pair.v_b)
    assert np.abs(pair.a.m * outcome.v_a + pair.b.m * outcome.v_b - before).max() < 1e-9 * np.abs(before).max()


def test_short_phases_inside_an_integrator_step_are_found():
    # Found by a review: at this spin a stick of 0.042 s sits inside one integrator step (the
    # longest is tau/8 = 0.088 s); seen only as sign changes between steps it was stepped over
    # (w_a 2.689006 against 2.689037 with 64 times shorter steps, which a step-by-step copy of
    # LAMMPS converges to). The switching function is now also sampled inside each step.
    contact, pair = PairContact(10.0, 8.0, mu=0.2), Pair(v_a=(1.0, 0.0, -1.0), w_a=(0.0, 3.1851, 0.0))
    outcome = contact.solve(pair)
    assert outcome.w_a[1] == pytest.approx(2.689037, abs=2e-6)


def test_a_grazing_pair_with_n_held_is_solved_at_its_contact_times_pace():
    # With n held the pair separates after about tau whatever v_t: the free-flight bound on the
    # step (for a turning n) took 35 s here; the check is on the outcome, the speed on the step.
    outcome = PairContact(mu=0.3).solve(Pair(v_a=(20.0, 0.0, -0.05)), planar=True)
    assert outcome.contact_time == pytest.approx(np.pi * np.sqrt(0.5 / 10.0), rel=1e-9)


def test_a_pair_at_the_default_step_has_the_walls_limits():
    with pytest.raises(SceneError, match="restitution"):  # 0.999 of critical damping: a creeping exit
        PairBatch([Pair(v_a=(0.0, 0.0, -1.0))], PairContact(10.0, 1.0, 4.46766, mu=0.3))
    # a large cap acts only near the contact's ends: accepted at the default step, which its probe chooses
    assert PairBatch([Pair(v_a=(0.0, 0.0, -1.0))], PairContact(mu=300.0)).default_step
    both_one = PairBatch([Pair(a=Sphere(1.0, 0.5, 1.0), b=Sphere(2.0, 0.4, 1.0), v_a=(0.3, 0.0, -1.0))])
    assert both_one.pairs[0].equivalent_wall(both_one.contact).alpha == 1.0  # was 1 + 2e-16, refused


def test_a_pair_sweeps_chunks_are_sized_by_the_pair_references_cost():
    # A pair's references take ~13 ms (exact, uncapped, one pair at a time), ~80 ms (capped, one at a
    # time) and ~0.1 ms (a Hookean batch solved together, capped or not) a collision: a chunk planned
    # as a wall's (25,000 collisions) could run for half an hour. Each pair chunk must be estimated
    # within CHUNK_SECONDS, the theory counted.
    from spinbounce.scenes.pair.contact import ONE_PAIR_SECONDS
    from spinbounce.sweeps import cost
    from spinbounce.sweeps.spec import CHUNK_SECONDS, DEFAULT_CHUNK, spec_from_dict

    states = {"n": 1_000_000, "v_n": [-1.5, -0.5], "v_t": [-1, 1], "r_omega": [-1, 1]}
    stiff = ONE_PAIR_SECONDS["capped stiff"]
    for model, theory in (({"scene": "pair", "mu": 0.3, "normal": "hertz", "kn": 1e4}, stiff),
                          ({"scene": "pair", "mu": 0.3}, cost.PAIR_BATCHED_SECONDS),
                          ({"scene": "pair", "normal": "hertz", "kn": 1e4}, ONE_PAIR_SECONDS["uncapped"]),
                          ({"scene": "pair"}, cost.PAIR_BATCHED_SECONDS)):
        spec = spec_from_dict({"model": model, "states": states})
        size = spec.chunk_sizes[0]
        estimate = cost.chunk_cost(spec, 0, size)
        assert estimate.seconds <= CHUNK_SECONDS and size * theory <= estimate.seconds
        # a wall sweep of these states takes DEFAULT_CHUNK; a batched reference does not shrink it
        assert size < DEFAULT_CHUNK or theory == cost.PAIR_BATCHED_SECONDS


@pytest.mark.lammps
def test_a_zero_cap_is_no_tangential_force_and_lammps_agrees(tmp_path):
    """mu = 0 caps |F_t| at nothing: the reference is the uncapped one without a tangential spring
    (the capped solver divides by mu and could not answer), and LAMMPS follows it to the default
    accuracy (1e-4 of the speed: the pair's first-order step error, as for every pair)."""
    import spinbounce

    report = spinbounce.collide(v_n=-1.0, v_t=1.0, omega=2.0, scene="pair", mu=0.0, out=tmp_path)
    assert report.status == "ok" and report.error < 1e-4
    pair = Pair(v_a=(1.0, 0.0, -1.0), w_a=(0.0, -2.0, 0.0))
    free = PairContact(kt=0.0).solve(pair)
    assert report.table.loc["v_t", "theory"] == pytest.approx(free.v_a[0], abs=1e-12)
    assert report.table.loc["r_omega", "theory"] == pytest.approx(2.0 * 0.5, abs=1e-12)  # no torque: spin kept


#: Hertz-Mindlin, a tangential dashpot without a normal one, in 3-D: a slide along the slip from first touch whose s
#: the history's growth pulls back onto the slip at ~4e19 per second (exact.pair_capped_phases), beyond DOP853.
_STIFF_MODEL = dict(wall="granular", normal="hertz", tangential="mindlin", mindlin_kt=12.0, mu=0.3, gamma_t=1.0)
_STIFF_STATE = (-0.8, 0.3, 0.2, 0.1, -0.2, 0.05)


def test_a_phase_neither_integrator_can_end_is_refused_not_followed_forever(monkeypatch):
    """With both integrators' budgets lowered (DOP853 and Radau: 2,000 evaluations each, not 200,000 and 1,000,000)
    the stiff pair is refused with an error that says why, instead of running for ever."""
    from spinbounce.errors import ResultError
    from spinbounce.exact import pair_capped_phases
    from spinbounce.model.contact import ContactModel
    from spinbounce.scenes.pair.kind import pair_contact, pairs_from_states

    monkeypatch.setattr(pair_capped_phases, "EXPLICIT_EVALUATIONS", 2_000)
    monkeypatch.setattr(pair_capped_phases, "MAX_EVALUATIONS", 2_000)
    model = ContactModel(**_STIFF_MODEL)
    b = Sphere(1.0, 0.5, 0.4)
    pair = pairs_from_states(model, b, np.array([_STIFF_STATE]))[0]
    with pytest.raises(ResultError, match="asked for 2,000 times in one phase, its steps sliding too short"):
        pair_contact(model, b).solve(pair)


@pytest.mark.slow  # the stiff reference takes ~7 s, twice; LAMMPS 40,000 steps
@pytest.mark.lammps
def test_a_stiff_3d_slide_is_answered_and_lammps_converges_to_it(tmp_path):
    """The stiff pair, once refused: DOP853 gives way to Radau for its stiff phases, and a slide whose cap falls
    below a switch's margin coasts to the end (there the growth turns s ever faster). LAMMPS meets the default
    accuracy, and at a sixteenth of the step its error is a sixteenth (first order, 4.00 measured over four
    quarterings down to 2.1e-7): what it converges to is the reference, to well below 1e-6 of the speed."""
    import spinbounce

    state = dict(zip(("v_n", "v_t", "omega", "v_s", "omega_s", "omega_n"), _STIFF_STATE, strict=True))
    model = {k: v for k, v in _STIFF_MODEL.items() if k != "wall"}
    report = spinbounce.collide(scene="pair", **state, **model, out=tmp_path / "default")
    assert report.status == "ok" and report.error <= 1e-4
    fine = spinbounce.collide(scene="pair", **state, **model, dt=report.dt / 16, out=tmp_path / "fine")
    assert fine.error == pytest.approx(report.error / 16, rel=0.05)  # first order: no floor from the reference
