"""Everything ``spinbounce reproduce`` makes, in one list: the paper's figures, the claims
ledger and the studies beyond the paper, each with the command that makes it alone.

Each :class:`Product` writes its files into one folder and returns its JSON records by name
(``figures/<name>.json`` in the repository is the stored copy of each). The repository's
``figures/`` is this list made with ``spinbounce reproduce --out figures``; a test makes it
afresh and compares every record with the stored one (:func:`compare_records`). Two studies
are listed (:data:`LISTED`) but not run by ``reproduce``.
"""

from __future__ import annotations

import inspect
import json
import math
from dataclasses import dataclass
from importlib import import_module
from pathlib import Path
from typing import Callable

__all__ = ["Product", "PRODUCTS", "LISTED", "product_names", "record_names", "make", "compare_records", "IGNORED_KEYS"]


@dataclass(frozen=True)
class Product:
    """One thing ``reproduce`` makes: ``make(out, runs, log)`` writes it and returns its JSON
    records ``{name: record}``, one per name in ``records`` (``<name>.json`` in the out folder)."""

    name: str
    command: str
    what: str
    make: Callable[[Path, Path, Callable], dict]
    records: tuple[str, ...]
    #: its reports beside the records; whether each record comes with a figure (<name>.png, .pdf)
    reports: tuple[str, ...] = ()
    drawn: bool = True
    #: about how long it takes on one quiet core, in seconds (measured, rounded up): the longest start first
    #: when products are made side by side (:mod:`spinbounce.making`)
    seconds: float = 10.0

    @property
    def files(self) -> tuple[str, ...]:
        """Every file it writes into its folder."""
        kinds = ("png", "pdf", "json") if self.drawn else ("json",)
        return tuple(f"{name}.{kind}" for name in self.records for kind in kinds) + self.reports


def _paper_figures(out, runs, log):
    from .figures import make_figures

    return {record["figure"]: record for record in make_figures(out, runs=runs, log=log)}


def _gases(runs: Path) -> Path:
    """Where gases that several products show are run once, read back by the rest (the claims' kt/kn = 0.1 gas is
    the gas figure's): the gases' folder beside the products' own run folders (:func:`make`), by content
    (:func:`spinbounce.scenes.gas.run.shared_gas`)."""
    from .scenes.gas.run import GASES

    return Path(runs).parent / GASES


def _claims(out, runs, log):
    from .studies.claims import make_claims

    *_, record = make_claims(out, runs, log=log, gases=_gases(runs))
    return {"claims": json.loads(record.read_text())}


def _figure(module: str, function: str):
    """A study whose ``function(out, runs[, log][, gases])`` returns its record (a dict or a FigureRecord)."""
    def make_one(out, runs, log):
        maker = getattr(import_module(f"spinbounce.{module}"), function)
        takes = inspect.signature(maker).parameters
        shared = ({"log": log} if "log" in takes else {}) | ({"gases": _gases(runs)} if "gases" in takes else {})
        made = maker(out, runs=runs, **shared)
        record = getattr(made, "metadata", made)
        return {Path(record["files"]["png"]).stem: record}
    return make_one


def _benchmarks(out, runs, log):
    from .studies.validation.report import make_benchmarks

    _, files = make_benchmarks(out, runs=runs, log=log)
    return {"benchmarks": json.loads(Path(files["json"]).read_text())}


PRODUCTS: tuple[Product, ...] = (
    Product("paper", "spinbounce figures", "the paper's figures 2-7 (fig2 ... fig7)", _paper_figures,
            tuple(f"fig{n}" for n in range(2, 8)), seconds=20),
    Product("claims", "spinbounce claims", "the claims ledger, CLAIMS.md", _claims, ("claims",),
            reports=("CLAIMS.md",), drawn=False, seconds=200),
    Product("benchmarks", "spinbounce benchmarks", "published validation cases, BENCHMARKS.md", _benchmarks,
            ("benchmarks",), reports=("BENCHMARKS.md",), seconds=40),
    Product("hertz", "spinbounce hertz", "Hertzian contact time and scattering, HERTZ.md",
            _figure("figures.hertz", "make_hertz"), ("hertz",),
            reports=("HERTZ.md",), seconds=5),
    Product("mindlin", "spinbounce reproduce --only mindlin", "Omega of LAMMPS's Mindlin springs against Poisson's ratio",
            _figure("figures.mindlin", "make_mindlin"), ("mindlin",), seconds=15),
    Product("classic", "spinbounce classic --figure", "this build's classic wall against the paper's model",
            _figure("figures.classic", "make_classic"), ("classic",), seconds=8),
    Product("two_walls", "spinbounce two-walls", "many bounces between two walls against the matrices",
            _figure("figures.two_walls", "make_figure"), ("two_walls",), seconds=15),
    Product("restitution", "spinbounce restitution", "restitution maps against incidence, Kharaz's data",
            _figure("studies.restitution", "make_figure"), ("restitution",), seconds=8),
    Product("tangential", "spinbounce tangential", "tangential restitution against the velocity ratio (Becker et al.)",
            _figure("studies.tangential", "make_figure"), ("tangential",), seconds=4),
    Product("pair_validity", "spinbounce reproduce --only pair_validity", "where the planar two-sphere theory holds",
            _figure("figures.pairs", "make_pair_validity"), ("pair_validity",), seconds=4),
    Product("gas", "spinbounce reproduce --only gas", "T_rot/T_tr of frictional-sphere gases against kinetic theory",
            _figure("figures.gas", "make_gas"), ("gas",), seconds=130),
)

#: Made by a command of their own, not by ``reproduce``: (command, what, why).
LISTED = (
    ("spinbounce accuracy", "the convergence study, ACCURACY.md", "tens of minutes"),
    ("spinbounce bench", "speed and cost ratios, bench.json", "its numbers belong to the machine"),
)


def product_names() -> list[str]:
    return [p.name for p in PRODUCTS]


def record_names() -> list[str]:
    """Every JSON record ``reproduce`` writes, by name."""
    return [name for p in PRODUCTS for name in p.records]


def make(product: Product, out: Path, runs: Path, log=print) -> dict:
    """Make one product into ``out``, its LAMMPS runs under ``runs``/<name> (and the gases products share
    under ``runs``/gases: :func:`_gases`)."""
    return product.make(Path(out), Path(runs) / product.name, log)


#: Keys whose values say when, where and how fast a record was made, not what it found.
IGNORED_KEYS = frozenset({"created", "runtime_seconds", "seconds", "files", "run", "run_dir", "deck", "software", "python",
                          "machine", "runs_kept_in", "spinbounce_version", "lammps_version", "numpy_version", "scipy_version",
                          "pandas_version", "pyarrow_version", "matplotlib_version", "jinja2_version"})


def compare_records(stored, fresh, tolerance: float, path: str = "") -> list[str]:
    """Where ``fresh`` differs from ``stored``: numbers by more than ``tolerance`` (absolute, or
    relative to the stored value where that is larger than 1), anything else when unequal.
    Keys of :data:`IGNORED_KEYS`, and timings (keys ending in ``_seconds``), are skipped at every depth."""
    if isinstance(stored, dict) and isinstance(fresh, dict):
        kept = {k for k in stored.keys() | fresh.keys() if k not in IGNORED_KEYS and not str(k).endswith("_seconds")}
        found = [f"{path}/{k}: missing" for k in sorted(kept - fresh.keys())]
        found += [f"{path}/{k}: new" for k in sorted(kept - stored.keys())]
        for key in sorted(kept & stored.keys() & fresh.keys()):
            found += compare_records(stored[key], fresh[key], tolerance, f"{path}/{key}")
        return found
    if isinstance(stored, list) and isinstance(fresh, list):
        if len(stored) != len(fresh):
            return [f"{path}: {len(fresh)} items, stored {len(stored)}"]
        return [d for k, (a, b) in enumerate(zip(stored, fresh)) for d in compare_records(a, b, tolerance, f"{path}[{k}]")]
    numbers = [float(v) for v in (stored, fresh) if isinstance(v, (int, float)) and not isinstance(v, bool)]
    if len(numbers) == 2:
        a, b = numbers
        same = math.isnan(a) == math.isnan(b) and (math.isnan(a) or abs(b - a) <= tolerance * max(1.0, abs(a)))
    else:
        same = stored == fresh
    return [] if same else [f"{path}: {fresh!r}, stored {stored!r}"]
