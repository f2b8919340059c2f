"""Every quantitative claim of the paper, measured with LAMMPS and set beside the exact theory.

* :mod:`.ledger`: the claim record, the verdict kinds and what every claim shares;
* :mod:`.collisions`, :mod:`.contact`, :mod:`.frozen`, :mod:`.damping`, :mod:`.energy`: the
  claims by topic, one function each; after the paper's, the LAMMPS implementation it used,
  in this build (:mod:`.collisions`), :mod:`.pairs` (two spheres of equal alpha have the
  wall's Omega) and :mod:`.nonlinear` (the prediction for nonlinear contacts, Hertzian and
  Hertz-Mindlin);
* here: the claims in order, and the ledger written as CLAIMS.md and claims.json.
"""

from __future__ import annotations

import warnings
from dataclasses import asdict
from pathlib import Path

from ...outputs import check_outputs, write_output
from ...records import software, to_json
from . import collisions, contact, damping, energy, frozen, gas, nonlinear, pairs
from .ledger import COLLISION_TOL, FROZEN_TOL, VERDICTS, Claim, Runs, g, verdict

__all__ = ["CLAIMS", "COLLISION_TOL", "FROZEN_TOL", "VERDICTS", "Claim", "counts", "evaluate_claims",
           "markdown", "verdict", "write_claims", "make_claims", "CLAIMS_FILES"]

#: The claims, in the paper's order.
CLAIMS = (
    collisions.omega_default, collisions.omega_sign, contact.tau_independent, contact.hertz_tau,
    contact.hard_sphere, contact.tau_damped_longer, contact.tau_damped_vn, frozen.frozen_mean_rolling,
    frozen.frozen_slope, collisions.rolling_unchanged, collisions.harmonic_ratios, collisions.magic_ratio,
    collisions.rough_no_spin, collisions.rough_no_slide, collisions.reflection_angle, damping.eq22,
    frozen.decay_rate, damping.rapid_damping_rolls, damping.eq23_matrix, damping.rolling_vs_rough,
    energy.no_slip_no_loss, energy.friction_less_dissipation, collisions.classic_wall_is_eq1,
    pairs.equal_alpha, nonlinear.hertz_special_speed, nonlinear.mindlin_every_speed, gas.magic_gas_equipartition,
    gas.magic_gas_energy, gas.soft_gas_steady_ratio, gas.soft_gas_relaxation,
)


def evaluate_claims(run_dir: Path, log=print, gases: Path | None = None) -> list[Claim]:
    """Run every claim's LAMMPS measurements under ``run_dir`` (its gases under ``gases``, by default in
    ``run_dir``: :class:`Runs`, read back where an earlier run left them finished); return the claims in order."""
    runs = Runs(run_dir, gases)
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # e.g. stiff-ratio step warnings: every claim states its dt
        for fn in CLAIMS:
            claim = fn(runs)
            log(f"  {claim.key:<22} {claim.verdict}")
            out.append(claim)
    return out


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


#: What :func:`write_claims` writes into its folder.
CLAIMS_FILES = ("CLAIMS.md", "claims.json")


def make_claims(out: Path, runs: Path, log=print, gases: Path | None = None) -> tuple[list[Claim], Path, Path]:
    """Judge the claims (LAMMPS runs in ``runs``, gases in ``gases``: :func:`evaluate_claims`) and write
    :data:`CLAIMS_FILES` into ``out``; a file there that spinbounce did not write is refused before anything runs."""
    check_outputs(out, CLAIMS_FILES)
    claims = evaluate_claims(runs, log=log, gases=gases)
    return claims, *write_claims(claims, out)


def write_claims(claims: list[Claim], out: Path) -> tuple[Path, Path]:
    """``CLAIMS.md`` and ``claims.json`` in ``out`` (atomic writes, with the software's provenance)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    provenance = software()
    md = write_output(out / CLAIMS_FILES[0], markdown(claims, provenance))
    js = write_output(out / CLAIMS_FILES[1], to_json({"claims": [asdict(c) for c in claims], "verdicts": counts(claims),
                                                    "verdict_meanings": VERDICTS, **provenance}))
    return md, js
