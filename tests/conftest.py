"""Shared fixtures, and the quick default run that leaves the slow tests to SPINBOUNCE_SLOW=1.

Shared fixtures, and the quick default run: tests marked ``slow`` (or that read the
whole reproduction) run only with SPINBOUNCE_SLOW=1, which ``.ci/run`` sets. Of a LAMMPS test run
over several cases (``pytest.mark.parametrize``), the quick run takes the first case and leaves the
others to the slow run: every check runs on one case in minutes, every case in CI.

The tests run on every core (pytest-xdist, ``-n auto`` in pyproject.toml; ``-n 0`` runs them in one
process). Tests that share a session's product, or the one SLURM, go to one worker together
(:data:`WORKER_GROUPS`), so that nothing is made twice and no two SLURM sessions queue behind each other;
so do a module's tests that share a fixture made once per module.
"""

import os
import sys

import pytest

# The tests' subprocesses (the fuzz set's 273 invocations, the pages' commands, the test workers themselves) load
# spinbounce's compiled modules as an ordinary install does: an environment that forbids writing them
# (PYTHONDONTWRITEBYTECODE, set on this project's machines) made each recompile the sources, 0.1-0.2 s a process.
os.environ.pop("PYTHONDONTWRITEBYTECODE", None)
sys.dont_write_bytecode = False

#: Set to 1 to run every test, the slow ones included (CI does; see .ci/run).
SLOW_SWITCH = "SPINBOUNCE_SLOW"
#: Fixtures that make a slow product once per session: a test that uses one is slow too.
SLOW_FIXTURES = {"reproduction"}
#: xdist groups (``--dist loadgroup``): the tests that read the reproduction, and those that use SLURM.
WORKER_GROUPS = {"reproduction": lambda item: bool(SLOW_FIXTURES & set(getattr(item, "fixturenames", ()))),
                 "slurm": lambda item: item.get_closest_marker("slurm") is not None}


def run_slow() -> bool:
    return os.environ.get(SLOW_SWITCH) == "1"


@pytest.hookimpl(tryfirst=True)  # before xdist reads the groups into the test ids
def pytest_collection_modifyitems(config, items):
    """Deselect the slow tests unless SPINBOUNCE_SLOW=1, and say so (never silently)."""
    for item in items:
        if SLOW_FIXTURES & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.slow)
        for group, member in WORKER_GROUPS.items():
            if member(item):
                item.add_marker(pytest.mark.xdist_group(group))
        if not item.get_closest_marker("xdist_group") and _uses_module_fixture(item):
            item.add_marker(pytest.mark.xdist_group(f"module:{item.module.__name__}"))
    if not (config.option.keyword or any("::" in arg for arg in config.args)):  # cases asked for by name all run
        _first_cases_only(items)
    if run_slow():
        return
    slow = [item for item in items if item.get_closest_marker("slow")]
    if slow:
        config.hook.pytest_deselected(items=slow)
        items[:] = [item for item in items if not item.get_closest_marker("slow")]
        config._spinbounce_slow_left = len(slow)
        if hasattr(config, "workeroutput"):  # an xdist worker: the controller reports it
            config.workeroutput["slow_left"] = len(slow)


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """xdist's controller: every worker collects every test, so each counts the same slow tests left out."""
    left = getattr(node, "workeroutput", {}).get("slow_left", 0)
    node.config._spinbounce_slow_left = max(left, getattr(node.config, "_spinbounce_slow_left", 0))


def _uses_module_fixture(item) -> bool:
    """Whether a test asks, itself or through the fixtures it asks for, for one made once per module (or class),
    such as a small gas: such tests of a module go to one worker together, so that it is made once, not once on
    each worker that runs one (an autouse fixture no test asks for does not count)."""
    info = getattr(item, "_fixtureinfo", None)
    asked, seen = list(info.argnames) if info is not None else [], set()
    while asked:
        name = asked.pop()
        for definition in info.name2fixturedefs.get(name, ()) if name not in seen else ():
            if definition.scope in ("module", "class"):
                return True
            asked.extend(definition.argnames)
        seen.add(name)
    return False


def _first_cases_only(items) -> None:
    """Of each parametrised LAMMPS test (not marked ``every_case``), mark every case but its first quick
    one slow."""
    kept = set()
    for item in items:
        if not hasattr(item, "callspec") or not item.get_closest_marker("lammps") or item.get_closest_marker("slow"):
            continue
        if item.get_closest_marker("every_case"):
            continue
        test = (item.module.__name__, item.cls.__name__ if item.cls else "", item.originalname)
        if test in kept:
            item.add_marker(pytest.mark.slow)
        kept.add(test)


def pytest_configure(config):
    """The compiled references compiled once, here, before the tests fan out (xdist's controller, or the one
    process of ``-n 0``): a fresh machine's first solver would otherwise pay it inside some test, with a
    subprocess's time limit running (exact.first_use: 32 to 55 s of one core, once a machine)."""
    if hasattr(config, "workerinput"):
        return
    from spinbounce.exact import first_use, pair_capped_batch  # noqa: F401 (it imports every pair solver)

    seconds = first_use.compile_all()
    if sum(seconds.values()) > 1.0:
        print(f"the compiled references compiled in {sum(seconds.values()):.0f} s", file=sys.stderr)


def pytest_report_header(config):
    if run_slow():
        return f"{SLOW_SWITCH}=1: every test runs, the slow ones included"
    return f"the quick run: tests marked slow are deselected (run them with {SLOW_SWITCH}=1, as CI does)"


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    left = getattr(config, "_spinbounce_slow_left", 0)
    if left:
        terminalreporter.write_line(f"{left} slow test(s) not run: {SLOW_SWITCH}=1 python -m pytest runs them (CI does)")


@pytest.fixture
def run_dir(tmp_path):
    """A fresh folder for one LAMMPS run."""
    path = tmp_path / "run"
    path.mkdir()
    return path


@pytest.fixture(scope="session")
def reproduction(tmp_path_factory):
    """Everything `spinbounce reproduce` makes (catalogue.PRODUCTS: figures 2-7, the claims and the
    studies beyond the paper, about 4 minutes), made once per session by its own function: the figure,
    claim, stored-record and command tests all read this one result."""
    from spinbounce.cli.reproduce import reproduce

    root = tmp_path_factory.mktemp("reproduce")
    lines = []
    made = reproduce(root / "figures", root / "runs", log=lines.append)
    return made, lines


@pytest.fixture(scope="session")
def figures_made(reproduction):
    """(out folder, figure records by name, the one log line of each figure)."""
    from spinbounce.figures import FIGURES

    made, lines = reproduction
    figure_lines = [line for line in lines if line.split(":")[0] in FIGURES]
    return made.out, {r["figure"]: r for r in made.figures}, figure_lines


@pytest.fixture(scope="session")
def claims_made(reproduction):
    """The judged claims, in order."""
    return reproduction[0].claims
