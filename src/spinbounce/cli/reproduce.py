"""spinbounce reproduce: the paper's figures 2-7 and its claims, in one go."""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

from ..studies.claims import Claim, counts, evaluate_claims, write_claims

HELP = ("regenerate the paper's figures 2-7 and check its claims (into a folder of their own; "
        "--out figures updates the repository's stored ones)")


@dataclass
class Reproduction:
    """What one ``reproduce`` made: the figures' records, the judged claims and CLAIMS.md."""

    out: Path
    records: list[dict]
    claims: list[Claim]
    claims_md: Path
    seconds: float


def register(sub) -> None:
    p = sub.add_parser("reproduce", help=HELP, description=HELP + ".")
    p.add_argument("--out", type=Path, default=Path("spinbounce-reproduced"), metavar="DIR",
                   help="figures, their metadata and CLAIMS.md (default %(default)s; the repository keeps its "
                        "own in figures/)")
    p.add_argument("--run-dir", type=Path, default=Path("spinbounce-runs") / "reproduce", metavar="DIR",
                   help="LAMMPS run folders of the figures and claims (default %(default)s)")
    p.set_defaults(handler=run)


def reproduce(out: Path, run_dir: Path, log=print) -> Reproduction:
    """Figures 2-7 into ``out`` and the claims into ``out``/CLAIMS.md, runs under ``run_dir``."""
    from ..figures import make_figures

    started = time.perf_counter()
    log(f"figures 2-7 -> {out}")
    records = make_figures(out, runs=Path(run_dir) / "figures", log=log)
    log(f"claims (LAMMPS runs in {Path(run_dir) / 'claims'}):")
    claims = evaluate_claims(Path(run_dir) / "claims", log=log)
    md, _ = write_claims(claims, out)
    return Reproduction(Path(out), records, claims, md, time.perf_counter() - started)


def summary(made: Reproduction) -> list[str]:
    """The closing lines: where the figures went, their worst deviation, the verdict counts."""
    worst = max(made.records, key=lambda r: r["max_deviation_exact"])
    tally = counts(made.claims)
    return [f"done in {made.seconds:.0f} s:",
            f"  {len(made.records)} figures in {made.out}/ (PNG, PDF, JSON); largest LAMMPS-theory deviation "
            f"{worst['max_deviation_exact']:.1e} ({worst['figure']})",
            f"  {made.claims_md}: {len(made.claims)} claims: " + ", ".join(f"{n} {v}" for v, n in tally.items())]


def run(args) -> int:
    made = reproduce(args.out, args.run_dir)
    for line in summary(made):
        print(line)
    return 1 if counts(made.claims)["unresolved"] else 0
