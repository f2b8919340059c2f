"""spinbounce references: check fresh runs against the stored reference outputs, or remake them."""

from __future__ import annotations

import sys
import time
from pathlib import Path

from ..model.parameters import SceneError

HELP = "compare fresh runs with the stored reference tables and golden decks (--check), or remake them (--regenerate)"


def register(sub) -> None:
    from ..studies.references.cases import CASES, DEFAULT_DIR

    p = sub.add_parser(
        "references", help=HELP,
        description=HELP + ". Only --regenerate writes into the reference folder; --check runs in a "
                           "temporary folder and exits 1 when any column is beyond its tolerance.")
    mode = p.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", action="store_true",
                      help="run every case afresh and print the largest deviation per case and column")
    mode.add_argument("--regenerate", action="store_true",
                      help="run every case and overwrite the stored tables, golden decks and MANIFEST.json")
    p.add_argument("--dir", type=Path, default=DEFAULT_DIR, metavar="DIR",
                   help="reference folder (default: %(default)s, from the repository's top folder)")
    p.add_argument("--case", action="append", metavar="NAME",
                   choices=[c.name for c in CASES],
                   help="with --check: only this case (repeatable; default: all)")
    p.set_defaults(handler=run)


def _progress(case) -> None:
    if sys.stderr.isatty():
        print(f"  running {case.name} ...", file=sys.stderr, end="\r", flush=True)


def run(args) -> int:
    from ..studies import references

    started = time.perf_counter()
    if args.regenerate:
        if args.case:
            print("spinbounce references: --case works with --check only: --regenerate remakes every case",
                  file=sys.stderr)
            return 2
        try:
            record = references.regenerate(args.dir, progress=_progress)
        except FileNotFoundError as exc:
            print(f"spinbounce references: {exc}", file=sys.stderr)
            return 1
        seconds = time.perf_counter() - started
        print(f"wrote {len(record['cases'])} reference tables, {len(record['decks'])} golden deck files and "
              f"{references.MANIFEST} to {args.dir} in {seconds:.1f} s")
        print(f"LAMMPS {record['lammps_version']}, spinbounce {record['spinbounce_version']}")
        print("review the change with: git diff --stat -- " + str(args.dir))
        return 0
    try:
        report = references.check(args.dir, names=args.case, progress=_progress)
    except FileNotFoundError as exc:  # nothing to compare with: a wrong --dir, refused like any bad value
        raise SceneError("--dir", str(args.dir), str(exc)) from None
    print(references.format_report(report), end="")
    seconds = time.perf_counter() - started
    cases = len(report.deviations)
    if report.ok:
        print(f"all {cases} case(s) and their golden decks reproduce the references in {args.dir} ({seconds:.1f} s)")
        return 0
    print(f"FAILED: {len(report.violations)} violation(s) against {args.dir} ({seconds:.1f} s)")
    return 1
