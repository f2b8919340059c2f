"""A pair sweep's default: two aligned runs combined (sweeps.pair_ladder), within 1e-4 of the exact reference."""

import numpy as np
import pytest

from spinbounce.exact import pair_exact
from spinbounce.model.contact import ContactModel
from spinbounce.scenes.pair.kind import pair_contact, pairs_from_states
from spinbounce.scenes.pair.scene import PairBatch, Sphere
from spinbounce.sweeps.pair_ladder import LONGEST, applies, ladder_steps, run_ladder
from spinbounce.sweeps.pairs import pair_chunk

pytestmark = pytest.mark.lammps

#: The default accuracy: every row's error (|LAMMPS - exact| over the pair's speed) must reach it.
ACCURACY = 1e-4


def _states(n: int, seed: int = 5) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(-1.5, -0.1, n), rng.uniform(-2.0, 2.0, n), rng.uniform(-4.0, 4.0, n)])


def test_a_default_pair_chunk_combines_two_short_runs_within_the_accuracy(tmp_path):
    model = ContactModel()
    columns, dt, steps, _ = pair_chunk(model, Sphere(), _states(400), None, tmp_path)
    assert columns["step_method"][0].startswith("extrapolated")
    assert np.max(columns["error"]) <= ACCURACY and set(columns["status"]) == {"ok"}
    # both runs together take fewer steps than one run of the plain rule (~1,400 at these radii)
    assert np.max(steps) < 2 * LONGEST


def test_the_combination_is_nearer_the_truth_than_either_run(tmp_path):
    """The combination removes the first-order error: each pair nearer the exact reference (solved here
    one pair at a time by scipy, not by the batch that checks the rows) than its finer run."""
    model, b = ContactModel(), Sphere()
    batch = PairBatch(tuple(pairs_from_states(model, b, _states(60, seed=9))), pair_contact(model, b))
    ladder = run_ladder(batch, 40, tmp_path)
    law = batch.contact.law()
    for k in range(0, batch.n, 6):
        pair = batch.pairs[k]
        exact = pair_exact.solve(**pair.vectors(), **pair.properties(), **law)
        speed = ladder.columns["speed"][k]
        combined = max(abs(ladder.columns[f"a_v{x}"][k] - exact.v_a[i]) for i, x in enumerate("xyz")) / speed
        fine = max(abs(ladder.fine.columns[f"a_v{x}"][k] - exact.v_a[i]) for i, x in enumerate("xyz")) / speed
        assert combined <= ACCURACY and combined < fine


@pytest.mark.parametrize("law", [{"gamma_n": 0.5, "gamma_t": 0.5}, {"mu": 0.3, "gamma_t": 0.5}, {"alpha": 0.25}])
def test_laws_it_was_not_measured_on_keep_the_plain_probe(law):
    model = ContactModel(**law)
    b = Sphere(alpha=law.get("alpha", Sphere().alpha))
    assert not applies(PairBatch(tuple(pairs_from_states(model, b, _states(4))), pair_contact(model, b)))


@pytest.mark.parametrize("mu", [0.3, 5.0])
def test_a_capped_chunk_combines_two_runs_within_the_accuracy_in_fewer_steps_than_one_plain_run(tmp_path, mu,
                                                                                               monkeypatch):
    """Every row within the accuracy of the capped exact reference, at fewer LAMMPS steps (both runs) than the
    plain probe's one run of the same chunk (measured 2,882 and 4,148 steps at mu = 0.3 and 5 on 2,000 pairs)."""
    model, b, states = ContactModel(mu=mu), Sphere(), _states(300, seed=7)
    columns, _, steps, _ = pair_chunk(model, b, states, None, tmp_path / "ladder")
    assert columns["step_method"][0].startswith("extrapolated")
    assert np.max(columns["error"]) <= ACCURACY and set(columns["status"]) == {"ok"}
    monkeypatch.setattr("spinbounce.sweeps.pairs.applies", lambda batch: False)
    plain = pair_chunk(model, b, states, None, tmp_path / "plain")
    assert plain[0]["step_method"][0].startswith("probe") and np.max(steps) < np.min(plain[2])


def test_a_caps_switches_leave_the_combination_second_order(tmp_path):
    """Doubling N divides the combination's largest error by about 4 (measured 4.0 to 4.2 at mu = 1 on 2,000
    pairs), where a first-order residue would halve it: above 3 holds the order and fails a first-order one."""
    model, b = ContactModel(mu=1.0), Sphere()
    batch = PairBatch(tuple(pairs_from_states(model, b, _states(200, seed=4))), pair_contact(model, b))
    coarse, fine = (np.max(run_ladder(batch, n, tmp_path / f"n{n}").columns["error"]) for n in (40, 80))
    assert coarse / fine > 3.0


#: A pair whose combined runs miss the accuracy at the group's steps (kt/kn = 0.5: about 1 row in 80 of the paper's
#: ranges): 3.3e-2 at 160 steps per contact; LAMMPS's plain error falls as 53 dt (3.4e-3 at dt = 6.25e-5).
HARD_ROW = (-0.12105644579643116, -0.8892477437237734, -3.502496066852922)


def test_a_row_the_combination_leaves_beyond_the_accuracy_runs_again_finer(tmp_path):
    """The hard row runs again alone at doubling steps until it reaches the accuracy; its steps count every run."""
    model, b, easy = ContactModel(kt=5.0), Sphere(), _states(40, seed=8)
    states = np.vstack([easy, HARD_ROW])
    columns, dt, steps, _ = pair_chunk(model, b, states, None, tmp_path, probe_states=easy)
    assert np.max(columns["error"]) <= ACCURACY and set(columns["status"]) == {"ok"}
    assert steps[-1] > np.max(steps[:-1]) and np.isscalar(dt)  # the group's one dt: a fit groups rows by it
    assert columns["step_method"][-1] != columns["step_method"][0]


#: A damped pair (gamma_t = 0.5, kt/kn = 0.5) the plain probed step leaves beyond the accuracy: 2.4e-4 at the
#: fine rule's 19,530 steps in a 1,000-pair sweep (seed 9) where every other row reached it, 7.8e-5 at a quarter;
#: here, probed on 40 other rows, 3.2e-4 at 13,601 steps.
HARD_DAMPED_ROW = (-0.49115533532146105, -1.9234749857254512, -2.430232865364802)


def test_a_plain_runs_row_beyond_the_accuracy_runs_again_at_a_finer_step(tmp_path):
    """Damped pairs keep one probed run (no smooth expansion to combine); a row it leaves beyond the accuracy runs
    again alone, aligned as the chunk ran, at a quarter of the step (first order), until it reaches it."""
    model, b, easy = ContactModel(kt=5.0, gamma_t=0.5), Sphere(), _states(40, seed=8)
    columns, dt, steps, _ = pair_chunk(model, b, np.vstack([easy, HARD_DAMPED_ROW]), None, tmp_path,
                                       probe_states=easy)
    assert np.max(columns["error"]) <= ACCURACY and set(columns["status"]) == {"ok"}
    assert columns["step_method"][-1].startswith("run again alone") and steps[-1] > np.max(steps[:-1])


def test_runs_again_stop_at_their_budget_and_leave_the_rows_flagged(tmp_path, monkeypatch):
    """REFINE_BUDGET bounds what the runs again may cost: with none, the hard row keeps its chunk's answer, flagged."""
    monkeypatch.setattr("spinbounce.sweeps.pairs.REFINE_BUDGET", 0.0)
    model, b, easy = ContactModel(kt=5.0, gamma_t=0.5), Sphere(), _states(40, seed=8)
    columns, _, steps, _ = pair_chunk(model, b, np.vstack([easy, HARD_DAMPED_ROW]), None, tmp_path, probe_states=easy)
    assert columns["status"][-1] == "inaccurate" and len(set(steps)) == 1


def test_a_sweep_with_a_row_run_again_fits_as_one_group(tmp_path):
    """The row run again keeps its group's dt (a fit groups rows by it) and says its own steps: one fit group."""
    from spinbounce.fitting import fit_groups
    from spinbounce.sweeps import read_results, run_sweep, spec_from_dict

    spec = spec_from_dict({"seed": 1, "model": {"scene": "pair", "kt": 5.0}, "chunk_size": 400,
                           "states": {"n": 400, "v_n": [-1.5, -0.2], "v_t": [-1.0, 1.0], "r_omega": [-4.0, 4.0]}})
    rows = read_results(run_sweep(spec, tmp_path / "sweep", workers=1, log=lambda *_: None))
    assert rows["step_method"].nunique() > 1 and rows["nsteps"].nunique() > 1  # a row ran again, finer
    assert set(rows["status"]) == {"ok"} and rows["dt"].nunique() == 1
    assert len(fit_groups(rows)) == 1


def test_a_row_still_beyond_the_accuracy_at_the_finest_steps_says_so(tmp_path, monkeypatch):
    monkeypatch.setattr("spinbounce.sweeps.pairs.FINEST", 320)
    model, b, easy = ContactModel(kt=5.0), Sphere(), _states(40, seed=8)
    columns, *_ = pair_chunk(model, b, np.vstack([easy, HARD_ROW]), None, tmp_path, probe_states=easy)
    assert columns["status"][-1] == "inaccurate" and columns["error"][-1] > ACCURACY


def test_the_probe_doubles_until_its_sample_is_within_half_the_accuracy(tmp_path):
    model, b = ContactModel(), Sphere()
    batch = PairBatch(tuple(pairs_from_states(model, b, _states(200, seed=3))), pair_contact(model, b))
    steps, tau = ladder_steps(batch, tmp_path)
    assert steps <= LONGEST and tau == np.median(batch.contact_times)
    assert np.max(run_ladder(batch, steps, tmp_path / "check", contact_time=tau).columns["error"]) <= ACCURACY


def test_every_chunk_of_a_group_runs_at_the_same_steps(tmp_path):
    """The step comes from the group's states (the probe), not each chunk's own contact times: one fit
    group per model group, as a plain probed step gives."""
    model, b = ContactModel(), Sphere()
    group = _states(600, seed=11)
    dts = {pair_chunk(model, b, group[k::3], None, tmp_path / f"chunk{k}", probe_states=group)[1] for k in range(3)}
    assert len(dts) == 1


def test_a_stiff_spring_takes_a_finer_ladder_or_the_probe_not_a_refusal(tmp_path):
    """kt = 15 (kt/kn 1.5): 40 steps per contact under-resolve its fastest mode, which the step's check
    refuses; the ladder then starts finer, and the rows still reach the accuracy."""
    columns, *_ = pair_chunk(ContactModel(kt=15.0), Sphere(), _states(200, seed=2), None, tmp_path)
    assert np.max(columns["error"]) <= ACCURACY and set(columns["status"]) == {"ok"}


def test_a_contact_shorter_than_a_step_keeps_the_finer_run_and_is_never_ok_unmeasured(tmp_path):
    """Pairs grazing fast past each other end their contact within a step or two, where the two runs give
    it the same count of steps: no expansion to combine. Their rows keep the finer run's state, every
    state finite, and a row is 'ok' only where its measured error reaches the accuracy."""
    rng = np.random.default_rng(1)
    states = np.column_stack([rng.uniform(-1.5, -0.001, 400), rng.uniform(-5.0, 5.0, 400), rng.uniform(-4, 4, 400)])
    model, b = ContactModel(), Sphere()
    batch = PairBatch(tuple(pairs_from_states(model, b, states)), pair_contact(model, b))
    ladder = run_ladder(batch, 40, tmp_path)
    assert np.all(np.isfinite(ladder.columns["a_vx"])) and np.all(np.isfinite(ladder.columns["error"]))
    ok = ladder.columns["status"] == "ok"
    assert np.all(ladder.columns["error"][ok] <= ACCURACY)


def test_a_row_whose_error_is_not_a_number_is_never_ok():
    from spinbounce.checks import RowStates, add_row_checks

    ones = np.ones((2, 3))
    final = np.array([[1.0, 1.0, 1.0], [np.nan, 1.0, 1.0]])
    columns: dict = {}
    add_row_checks(columns, RowStates(ones, final, ones, ones, np.ones(2), np.ones(2), np.ones(2)))
    assert list(columns["status"]) == ["ok", "inaccurate"]
