"""spinbounce claims: every quantitative claim of the paper, measured and judged."""

from __future__ import annotations

from pathlib import Path

from .options import out_folder, out_option

HELP = "check the paper's quantitative claims with LAMMPS and the exact theory; write CLAIMS.md and claims.json"


def register(sub) -> None:
    p = sub.add_parser("claims", help=HELP, description=HELP + ".")
    out_option(p, "CLAIMS.md and claims.json")
    p.add_argument("--runs", type=out_folder, default=Path("spinbounce-runs") / "claims", metavar="DIR",
                   help="LAMMPS run folders (default %(default)s)")
    p.set_defaults(handler=run)


def run(args) -> int:
    from ..studies.claims import make_claims

    print(f"checking the paper's claims (LAMMPS runs in {args.runs}):")
    claims, md, js = make_claims(args.out, args.runs)
    print(f"claims: {md} and {js}")
    return 1 if any(c.verdict == "unresolved" for c in claims) else 0
