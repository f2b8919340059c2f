"""The spinbounce command, as a user runs it (in a subprocess for the import test)."""

import json
import math
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

from spinbounce.cli import COMMANDS, main


def run_cli(capsys, *args):
    code = main(list(args))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_import_does_not_load_lammps():
    code = (
        "import sys, spinbounce, spinbounce.exact.linear, spinbounce.scenes.collision, spinbounce.lammps.decks, "
        "spinbounce.pipeline, spinbounce.cli; print('lammps' in sys.modules)"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "False"


#: What no command's ``--help`` may import: the heavy libraries a run needs (each takes a
#: tenth of a second or more to import), so that help starts at once.
HEAVY = ("pandas", "scipy", "matplotlib", "lammps", "pyarrow", "jinja2")


@pytest.mark.parametrize("command", [None] + [c.__name__.rsplit(".", 1)[1].replace("_", "-") for c in COMMANDS])
def test_help_imports_nothing_heavy(command):
    argv = ["--help"] if command is None else [command, "--help"]
    code = ("import sys\nfrom spinbounce.cli import main\ntry:\n    main(%r)\nexcept SystemExit:\n    pass\n"
            "print(' '.join(m for m in %r if m in sys.modules), file=sys.stderr)" % (argv, HEAVY))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stderr.strip() == "", f"spinbounce {' '.join(argv)} imports {done.stderr.strip()}"
    assert "usage: spinbounce" in done.stdout


def test_theory_json_at_paper_defaults(capsys):
    code, out, _ = run_cli(capsys, "theory", "--json")
    assert code == 0
    report = json.loads(out)
    assert abs(report["Omega"] - (-1.28384)) < 1e-5  # acceptance; the paper quotes -1.2838
    assert report["tau"] == pytest.approx(math.pi * math.sqrt(1 / 10), rel=1e-15)
    assert report["Q"] == pytest.approx(3.5, rel=1e-15)
    matrix = report["matrix"]
    assert len(matrix) == 3 and all(len(row) == 3 for row in matrix)
    assert matrix[0] == [-1.0, 0.0, 0.0]


def test_theory_magic_ratio_for_a_shell(capsys):
    _, out, _ = run_cli(capsys, "theory", "--json", "--alpha", "0.6666666666666666", "--kt", "4")
    assert json.loads(out)["Omega"] == pytest.approx(-2.0, abs=1e-7)  # kt/kn = 0.4 = alpha/(1+alpha)


def test_every_command_has_help(capsys):
    for command in ("theory", "collide", "frozen"):
        with pytest.raises(SystemExit) as info:
            main([command, "--help"])
        assert info.value.code == 0
        assert "--kn" in capsys.readouterr().out


@pytest.mark.lammps
def test_collide_json(capsys, tmp_path):
    code, out, _ = run_cli(capsys, "collide", "--vn", "-1", "--vt", "1", "--omega", "0", "--json",
                           "--out", str(tmp_path / "c"))
    assert code == 0
    report = json.loads(out)
    for key in ("initial", "lammps", "theory", "error"):
        assert set(report[key]) == {"v_n", "v_t", "omega", "r_omega"}
    assert max(abs(v) for v in report["error"].values()) < 2e-4  # acceptance bound
    assert report["lammps"]["v_t"] - report["theory"]["v_t"] == pytest.approx(report["error"]["v_t"], abs=1e-15)
    assert report["deck"].endswith("in.lammps") and report["dump"].endswith("state.dump")
    assert report["lammps_version"].startswith("2025.7.22.4.0")
    saved = json.loads((tmp_path / "c" / "result.json").read_text())
    assert saved["parameters"]["model"]["kn"] == 10.0 and saved["spinbounce_version"]
    # what produced it, as the record says: the parameters it ran and the versions
    assert report["parameters"]["kn"] == 10.0 and report["parameters"]["v_t"] == 1.0
    assert report["spinbounce_version"] == saved["spinbounce_version"] and report["python"]


@pytest.mark.lammps
def test_sweep_json_reports_the_dataset_and_what_made_it(capsys, tmp_path):
    """--json once printed the log lines and the summary as text, as if not given."""
    code, out, _ = run_cli(capsys, "sweep", "--n", "10", "--out", str(tmp_path / "s"), "--json")
    report = json.loads(out)
    assert code == 0 and report["counts"]["ok"] == report["collisions"] == 10
    assert report["dataset"] == str(tmp_path / "s" / "chunks") and report["lammps_version"].startswith("2025.7.22")
    # the sweep as it ran (chunked for the workers), as its record holds it
    assert report["scene_hash"] == json.loads((tmp_path / "s" / "sweep.json").read_text())["scene_hash"]


@pytest.mark.lammps
def test_the_api_runs_the_frozen_contact_the_command_runs(capsys, tmp_path):
    """spinbounce.frozen is the command's work: the same series, to the last digit, and its record."""
    import spinbounce

    report = spinbounce.frozen(z=0.1, v_t=1.0, omega=0.0, t_end=2.0, gamma_t=0.2, out=tmp_path / "api")
    code, _, _ = run_cli(capsys, "frozen", "--z", "0.1", "--vt", "1", "--omega", "0", "--t-end", "2",
                         "--gamma-t", "0.2", "--out", str(tmp_path / "cli"))
    assert code == 0
    assert pd.read_csv(tmp_path / "cli" / "frozen.csv").equals(pd.read_csv(report.csv))
    t = report.table
    worst = max((t["v_t"] - t["v_t_theory"]).abs().max(), (t["r_omega"] - t["r_omega_theory"]).abs().max())
    assert report.record["max_abs_error"] == pytest.approx(worst, rel=1e-12)  # the record's is the table's
    assert report.record["max_abs_error"] < 1e-4 and report.record["parameters"]["model"]["gamma_t"] == 0.2


@pytest.mark.lammps
def test_frozen_writes_csv_with_theory_and_provenance(capsys, tmp_path):
    run = tmp_path / "run"
    code, out, _ = run_cli(capsys, "frozen", "--z", "0.1", "--vt", "1", "--omega", "0", "--t-end", "2",
                           "--out", str(run))
    assert code == 0
    table = pd.read_csv(run / "frozen.csv")
    assert list(table.columns) == ["t", "v_t", "omega", "r_omega", "v_t_theory", "r_omega_theory"]
    assert table["t"].iloc[0] == 0.0 and table["t"].iloc[-1] >= 2.0
    assert (table["v_t"] - table["v_t_theory"]).abs().max() < 1e-5  # the frozen contact's default accuracy
    meta = json.loads((run / "result.json").read_text())
    assert meta["parameters"]["z"] == 0.1 and meta["lammps_version"].startswith("2025")


@pytest.mark.parametrize(
    "args, needle",
    [
        (["--vn", "-1.6", "--vt", "0", "--omega", "0"], "v_n = -1.6"),
        (["--vn", "-1", "--vt", "0", "--omega", "0", "--kn", "0"], "kn = 0.0"),
        (["--vn", "-1", "--vt", "0", "--omega", "0", "--alpha", "1.2"], "alpha = 1.2"),
        (["--vn", "-1", "--vt", "0", "--omega", "0", "--dt", "0.7"], "dt = 0.7"),
        (["--vn", "-1", "--vt", "0", "--omega", "0", "--mu", "-1"], "mu = -1.0"),
    ],
)
def test_bad_input_exits_before_lammps(capsys, tmp_path, args, needle):
    out_dir = tmp_path / "never"
    with pytest.raises(SystemExit) as info:
        main(["collide", *args, "--out", str(out_dir)])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert needle in err
    assert not out_dir.exists()  # nothing was written, LAMMPS never started


STUDIES = ("claims", "figures", "hertz", "benchmarks", "two-walls", "restitution", "accuracy")


@pytest.mark.parametrize("command", STUDIES)
def test_studies_write_into_a_folder_of_their_own_by_default(command, capsys):
    """No study writes into the repository's figures/ (or a folder of the user's) unless told to."""
    from spinbounce.cli import build_parser

    assert build_parser().parse_args([command]).out == Path("spinbounce-figures")
    with pytest.raises(SystemExit):
        main([command, "--help"])
    assert "only with --out figures" in " ".join(capsys.readouterr().out.split())


@pytest.mark.parametrize("command", STUDIES)
def test_studies_refuse_a_file_as_their_folder(command, tmp_path, capsys):
    user_file = tmp_path / "notes.txt"
    user_file.write_text("the user's notes")
    with pytest.raises(SystemExit) as info:
        main([command, "--out", str(user_file)])
    assert info.value.code == 2 and "is a file, not a folder" in capsys.readouterr().err
    assert user_file.read_text() == "the user's notes"
