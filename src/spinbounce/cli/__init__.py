"""The ``spinbounce`` command: one subcommand per concern."""

from __future__ import annotations

import argparse
import sys
import warnings

from .. import __version__
from ..errors import (DumpError, FileFault, LammpsError, NoMatrix, PhysicsWarning, ResultError, SceneError,
                      SweepError)
from .options import allow_negative_numbers
from . import (accuracy, bench, benchmarks, calibrate, claims, classic, collide, doctor, figures, fit, frozen, gas,
               hertz, references, reproduce, restitution, sweep, tangential, theory, two_walls)

COMMANDS = (theory, collide, frozen, sweep, fit, bench, accuracy, benchmarks, figures, hertz, claims, reproduce,
            references, doctor, classic, two_walls, restitution, tangential, calibrate, gas)


class OneLineParser(argparse.ArgumentParser):
    """An argument parser whose refusals are one line on stderr (exit 2): what is wrong, and where
    the options are listed, instead of the usage block above the message. An option is taken only as it is spelled
    (no abbreviation: ``--ma`` would be ``--mass``, and ``--n`` ``--normal``)."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")

    def parse_known_args(self, args=None, namespace=None):
        self._refuse_repeats(sys.argv[1:] if args is None else list(args))
        return super().parse_known_args(args, namespace)

    def _refuse_repeats(self, tokens: list[str]) -> None:
        """An option that holds one value, given twice, is refused: which one was meant is unclear."""
        given = {}
        for token in tokens:
            if token == "--":
                break
            flag = token.split("=", 1)[0]
            action = self._option_string_actions.get(flag)
            if action is None or isinstance(action, (argparse._AppendAction, argparse._StoreConstAction, argparse._HelpAction)):
                continue
            if action.dest in given:
                self.error(f"argument {flag}: given twice (also as {given[action.dest]}): give it once")
            given[action.dest] = flag


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="spinbounce",
        description="Frictional sphere-wall collisions in LAMMPS against Wang and Harrowell's theory.",
    )
    parser.add_argument("--version", action="version", version=f"spinbounce {__version__}")
    parser.add_argument("--debug", action="store_true", help="show the Python traceback of an error")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command.register(sub)
    allow_negative_numbers(parser)
    return parser


def _show_warning(message, category, filename, lineno, file=None, line=None):
    print(f"warning: {message}", file=sys.stderr)


def _failure(exc: BaseException, command: str) -> tuple[int, str]:
    """A command's exit status and its one line on stderr for an error it raised."""
    who = f"spinbounce {command}"
    if isinstance(exc, KeyboardInterrupt):
        return 130, f"{who}: interrupted\n"
    if isinstance(exc, OSError):
        where = f" {exc.filename}:" if exc.filename else ""
        return 2, f"{who}: error:{where} {exc.strerror or exc}\n"
    if isinstance(exc, (LammpsError, ResultError, DumpError)):
        return 1, f"{who}: {type(exc).__name__}: {exc}\n"
    from concurrent.futures.process import BrokenProcessPool

    if isinstance(exc, BrokenProcessPool):  # a worker killed (by a signal, or for memory): what was whole stays
        return 1, f"{who}: error: a worker process ended abruptly (killed, or out of memory); run it again\n"
    return 2, f"{who}: error: {exc}\n"


def _parse(parser: argparse.ArgumentParser, argv: list[str] | None) -> argparse.Namespace:
    """The arguments; what no option of the command takes is refused by the command's own parser, so
    that the message and its hint name the subcommand (spinbounce collide --help)."""
    args, extra = parser.parse_known_args(argv)
    if extra:
        commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
        commands.choices[args.command].error(f"unrecognized arguments: {' '.join(extra)}")
    return args


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = _parse(parser, argv)
    warnings.showwarning = _show_warning
    warnings.simplefilter("always", PhysicsWarning)
    from concurrent.futures.process import BrokenProcessPool

    from ..outputs import replacing  # numpy comes with it: not before --help

    try:
        with replacing(getattr(args, "replace_outputs", False)):
            return args.handler(args)
    except BrokenPipeError:  # `spinbounce theory | head`: the reader has gone, and that is fine
        sys.stdout = None
        return 0
    except (KeyboardInterrupt, OSError, SceneError, SweepError, FileFault, NoMatrix, LammpsError, ResultError,
            DumpError, BrokenProcessPool) as exc:
        if args.debug:
            raise
        parser.exit(*_failure(exc, args.command))
