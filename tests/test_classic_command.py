"""spinbounce classic: this build's classic wall against the paper's model, for a user's numbers."""

import json
import subprocess
import sys

import numpy as np
import pytest

from spinbounce.figures.classic import largest_lammps_error
from spinbounce.scenes.collision.deck import render_collision
from spinbounce.model.contact import ContactModel
from spinbounce.scenes.collision import Collision
from spinbounce.studies import classic_effect
from spinbounce.exact import linear

#: The default accuracy every LAMMPS result is held to (model.timestep.ACCURACY).
ACCURACY = 1e-4


def spinbounce(*argv):
    return subprocess.run([sys.executable, "-m", "spinbounce.cli", *argv], capture_output=True, text=True, timeout=120)


def test_table_puts_the_classic_omega_beside_eq18():
    done = spinbounce("classic", "--kt", "2.857142857142857", "--speeds", "0.2", "1.0", "--json")
    assert done.returncode == 0, done.stderr
    rows = json.loads(done.stdout)["rows"]
    eq18 = linear.Omega(10.0, 2.857142857142857, 0.4)
    # the paper's side is Eq. 18 exactly (1e-12: the exact solver's rounding), the same at every speed
    assert [r["omega_meant"] for r in rows] == pytest.approx([eq18, eq18], abs=1e-12)
    # the classic side depends on v_n (its spring grows with the overlap) and is softer than Eq. 18's
    slow, fast = (r["omega_classic"] for r in rows)
    assert eq18 < fast < slow < 0.0 and fast - slow < -0.1


def test_you_meant_line_is_the_granular_deck_line():
    model = ContactModel(kt=2.0, gamma_n=0.5, gamma_t=0.2, mu=0.3)
    lines = classic_effect.fix_lines(model)
    deck = render_collision(Collision(model.replace(wall="granular"), v_n=-1.0, v_t=1.0, omega=0.0)).text
    granular = lines["granular"].split(" wall/gran ")[1]
    assert f"wall/gran {granular}" in deck and "hooke/history" in lines["classic"]
    classic_deck = render_collision(Collision(model.replace(wall="classic"), v_n=-1.0, v_t=1.0, omega=0.0)).text
    assert f"wall/gran {lines['classic'].split(' wall/gran ')[1]}" in classic_deck


@pytest.mark.parametrize("argv, named", [
    (["--speeds", "2.0"], "--speeds"),           # above the tunnelling speed r sqrt(kn/m) = 1.58
    (["--speeds", "0"], "--speeds"),
    (["--normal", "hertz"], "normal"),           # hooke/history is Hookean
    (["--limit-damping"], "limit_damping"),
])
def test_refusals_are_one_line_naming_the_parameter(argv, named):
    done = spinbounce("classic", *argv)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1 and named in done.stderr


@pytest.mark.lammps
def test_lammps_classic_wall_gains_the_energy_the_table_says(tmp_path):
    """With a large radius and a cap, the classic wall can give the sphere energy: the table's
    E_out/E_in - 1 is confirmed by LAMMPS's own classic wall at the default step. The tolerance is
    the energy's share of the state's accuracy: |dE/E| <= 2 |d state| / |state| ~ 2e-4."""
    model = ContactModel(r=5.0, kt=5.0, mu=0.5, wall="classic")
    speed, v_t, omega = 4.743, 1.0, 0.5
    row = classic_effect.compare(model, [speed], v_t, omega)[0]
    assert row["energy_gain_classic"] > 1.0 and row["energy_gain_meant"] < 0.0
    from spinbounce.pipeline import run_scene

    table = run_scene(Collision(model, v_n=-speed, v_t=v_t, omega=omega), tmp_path, record=False).table
    initial = np.array([-speed, v_t, model.r * omega])
    final = table[["v_n_lammps", "v_t_lammps", "r_omega_lammps"]].to_numpy()[0]
    gained = linear.energy(final, model.m, model.alpha) / linear.energy(initial, model.m, model.alpha) - 1.0
    assert gained == pytest.approx(row["energy_gain_classic"], abs=2 * ACCURACY * (1 + row["energy_gain_classic"]))


@pytest.mark.lammps
def test_figure_record_has_three_ratios_and_lammps_within_the_accuracy(reproduction):
    made, _ = reproduction
    record = made.records["classic"]
    assert len(record["curves"]) >= 3
    assert largest_lammps_error(record) < ACCURACY
    for curve in record["curves"]:  # Omega_eff moves with v_n; the paper's does not
        assert np.ptp(curve["omega_classic"]) > 0.05
