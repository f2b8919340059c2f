"""spinbounce reproduce: the paper's figures 2-7, its claims and the studies beyond it, in one go."""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from ..catalogue import LISTED, PRODUCTS, product_names
from .options import name_list, out_folder, replace_flag, worker_count

if TYPE_CHECKING:
    from ..studies.claims import Claim

HELP = ("regenerate the paper's figures 2-7, judge its claims and make the studies beyond it (into a folder of "
        "their own; --out figures updates the repository's stored ones)")


@dataclass
class Reproduction:
    """What one ``reproduce`` made: every JSON record by name, the judged claims, CLAIMS.md."""

    out: Path
    records: dict[str, dict]
    claims: list[Claim]
    claims_md: Path
    seconds: float

    @property
    def figures(self) -> list[dict]:
        """The paper's figures' records, fig2 to fig7."""
        return [record for name, record in self.records.items() if name.startswith("fig")]


def register(sub) -> None:
    listing = "; ".join(f"{p.name}: {p.what} ({p.command})" for p in PRODUCTS)
    elsewhere = "; ".join(f"{command}: {what}" for command, what, _ in LISTED)
    p = sub.add_parser("reproduce", help=HELP, description=f"{HELP}. Makes {listing}. Not run here: {elsewhere}.")
    p.add_argument("--out", type=out_folder, default=Path("spinbounce-reproduced"), metavar="DIR",
                   help="figures, their JSON records, CLAIMS.md and the studies' reports (default %(default)s; the "
                        "repository keeps its own in figures/)")
    p.add_argument("--runs", type=out_folder, default=Path("spinbounce-runs") / "reproduce", metavar="DIR",
                   help="LAMMPS run folders, one per product, and gases/ for the gases more than one "
                        "shows, run once (default %(default)s)")
    replace_flag(p)
    p.add_argument("--only", type=name_list("product", product_names), default=None, metavar="NAME[,NAME...]",
                   help=f"make only these products (from {', '.join(product_names())}); the claims are judged only "
                        "when 'claims' is among them")
    p.add_argument("--workers", type=worker_count, default=None, metavar="N",
                   help="make products side by side in N processes (default: one per core this process may use; "
                        "the output reads the same, each product's lines together and in order)")
    p.set_defaults(handler=run)


def reproduce(out: Path, runs: Path, log=print, only=None, workers: int | None = None) -> Reproduction:
    """Every product of :data:`spinbounce.catalogue.PRODUCTS` (``only``: those named) into ``out``,
    runs under ``runs``, side by side on ``workers`` processes (default: one per core this process
    may use; :mod:`spinbounce.making`)."""
    from ..making import make_products
    from ..outputs import check_outputs
    from ..studies.claims import Claim
    from ..workers import cores

    started = time.perf_counter()
    chosen = [p for p in PRODUCTS if only is None or p.name in only]
    check_outputs(out, [file for product in chosen for file in product.files])  # before any product runs
    records = make_products(chosen, Path(out), Path(runs), log, workers or cores())
    claims = [Claim(**claim) for claim in records["claims"]["claims"]] if "claims" in records else []
    return Reproduction(Path(out), records, claims, Path(out) / "CLAIMS.md", time.perf_counter() - started)


def summary(made: Reproduction) -> list[str]:
    """The closing lines: where everything went, the paper figures' worst deviation, the verdicts."""
    from ..studies.claims import counts

    worst = max(made.figures, key=lambda r: r["max_deviation_exact"])
    tally = counts(made.claims)
    lines = [f"done in {made.seconds:.0f} s: {len(made.records)} JSON records in {made.out}/",
             f"  made: {', '.join(product_names())}",
             f"  figures 2-7: largest LAMMPS-theory deviation {worst['max_deviation_exact']:.1e} ({worst['figure']})",
             f"  {made.claims_md}: {len(made.claims)} claims: " + ", ".join(f"{n} {v}" for v, n in tally.items())]
    lines += [f"  not run here: {command} ({what}; {why})" for command, what, why in LISTED]
    return lines


def run(args) -> int:
    from ..studies.claims import counts

    made = reproduce(args.out, args.runs, only=args.only, workers=args.workers)
    if args.only is not None:
        print(f"done in {made.seconds:.0f} s: {', '.join(sorted(made.records))} in {made.out}/")
    else:
        print("\n".join(summary(made)))
    return 1 if counts(made.claims)["unresolved"] else 0
