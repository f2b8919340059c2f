"""Runs the fenced examples of a Markdown page, in order, in one folder, and checks what they print.

Used by test_docs (docs/**/*.md), test_workflow and test_slurm (workflows/README.md):

* ``console``: each ``$ command`` runs (``spinbounce ...`` in this process, anything else in
  bash; a line ending in ``\\`` goes on on the next) and its output must match the lines below
  it; ``...`` on a line of its own stands for any lines, and inside a line for any text
  (timings, job ids, absolute paths). ``export NAME=VALUE ...`` sets variables for the page's
  later commands;
* ``pycon``: a doctest (ELLIPSIS, NORMALIZE_WHITESPACE), one namespace per page;
* a block with ``title="FILE"`` is written to FILE before the page's later examples;
* ``toml`` scene files are validated as sweeps; ``text`` blocks are shown, not run.

A block preceded by ``<!-- example: KIND -->`` runs only when the caller asks for KIND: ``slow``
(over ten seconds), ``slurm`` (needs a running SLURM).
"""

from __future__ import annotations

import atexit
import contextlib
import doctest
import functools
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import textwrap
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FENCE = re.compile(r"(?:<!-- example: (?P<kind>\w+) -->\n)?"
                   r"^(?P<indent> *)```(?P<info>[^\n]*)\n(?P<body>.*?)^(?P=indent)```$", re.M | re.S)
#: Folders of the repository that examples read (workflows/, tests/reference/), linked into
#: each page's working folder as if it were the repository's top folder.
LINKED = ("workflows", "tests")


def base_env(**extra: str) -> dict[str, str]:
    """This interpreter's environment with spinbounce importable and its scripts first on PATH."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")]))
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), env.get("PATH", "")])
    return {**env, **extra}


def without_controller(env: dict[str, str]) -> dict[str, str]:
    """``env`` for a Snakemake run that needs no cluster. Snakemake's SLURM executor plugin runs
    ``scontrol show config`` as it is imported (to word a help text), which waits 10 s for a controller
    when a SLURM client is installed and none is up (this machine between CI runs): a ``scontrol`` that
    answers at once that there is none stands first on PATH. The tests on a real SLURM do not use it."""
    return {**env, "PATH": os.pathsep.join([str(_no_controller()), env.get("PATH", "")])}


@functools.cache
def _no_controller() -> Path:
    folder = Path(tempfile.mkdtemp(prefix="spinbounce-no-slurm-"))
    atexit.register(shutil.rmtree, folder, True)
    stub = folder / "scontrol"
    stub.write_text("#!/bin/sh\necho 'scontrol: no controller here (a test stand-in)' >&2\nexit 1\n")
    stub.chmod(0o755)
    return folder


def pattern(expected: str) -> re.Pattern:
    """Expected output as a regex: '...' alone on a line is any lines, within a line any text."""
    parts = []
    for line in expected.splitlines():
        if line.strip() == "...":
            parts.append(r"(?:[^\n]*\n)*?")
        else:
            parts.append(".*?".join(re.escape(piece) for piece in line.rstrip().split("...")) + r"[ \t]*\n")
    return re.compile("".join(parts), re.S)


def normalised(text: str) -> str:
    """Trailing blanks dropped, tabs as a terminal shows them."""
    return "".join(line.expandtabs().rstrip() + "\n" for line in text.splitlines())


def console(body: str) -> list[tuple[str, str]]:
    """(command, expected output) pairs of a console block."""
    pairs: list[list] = []
    going_on = False
    for line in body.splitlines():
        command = going_on or line.startswith("$ ")
        if going_on:
            pairs[-1][0] += " " + line.strip().removesuffix("\\").strip()
        elif command:
            pairs.append([line[2:].removesuffix("\\").strip(), []])
        else:
            assert pairs, f"output before any command: {line!r}"
            pairs[-1][1].append(line)
        going_on = command and line.endswith("\\")  # an output line may end in a backslash too
    return [(command, "\n".join(lines)) for command, lines in pairs]


class Page:
    """One page's examples run in ``folder``: its shell variables and Python namespace carry over."""

    def __init__(self, name: str, folder: Path, env: dict[str, str]):
        self.name, self.folder, self.env, self.namespace = name, folder, env, {}
        for linked in LINKED:
            if not (folder / linked).exists():
                (folder / linked).symlink_to(ROOT / linked)

    def run(self, command: str) -> str:
        """One shell line's output (stdout and stderr, in order)."""
        argv = shlex.split(command)
        if argv[0] == "export":
            self.env.update(word.split("=", 1) for word in argv[1:])
            return ""
        if argv[0] != "spinbounce":
            done = subprocess.run(["bash", "-c", command], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                  env={**self.env, "PYTHONUNBUFFERED": "1"}, cwd=self.folder, timeout=900)
            return done.stdout
        from spinbounce import cli

        with contextlib.redirect_stdout(io.StringIO()) as text, contextlib.redirect_stderr(text), \
                contextlib.chdir(self.folder):
            try:
                cli.main(argv[1:])
            except SystemExit as exc:  # --version and errors exit through argparse
                if exc.code not in (None, 0, 1, 2, 3, 4):
                    raise
        return text.getvalue()

    def check_console(self, body: str) -> None:
        for command, expected in console(body):
            actual = normalised(self.run(command))
            assert pattern(expected).fullmatch(actual), (
                f"{self.name}: `{command}` printed\n{actual}\nwhich does not match the page's\n{expected}")

    def check_pycon(self, body: str) -> None:
        test = doctest.DocTestParser().get_doctest(body, self.namespace, self.name, self.name, 0)
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
        output = io.StringIO()
        with contextlib.chdir(self.folder):
            runner.run(test, out=output.write, clear_globs=False)
        self.namespace.update(test.globs)  # the page's later blocks use its names
        assert runner.failures == 0, output.getvalue()

    def run_blocks(self, text: str, kinds: set[str] = frozenset(), only: bool = False) -> int:
        """Every block of ``text`` in order (a marked one only if its kind is in ``kinds``; with ``only``,
        no unmarked one, though files of titled blocks are still written); how many ran."""
        ran = 0
        for block in FENCE.finditer(text):
            info, body = block["info"].strip(), textwrap.dedent(block["body"])
            language = info.split()[0] if info else ""
            if title := re.search(r'title="([^"]+)"', info):
                (self.folder / title[1]).write_text(body)
            if (block["kind"] not in kinds) if (block["kind"] or only) else False:
                continue
            if language == "console":
                self.check_console(body)
            elif language == "pycon":
                self.check_pycon(body)
            elif language == "toml":
                check_toml(body)
            else:
                assert language == "text", f"{self.name}: a ```{language} block is neither run nor marked text"
                continue
            ran += 1
        return ran


def check_toml(body: str) -> None:
    from spinbounce.sweeps import spec_from_dict

    spec_from_dict(tomllib.loads(body))
