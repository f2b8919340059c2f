"""Regression against the stored reference outputs in tests/reference/.

Fresh runs of every reference case must reproduce the stored tables column by column
within the tolerances of :mod:`spinbounce.studies.references` (their reasons and the
measurements behind them are in that module and in MANIFEST.json), and every deck must
render exactly as its golden copy, version number aside. The tests below also show that
each comparison can fail: a stored value moved by just over its tolerance is reported,
by case and column, and one moved by just under it is not.

Nothing here writes into tests/reference/: runs go to pytest's temporary folders, and a
module fixture fails the tests if the folder's content changed. The references are
remade only by ``spinbounce references --regenerate``.
"""

import argparse
import hashlib
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from spinbounce import __version__
from spinbounce.model.contact import ContactModel
from spinbounce.studies import references as refs
from spinbounce.cli import references as references_command
from spinbounce.lammps.decks import ATOM_ROUTES

REFERENCE_DIR = Path(__file__).parent / "reference"
CASE_NAMES = [case.name for case in refs.CASES]


def _digest(directory: Path) -> str:
    h = hashlib.sha256()
    for path in sorted(directory.rglob("*")):
        if path.is_file():
            h.update(path.relative_to(directory).as_posix().encode())
            h.update(path.read_bytes())
    return h.hexdigest()


@pytest.fixture(scope="module", autouse=True)
def references_stay_untouched():
    """Fail if anything in this module wrote into the stored references."""
    before = _digest(REFERENCE_DIR)
    yield
    assert _digest(REFERENCE_DIR) == before, "a test changed tests/reference/: only --regenerate may"


@pytest.fixture(scope="module")
def stored_manifest():
    return refs.read_manifest(REFERENCE_DIR)


def _cli(*args) -> int:
    """The references command as the spinbounce CLI runs it."""
    parser = argparse.ArgumentParser(prog="spinbounce")
    references_command.register(parser.add_subparsers(dest="command", required=True))
    ns = parser.parse_args(["references", *args])
    return ns.handler(ns)


# -- the stored files match the code's list of cases -------------------------------------


def test_every_case_is_stored_and_every_stored_file_is_a_case(stored_manifest):
    assert len(CASE_NAMES) == len(set(CASE_NAMES))
    assert set(stored_manifest["cases"]) == set(CASE_NAMES)
    stored = {p.relative_to(REFERENCE_DIR).as_posix() for p in REFERENCE_DIR.rglob("*") if p.is_file()}
    assert stored == refs.expected_files()
    assert set(stored_manifest["decks"]) == {n.split("/", 1)[1] for n in refs.expected_files() if "/" in n}


def test_the_cases_cover_the_required_parameters():
    models = {case.name: case.contact_model() for case in refs.CASES}
    kinds = {case.name: case.kind for case in refs.CASES}
    collisions = [m for name, m in models.items() if kinds[name] == "collision"]
    assert any(m == ContactModel() for m in collisions)
    assert any(m.alpha == 0.4 and math.isclose(m.kt / m.kn, 2 / 7) for m in collisions)
    assert any(m.alpha == 0.1 for m in collisions)
    assert any(math.isclose(m.alpha, 2 / 3) and math.isclose(m.kt / m.kn, 0.4) for m in collisions)
    assert any(m.gamma_t > 0 and m.gamma_n == 0 and m.zeta < math.sqrt(m.Q) for m in collisions)
    assert any(m.gamma_n > 0 and m.restitution < 1 for m in collisions)
    assert any(m.zeta > math.sqrt(m.Q) for m in collisions)  # overdamped slip
    assert any(math.isclose(m.kt / m.kn, 1e-3) for m in collisions)
    assert any(m.kt / m.kn == 5 for m in collisions)
    assert any(m.mu == 0.1 for m in collisions)
    states = np.array([s for case in refs.CASES if case.kind == "collision" for s in case.states])
    r = ContactModel().r
    assert np.any(np.abs(states[:, 0]) == 1e-3)  # grazing
    assert np.any(np.abs(states[:, 0]) >= 1.5)  # near tunnelling
    assert np.any(np.abs(r * states[:, 2]) >= 20 * np.abs(states[:, 0]))  # large spin
    assert sorted(name for name, kind in kinds.items() if kind == "frozen") == ["frozen_damped", "frozen_defaults"]
    for case in refs.CASES:
        assert case.rows() <= (8 if case.kind == "collision" else 201), case.name


def test_manifest_records_the_code_s_cases_and_tolerances(stored_manifest):
    assert refs.compare_manifest(stored_manifest) == []
    assert stored_manifest["lammps_version"] and stored_manifest["spinbounce_version"]
    for name, entry in stored_manifest["cases"].items():
        assert entry["dt"] > 0 and entry["table"] == f"{name}.csv"


def test_a_changed_case_or_tolerance_is_noticed_in_the_manifest(stored_manifest):
    changed = json.loads(json.dumps(stored_manifest))
    changed["cases"]["defaults"]["dt"] *= 1.0 + 1e-12
    del changed["cases"]["grazing"]
    changed["cases"]["retired"] = changed["cases"]["mu_0.1"]
    changed["tolerances"]["collision"]["v_t_lammps"]["atol"] = 1e-6
    found = {(v.case, v.column) for v in refs.compare_manifest(changed)}
    assert found == {("defaults", "*"), ("grazing", "*"), ("retired", "*"), ("*", "tolerances")}


@pytest.mark.parametrize("name", CASE_NAMES)
def test_stored_table_matches_its_case_without_lammps(name):
    """Shape, inputs and theory of a stored table follow from the case alone."""
    case = refs.case_by_name(name)
    stored = refs.read_table(REFERENCE_DIR / f"{name}.csv")
    tolerances = refs.tolerances_for(case)
    assert list(stored.columns) == list(tolerances)
    assert len(stored) == case.rows()
    scene = case.scene()
    if case.kind == "collision":
        expected = {"id": np.arange(1, scene.n + 1), "v_n_initial": scene.v_n, "v_t_initial": scene.v_t, "omega_initial": scene.omega}
        theory = scene.predicted()
        expected.update(v_n_theory=theory[:, 0], v_t_theory=theory[:, 1], omega_theory=theory[:, 2] / scene.model.r)
    else:
        t = np.arange(len(stored)) * scene.every * scene.dt
        vt, r_omega = scene.predicted(t)
        expected = {"t": t, "v_t_theory": vt, "r_omega_theory": r_omega}
    for column, values in expected.items():
        deviation = np.max(np.abs(stored[column].to_numpy() - np.asarray(values, dtype=float)))
        assert deviation <= tolerances[column].atol, (column, deviation)


# -- golden decks ------------------------------------------------------------------------


@pytest.mark.parametrize("golden", refs.GOLDEN_DECKS, ids=[g.key for g in refs.GOLDEN_DECKS])
def test_deck_renders_as_its_golden_copy(golden):
    assert refs.compare_decks(REFERENCE_DIR / refs.DECKS_DIR, [golden]) == []


def test_golden_decks_cover_every_case_and_the_other_atom_routes():
    keys = {g.key for g in refs.GOLDEN_DECKS}
    assert set(CASE_NAMES) <= keys
    for route in ATOM_ROUTES:
        if route != "inline":
            assert {f"defaults.{route}", f"alpha_0.1.{route}"} <= keys  # one nve/sphere, one rigid


def test_deck_comparison_ignores_the_version_and_nothing_else(tmp_path):
    decks = tmp_path / "decks"
    shutil.copytree(REFERENCE_DIR / refs.DECKS_DIR, decks)
    golden = refs.GoldenDeck("alpha_0.1", "data_file")
    deck, data = decks / golden.deck_file, decks / golden.extra_file("spheres.data")
    for path in (deck, data):
        first, rest = path.read_text().split("\n", 1)
        assert "spinbounce " in first
        path.write_text(first.replace(__version__, "97.3.1.dev4") + "\n" + rest)
    assert refs.compare_decks(decks, [golden]) == []  # a release does not break the golden decks

    text = deck.read_text()
    assert text.count("timestep") == 1
    deck.write_text(text.replace("timestep        ", "timestep        1"))  # one changed command
    found = refs.compare_decks(decks, [golden])
    assert [(v.case, v.column) for v in found] == [("alpha_0.1", golden.deck_file)]
    assert "timestep" in found[0].message

    data.write_text(data.read_text().replace("2 atom types", "3 atom types"))
    found = refs.compare_decks(decks, [golden])
    assert {v.column for v in found} == {golden.deck_file, golden.extra_file("spheres.data")}

    data.unlink()
    assert "missing" in refs.compare_decks(decks, [golden])[-1].message


def test_normalise_deck_touches_only_the_first_line():
    text = "# spinbounce 0.1.0: collision deck\nprint spinbounce 0.1.0: kept\n"
    assert refs.normalise_deck(text) == "# spinbounce <version>: collision deck\nprint spinbounce 0.1.0: kept\n"
    assert refs.normalise_deck("spinbounce 2.0: 3 spheres\n") == "spinbounce <version>: 3 spheres\n"


# -- the comparison can fail -------------------------------------------------------------


def test_each_value_moved_beyond_its_tolerance_is_caught_and_within_it_passes(tmp_path):
    """For every case and column: move one stored value (through the CSV file, as a hand
    edit would) by 1.01 x its tolerance, and the comparison names exactly that case,
    column and row; by 0.99 x, it passes. Zero-tolerance columns move by one ulp (ids by one)."""
    checked = 0
    for k, case in enumerate(refs.CASES):
        source = REFERENCE_DIR / f"{case.name}.csv"
        fresh = refs.read_table(source)  # stands in for a fresh run that matches exactly
        tolerances = refs.tolerances_for(case)
        for j, (column, tol) in enumerate(tolerances.items()):
            row = (k + j) % len(fresh)
            value = float(fresh[column].iloc[row])
            steps = [(1.01, True)] if tol.atol == 0 else [(1.01, True), (0.99, False), (-1.01, True)]
            for factor, caught in steps:
                if tol.atol > 0:
                    moved = value + factor * tol.atol
                else:
                    moved = value + 1.0 if column == "id" else float(np.nextafter(value, math.inf))
                assert (abs(moved - value) > tol.atol) == caught  # the edit is on the intended side
                perturbed = fresh.copy()
                perturbed.loc[row, column] = moved
                path = tmp_path / source.name
                refs.write_table(perturbed, path)
                found = refs.compare_tables(fresh, refs.read_table(path), tolerances, case=case.name)
                if caught:
                    assert [(v.case, v.column, v.row, v.rows) for v in found] == [(case.name, column, row, 1)]
                    assert found[0].deviation > tol.atol and found[0].stored == moved
                else:
                    assert found == [], (case.name, column)
                checked += 1
    assert checked > 300


def test_structural_differences_are_violations():
    stored = refs.read_table(REFERENCE_DIR / "defaults.csv")
    tol = refs.COLLISION_TOLERANCES
    assert refs.compare_tables(stored, stored, tol, case="defaults") == []
    missing = refs.compare_tables(stored.drop(columns=["v_t_lammps"]), stored, tol, case="defaults")
    assert [(v.column, v.message) for v in missing] == [("v_t_lammps", "missing from the fresh table")]
    short = refs.compare_tables(stored.iloc[:-1], stored, tol, case="defaults")
    assert [v.column for v in short] == ["*"]
    extra = stored.assign(energy=0.0)
    assert [v.column for v in refs.compare_tables(extra, extra, tol)] == ["energy"]  # no tolerance, no pass
    nan = stored.copy()
    nan.loc[2, "omega_lammps"] = math.nan
    assert [(v.column, v.row) for v in refs.compare_tables(nan, stored, tol)] == [("omega_lammps", 2)]


def test_reference_module_does_not_load_lammps():
    code = "import sys, spinbounce.studies.references, spinbounce.cli.references; print('lammps' in sys.modules)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "False"


# -- fresh LAMMPS runs against the references --------------------------------------------


@pytest.mark.lammps
@pytest.mark.parametrize("name", CASE_NAMES)
def test_fresh_run_reproduces_the_reference(tmp_path, name):
    case = refs.case_by_name(name)
    fresh = refs.run_case(case, tmp_path / "run")
    stored = refs.read_table(REFERENCE_DIR / f"{name}.csv")
    violations = refs.compare_tables(fresh, stored, refs.tolerances_for(case), case=name)
    assert violations == [], "\n".join(map(str, violations))


@pytest.mark.lammps
@pytest.mark.parametrize("name, route", [(c, r) for c in ("defaults", "alpha_0.1") for r in ATOM_ROUTES
                                         if r != "inline"])
def test_other_atom_routes_reproduce_the_reference(tmp_path, name, route):
    case = refs.case_by_name(name)
    fresh = refs.run_case(case, tmp_path / "run", atoms=route)
    stored = refs.read_table(REFERENCE_DIR / f"{name}.csv")
    assert refs.compare_tables(fresh, stored, refs.tolerances_for(case), case=name) == []


@pytest.mark.lammps
def test_check_command_passes_on_a_copy_and_fails_on_a_perturbed_one(tmp_path, capsys):
    copy = tmp_path / "reference"
    shutil.copytree(REFERENCE_DIR, copy)
    assert _cli("--check", "--dir", str(copy), "--case", "stiff_kt", "--case", "frozen_damped") == 0
    out = capsys.readouterr().out
    assert "stiff_kt" in out and "frozen_damped" in out and "FAIL" not in out

    table = refs.read_table(copy / "frozen_damped.csv")
    table.loc[150, "omega"] += 2e-10  # twice the tolerance
    refs.write_table(table, copy / "frozen_damped.csv")
    (copy / "retired_case.csv").write_text("id\n1\n")  # left behind by a removed case
    before = _digest(copy)
    assert _cli("--check", "--dir", str(copy), "--case", "stiff_kt", "--case", "frozen_damped") == 1
    out = capsys.readouterr().out
    failing = [line for line in out.splitlines() if "FAIL (" in line]
    assert len(failing) == 1 and failing[0].split()[:2] == ["frozen_damped", "omega"]
    assert "frozen_damped: omega: 1 row(s) beyond tolerance" in out
    assert "*: retired_case.csv: stored file that no case in the code produces" in out
    assert _digest(copy) == before  # a check only reads


@pytest.mark.lammps
def test_regenerate_writes_what_is_stored(tmp_path, capsys, stored_manifest):
    target = tmp_path / "reference"
    (target / refs.DECKS_DIR).mkdir(parents=True)
    (target / "retired_case.csv").write_text("id\n1\n")
    (target / refs.DECKS_DIR / "retired_case.lmp").write_text("run 0\n")
    (target / "NOTES.txt").write_text("not ours\n")
    assert _cli("--regenerate", "--dir", str(target)) == 0
    written = {p.relative_to(target).as_posix() for p in target.rglob("*") if p.is_file()}
    assert written == refs.expected_files() | {"NOTES.txt"}  # stale references removed, others kept
    for case in refs.CASES:
        fresh = refs.read_table(target / f"{case.name}.csv")
        stored = refs.read_table(REFERENCE_DIR / f"{case.name}.csv")
        assert refs.compare_tables(fresh, stored, refs.tolerances_for(case), case=case.name) == []
    assert refs.compare_decks(target / refs.DECKS_DIR) == []
    manifest = refs.read_manifest(target)
    for key in ("cases", "tolerances", "decks", "format"):
        assert manifest[key] == stored_manifest[key]
    assert "wrote 15 reference tables" in capsys.readouterr().out


def test_regenerate_refuses_a_case_filter_and_a_missing_parent(tmp_path, capsys):
    assert _cli("--regenerate", "--dir", str(tmp_path / "r"), "--case", "defaults") == 2
    assert _cli("--regenerate", "--dir", str(tmp_path / "elsewhere" / "r")) == 1
    assert "does not exist" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []  # nothing was created
