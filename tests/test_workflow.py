"""The Snakemake workflow in workflows/, run as a user runs it, and the fit's figure."""

import json
import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

import examples
from spinbounce.cli import main
from spinbounce.fitting import GROUP_KEYS, plot_groups
from spinbounce.sweeps.cost import chunk_cost, job_request
from spinbounce.sweeps import load_spec

ROOT = Path(__file__).resolve().parents[1]
WORKFLOW = ROOT / "workflows"
TINY = WORKFLOW / "scenes" / "tiny.toml"


def snakemake(workdir: Path, *args: str) -> subprocess.CompletedProcess:
    """Snakemake from this interpreter's environment, on the tiny scene, writing into workdir/out."""
    env = dict(os.environ)
    # The rules run `spinbounce`: find this environment's one even when it is not activated.
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    env = examples.without_controller(env)
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(WORKFLOW / "Snakefile"),
               "--directory", str(workdir), "--config", f"scene={TINY}", "out=out", *args]
    return subprocess.run(command, capture_output=True, text=True, env=env, timeout=300, check=False)


def job_counts(done) -> dict[str, int]:
    """The 'Job stats' table Snakemake prints: rule -> number of jobs."""
    text = done if isinstance(done, str) else done.stdout + done.stderr
    return {m[1]: int(m[2]) for m in re.finditer(r"^(chunk|fit|figure|all)\s+(\d+)$", text, re.MULTILINE)}


def tiny_layout() -> tuple[int, int, int]:
    raw = tomllib.loads(TINY.read_text())
    return raw["states"]["n"], len(raw["model"]["kt_over_kn"]), raw["chunk_size"]


@pytest.mark.slow
@pytest.mark.lammps
@pytest.mark.workflow
def test_workflow_runs_the_tiny_sweep_end_to_end(tmp_path):
    done = snakemake(tmp_path, "--cores", "2")
    assert done.returncode == 0, done.stderr[-3000:]
    out = tmp_path / "out"
    n, groups, chunk_size = tiny_layout()

    per_group = -(-n // chunk_size)
    expected = {f"chunk-{g:04d}-{c:06d}.parquet" for g in range(groups) for c in range(per_group)}
    assert {p.name for p in (out / "chunks").glob("*.parquet")} == expected
    rows = pd.concat([pd.read_parquet(p) for p in sorted((out / "chunks").glob("*.parquet"))])
    assert len(rows) == n * groups
    assert not rows.duplicated(["group", "index"]).any()
    for g in range(groups):
        assert sorted(rows.loc[rows["group"] == g, "index"]) == list(range(n))

    fits = json.loads((out / "fit.json").read_text())
    assert len(fits) == groups
    # The two groups are the intended models: kt/kn = 0.1 and the ratio where Omega = -2.
    assert sorted(f["Omega_theory"] for f in fits) == pytest.approx([-2.0, -1.28384], abs=1e-5)
    for f in fits:
        assert f["n"] == n
        # Each of the 200 collisions is off the theory by ~3e-5 at the default step, so the
        # fitted Omega lands well inside 2e-4; a wrong contact model misses by far more.
        assert abs(f["Omega"] - f["Omega_theory"]) < 2e-4
    assert (out / "fit.txt").read_text().count(f"collisions {n};") == groups

    png = (out / "slip.png").read_bytes()
    assert png.startswith(b"\x89PNG\r\n\x1a\n") and len(png) > 10_000

    # Run again: nothing to do. As if killed after three chunks: only the fourth is planned.
    again = snakemake(tmp_path, "--cores", "2")
    assert again.returncode == 0 and "Nothing to be done" in again.stdout + again.stderr
    for name in ("chunks/chunk-0001-000000.parquet", "fit.json", "fit.txt", "slip.png"):
        (out / name).unlink()
    plan = snakemake(tmp_path, "--cores", "2", "--dry-run")
    assert plan.returncode == 0, plan.stderr[-3000:]
    assert job_counts(plan) == {"chunk": 1, "fit": 1, "figure": 1, "all": 1}


@pytest.mark.slow
@pytest.mark.lammps
@pytest.mark.workflow
def test_the_readme_examples_run_as_shown(tmp_path):
    """workflows/README.md's examples, in order, in one folder: the tiny run on one machine, its files
    and fit, the SLURM profile's plan and its refusals (the session on a real SLURM is test_slurm's)."""
    env = examples.without_controller({k: v for k, v in examples.base_env().items()
                                       if not k.startswith("SPINBOUNCE_SLURM_")})
    page = examples.Page("workflows/README.md", tmp_path, env)
    assert page.run_blocks((WORKFLOW / "README.md").read_text(), {"slow"}) == 6


@pytest.mark.workflow
def test_slurm_profile_plans_the_jobs_without_a_cluster(tmp_path):
    done = snakemake(tmp_path, "--dry-run", "--profile", str(WORKFLOW / "profiles" / "slurm"))
    assert done.returncode == 0, done.stderr[-3000:]
    n, groups, chunk_size = tiny_layout()
    assert job_counts(done) == {"chunk": groups * -(-n // chunk_size), "fit": 1, "figure": 1, "all": 1}
    text = done.stdout + done.stderr
    # The profile's requests reach the jobs: its partition placeholder, and each chunk's own
    # estimate (sweeps/cost.py) rather than the profile's 1000 MB and 30 minutes.
    assert "slurm_partition=CHANGE_ME" in text
    assert "rule chunk:" in text and "localrule chunk:" not in text  # chunks go to sbatch
    request = job_request(chunk_cost(load_spec(TINY), 0, chunk_size))
    assert re.search(rf"mem_mb={request.mem_mb},.*runtime={request.runtime}\b", text)
    assert not (tmp_path / "out").exists()  # a plan writes nothing


MILLION_FINITE_MU = """seed = 1
{chunking}
[model]
{model}
[states]
n = 500000
v_n = [-1.5, -0.1]
v_t = [-2.0, 2.0]
r_omega = [-2.0, 2.0]
"""


def slurm_plan(tmp_path: Path, chunk_size: int | None, model: str = "mu = [0.0, 0.5]") -> subprocess.CompletedProcess:
    """`snakemake -n` with the SLURM profile on a million finite-mu collisions (two groups);
    chunk_size None leaves it to the cost estimate."""
    scene = tmp_path / f"million-{chunk_size}.toml"
    chunking = "" if chunk_size is None else f"chunk_size = {chunk_size}"
    scene.write_text(MILLION_FINITE_MU.format(chunking=chunking, model=model))
    return snakemake(tmp_path, "--dry-run", "--profile", str(WORKFLOW / "profiles" / "slurm"),
                     "--config", f"scene={scene}", "out=out")


@pytest.mark.workflow
def test_slurm_plan_of_a_million_finite_mu_collisions_fits_the_profile_limits(tmp_path):
    limits = yaml.safe_load((WORKFLOW / "profiles" / "slurm" / "limits.yaml").read_text())["job_limits"]
    done = slurm_plan(tmp_path, 25_000)
    assert done.returncode == 0, done.stderr[-3000:]
    text = done.stdout + done.stderr
    assert job_counts(text)["chunk"] == 40
    asked = re.findall(r"mem_mb=(\d+),.*runtime=(\d+)\b", text)
    assert len(asked) >= 42  # every chunk, the fit and the figure (Snakemake prints each twice)
    for mem_mb, runtime in asked:
        assert int(mem_mb) <= limits["mem_mb"] and int(runtime) <= limits["runtime"]


@pytest.mark.workflow
def test_slurm_plan_refuses_a_sweep_whose_chunk_cannot_fit(tmp_path):
    # a large cap with tangential damping and no normal damping needs a fine step (the cap
    # is zero at first touch; stepping.expected_steps): 250,000 such collisions take days
    done = slurm_plan(tmp_path, 250_000, model="mu = [10.0]\ngamma_t = 1.0")
    assert done.returncode != 0
    text = done.stdout + done.stderr
    assert "chunk 0 (250000 collisions of group 0) would ask for" in text and "chunk_size <=" in text
    assert "rule chunk:" not in text and not (tmp_path / "out").exists()


@pytest.mark.workflow
def test_chunk_sizes_follow_the_estimated_cost_when_the_scene_leaves_them_open(tmp_path):
    """The sweep above, with no chunk_size: each chunk holds what is estimated to run in
    CHUNK_SECONDS, so every job fits the profile; the frictionless default stays 25,000."""
    from spinbounce.sweeps.spec import CHUNK_SECONDS, DEFAULT_CHUNK

    limits = yaml.safe_load((WORKFLOW / "profiles" / "slurm" / "limits.yaml").read_text())["job_limits"]
    done = slurm_plan(tmp_path, None, model="mu = [10.0]\ngamma_t = 1.0")
    assert done.returncode == 0, done.stderr[-3000:]
    for mem_mb, runtime in re.findall(r"mem_mb=(\d+),.*runtime=(\d+)\b", done.stdout + done.stderr):
        assert int(mem_mb) <= limits["mem_mb"] and int(runtime) <= limits["runtime"]
    spec = load_spec(tmp_path / "million-None.toml")
    (size,) = spec.chunk_sizes
    assert 1 <= size < DEFAULT_CHUNK
    assert chunk_cost(spec, 0, size).seconds <= CHUNK_SECONDS < chunk_cost(spec, 0, size + 1).seconds
    assert job_counts(done.stdout + done.stderr)["chunk"] == -(-500_000 // size)
    frictionless = tmp_path / "frictionless.toml"
    frictionless.write_text(MILLION_FINITE_MU.format(chunking="", model="mu = [\"none\"]"))
    assert load_spec(frictionless).chunk_sizes == (DEFAULT_CHUNK,)


@pytest.mark.workflow
def test_workflow_refuses_a_folder_that_holds_another_sweep(tmp_path):
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "sweep.json").write_text(json.dumps({"scene_hash": "0123456789abcdef"}))
    done = snakemake(tmp_path, "--dry-run")
    assert done.returncode != 0
    assert "holds sweep 0123456789abcdef" in done.stdout + done.stderr


def synthetic_rows(n: int = 50) -> pd.DataFrame:
    """Rows shaped like a sweep's, following Eq. 19 exactly (plotting needs nothing more)."""
    rng = np.random.default_rng(0)
    alpha, big_omega = 0.4, -1.28384
    rows = pd.DataFrame({k: 1.0 for k in GROUP_KEYS}, index=range(n))
    rows["alpha"], rows["kn"], rows["Omega_theory"] = alpha, 10.0, big_omega
    rows["v_t_initial"], rows["r_omega_initial"] = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
    slip = rows["v_t_initial"] + rows["r_omega_initial"]
    rows["v_t_lammps"] = rows["v_t_initial"] + alpha * big_omega / (1 + alpha) * slip
    rows["r_omega_lammps"] = rows["r_omega_initial"] + big_omega / (1 + alpha) * slip
    return rows


def test_plot_writes_a_pdf_by_its_suffix_and_leaves_no_temporary_file(tmp_path):
    path = plot_groups(synthetic_rows(), tmp_path / "figs" / "slip.pdf")
    assert path.read_bytes().startswith(b"%PDF")
    assert [p.name for p in path.parent.iterdir()] == ["slip.pdf"]


def test_fit_refuses_a_figure_format_it_cannot_write(capsys, tmp_path):
    with pytest.raises(SystemExit) as info:
        main(["fit", str(tmp_path), "--plot", str(tmp_path / "slip.svg")])
    assert info.value.code == 2
    assert ".png or .pdf" in capsys.readouterr().err


def test_the_readme_install_is_what_the_tests_install():
    """workflows/README.md's one command not run as shown, `pip install -e ".[workflow]"`: CI installs
    ".[test]" (README.md's test command), which must hold every package of the workflow extra."""
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    assert 'python -m pip install -e ".[workflow]"' in (WORKFLOW / "README.md").read_text()
    assert set(extras["workflow"]) <= set(extras["test"])
