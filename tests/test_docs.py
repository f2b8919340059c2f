"""The documentation site builds without a warning, and every example on it runs as shown.

Examples are the fenced blocks of docs/**/*.md, run page by page in a fresh folder, in order:

* ``console``: each ``$ command`` runs (``spinbounce ...`` in this process, anything else in
  bash) and its output must match the lines below it; ``...`` on a line of its own stands for
  any lines, and inside a line for any text (timings, absolute paths);
* ``pycon``: a doctest (ELLIPSIS, NORMALIZE_WHITESPACE), one namespace per page;
* a block with ``title="FILE"`` is written to FILE before the page's later examples;
* ``toml`` scene files are validated as sweeps; ``text`` blocks are shown, not run.

A console block preceded by ``<!-- example: slow -->`` takes more than ten seconds (the paper's
reproduction, the workflow, the Hertz study): it runs when SPINBOUNCE_SLOW=1, not by
default, so that this file stays near a minute.
"""

from __future__ import annotations

import contextlib
import doctest
import importlib.util
import io
import os
import re
import shlex
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
PAGES = sorted(p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md"))
#: Pages whose quick examples still take seconds of LAMMPS (measured 6 s and 5 s): slow tests.
SLOW_PAGES = {"how-to/pair.md", "how-to/two-walls.md"}
FENCE = re.compile(r"(?P<marker><!-- example: slow -->\n)?^```(?P<info>[^\n]*)\n(?P<body>.*?)^```$", re.M | re.S)
RUN_SLOW = os.environ.get("SPINBOUNCE_SLOW") == "1"
#: Folders of the repository that examples read (workflows/, tests/reference/), linked into
#: each page's working folder as if it were the repository's top folder.
LINKED = ("workflows", "tests")


def _mkdocs_available() -> bool:
    if importlib.util.find_spec("mkdocs") is None or importlib.util.find_spec("mkdocstrings") is None:
        if os.environ.get("CI") == "true":
            pytest.fail("mkdocs and mkdocstrings are not installed: CI must install the docs extra")
        return False
    return True


def _env() -> dict[str, str]:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")]))
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), env.get("PATH", "")])
    return env


def test_site_builds_strictly(tmp_path):
    """Warnings are errors: a broken link, anchor, nav entry or API reference fails the build."""
    if not _mkdocs_available():
        pytest.skip("mkdocs/mkdocstrings not installed (pip install -e '.[docs]'); CI=true makes this a failure")
    build = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(ROOT / "mkdocs.yml"),
                            "-d", str(tmp_path / "site")], capture_output=True, text=True, env=_env(), cwd=ROOT)
    assert build.returncode == 0, build.stdout + build.stderr
    assert "WARNING" not in build.stderr, build.stderr
    for page in ("reference/cli/index.html", "reference/parameters/index.html", "reference/outputs/index.html",
                 "reference/scene-files/index.html", "reference/api/index.html"):
        assert (tmp_path / "site" / page).is_file(), page
    # the math is MathML made at build time (docs/mathml.py): it renders offline, nothing is fetched
    theory = (tmp_path / "site" / "theory" / "index.html").read_text()
    assert theory.count("<math") > 100 and 'class="arithmatex"' not in theory
    pages = [p.read_text() for p in (tmp_path / "site").rglob("*.html")]
    assert not [p for p in pages if "mathjax" in p.lower() or "cdn.jsdelivr" in p]


def _pattern(expected: str) -> re.Pattern:
    """Expected output as a regex: '...' alone on a line is any lines, within a line any text."""
    parts = []
    for line in expected.splitlines():
        if line.strip() == "...":
            parts.append(r"(?:[^\n]*\n)*?")
        else:
            parts.append(".*?".join(re.escape(piece) for piece in line.rstrip().split("...")) + r"[ \t]*\n")
    return re.compile("".join(parts), re.S)


def _normalised(text: str) -> str:
    return "".join(line.rstrip() + "\n" for line in text.splitlines())


def _run(command: str) -> str:
    """One shell line's output (stdout and stderr, in order)."""
    argv = shlex.split(command)
    if argv[0] != "spinbounce":
        done = subprocess.run(["bash", "-c", command], capture_output=True, text=True, env=_env())
        return done.stdout + done.stderr
    from spinbounce import cli

    with contextlib.redirect_stdout(io.StringIO()) as text, contextlib.redirect_stderr(text):
        try:
            cli.main(argv[1:])
        except SystemExit as exc:  # --version and errors exit through argparse
            if exc.code not in (None, 0, 1, 2, 3, 4):
                raise
    return text.getvalue()


def _console(body: str):
    """(command, expected output) pairs of a console block."""
    pairs = []
    for line in body.splitlines():
        if line.startswith("$ "):
            pairs.append([line[2:], []])
        else:
            assert pairs, f"output before any command: {line!r}"
            pairs[-1][1].append(line)
    return [(command, "\n".join(lines)) for command, lines in pairs]


def _check_console(body: str, page: str):
    for command, expected in _console(body):
        actual = _normalised(_run(command))
        assert _pattern(expected).fullmatch(actual), (
            f"{page}: `{command}` printed\n{actual}\nwhich does not match the page's\n{expected}")


def _check_pycon(body: str, page: str, namespace: dict):
    parser = doctest.DocTestParser()
    test = parser.get_doctest(body, namespace, page, page, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    output = io.StringIO()
    runner.run(test, out=output.write, clear_globs=False)
    namespace.update(test.globs)  # the page's later blocks use its names
    assert runner.failures == 0, output.getvalue()


def _check_toml(body: str, page: str):
    from spinbounce.sweeps import spec_from_dict

    spec_from_dict(tomllib.loads(body))


@pytest.mark.lammps
@pytest.mark.parametrize("page", [pytest.param(page, marks=[pytest.mark.slow] if page in SLOW_PAGES else [])
                                  for page in PAGES])
def test_page_examples(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    for name in LINKED:
        (tmp_path / name).symlink_to(ROOT / name)
    namespace: dict = {}
    for block in FENCE.finditer((DOCS / page).read_text()):
        info, body = block["info"].strip(), block["body"]
        title = re.search(r'title="([^"]+)"', info)
        language = info.split()[0] if info else ""
        if title:
            (tmp_path / title[1]).write_text(body)
        if language == "console":
            if block["marker"] and not RUN_SLOW:
                continue
            _check_console(body, page)
        elif language == "pycon":
            _check_pycon(body, page, namespace)
        elif language == "toml":
            _check_toml(body, page)
        else:
            assert language == "text", f"{page}: a ```{language} block is neither run nor marked text"


def test_generated_scene_file_example_is_valid():
    """The scene-file reference shows spinbounce.sweeps.spec's example: it must be a valid sweep."""
    sys.path.insert(0, str(DOCS))
    try:
        from gen_reference import scene_file_example
    finally:
        sys.path.remove(str(DOCS))
    _check_toml(scene_file_example(), "reference/scene-files.md")


def test_examples_are_checked_against_their_output():
    """The matcher itself: '...' spans lines or text, and anything else must match exactly."""
    shown = "collision: dt = ...\n...\nstatus ok"
    assert _pattern(shown).fullmatch("collision: dt = 0.005\nline\nline\nstatus ok\n")
    assert not _pattern(shown).fullmatch("collision: dt = 0.005\nstatus inaccurate\n")
    assert not _pattern("a\nb").fullmatch("a\nb\nc\n")


def _docstring_examples() -> list[tuple[str, str]]:
    """(object, code) for each Python literal block (after '::') in a docstring the API page renders."""
    import ast
    import inspect

    found = []
    for module_name in re.findall(r"^::: ([\w.]+)", (DOCS / "reference" / "api.md").read_text(), re.M):
        module = importlib.import_module(module_name)
        objects = [module] + [v for v in vars(module).values()
                              if getattr(v, "__module__", None) == module_name and inspect.getdoc(v)]
        for obj in objects:
            for block in re.findall(r"::\n\n((?:(?: {4}.*)?\n)+)", (inspect.getdoc(obj) or "") + "\n"):
                code = "\n".join(line[4:] for line in block.splitlines())
                with contextlib.suppress(SyntaxError):
                    ast.parse(code)
                    found.append((f"{module_name}:{getattr(obj, '__name__', '')}", code))
    return found


@pytest.mark.lammps
def test_api_docstring_examples(tmp_path, monkeypatch):
    """The API page's docstring examples run (the API's runs a 4,000-collision sweep with a cap: ~30 s)."""
    examples = _docstring_examples()
    assert examples, "the API page renders no docstring example: the collector is broken"
    if not RUN_SLOW:
        pytest.skip(f"{len(examples)} docstring example(s) take ~30 s: run with SPINBOUNCE_SLOW=1")
    monkeypatch.chdir(tmp_path)
    for where, code in examples:
        with contextlib.redirect_stdout(io.StringIO()):
            exec(compile(code, where, "exec"), {})
