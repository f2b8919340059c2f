"""The shape of the code: one direction of flow, no module past 400 lines, one definition
of each shared decision (the atomic write, the timestep rule, which theory applies, the
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


def _imports(name: str, path: Path, modules: dict) -> set[str]:
    """The spinbounce modules ``name`` imports at its top level (run time, not typing-only)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.parse(path.read_text()).body:  # top level only: lazy imports inside functions are calls
        if isinstance(node, ast.ImportFrom):
            base = package.split(".")[: len(package.split(".")) - node.level + 1] if node.level else []
            target = ".".join(base + ([node.module] if node.module else [])) if node.level else node.module or ""
            for alias in node.names:
                candidate = f"{target}.{alias.name}"
                found.add(candidate if candidate in modules else target)
        elif isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
    return {m for m in found if m in modules and m != name}


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
    modules = _modules()
    graph = {name: {m for m in _imports(name, path, modules) if not name.startswith(m + ".")}
             for name, path in modules.items()}
    assert _cycle(graph) is None, f"import cycle: {' -> '.join(_cycle(graph))}"


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
    assert _files_matching(r"\( steps \+ 0\.5 \)") <= {"model/timestep.py", "pairs/scene.py"}


def test_one_place_decides_which_theory_applies():
    # predictions come from theory/choose.py; the solvers behind it are imported elsewhere
    # only to measure them (solver_speed) or, for the published benchmarks, as the
    # independent oracle whose regime patterns the report shows
    solvers = _files_matching(r"import [\w ,]*\b(oracle|coulomb)\b")
    assert "theory/choose.py" in solvers
    assert solvers <= {"theory/choose.py", "studies/solver_speed.py", "studies/validation/run.py"}, solvers
