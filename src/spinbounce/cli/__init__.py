"""The ``spinbounce`` command: one subcommand per concern."""

from __future__ import annotations

import argparse
import sys
import warnings

from .. import __version__
from ..lammps.dumps import DumpError
from ..pipeline import ResultError
from ..lammps.runner import LammpsError
from ..model.scenes import PhysicsWarning, SceneError
from ..sweeps import SweepError
from . import accuracy, bench, benchmarks, claims, collide, figures, fit, frozen, hertz, references, reproduce, sweep, theory

COMMANDS = (theory, collide, frozen, sweep, fit, bench, accuracy, benchmarks, figures, hertz, claims, reproduce,
            references)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="spinbounce",
        description="Frictional sphere-wall collisions in LAMMPS against Wang and Harrowell's theory.",
    )
    parser.add_argument("--version", action="version", version=f"spinbounce {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command.register(sub)
    return parser


def _show_warning(message, category, filename, lineno, file=None, line=None):
    print(f"warning: {message}", file=sys.stderr)


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    warnings.showwarning = _show_warning
    warnings.simplefilter("always", PhysicsWarning)
    try:
        return args.handler(args)
    except (SceneError, SweepError) as exc:
        parser.exit(2, f"spinbounce {args.command}: error: {exc}\n")
    except (LammpsError, ResultError, DumpError) as exc:
        parser.exit(1, f"spinbounce {args.command}: {type(exc).__name__}: {exc}\n")
    return 1
