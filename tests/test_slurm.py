"""The workflow through a real SLURM scheduler: every chunk an sbatch job, faults, resuming.

Needs a running SLURM whose default partition takes jobs: `workflows/ci/slurm up` makes a
one-node one on this machine (CI does it before the tests). Without one these tests are
skipped, except under CI=true, where a missing cluster is a failure.
"""

import getpass
import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import examples
from spinbounce.records import TEMP_SUFFIX
from spinbounce.sweeps.cost import chunk_cost, job_request
from spinbounce.sweeps import load_spec, read_results

# slow too: minutes of sbatch round trips (CI runs them; the quick default run leaves them)
pytestmark = [pytest.mark.slurm, pytest.mark.workflow, pytest.mark.lammps, pytest.mark.slow]

ROOT = Path(__file__).resolve().parents[1]
WORKFLOW = ROOT / "workflows"
# Frictionless (mu = 0: no tangential force) and finite-mu groups, 60 collisions each in
# chunks of 30: four chunk jobs of ~2 s (the Coulomb oracle runs for both groups).
MIXED_SCENE = """seed = 3
chunk_size = 30
[model]
mu = [0.0, 0.5]
[states]
n = 60
v_n = [-1.5, -0.1]
v_t = [-2.0, 2.0]
r_omega = [-2.0, 2.0]
"""


def slurm_site() -> dict[str, str]:
    """The profile's overrides for a SLURM that answers: its default partition and this
    user's default account; or skip (fail under CI=true) saying why."""
    why = None
    if shutil.which("sbatch") is None or shutil.which("sacct") is None:
        why = "no SLURM client here (sbatch, sacct)"
    else:
        info = subprocess.run(["sinfo", "-h", "-o", "%P %a"], capture_output=True, text=True, check=False)
        default = [line.split()[0][:-1] for line in info.stdout.splitlines() if line.split()[0].endswith("*")]
        if info.returncode != 0 or not default:
            why = f"SLURM does not answer or has no default partition: {info.stderr.strip() or info.stdout!r}"
        elif subprocess.run(["sacct", "-n", "-X", "-S", "now"], capture_output=True, check=False).returncode:
            why = "sacct fails: the workflow's SLURM plugin needs job accounting (slurmdbd)"
    if why is None:
        user = subprocess.run(["sacctmgr", "-n", "-P", "show", "user", getpass.getuser(), "format=DefaultAccount"],
                              capture_output=True, text=True, check=False).stdout.split()
        if user:
            return {"SPINBOUNCE_SLURM_PARTITION": default[0], "SPINBOUNCE_SLURM_ACCOUNT": user[0]}
        why = f"SLURM knows no account of user {getpass.getuser()} (sacctmgr show user)"
    why += "; start one with `workflows/ci/slurm up` (as root)"
    if os.environ.get("CI") == "true":
        pytest.fail(why)
    pytest.skip(why)


@pytest.fixture(scope="module")
def site() -> dict[str, str]:
    return slurm_site()


def snakemake_on_slurm(workdir: Path, scene: Path, site: dict[str, str], *args: str, seconds: int = 400):
    """The workflow with the real SLURM profile, its partition and account set through the
    profile's environment variables (the plugin refuses an account SLURM does not know).

    `timeout -k 30`: on SIGTERM Snakemake waits for the jobs it believes are running.
    The first status check comes after 1 s instead of 40 s (a test's jobs take seconds).
    """
    env = dict(os.environ, **site)
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    command = ["timeout", "-k", "30", str(seconds), sys.executable, "-m", "snakemake",
               "--snakefile", str(WORKFLOW / "Snakefile"), "--directory", str(workdir),
               "--profile", str(WORKFLOW / "profiles" / "slurm"), "--config", f"scene={scene}", "out=out",
               "--slurm-init-seconds-before-status-checks", "1", *args]
    return subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)


def finish(process: subprocess.Popen) -> str:
    return process.communicate()[0]


def submitted(text: str) -> dict[str, str]:
    """Snakemake's log: rule/wildcards -> SLURM job id, from its 'submitted with SLURM jobid' lines."""
    found = re.findall(r"submitted with SLURM jobid (\d+) \(log: \S*/slurm_logs/rule_(\w+)/(?:([^/\s]+)/)?\1\.log\)", text)
    return {f"{rule}/{wildcards}" if wildcards else rule: job for job, rule, wildcards in found}


def states(job_ids) -> dict[str, str]:
    """The scheduler's final state of each job (its accounting record)."""
    done = subprocess.run(["sacct", "-n", "-X", "-P", "-o", "JobID,State", "-j", ",".join(job_ids)],
                          capture_output=True, text=True, check=True)
    return dict(line.split("|")[:2] for line in done.stdout.splitlines())


def chunk_files(out: Path) -> set[str]:
    return {p.name for p in (out / "chunks").iterdir()}


def assert_identical(left: pd.DataFrame, right: pd.DataFrame) -> None:
    """Same columns in the same order, same rows after sorting, every float the same bits."""
    left, right = (f.sort_values(["group", "index"], ignore_index=True) for f in (left, right))
    assert list(left.columns) == list(right.columns)
    pd.testing.assert_frame_equal(left, right, check_exact=True)
    for name in left.columns:
        if left[name].dtype.kind == "f":
            assert np.array_equal(left[name].to_numpy().view(np.uint64), right[name].to_numpy().view(np.uint64)), name


#: The fault sweep's two groups: a Coulomb cap and a slip mode that turns 590 times a contact, so
#: that each collision costs LAMMPS about 0.08 s (a chunk of a few thousand runs for minutes,
#: whatever the theory's speed), and the same cap on a spring ten times softer, whose chunk of as
#: many collisions takes about a sixth of that (its cost estimate says 113 s against 600 s).
FAULT_MODEL = "mu = 0.5\nkt = [100000.0, 10000.0]"


def fault_chunk_size(seconds: float) -> int:
    """Collisions of the fault sweep's model that the cost estimate puts at ``seconds`` on one
    core (the estimate runs high: for this capped model about 5x since this round's faster sweep)."""
    from spinbounce.sweeps.cost import chunk_cost
    from spinbounce.sweeps import spec_from_dict

    probe = spec_from_dict({"model": {"mu": 0.5, "kt": 100000.0}, "states": {"n": 1000, "v_n": [-1.5, -0.1],
                                                                              "v_t": [-2, 2], "r_omega": [-2, 2]}})
    return round(seconds / (chunk_cost(probe, 0, 1000).seconds / 1000))


def wait_until_running(job: str, seconds: float = 60) -> None:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        state = subprocess.run(["squeue", "-h", "-j", job, "-o", "%T"], capture_output=True, text=True).stdout
        if state.strip() == "RUNNING":
            return
        time.sleep(0.5)
    pytest.fail(f"job {job} did not start within {seconds} s")


def wait_until_idle(seconds: float = 300) -> None:
    """Until the cluster runs no job and its node is idle: an earlier test's jobs (a timed-out chunk, a finished
    job's clean-up) may still hold it, and the README's session starts on an idle cluster."""
    deadline, jobs, node = time.monotonic() + seconds, "", ""
    while time.monotonic() < deadline:
        jobs = subprocess.run(["squeue", "-h", "-o", "%i %j %T"], capture_output=True, text=True).stdout.strip()
        node = subprocess.run(["sinfo", "-h", "-o", "%T"], capture_output=True, text=True).stdout.strip()
        if not jobs and node == "idle":
            return
        time.sleep(1.0)
    pytest.fail(f"the cluster is still busy after {seconds:.0f} s: jobs {jobs!r}, node {node!r}")


def wait_for_submission(process: subprocess.Popen, name: str, log: list[str], seconds: float = 60) -> str:
    """Read Snakemake's output until it reports the job of ``name`` submitted; its job id."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        line = process.stdout.readline()
        if not line:
            break
        log.append(line)
        job = submitted("".join(log)).get(name)
        if job:
            return job
    pytest.fail(f"{name} was not submitted within {seconds} s:\n{''.join(log)[-3000:]}")


def leftovers(out: Path, scene: Path) -> list[str]:
    """Half-written files in the output folder, and live processes of the scene's chunks."""
    temporary = [p.name for p in out.rglob(f"*{TEMP_SUFFIX}")]
    processes = subprocess.run(["pgrep", "-f", "--", f"spinbounce sweep {scene}"],
                               capture_output=True, text=True).stdout.split()
    return temporary + [f"process {pid}" for pid in processes]


# No retries: a failed chunk stays failed, for the rerun to find. Job states from squeue:
# plugin 2.8.0 reads sacct's "CANCELLED by 0" as still running and would wait forever. A
# failed job's outputs are awaited for `latency-wait` (60 s in the profile, for shared
# filesystems); this one is local.
FAULT_OPTIONS = ("--retries", "0", "--slurm-status-command", "squeue", "--latency-wait", "5")


#: The fault sweep's chunks: (group 0's first, run into its limit), (group 1's first, cancelled), and the
#: two of 10 collisions that complete.
TIMED_OUT, CANCELLED = "chunk/chunk-0000-000000", "chunk/chunk-0001-000000"
COMPLETED = ("chunk/chunk-0000-000001", "chunk/chunk-0001-000001")


@pytest.fixture(scope="module")
def faults(tmp_path_factory, site):
    """A finite-mu sweep of two groups started with a 1-minute limit per chunk, one chunk cancelled.

    Chunks of the stiff group estimated at 600 s on one core (the estimate runs high: a chunk estimated
    at 300 s took 58 s on an idle core once the sweep got faster, inside SLURM's kill window; 600 s
    takes about twice that): its chunk 0 runs into its limit (SLURM kills it 60 to 90 s after its
    start); the soft group's chunk 0, as many collisions at about a sixth of the cost, is cancelled
    while it runs; each group's chunk 1 (10 collisions) completes. The rerun then does one long chunk
    and one short one, not two long ones. Returns the folder, the scene, the running Snakemake, its
    output so far and the cancelled job's id.
    """
    workdir = tmp_path_factory.mktemp("faults")
    size = fault_chunk_size(600.0)
    scene = workdir / "faults.toml"
    scene.write_text(MIXED_SCENE.replace("mu = [0.0, 0.5]", FAULT_MODEL)
                     .replace("chunk_size = 30", f"chunk_size = {size}").replace("n = 60", f"n = {size + 10}"))
    first = snakemake_on_slurm(workdir, scene, site, "--set-resources", "chunk:runtime=1", *FAULT_OPTIONS)
    log: list[str] = []
    cancelled = wait_for_submission(first, CANCELLED, log)
    wait_until_running(cancelled)
    time.sleep(3)  # into its run: LAMMPS or the oracle, not the start-up
    subprocess.run(["scancel", cancelled], check=True)
    yield workdir, scene, first, log, cancelled
    if first.poll() is None:
        first.kill()


def test_sweep_through_sbatch_matches_the_same_sweep_on_one_machine(tmp_path, site, faults):
    # `faults` first: its chunk runs into its time limit on one core while this runs on the other.
    scene = tmp_path / "mixed.toml"
    scene.write_text(MIXED_SCENE)
    text = finish(snakemake_on_slurm(tmp_path, scene, site))
    assert "steps (100%) done" in text, text[-4000:]

    spec = load_spec(scene)
    jobs = submitted(text)
    chunk_jobs = {name: job for name, job in jobs.items() if name.startswith("chunk/")}
    assert len(chunk_jobs) == len(spec.chunks()) == 4
    assert {"fit", "figure"} <= set(jobs)  # the fit and the figure went through sbatch too
    assert set(states(jobs.values()).values()) == {"COMPLETED"}
    for name, job in chunk_jobs.items():  # each job asked for its chunk's own estimate
        group = int(name.split("-")[1])
        request = job_request(chunk_cost(spec, group, spec.chunk_size))
        asked = subprocess.run(["sacct", "-n", "-X", "-P", "-o", "ReqMem,Timelimit,ReqCPUS", "-j", job],
                               capture_output=True, text=True, check=True).stdout.split()
        minutes = f"{request.runtime // 60:02d}:{request.runtime % 60:02d}:00"
        assert asked == [f"{request.mem_mb}M|{minutes}|{request.cpus_per_task}"], (name, asked)

    reference = tmp_path / "reference"
    local = subprocess.run([sys.executable, "-m", "spinbounce.cli", "sweep", str(scene), "--out", str(reference),
                            "--workers", "2"], capture_output=True, text=True, check=False)
    assert local.returncode == 0, local.stderr[-3000:]
    assert_identical(read_results(tmp_path / "out"), read_results(reference))


def test_cancelled_and_timed_out_chunks_leave_nothing_and_a_rerun_finishes_them(site, faults):
    workdir, scene, first, log, cancelled = faults
    spec, out = load_spec(scene), workdir / "out"
    text = "".join(log) + finish(first)
    assert first.returncode != 0  # two chunks failed, so no fit
    jobs = submitted(text)
    ended = states([jobs[name] for name in (TIMED_OUT, CANCELLED, *COMPLETED)])
    assert ended == {jobs[TIMED_OUT]: "TIMEOUT", cancelled: "CANCELLED by 0"} | {jobs[n]: "COMPLETED" for n in COMPLETED}
    # Only the finished chunks have files: nothing half-written, no process left behind.
    assert {n for n in chunk_files(out) if not n.startswith(".")} == {f"{n[6:]}.parquet" for n in COMPLETED}
    assert leftovers(out, scene) == []

    # the two chunks again, whole: the long one about two minutes on an idle core and up to six while the tests'
    # own workers share the two cores (seen in CI, past the default 400 s, when Snakemake was stopped before the end)
    second = finish(snakemake_on_slurm(workdir, scene, site, *FAULT_OPTIONS, seconds=1500))
    assert "steps (100%) done" in second, second[-4000:]
    rerun = submitted(second)
    assert sorted(n for n in rerun if n.startswith("chunk/")) == [TIMED_OUT, CANCELLED]
    assert set(states(rerun.values()).values()) == {"COMPLETED"}
    rows = read_results(out)
    assert len(rows) == 2 * spec.n and not rows.duplicated(["group", "index"]).any()
    for group in (0, 1):
        assert sorted(rows.loc[rows["group"] == group, "index"]) == list(range(spec.n))
    assert leftovers(out, scene) == []


def test_a_gas_runs_as_one_job_on_two_ranks(tmp_path, site):
    """workflows/Gasfile through sbatch: one job with two tasks, `spinbounce gas --ranks 2` inside it (LAMMPS
    under mpiexec -np 2 in the allocation), the gas's series and record in its folder; the same gas on one
    rank, here, starts from the same state (every draw from the atom ids) and agrees to 1e-10 after its
    four collisions per sphere (tests/test_gas.py)."""
    env = dict(os.environ, **site)
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    gas = "gas={spheres: 2000, kn: 10000, kt: 2857.1428571428573, collisions: 2, samples: 8, draws: 2000}"
    done = subprocess.run(["timeout", "-k", "30", "400", sys.executable, "-m", "snakemake", "--snakefile",
                           str(WORKFLOW / "Gasfile"), "--directory", str(tmp_path), "--profile",
                           str(WORKFLOW / "profiles" / "slurm"), "--config", "out=gas", "ranks=2", gas,
                           "--slurm-init-seconds-before-status-checks", "1"], capture_output=True, text=True, env=env)
    text = done.stdout + done.stderr
    assert done.returncode == 0 and "steps (100%) done" in text, text[-4000:]
    job = submitted(text)["gas"]
    assert states([job]) == {job: "COMPLETED"}
    tasks = subprocess.run(["sacct", "-n", "-X", "-P", "-o", "NTasks,AllocCPUS", "-j", job], capture_output=True,
                           text=True, check=True).stdout.split()[0]
    assert tasks.split("|")[1] == "2", tasks
    record = json.loads((tmp_path / "gas" / "result.json").read_text())
    assert record["ranks"] == 2 and record["parameters"]["spheres"] == 2000
    from spinbounce.api import gas as run_gas

    alone = run_gas(spheres=2000, kn=1e4, kt=1e4 * 2 / 7, collisions=2, samples=8, draws=2000, out=tmp_path / "one")
    cluster = pd.read_csv(tmp_path / "gas" / "gas.csv")
    for q in ("t_tr", "t_rot", "energy"):
        assert np.max(np.abs(cluster[q].to_numpy() - alone.series[q])) < 1e-10


def test_the_readme_session_on_a_one_node_slurm(tmp_path, site):
    """workflows/README.md's session on workflows/ci/slurm's cluster, as shown: up, a sweep through
    sbatch, sacct on its jobs, down. Last in this file, since it stops the cluster (and starts it
    again after, for whatever runs next)."""
    conf = Path("/etc/slurm/slurm.conf")
    ours = conf.is_file() and "# written by spinbounce's workflows/ci/slurm" in conf.read_text()
    if not ours or site != {"SPINBOUNCE_SLURM_PARTITION": "ci", "SPINBOUNCE_SLURM_ACCOUNT": "root"}:
        # it stops the cluster: never a SLURM that workflows/ci/slurm did not set up
        pytest.skip(f"the README's session runs on workflows/ci/slurm's own cluster (partition ci, account root): "
                    f"{conf} is {'its' if ours else 'not its'}, and the site is {site}")
    wait_until_idle()
    page = examples.Page("workflows/README.md", tmp_path, examples.base_env())
    try:
        assert page.run_blocks((WORKFLOW / "README.md").read_text(), {"slurm"}, only=True) == 1
    finally:
        subprocess.run([str(WORKFLOW / "ci" / "slurm"), "up"], check=True, capture_output=True, timeout=600)
    assert (tmp_path / "results" / "mu" / "fit.txt").is_file()
