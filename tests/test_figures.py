"""spinbounce figures: the figure files, their records, the step choice and the command."""

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from spinbounce import exact
from spinbounce.cli import figures as figures_cli
from spinbounce.lammps.dumps import read_dump
from spinbounce.figures import FIGURES, FigureNameError, check_names
from spinbounce.figures.collisions import dissipation_curve, fig4_states, fig6_states
from spinbounce.figures.core import ACCEPTANCE, STYLE, TARGET, tune_dt
from spinbounce.pipeline import ResultError

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
RECORD_KEYS = ("figure", "files", "parameters", "dt", "runs", "lammps_version", "spinbounce_version",
               "max_deviation_exact", "runtime_seconds")


def parse(argv):
    parser = argparse.ArgumentParser(prog="spinbounce")
    sub = parser.add_subparsers(dest="command", required=True)
    figures_cli.register(sub)
    return parser.parse_args(argv)


# ---------------------------------------------------------------------------
# No LAMMPS
# ---------------------------------------------------------------------------

def test_importing_loads_neither_matplotlib_nor_lammps():
    code = ("import sys, spinbounce.figures, spinbounce.cli.figures; "
            "print('matplotlib' in sys.modules, 'lammps' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.split() == ["False", "False"]


def test_cli_refuses_an_unknown_figure_naming_the_allowed_ones(capsys):
    with pytest.raises(SystemExit) as info:
        parse(["figures", "--only", "fig9"])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert "--only" in err and "'fig9'" in err
    assert all(name in err for name in FIGURES)


def test_cli_refuses_one_bad_name_in_a_list(capsys):
    with pytest.raises(SystemExit) as info:
        parse(["figures", "--only", "fig2,figure3"])
    assert info.value.code == 2
    assert "'figure3'" in capsys.readouterr().err


def test_cli_only_accepts_lists_and_repeats():
    args = parse(["figures", "--only", "fig7,fig2", "--only", "fig3", "--out", "x"])
    assert args.only == [["fig2", "fig7"], ["fig3"]]
    assert args.out == Path("x") and args.runs is None
    assert parse(["figures"]).only is None


def test_check_names_orders_and_refuses():
    assert check_names(["fig6", "fig2", "fig6"]) == ["fig2", "fig6"]
    with pytest.raises(FigureNameError, match="fig1"):
        check_names(["fig1"])


def test_style_file_is_in_the_package_and_readable():
    import matplotlib.style

    assert STYLE.is_file() and STYLE.parent.name == "figures"
    with matplotlib.style.context(STYLE):
        import matplotlib

        assert matplotlib.rcParams["mathtext.fontset"] == "cm"


def test_dissipation_curve_is_eqs_18_and_21():
    alpha, m = 0.4, 1.0
    states = fig6_states(alpha, m)
    assert np.allclose(exact.energy(states, m, alpha), 1.0, rtol=0, atol=1e-12)
    for Omega in (0.0, -0.5, -1.0, -1.2838, -2.0):
        final = states @ exact.scattering_matrix(alpha, Omega).T
        slip = states[:, 1] + states[:, 2]
        assert np.allclose(dissipation_curve(slip, Omega, alpha, m), exact.dissipation(states, final, m, alpha),
                           rtol=0, atol=1e-13)
    # the rough sphere loses nothing; the rolling collision loses the most for any slip
    assert dissipation_curve(1.3, -2.0, alpha) == pytest.approx(0.0, abs=1e-15)
    omegas = np.linspace(-2, 0, 41)
    assert np.argmax([dissipation_curve(1.0, w, alpha) for w in omegas]) == 20  # Omega = -1


def test_fig4_states_fill_their_box_without_repeats():
    s = fig4_states()
    assert s.shape == (200, 3)
    assert s[:, 0].min() >= -1.4 and s[:, 0].max() <= -0.3
    assert np.abs(s[:, 1:]).max() <= 2.0
    assert len(np.unique(np.round(s[:, 1] + s[:, 2], 12))) == 200


def _fake_first_order(constant, calls):
    def run(dt):
        calls.append(dt)
        return None, {"v_t": constant * dt}, Path(f"dt_{dt}")
    return run


def test_tune_dt_refines_a_first_order_error_below_the_target():
    calls = []
    tuned = tune_dt(_fake_first_order(5.0, calls), 1e-3, lambda dt: dt, "fake")
    assert len(calls) == 2 and calls[0] == 1e-3
    assert tuned.deviation < TARGET and tuned.dt == calls[-1]
    assert "first order" in tuned.choice["reason"] and "1.00" in tuned.choice["reason"]


def test_tune_dt_keeps_a_default_that_is_good_enough():
    calls = []
    tuned = tune_dt(_fake_first_order(1e-3, calls), 1e-3, lambda dt: dt, "fake")
    assert calls == [1e-3] and "already below" in tuned.choice["reason"]


def test_tune_dt_refuses_an_error_that_does_not_shrink():
    def run(dt):
        return None, {"v_t": 2 * ACCEPTANCE}, Path("x")

    with pytest.raises(ResultError, match="not below|limit"):
        tune_dt(run, 1e-3, lambda dt: dt, "stuck")


def test_tune_dt_refines_a_run_with_problems():
    calls = []

    def run(dt):
        calls.append(dt)
        return dt, {"v_t": 1e-6}, Path("x")

    tuned = tune_dt(run, 1e-3, lambda dt: dt, "fake", problems=lambda dt: ["energy grew"] if dt > 6e-4 else [])
    assert tuned.dt == pytest.approx(5e-4) and len(calls) == 2


# ---------------------------------------------------------------------------
# LAMMPS: every figure, end to end (made once per session with the claims, conftest)
# ---------------------------------------------------------------------------

@pytest.fixture
def made(figures_made):
    """Every figure, made once per session (conftest.reproduction)."""
    return figures_made


@pytest.mark.lammps
def test_every_figure_is_written_with_its_record(made):
    out, records, lines = made
    assert list(records) == list(FIGURES) and len(lines) == len(FIGURES)
    for name, record in records.items():
        png, pdf, meta = (out / f"{name}.{ext}" for ext in ("png", "pdf", "json"))
        assert png.read_bytes()[:8] == PNG_MAGIC
        assert pdf.read_bytes()[:5] == b"%PDF-" and b"%%EOF" in pdf.read_bytes()[-32:]
        on_disk = json.loads(meta.read_text())
        assert on_disk == json.loads(json.dumps(record))
        for key in RECORD_KEYS:
            assert key in on_disk, f"{name}: {key}"
        assert on_disk["files"] == {"png": png.name, "pdf": pdf.name}
        assert on_disk["units"].startswith("units: LAMMPS lj")  # every figure says its units, in its corner too
        assert 0.0 < on_disk["max_deviation_exact"] < ACCEPTANCE
        for run in on_disk["runs"]:
            assert (out / run["run_dir"] / "in.lammps").is_file()
            assert run["dt"] == on_disk["dt"][run["series"]] and run["dt_choice"]["reason"]
            assert run["max_deviation_exact"] <= on_disk["max_deviation_exact"]


@pytest.mark.lammps
def test_fig2_deviation_recomputed_from_the_dump(made):
    out, records, _ = made
    record = records["fig2"]
    (run,) = record["runs"]
    model = record["parameters"]["model"]
    frames = read_dump(out / run["run_dir"] / "state.dump")
    t = frames["step"].to_numpy() * run["dt"]
    vt, r_omega = exact.frozen_velocities(t, 1.0, 0.0, model["kt"], model["m"], model["alpha"])
    omega = -frames["omegay"].to_numpy()
    dev = max(np.abs(frames["vx"] - vt).max(), np.abs(omega - r_omega / model["r"]).max())
    assert dev == pytest.approx(record["max_deviation_exact"], rel=1e-9)
    assert record["parameters"]["z"] == 0.1 and np.allclose(frames["z"], 0.1)


@pytest.mark.lammps
def test_fig7_needs_a_finer_step_and_records_eq22(made):
    out, records, _ = made
    record = records["fig7"]
    assert [r["gamma_t"] for r in record["runs"]] == [0.2, 1.0, 5.0]
    for run in record["runs"]:
        history = run["dt_choice"]["history"]
        assert len(history) >= 2 and history[0]["max_deviation_exact"] > TARGET  # the default is too coarse
        assert run["dt"] < history[0]["dt"] and run["max_deviation_exact"] < TARGET
        # recompute the deviation from Eq. 22 (the paper's damped recipe) from the dump
        frames = read_dump(out / run["run_dir"] / "state.dump")
        t = frames["step"].to_numpy() * run["dt"]
        vt22, rw22 = exact.frozen_velocities_paper_damped(t, 1.0, 0.5, 1.0, 1.0, 0.4, run["gamma_t"])
        dev22 = max(np.abs(frames["vx"] - vt22).max(), np.abs(-frames["omegay"] - rw22 / 0.5).max())
        assert dev22 == pytest.approx(run["max_deviation_eq22"], rel=1e-9)
    # Eq. 22 is an approximation: LAMMPS follows the exact solution, far from the recipe
    assert record["max_deviation_eq22"] > 100 * record["max_deviation_exact"]


@pytest.mark.lammps
def test_fig4_deviation_recomputed_from_the_batch_table(made):
    out, records, _ = made
    record = records["fig4"]
    (run,) = record["runs"]
    table = pd.read_parquet(out / run["run_dir"] / "result.parquet")
    initial = table[["v_n_initial", "v_t_initial", "r_omega_initial"]].to_numpy()
    final = table[["v_n_lammps", "v_t_lammps", "r_omega_lammps"]].to_numpy()
    matrix = exact.scattering_matrix(0.4, exact.Omega(10.0, 1.0, 0.4))
    error = final - initial @ matrix.T
    dev = max(np.abs(error).max(), np.abs(error[:, 2]).max() / 0.5)  # omega = r omega / r
    assert dev == pytest.approx(record["max_deviation_exact"], rel=1e-6)
    assert len(table) == record["parameters"]["n_collisions"]


@pytest.mark.lammps
def test_fig5_and_fig6_rolling_runs_follow_the_exact_damped_omega(made):
    _, records, _ = made
    rolling = next(r for r in records["fig5"]["runs"] if "rolling" in r["series"])
    assert rolling["max_deviation_exact"] < 1e-6
    # Eq. 23 is the limit only: at gamma_t = 20 the exact Omega differs from -1 by 7e-4
    assert records["fig5"]["max_deviation_rolling_vs_eq23"] > 1e-4
    kt_models = records["fig6"]["parameters"]["models"]
    assert math.isclose(kt_models["kt/kn=2/7"]["Omega_exact"], -2.0, abs_tol=1e-12)
    assert "f" in records["fig6"]["runs"][0]["deviations_exact"]
