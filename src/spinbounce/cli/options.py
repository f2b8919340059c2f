"""Options shared by several commands, every model and state flag made from the declaration.

:mod:`spinbounce.model.parameters` gives each flag its help (meaning, unit, accepted range and
default) and its parsing. A command offers the groups it can honour, or refuses a flag with the reason.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import sys
from pathlib import Path

from ..model import parameters
from ..model.parameters import Parameter
from ..workers import checked_count

#: argparse reads "-1e-3" as an option unless it looks like a negative number to it; its own
#: pattern misses e-notation. Every parser here takes a word that starts like a negative number
#: ("-1e-3", "-.5", "-inf", also "-1m/s") as a value, so that the number parser names what is wrong.
NEGATIVE_NUMBER = re.compile(r"^-(\d|\.\d|inf|nan)", re.IGNORECASE)


def number(text: str) -> float:
    """A float from the command line, e-notation and signs included; 'nan' and 'inf' are refused."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r}: must be finite")
    return value


def optional_number(text: str) -> float | None:
    """A number, or 'none' for a parameter that may be absent (mu: no Coulomb cap); 'inf' too,
    which the declaration reads as none where that is what it means (mu) and refuses elsewhere."""
    word = text.strip().lower()
    if word == "none":
        return None
    if word in ("inf", "+inf", "infinity"):
        return math.inf
    return number(text)


def count(text: str) -> int:
    """A whole number, also written as an integral float (1e5, 2000.0)."""
    value = number(text)
    if value != int(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number")
    return int(value)


def positive_count(text: str) -> int:
    """A whole number >= 1 (collisions, spheres, points)."""
    value = count(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r}: must be >= 1")
    return value


def worker_count(text: str) -> int:
    """Worker processes: >= 1 and at most the cores this process may use (more only slow each other)."""
    try:
        return checked_count(count(text))
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def name_list(what: str, choices):
    """argparse type of comma-separated names, each one of ``choices()`` (called when parsing)."""
    def parse(text: str) -> tuple[str, ...]:
        names = tuple(n.strip() for n in text.split(",") if n.strip())
        unknown = [n for n in names if n not in choices()]
        if not names or unknown:
            raise argparse.ArgumentTypeError(f"unknown {what} {', '.join(unknown) or repr(text)}; "
                                             f"choose from: {', '.join(choices())}")
        return names
    return parse


def allow_negative_numbers(parser: argparse.ArgumentParser) -> None:
    """Let ``parser`` (and its subparsers) take e-notation negative values (``--vn -1e-3``)."""
    parser._negative_number_matcher = NEGATIVE_NUMBER  # argparse has no public switch for it
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                allow_negative_numbers(sub)


def _flag(text: str) -> bool:
    lowered = text.strip().lower()
    if lowered in ("true", "yes", "1"):
        return True
    if lowered in ("false", "no", "0"):
        return False
    raise argparse.ArgumentTypeError(f"{text!r}: give true or false")


def parameter_help(p: Parameter, default=True) -> str:
    unit = "" if p.unit in ("-", "1") else f" [{p.unit}]"
    shown = "none" if p.default is None else p.default
    return f"{p.meaning}{unit}; {p.range_text()}" + (f" (default {shown})" if default else "")


class _Given(argparse.Action):
    """Store the value and note that the user gave the option (``given_options``): a default
    is not a value given, so it never clashes with the same parameter given by ``--contact``."""

    def __call__(self, parser, namespace, values, option_string=None):
        setattr(namespace, self.dest, True if self.nargs == 0 else values)
        namespace.__dict__.setdefault("given_options", set()).add(self.dest)


def _add(group, p: Parameter, **overrides) -> None:
    """One declared parameter as an option of ``group``."""
    if p.kind == "flag":
        group.add_argument(*p.flags, dest=p.name, action=_Given, nargs=0, default=p.default,
                           help=parameter_help(p, default=False))
        return
    kwargs = {"dest": p.name, "default": p.default, "help": parameter_help(p),
              "metavar": p.name.upper(), "action": _Given}
    if p.kind == "choice":
        kwargs.update(choices=p.choices, type=str, metavar=None)
    else:
        kwargs["type"] = optional_number if p.optional else number
    kwargs.update(overrides)
    group.add_argument(*p.flags, **kwargs)


def _parent(title: str, declared, **overrides) -> argparse.ArgumentParser:
    """A parent parser of one option group: each declared parameter as an option."""
    p = argparse.ArgumentParser(add_help=False)
    group = p.add_argument_group(title)
    for parameter in declared:
        _add(group, parameter, **overrides)
    return p


#: ``--contact``'s help: the one option that sets several model parameters at once.
CONTACT_HELP = ("the contact law as LAMMPS's granular words, after 'fix wall/gran granular' or in pair_coeff, e.g. "
                "'hertz/material 1e4 0.3 0.3 damping tsuji tangential mindlin NULL 1.0 1e12': read into the "
                "parameters below (never passed to LAMMPS as text); a parameter may not be given both ways")


def model_parser() -> argparse.ArgumentParser:
    """Every contact-model option (declared defaults: the paper's), and ``--contact``, as a parent parser."""
    parser = _parent("contact model (defaults: the paper's; units: LAMMPS lj)", parameters.MODEL)
    parser.add_argument("--contact", default=None, metavar="'WORDS'", help=CONTACT_HELP)
    return parser


def state_parser(three_d: bool = True, optional: bool = False) -> argparse.ArgumentParser:
    """The initial state's options (the paper's plane, and the 3-D ones where honoured);
    ``optional``: none has a default (a state that may be left out altogether)."""
    title = "initial state" + (" (3-D: v_s, omega_s, omega_n)" if three_d else "")
    title += " (optional)" if optional else ""
    title += "; the velocity as --vn and --vt, or --speed and --angle-deg"
    return _parent(title, (parameters.STATE if three_d else parameters.STATE[:3]) + parameters.POLAR,
                   **({"default": None} if optional else {}))


def pair_parsers() -> list[argparse.ArgumentParser]:
    """The scene's options (:data:`~spinbounce.model.parameters.SCENE`: --scene wall|pair, sphere b's
    --m-b, --r-b, --alpha-b) and b's state at first touch (``STATE_B``), as parent parsers."""
    return [_parent("scene: the wall (default), or a free sphere b at rest along the normal (a pair)",
                    parameters.SCENE, default=None),
            _parent("sphere b's state (--scene pair; default: at rest), in a's frame and sign",
                    parameters.STATE_B, default=None)]


def values_of(args: argparse.Namespace) -> dict:
    """Every declared parameter the command parsed, by name, as the API takes them (the scene's
    and b's only where given)."""
    values = {}
    contact = getattr(args, "contact", None)
    given = getattr(args, "given_options", set())
    polar = any(getattr(args, p.name, None) is not None for p in parameters.POLAR)
    for parameter in parameters.MODEL + parameters.STATE + parameters.POLAR + parameters.SCENE + parameters.STATE_B:
        value = getattr(args, parameter.name, None)
        if parameter in parameters.MODEL and contact is not None and parameter.name not in given:
            continue  # a default: --contact sets it, or the model's default applies
        if polar and parameter.name in ("v_n", "v_t") and parameter.name not in given:
            continue  # the velocity is --speed and --angle-deg's: a default v_n or v_t is no clash
        if value is not None or parameter in parameters.MODEL:
            values[parameter.name] = value
    return values if contact is None else {**values, "contact": contact}


def model_values(args: argparse.Namespace) -> dict:
    """The contact model's parameters the command parsed, by name (``--contact`` read into them)."""
    from ..laws.words import expand_contact

    values = {p.name: getattr(args, p.name) for p in parameters.MODEL}
    if getattr(args, "contact", None) is None:
        return values
    given = getattr(args, "given_options", set())
    return expand_contact({**{k: v for k, v in values.items() if k in given}, "contact": args.contact})


def sweep_model_flags(p: argparse.ArgumentParser) -> None:
    """A sweep's model options: every sweepable parameter takes one value or several (a grid)."""
    group = p.add_argument_group("model, from flags (one value or several: every combination is a group)")
    for parameter in parameters.MODEL:
        if not parameter.sweepable:
            continue
        if parameter.kind == "flag":
            # alone it means true; with values (true false) it is a grid like the others
            group.add_argument(*parameter.flags, dest=parameter.name, type=_flag, nargs="*", default=None,
                               metavar="true|false", help=parameter_help(parameter, default=False))
        else:
            _add(group, parameter, nargs="+", default=None)
    group.add_argument("--kt-over-kn", dest="kt_over_kn", type=number, nargs="+", default=None, metavar="RATIO",
                       help="instead of --kt: the stiffness ratio kt/kn (kt = ratio * kn)")
    group.add_argument("--contact", nargs="+", default=None, metavar="'WORDS'",
                       help=CONTACT_HELP + "; several lines: each a group")


def run_folder_flags(p: argparse.ArgumentParser, help_: str) -> None:
    """A run's --out (its run folder: ``help_``), --force and --json."""
    p.add_argument("--out", type=out_folder, default=None, metavar="DIR", help=help_)
    p.add_argument("--force", action="store_true",
                   help="run into an --out folder that holds an earlier run, replacing its results")
    json_flag(p)


def check_run_folder(out: Path | None, force: bool) -> None:
    """A run's --out: not a file, and no earlier run in it unless --force (:func:`records.check_run_folder`)."""
    from ..records import check_run_folder as check

    check(out, force, "--out", "--force")


def note(line: str) -> None:
    """A line for the user beside a command's output: on stderr, at once."""
    print(line, file=sys.stderr, flush=True)


def shown_path(path) -> str:
    """A file the command made, as the user reads it: relative to the working folder when inside it."""
    if path is None:
        return "none"
    path = Path(path)
    try:
        return str(path.resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(path)


def state_cell(value: float) -> str:
    """A velocity or r omega in a 16-wide column: ten decimals, or in exponent form beyond 1e5."""
    return f"{value:>16.10f}" if abs(value) < 1e5 else f"{value:>16.8e}"


def print_json(value, **options) -> int:
    """``value`` as indented JSON on stdout, every NaN and infinity as null (JSON has neither: a reader's parser
    refuses them); 0, the command's exit status. A record (a dict) that does not say what produced it gets
    :func:`~spinbounce.records.software`'s versions (LAMMPS's where this process ran it)."""
    from ..records import json_ready, software

    if isinstance(value, dict) and "spinbounce_version" not in value:
        value = {**value, **software(with_lammps="lammps" in sys.modules)}
    print(json.dumps(json_ready(value), indent=2, allow_nan=False, **options))
    return 0


#: Where a study writes its figures and records unless told otherwise: a folder of its own, so that
#: neither the repository's stored outputs (figures/) nor a folder of the user's is written into by default.
FIGURES_OUT = Path("spinbounce-figures")


def _writable_ancestor(path: Path, text: str) -> None:
    """Refuse ``path`` unless its nearest existing ancestor is a folder a file can be created in
    (probed with a temporary file, removed at once: a permission check alone passes for root)."""
    import tempfile

    ancestor = path.absolute()
    while not ancestor.exists():
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise argparse.ArgumentTypeError(f"{text!r}: {ancestor} is a file, not a folder")
    try:
        with tempfile.TemporaryFile(dir=ancestor):
            pass
    except OSError as exc:
        raise argparse.ArgumentTypeError(f"{text!r}: cannot write in {ancestor} ({exc.strerror or exc})") from None


def out_folder(text: str) -> Path:
    """argparse type of an output folder: not an existing file, and somewhere writable."""
    path = Path(text)
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty name is not a folder")
    if path.exists() and not path.is_dir():
        raise argparse.ArgumentTypeError(f"{text!r} is a file, not a folder")
    _writable_ancestor(path, text)
    return path


def out_file(text: str) -> Path:
    """argparse type of an output file: not an existing folder, and somewhere writable."""
    path = Path(text)
    if not text.strip() or text.endswith(os.sep):
        raise argparse.ArgumentTypeError(f"{text!r} is not a file name")
    if path.is_dir():
        raise argparse.ArgumentTypeError(f"{text!r} is a folder, not a file")
    _writable_ancestor(path.parent, text)
    return path


def out_option(p: argparse.ArgumentParser, what: str) -> None:
    """The one --out of the studies: a folder, by default :data:`FIGURES_OUT`. Only the files the
    command writes (``what``) are replaced in it; the repository's stored outputs only when asked."""
    p.add_argument("--out", type=out_folder, default=FIGURES_OUT, metavar="DIR",
                   help=f"folder for {what} (default: %(default)s; the repository's stored ones are "
                        "updated only with --out figures)")
    replace_flag(p)


def replace_flag(p: argparse.ArgumentParser) -> None:
    """--force of a command that writes into --out: replace files there that spinbounce did not write
    (:mod:`spinbounce.outputs`), which are otherwise refused and kept."""
    p.add_argument("--force", dest="replace_outputs", action="store_true",
                   help="replace files in --out that spinbounce did not write, or that were changed since (they "
                        "are otherwise refused and kept; spinbounce's own earlier outputs are refreshed anyway)")


def figure_options(p: argparse.ArgumentParser) -> None:
    """--out (the figure's folder), --runs (keep the LAMMPS runs) and --json, for a study's figure."""
    out_option(p, "the figure and its JSON record")
    p.add_argument("--runs", type=out_folder, default=None, metavar="DIR",
                   help="keep the LAMMPS runs here (default: a temporary folder, removed)")
    json_flag(p)


def make_with_runs(make, out: Path | None, runs: Path | None, prefix: str):
    """``make(out, runs_folder)``, the runs kept in ``runs`` or in a temporary folder removed after."""
    import tempfile

    if runs is not None:
        return make(out, runs)
    with tempfile.TemporaryDirectory(prefix=prefix) as folder:
        return make(out, Path(folder))


def json_flag(p: argparse.ArgumentParser) -> None:
    p.add_argument("--json", action="store_true", help="print machine-readable JSON instead of text")
