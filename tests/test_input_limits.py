"""Values beyond a float's reach and counts beyond a machine's: refused at once in one line naming the parameter."""

import json
import re
import subprocess
import sys
import textwrap

import pytest

from spinbounce import api
from spinbounce.cli import main
from spinbounce.errors import SceneError, SweepError
from spinbounce.model.contact import ContactModel
from spinbounce.scenes.collision import Collision
from spinbounce.scenes.gas.run import run_gas
from spinbounce.scenes.gas.scene import Gas
from spinbounce.sweeps import read_results, spec_from_dict

STATES = {"n": 10, "v_n": [-1.5, -0.1], "v_t": [-2.0, 2.0], "r_omega": [-2.0, 2.0]}


@pytest.mark.parametrize("name, value", [("gamma_t", 1e200), ("kt", 1e308), ("gamma_t", 1e12)])
def test_a_mode_too_fast_for_any_run_is_refused_naming_its_parameter(name, value):
    """The fewest steps any accepted step takes (20 a half-period of the fastest mode), checked before a step is
    computed from rates beyond a float (1e200 once divided by zero)."""
    with pytest.raises(SceneError, match="^" + re.escape(f"{name} = {value!r}: needs ")):
        Collision(ContactModel(**{name: value}), v_n=-1.0, v_t=1.0, omega=0.0)


@pytest.mark.parametrize("given, named", [({"kt": 1e308}, "kt = "), ({"kt": 1e200}, "kt = "),
                                          ({"dt": 5e-324}, "dt = 5e-324")])
def test_a_gas_beyond_a_float_is_refused_naming_the_parameter(given, named):
    model = ContactModel(kn=1e4, kt=given.get("kt", 2e3))
    with pytest.raises(SceneError, match=named):
        Gas(model, 0.0221, spheres=1000, dt=given.get("dt"))


def test_a_gas_default_step_resolves_a_stiff_tangential_spring():
    """kt = 3 kn: the slip mode of the fastest collisions is faster than the contact over 50 steps, and the
    default step resolves it as the gas's pair runs ask (20 steps a half-period); the claims' magic ratio keeps
    the contact over 50 steps (its two modes alike)."""
    tc = 0.0221
    stiff = Gas(ContactModel(kn=1e4, kt=3e4), tc, spheres=1000)
    wall, fastest = stiff._fastest()
    assert stiff.dt < tc / 50
    assert wall.check_dt(stiff.dt, False, fastest) == stiff.dt
    assert Gas(ContactModel(kn=1e4, kt=1e4 * 2 / 7), tc, spheres=1000).dt == tc / 50


def test_a_gas_whose_references_take_hours_is_refused_before_its_contact_time():
    """A capped Hertz-Mindlin gas solves each collision of its theories on its own (41 to 48 ms each, measured;
    ONE_PAIR_SECONDS): the estimate counts them, and the refusal of 5,000 draws (75,000 such collisions at
    five temperatures, four hours as estimated) comes before the 2,000 collisions of the contact time, naming
    the draws."""
    model = api.model(contact="hertz/material 1e5 0.3 0.3 tangential mindlin NULL 1.0 0.3")
    with pytest.raises(SceneError, match=r"^draws = 5000: .*one pair at a time.*hours"):
        run_gas(model, spheres=1000, draws=5000, collisions=2.0)


def test_a_stiff_capped_law_is_charged_by_the_states_it_meets():
    """A capped Hertzian force on linear_history is 'capped stiff' in a sweep's slower impacts (0.3 to 4.3 s a pair
    measured), but a gas's hot collisions were measured at the capped figure (41 to 48 ms): charged the stiff 6 s,
    a gas's 2,000-collision contact time alone would be over the hour and no --draws could pass. The classic
    spring's cap is stiff in a sweep too (0.8 to 0.9 s a pair)."""
    from spinbounce.scenes.gas.run import one_pair_seconds
    from spinbounce.scenes.pair.contact import ONE_PAIR_SECONDS
    from spinbounce.scenes.pair.kind import equal_pair

    stiff = api.model(normal="hertz/material", youngs_modulus=1e5, poisson_ratio=0.3, mu=0.3)
    classic = api.model(tangential="linear_history_classic", mu=0.3)
    for model in (stiff, classic):
        assert equal_pair(model)[1].one_pair_seconds() == ONE_PAIR_SECONDS["capped stiff"]
        assert one_pair_seconds(model) == ONE_PAIR_SECONDS["capped"]


def test_an_unfinished_sweep_is_not_fitted_as_a_whole(tmp_path):
    out = tmp_path / "sweep"
    api.run_sweep({"chunk_size": 20, "model": {"mu": ["none", 0.3]}, "states": {**STATES, "n": 40}}, out)
    (out / "chunks" / "chunk-0001-000001.parquet").unlink()  # as a sweep stopped before its last chunk leaves it
    with pytest.raises(SweepError, match=r"an unfinished sweep: 1 of its 4 chunks \(20 of 80 collisions\)"):
        api.fit_groups(out)
    assert len(api.fit_groups(out / "chunks")) == 2  # its chunks/ folder, read as it stands


@pytest.mark.parametrize("model", [{"kt": [1.0, 1.0]}, {"mu": [0.0, -0.0]}])
def test_a_model_listed_twice_is_refused(model):
    with pytest.raises(SweepError, match="model again"):
        spec_from_dict({"model": model, "states": STATES})


def test_a_range_wider_than_a_float_is_refused():
    with pytest.raises(SweepError, match=r"states.v_t = \[-1e\+308, 1e\+308\]"):
        spec_from_dict({"states": {**STATES, "v_t": [-1e308, 1e308]}})


@pytest.mark.parametrize("workers", [0, 64, 1.5, True])
def test_the_api_takes_the_worker_counts_the_command_takes(tmp_path, workers):
    with pytest.raises(SweepError, match=f"workers = {workers!r}: must be a whole number"):
        api.sweep(n=10, out=tmp_path / "w", workers=workers)


def test_a_grid_beyond_a_machine_is_refused(capsys):
    with pytest.raises(SystemExit) as stopped:
        main(["hertz", "--points", "1e9", "--out", "unused"])
    assert stopped.value.code == 2
    assert "points = 1000000000: must be at most" in capsys.readouterr().err


@pytest.mark.parametrize("argv", [["collide", "--ma", "2"], ["collide", "--n", "5"]])
def test_an_option_is_taken_only_as_it_is_spelled(argv):
    """No abbreviation: --ma was --mass, and --n --normal."""
    with pytest.raises(SystemExit) as stopped:
        main(argv)
    assert stopped.value.code == 2


def test_json_holds_no_infinity_and_a_record_says_what_made_it(capsys):
    assert main(["theory", "--gamma-t", "1e308", "--json"]) == 0
    printed = capsys.readouterr().out
    record = json.loads(printed)  # Python's parser takes Infinity: the text must not hold it
    assert "Infinity" not in printed and record["Omega"] is None
    assert record["spinbounce_version"] and record["python"]


@pytest.mark.lammps
def test_a_script_without_a_main_guard_runs_once_beside_its_workers(tmp_path):
    """Once LAMMPS is loaded the workers are spawned, which imported the script again and ran its top level in
    each of them: its collision three times, then a sweep refused by the folder's lock."""
    script = tmp_path / "unguarded.py"
    script.write_text(textwrap.dedent("""
        import spinbounce
        print("top level")
        spinbounce.collide(v_n=-1.0, v_t=1.0, out="c")
        spinbounce.sweep(n=10, out="sw", workers=2)
    """))
    done = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.count("top level") == 1
    assert len(read_results(tmp_path / "sw")) == 10


@pytest.mark.parametrize("argv, said", [
    (["calibrate", "--no-run", "--e", "1", "--contact-time", "1e-300", "--beta", "0.3"],
     "contact_time = 1e-300: gives kn = inf"),
    (["calibrate", "--no-run", "--e", "0.9", "--contact-time", "1e300", "--beta", "0.3"],
     "contact_time = 1e+300: gives kn = 0"),
    (["frozen", "--z", "0.1", "--vt", "1", "--omega", "0", "--t-end", "1e308"], "t_end = 1e+308: needs inf steps"),
    (["calibrate", "--no-run", "--e", "0.5", "--tangential", "mindlin", "--youngs-modulus", "1e200", "--beta", "0.3"],
     "the deepest overlap at |v_n| = 1")])
def test_a_time_beyond_a_float_is_refused_naming_it(argv, said, capsys):
    """A contact time that puts kn = m (pi/t_c)^2 beyond a float, a run whose default step underflows to zero, and
    a Hertz-Mindlin scan whose contact no float resolves (once a division by zero, or scipy's error, each)."""
    with pytest.raises(SystemExit) as stopped:
        main(argv)
    assert stopped.value.code == 2 and said in capsys.readouterr().err


def test_the_word_none_means_none_wherever_a_parameter_may_be_none():
    """As a scene file and a command line write it (api.sweep took mu = ["none", 0.3], api.collide refused "none")."""
    assert ContactModel(mu="none").mu is None and ContactModel(mu=" None ").mu is None
    with pytest.raises(SceneError, match="kt = 'none': must be a number"):
        ContactModel(kt="none")


def test_a_gas_given_step_is_checked_before_its_contact_time():
    """A given dt beyond the stability limit, on a law whose 2,000 contact-time collisions are each solved on their
    own (minutes): refused at once, before them (it was checked only after)."""
    model = api.model(normal="hertz/material", youngs_modulus=1e5, poisson_ratio=0.3, tangential="mindlin")
    with pytest.raises(SceneError, match="^dt = 1.0: must be below the stability limit"):
        run_gas(model, spheres=1000, draws=1000, collisions=2.0, dt=1.0, force=True)


@pytest.mark.parametrize("gamma_t", [1e200, 1e12])
def test_a_pair_whose_mode_no_run_resolves_is_refused_naming_it(gamma_t):
    """As the wall: 1e200 was 'dt = 0.0: must be > 0', 1e12 an exact reference integrating for minutes."""
    with pytest.raises(SceneError, match="^" + re.escape(f"gamma_t = {gamma_t!r}: needs ")):
        api.collide(scene="pair", gamma_t=gamma_t)


def test_a_finished_sweep_an_earlier_version_took_is_still_fitted(tmp_path):
    """Its record holds a spec this version refuses (a model listed twice): its chunks are read as they are."""
    out = tmp_path / "sweep"
    api.run_sweep({"model": {"kt": [1.0, 2.0]}, "states": {**STATES, "n": 20}}, out)
    record = json.loads((out / "sweep.json").read_text())
    record["spec"]["model"]["kt"] = [1.0, 1.0]
    (out / "sweep.json").write_text(json.dumps(record))
    assert len(api.fit_groups(out)) == 2
