"""The README tells the truth: its commands print what it shows and its table is the declaration.

The README tells the truth: every command it shows is run here and prints what it shows,
its Python example runs, and its parameter table is the declaration's.

Output is compared line by line. A line ``  ...`` in the README stands for lines left out.
Numbers must agree to 1e-6 relative (LAMMPS is deterministic on one build; the margin is
for another CPU's rounding), and deviations below 1e-3 (differences of near-equal numbers,
printed to 4 digits) to 1e-2 relative; numbers below 1e-12 are rounding residues. Durations
("3.2 s") and paths are not compared.
"""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

from spinbounce.model.parameters import markdown_table

README = Path(__file__).resolve().parent.parent / "README.md"
NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
DURATION = re.compile(r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)? s\b")


def _blocks(kind: str) -> list[str]:
    return re.findall(rf"```{kind}\n(.*?)```", README.read_text(), flags=re.S)


def _sessions() -> list[list[tuple[str, list[str]]]]:
    """Each console block: its commands, each with the output lines the README shows."""
    sessions = []
    for block in _blocks("console"):
        steps = []
        for line in block.splitlines():
            if line.startswith("$ "):
                steps.append((line[2:], []))
            elif steps:
                steps[-1][1].append(line)
        sessions.append(steps)
    return sessions


def _normal(line: str) -> str:
    line = DURATION.sub("<s>", line)
    return " ".join(tok for tok in line.split() if "/" not in tok or tok.startswith("|"))


def _numbers_agree(expected: str, actual: str) -> bool:
    a, b = NUMBER.findall(expected), NUMBER.findall(actual)
    if NUMBER.sub("#", expected) != NUMBER.sub("#", actual) or len(a) != len(b):
        return False
    for x, y in zip(map(float, a), map(float, b), strict=True):
        scale = max(abs(x), abs(y))
        if scale < 1e-12:  # rounding residues (a fit's 1e-16 scatter): any two agree
            continue
        if abs(x - y) > (1e-2 if scale < 1e-3 else 1e-6) * scale:
            return False
    return True


def _match(expected: list[str], actual: list[str]) -> str | None:
    """None if ``actual`` is what the README shows, else the first line that differs."""
    i = 0
    for k, line in enumerate(expected):
        if line.strip() == "...":
            following = _normal(expected[k + 1]) if k + 1 < len(expected) else None
            while i < len(actual) and (following is None or not _numbers_agree(following, _normal(actual[i]))):
                i += 1
            continue
        if i >= len(actual) or not _numbers_agree(_normal(line), _normal(actual[i])):
            return f"README: {line!r}\nran:    {actual[i] if i < len(actual) else '<no more output>'!r}"
        i += 1
    return None if i == len(actual) else f"more output than the README shows: {actual[i]!r}"


EXIT = re.compile(r"\(exit (\d+)\)\s*$")


def _run(command: str, cwd: Path, shown: list[str]) -> list[str]:
    """Run a README command; it must exit 0, or with the status its shown output ends with."""
    argv = shlex.split(command)
    assert argv[0] == "spinbounce", f"the README shows a command that is not spinbounce's: {command}"
    done = subprocess.run([sys.executable, "-m", "spinbounce.cli", *argv[1:]], cwd=cwd, capture_output=True,
                          text=True, timeout=900)
    status = next((m for m in map(EXIT.search, shown) if m), None)
    assert done.returncode == (int(status.group(1)) if status else 0), done.stderr
    return done.stdout.splitlines()


SESSIONS = _sessions()


def _printed(command: str, cwd: Path, shown: list[str], request) -> list[str]:
    """What the command prints. `spinbounce reproduce` is the session's one reproduction
    (conftest.reproduction: the command's own function; its log, then its summary lines), so
    that its four minutes are spent once; every other command runs here."""
    if command == "spinbounce reproduce":
        from spinbounce.cli.reproduce import summary

        made, lines = request.getfixturevalue("reproduction")
        return [*lines, *summary(made)]
    return _run(command, cwd, shown)


@pytest.mark.lammps
@pytest.mark.every_case  # each session (page) its own check: the quick run keeps them all
@pytest.mark.parametrize("session", [
    # the reproduction (minutes) is a slow test: its session reads the whole reproduction (asked for by name, so
    # it joins the reproduction's worker by its mark: conftest.WORKER_GROUPS sees fixtures a test names)
    pytest.param(s, id=s[0][0].split()[1], marks=[pytest.mark.slow, pytest.mark.xdist_group("reproduction")]
                 if s[0][0] == "spinbounce reproduce" else [])
    for s in SESSIONS])
def test_every_command_prints_what_the_readme_shows(session, tmp_path, request):
    for command, shown in session:
        problem = _match(shown, _printed(command, tmp_path, shown, request))
        assert problem is None, f"$ {command}\n{problem}"


@pytest.mark.lammps
def test_the_python_example_runs(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    for block in _blocks("python"):
        exec(compile(block, "README.md", "exec"), {})
    assert "status ok" in capsys.readouterr().out


def test_the_parameter_table_is_the_declarations():
    text = README.read_text()
    table = text.split("<!-- parameters: generated -->\n", 1)[1].split("\n<!-- /parameters -->", 1)[0]
    assert table == markdown_table()


def test_the_readme_opens_with_the_two_set_up_commands_and_stays_short():
    lines = README.read_text().splitlines()
    setup = [line for line in lines[:25] if line.startswith("python -m pip install -e")]
    assert setup == ['python -m pip install -e . && spinbounce reproduce',
                     'python -m pip install -e ".[test]" && python -m pytest']
    assert len(lines) <= 185  # about 150 lines of prose and real output, the parameter table and a bench run
