"""spinbounce reproduce: the paper's figures 2-7 and its claims, in one go."""

from __future__ import annotations

import time
from pathlib import Path

from ..studies.claims import evaluate_claims, write_claims

HELP = "regenerate the paper's figures 2-7 and check its claims (figures/ and figures/CLAIMS.md)"


def register(sub) -> None:
    p = sub.add_parser("reproduce", help=HELP, description=HELP + ".")
    p.add_argument("--out", type=Path, default=Path("figures"), metavar="DIR",
                   help="figures, their metadata and CLAIMS.md (default %(default)s)")
    p.add_argument("--run-dir", type=Path, default=Path("spinbounce-runs") / "reproduce", metavar="DIR",
                   help="LAMMPS run folders of the figures and claims (default %(default)s)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..figures import make_figures

    started = time.perf_counter()
    print(f"figures 2-7 -> {args.out}")
    records = make_figures(args.out, runs=args.run_dir / "figures")
    print(f"claims (LAMMPS runs in {args.run_dir / 'claims'}):")
    claims = evaluate_claims(args.run_dir / "claims")
    md, _ = write_claims(claims, args.out)
    worst = max(records, key=lambda r: r["max_deviation_exact"])
    counts = {v: sum(c.verdict == v for c in claims) for v in ("reproduced", "approximate", "contradicted", "unresolved")}
    print(f"done in {time.perf_counter() - started:.0f} s:")
    print(f"  {len(records)} figures in {args.out}/ (PNG, PDF, JSON); largest LAMMPS-theory deviation "
          f"{worst['max_deviation_exact']:.1e} ({worst['figure']})")
    print(f"  {md}: {len(claims)} claims: " + ", ".join(f"{n} {v}" for v, n in counts.items()))
    return 1 if counts["unresolved"] else 0
