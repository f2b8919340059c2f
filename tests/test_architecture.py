"""The shape of the code: layers, no import cycle, short modules, one definition per decision.

The shape of the code: layers with one direction of flow (imports inside functions count),
no module past 400 lines, one definition of each shared decision (the atomic write, the timestep rule, which theory applies, the
LAMMPS version). Read from the source files, not from imports, so nothing here runs LAMMPS.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent / "src" / "spinbounce"
MAX_LINES = 400


def _modules() -> dict[str, Path]:
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


#: The layers, bottom first: a module imports only from its own layer or below, wherever the
#: import stands (module level or inside a function: a lazy import is still a dependency).
#: The errors a user sees and the unit of declaration import nothing; the exact references know
#: nothing else; the contact laws' sub-models declare their coefficients and answer from the
#: references; the model (parameters, contact law, step rule) only them; the engine (what
#: decks share, runner, dumps, records, the outputs writer, row checks, the step probe, worker processes) knows no scene; each scene
#: is a folder on the engine; the pipeline runs any scene; extrapolation is a run mode; sweeps and fits use all of that; studies and figures are made from
#: sweeps and runs; the API and the catalogue of products (and its making) call them; the CLI calls the API.
LAYERS = (
    ("errors", "declaration"),
    ("exact",),
    ("laws",),
    ("model",),
    ("lammps", "records", "outputs", "checks", "stepping", "workers"),
    ("scenes",),
    ("pipeline",),
    ("extrapolation",),
    ("sweeps", "fitting", "fitting_stream"),
    ("studies", "figures"),
    ("api", "catalogue", "making"),
    ("cli", "__main__"),
)


def _layer(module: str) -> int | None:
    """The layer of ``spinbounce.<top>...``; None for the package itself (its version, its lazy API)."""
    top = module.split(".")[1] if "." in module else ""
    for index, names in enumerate(LAYERS):
        if top in names:
            return index
    return None if not top else -1


def _typing_only(tree: ast.AST) -> set[int]:
    """The nodes under ``if TYPE_CHECKING:``: annotations, not dependencies."""
    return {id(inner) for node in ast.walk(tree) if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)
            for statement in node.body for inner in ast.walk(statement)}


def _imports(name: str, path: Path, modules: dict) -> set[str]:
    """The spinbounce modules ``name`` imports anywhere in its code (typing-only imports aside)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    tree = ast.parse(path.read_text())
    skip = _typing_only(tree)
    found = set()
    for node in ast.walk(tree):
        if id(node) in skip:
            continue
        if isinstance(node, ast.ImportFrom):
            base = package.split(".")[: len(package.split(".")) - node.level + 1] if node.level else []
            target = ".".join(base + ([node.module] if node.module else [])) if node.level else node.module or ""
            for alias in node.names:
                candidate = f"{target}.{alias.name}"
                found.add(candidate if candidate in modules else target)
        elif isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
    return {m for m in found if m in modules and m != name}


def _graph() -> dict[str, set[str]]:
    modules = _modules()
    return {name: {m for m in _imports(name, path, modules) if not name.startswith(m + ".")}
            for name, path in modules.items()}


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    state = {}

    def visit(node, trail):
        state[node] = "open"
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                return trail + [node, nxt]
            if nxt not in state:
                found = visit(nxt, trail + [node])
                if found:
                    return found
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node, [])
            if found:
                return found
    return None


def test_no_import_cycle_between_modules():
    graph = _graph()
    assert _cycle(graph) is None, f"import cycle: {' -> '.join(_cycle(graph))}"


def test_the_cycle_check_sees_imports_inside_functions():
    # the check must not pass by missing lazy imports: the API's imports of the pipeline and
    # the sweeps stand inside functions, and the graph holds them
    graph = _graph()
    assert "spinbounce.pipeline" in graph["spinbounce.api.collisions"]
    assert "spinbounce.sweeps" in graph["spinbounce.api.sweeping"]
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) is not None


def test_every_module_has_a_layer():
    unplaced = sorted(name for name in _modules() if _layer(name) == -1)
    assert not unplaced, f"modules in no layer of LAYERS: {unplaced}"


def test_no_module_imports_from_a_layer_above_its_own():
    upward = sorted(f"{name} -> {target}" for name, targets in _graph().items() for target in targets
                    if _layer(name) is not None and _layer(target) is not None and _layer(target) > _layer(name))
    assert not upward, upward


def test_no_module_over_400_lines():
    long = {str(p.relative_to(PACKAGE)): n for p in PACKAGE.rglob("*.py")
            if (n := len(p.read_text().splitlines())) > MAX_LINES}
    assert not long, long


def _code(path: Path) -> str:
    """A module's code without comments and strings (docstrings may name a rule; code may not)."""
    tokens = tokenize.generate_tokens(io.StringIO(path.read_text()).readline)
    return " ".join(tok.string for tok in tokens if tok.type not in (tokenize.COMMENT, tokenize.STRING))


def _files_matching(pattern: str) -> set[str]:
    rx = re.compile(pattern)
    return {str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py") if rx.search(_code(p))}


def test_one_atomic_writer():
    # only records.py renames a finished temporary file over its target
    assert _files_matching(r"os \. replace \(|\. rename \(") == {"records.py"}


def test_one_place_asks_lammps_for_its_version():
    assert _files_matching(r"\. version \( \)") == {"lammps/runner.py"}
    assert _files_matching(r"def lammps_version") == {"lammps/runner.py", "records.py"}


def test_one_timestep_rule():
    # the mid-step form t/(N + 1/2) is computed in model/timestep.py only; a pair batch computes
    # the converse, the lead that puts each pair's end mid-step at a given dt
    assert _files_matching(r"/ \( .* \+ 0\.5 \)") == {"model/timestep.py"}
    assert _files_matching(r"\( steps \+ 0\.5 \)") <= {"model/timestep.py", "scenes/pair/scene.py"}


def test_one_place_decides_which_theory_applies():
    # predictions come from exact/choose.py (exact/per_state.py runs the solver it chose a state at a
    # time); the solvers behind it are imported elsewhere only to measure them (solver_speed) or, for
    # the published benchmarks, as the independent oracle whose regime patterns the report shows
    solvers = _files_matching(r"import [\w ,]*\b(oracle|coulomb)\b")
    assert "exact/choose.py" in solvers
    assert solvers <= {"exact/choose.py", "exact/per_state.py", "studies/solver_speed.py",
                       "studies/validation/run.py"}, solvers


def test_every_test_module_says_in_one_line_what_it_holds():
    # a reader picks the file from its first line: a docstring whose first line is whole
    tests = Path(__file__).resolve().parent
    unsaid = []
    for path in sorted(tests.glob("*.py")):
        doc = ast.get_docstring(ast.parse(path.read_text())) or ""
        lines = doc.splitlines()
        if not lines or len(lines[0]) > 120 or (len(lines) > 1 and lines[1].strip()):
            unsaid.append(path.name)
    assert not unsaid, f"test modules without a one-line summary: {unsaid}"


def _law_keywords() -> set[str]:
    from spinbounce.laws import NORMAL, STYLES

    return set(NORMAL) | set(STYLES)


def _keyword_branches(text: str, keywords: set[str]) -> list[int]:
    """Lines where a registered keyword is compared (==, !=, in a membership test), not
    iterated over (``for wall in ("classic", "granular")`` runs a study of both)."""
    tokens = [t for t in tokenize.generate_tokens(io.StringIO(text).readline)
              if t.type not in (tokenize.NL, tokenize.COMMENT, tokenize.INDENT, tokenize.DEDENT)]
    lines = []
    for k, token in enumerate(tokens):
        if token.type != tokenize.STRING or token.string.strip("\"'") not in keywords:
            continue
        before = [t.string for t in tokens[max(0, k - 2):k]]
        after = tokens[k + 1].string if k + 1 < len(tokens) else ""
        membership = before[-1:] == ["in"] or before == ["in", "("]
        if membership:
            start = max(j for j in range(k) if j == 0 or tokens[j - 1].type == tokenize.NEWLINE)
            membership = "for" not in [t.string for t in tokens[start:k]]
        if membership or before[-1:] in (["=="], ["!="]) or after in ("==", "!="):
            lines.append(token.start[0])
    return lines


def test_no_code_outside_the_laws_branches_on_a_laws_keyword():
    # consumers ask a sub-model's flags; comparing with a registered keyword anywhere else is a
    # branch on a law's name
    keywords = _law_keywords()
    assert {"hooke", "hertz", "granular", "classic"} <= keywords
    found = [f"{path.relative_to(PACKAGE)}:{line}" for path in PACKAGE.rglob("*.py")
             if path.relative_to(PACKAGE).parts[0] != "laws"
             for line in _keyword_branches(path.read_text(), keywords)]
    assert not found, found


def test_no_template_branches_on_a_laws_keyword():
    # a deck's comments and words come from the law's flags and keyword, never a comparison
    # with a name (a hertz/material deck once got the Hookean header that way)
    compared = re.compile(r"""(==|!=|\bin)\s*["']([^"']+)["']|["']([^"']+)["']\s*(==|!=)""")
    keywords = _law_keywords()
    found = [f"{path.relative_to(PACKAGE)}:{n}" for path in PACKAGE.rglob("*.j2")
             for n, line in enumerate(path.read_text().splitlines(), 1)
             for m in compared.finditer(line) if (m.group(2) or m.group(3)) in keywords]
    assert not found, found


def test_the_keyword_check_sees_a_branch_and_not_an_iteration():
    snippet = ('if model.normal == "hertz" or "classic" != wall:\n    pass\n'
               'ok = wall in ("hooke", "y")\n'
               'for wall in ("classic", "granular"):\n    pass\n'
               'sides = {w: 1 for w in ("classic", "granular")}\n')
    assert _keyword_branches(snippet, _law_keywords()) == [1, 1, 3]


def test_every_scene_is_one_folder_with_its_template_and_its_theory():
    """A scene's class, template and the note of what it is checked against live together."""
    folders = [p for p in (PACKAGE / "scenes").iterdir() if p.is_dir() and not p.name.startswith("__")]
    assert {p.name for p in folders} >= {"collision", "frozen", "pair", "two_walls"}
    for folder in folders:
        assert list(folder.glob("*.lmp.j2")), f"{folder.name}: no template"
        assert (folder / "theory.md").read_text().startswith("# "), f"{folder.name}: no theory.md"
    templates = {p.relative_to(PACKAGE).parts[0] for p in PACKAGE.rglob("*.lmp.j2")}
    assert templates <= {"scenes", "studies"}, f"templates outside a scene or study folder: {templates}"
