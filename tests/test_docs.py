"""The documentation site builds without a warning, and every example on it runs as shown.

Examples are the fenced blocks of docs/**/*.md, run page by page in a fresh folder, in order, by
tests/examples.py (which says how each kind of block is checked). A block preceded by
``<!-- example: slow -->`` takes more than ten seconds (the paper's reproduction, the workflow,
the Hertz study): it runs when SPINBOUNCE_SLOW=1, not by default, so that this file stays near a
minute.
"""

from __future__ import annotations

import contextlib
import importlib
import importlib.util
import io
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import examples

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
PAGES = sorted(p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md"))
#: Pages whose quick examples still take seconds of LAMMPS (measured 6 s and 5 s): slow tests.
SLOW_PAGES = {"how-to/pair.md", "how-to/two-walls.md"}
RUN_SLOW = os.environ.get("SPINBOUNCE_SLOW") == "1"
#: The page whose slow example is `spinbounce reproduce`: checked against the session's one reproduction
#: (conftest.reproduction) by test_the_reproduce_tutorial_prints_the_sessions_reproduction, not run again.
REPRODUCED = "tutorials/reproduce.md"


def _mkdocs_available() -> bool:
    if importlib.util.find_spec("mkdocs") is None or importlib.util.find_spec("mkdocstrings") is None:
        if os.environ.get("CI") == "true":
            pytest.fail("mkdocs and mkdocstrings are not installed: CI must install the docs extra")
        return False
    return True


@pytest.mark.slow  # mkdocs builds the whole site
def test_site_builds_strictly(tmp_path):
    """Warnings are errors: a broken link, anchor, nav entry or API reference fails the build."""
    if not _mkdocs_available():
        pytest.skip("mkdocs/mkdocstrings not installed (pip install -e '.[docs]'); CI=true makes this a failure")
    build = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(ROOT / "mkdocs.yml"),
                            "-d", str(tmp_path / "site")], capture_output=True, text=True, env=examples.base_env(), cwd=ROOT)
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


@pytest.mark.lammps
@pytest.mark.every_case  # each session (page) its own check: the quick run keeps them all
@pytest.mark.parametrize("page", [pytest.param(page, marks=[pytest.mark.slow] if page in SLOW_PAGES else [])
                                  for page in PAGES])
def test_page_examples(page, tmp_path):
    kinds = {"slow"} if RUN_SLOW and page != REPRODUCED else set()
    # the pages' Snakemake runs need no cluster (the session on a real SLURM is test_slurm's)
    env = examples.without_controller(examples.base_env())
    examples.Page(page, tmp_path, env).run_blocks((DOCS / page).read_text(), kinds)


@pytest.mark.lammps
def test_the_reproduce_tutorial_prints_the_sessions_reproduction(reproduction, tmp_path, monkeypatch):
    """The tutorial's `spinbounce reproduce --out paper --runs paper-runs` through the command (its options
    parsed, its summary printed), its products the session's one reproduction (conftest.reproduction: its log
    replayed, its folder named as the page names it): the four minutes are spent once."""
    import dataclasses

    from spinbounce.cli import reproduce as reproduce_cli

    made, lines = reproduction
    asked = []

    def replay(out, runs, only=None, workers=None):
        asked.append((out, runs, only))
        for line in lines:
            print(line.replace(str(made.out), str(out)))
        return dataclasses.replace(made, out=out, claims_md=out / made.claims_md.name)

    monkeypatch.setattr(reproduce_cli, "reproduce", replay)
    page = examples.Page(REPRODUCED, tmp_path, examples.base_env())
    assert page.run_blocks((DOCS / REPRODUCED).read_text(), {"slow"}, only=True) == 1
    assert asked == [(Path("paper"), Path("paper-runs"), None)]


def test_generated_scene_file_example_is_valid():
    """The scene-file reference shows spinbounce.sweeps.spec's example: it must be a valid sweep."""
    sys.path.insert(0, str(DOCS))
    try:
        from gen_reference import scene_file_example
    finally:
        sys.path.remove(str(DOCS))
    examples.check_toml(scene_file_example())


def test_examples_are_checked_against_their_output():
    """The matcher itself: '...' spans lines or text, and anything else must match exactly."""
    shown = "collision: dt = ...\n...\nstatus ok"
    assert examples.pattern(shown).fullmatch("collision: dt = 0.005\nline\nline\nstatus ok\n")
    assert not examples.pattern(shown).fullmatch("collision: dt = 0.005\nstatus inaccurate\n")
    assert not examples.pattern("a\nb").fullmatch("a\nb\nc\n")
    assert examples.console("$ a \\\n   --b c\nout") == [("a --b c", "out")]


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
