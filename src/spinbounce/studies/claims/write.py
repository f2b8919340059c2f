"""CLAIMS.md and claims.json: the ledger as a table with its evidence, and as a record."""

from __future__ import annotations

from dataclasses import asdict
from pathlib import Path

from ...records import software, to_json, write_atomic
from .ledger import VERDICTS, Claim, g


def counts(claims: list[Claim]) -> dict[str, int]:
    """How many claims got each verdict, in :data:`VERDICTS` order."""
    return {kind: sum(c.verdict == kind for c in claims) for kind in VERDICTS}


def _cell(value) -> str:
    if isinstance(value, float):
        return g(value, 8)
    return str(value).replace("|", "\\|")


def markdown(claims: list[Claim], provenance: dict) -> str:
    """CLAIMS.md: the verdict table, what each verdict means, and each claim's evidence."""
    tally = counts(claims)
    lines = [
        "# The paper's claims, checked",
        "",
        "Wang and Harrowell, *Translational-rotational coupling during the scattering of a frictional sphere "
        "from a flat surface*: each quantitative claim, the paper's value, the value measured with LAMMPS "
        f"({provenance['lammps_version']}) and the exact theory's value. Regenerate with `spinbounce claims`.",
        "",
        "Verdicts: " + ", ".join(f"{n} {kind}" for kind, n in tally.items()) + ".",
        "",
        "| # | claim | where | paper | LAMMPS | exact theory | verdict |",
        "|---|---|---|---|---|---|---|",
    ]
    for i, c in enumerate(claims, 1):
        lines.append(f"| {i} | {_cell(c.statement)} | {_cell(c.where)} | {_cell(c.paper)} | {_cell(c.lammps)} | "
                     f"{_cell(c.exact)} | **{c.verdict}** |")
    lines += ["", "## Verdicts", ""]
    lines += [f"- **{kind}**: {meaning}." for kind, meaning in VERDICTS.items()]
    lines += ["", "## Evidence", ""]
    lines += [f"{i}. **{c.key}** ({c.verdict}): {c.evidence}" for i, c in enumerate(claims, 1)]
    return "\n".join(lines) + "\n"


def write_claims(claims: list[Claim], out: Path) -> tuple[Path, Path]:
    """``CLAIMS.md`` and ``claims.json`` in ``out`` (atomic writes, with the software's provenance)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    provenance = software()
    md = write_atomic(out / "CLAIMS.md", markdown(claims, provenance))
    js = write_atomic(out / "claims.json", to_json({"claims": [asdict(c) for c in claims], "verdicts": counts(claims),
                                                    "verdict_meanings": VERDICTS, **provenance}))
    return md, js
