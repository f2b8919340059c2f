"""One collision's report, wall or pair, and the one JSON shape both are written in.

A report's states are the columns of one table with a row per state component, in the paper's
names and signs (a pair's sphere b with ``_b``): ``initial``, ``LAMMPS`` (as the run ended it),
``theory`` (the reference the run is judged against: the wall's exact theory, the pair's exact
reference) and ``error`` (LAMMPS - theory); a pair adds ``planar`` (the planar theory, exact only
as eps -> 0). As JSON each column is a state by name, each spin also as an angular velocity
(``r_omega`` -> ``omega``, ``r_omega_b`` -> ``omega_b``), beside the keys both scenes share:
``error_estimate`` (how far the result may be from the truth, over the state's size: the wall's
initial state, the pair's speed), ``status``, ``theory_kind``, ``theory_name``, ``dt``,
``nsteps``, ``contact_time``, ``step``, ``Omega``, ``run_dir``, ``deck``, ``dump``,
``lammps_version`` and ``warnings``. The names are the sweep table's as JSON keys: ``theory[s]``
is the column ``{s}_theory``, ``error[s]`` is ``{s}_error``, ``error_estimate`` the row's
``error`` (a key cannot be both the state and its size), ``theory_kind`` the ``theory`` column.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["CollisionReport", "PairReport", "ToleranceReport", "state_table", "state_record"]

#: A report's state columns as its table labels them; lower case, the run's column suffix and the JSON key.
REPORT_COLUMNS = ("initial", "LAMMPS", "theory", "error")


def state_table(row, names, r: float) -> pd.DataFrame:
    """One row per state column of a run's row: initial, LAMMPS, theory and error (``attrs["r"]``: r)."""
    import pandas as pd

    table = pd.DataFrame({label: [float(row[f"{s}_{label.lower()}"]) for s in names]
                          for label in REPORT_COLUMNS}, index=list(names))
    table.attrs["r"] = r
    return table


def state_record(table: pd.DataFrame) -> dict:
    """A state table as JSON-ready data: per column a state by name, each spin also as an angular
    velocity (``r_omega`` -> ``omega`` over ``attrs["r"]``; sphere b's ``r_omega_b`` -> ``omega_b``
    over ``attrs["r_b"]``)."""
    out = {}
    for label in table.columns:
        state = {name: float(table.loc[name, label]) for name in table.index}
        for name, value in list(state.items()):
            if name.startswith("r_"):
                state[name[2:]] = value / table.attrs["r_b" if name.endswith("_b") else "r"]
        out[label.lower()] = state
    return out


@dataclass(frozen=True, kw_only=True)
class _Ran:
    """What a collision report says beside its states, wall or pair: which theory it is judged against, how it
    ran (``run_dir`` None: it did not), and how far from the truth it is (``error``: the largest component of
    LAMMPS - theory over the state's size, the JSON's ``error_estimate``)."""

    theory_kind: str = ""
    theory_name: str = ""
    dt: float = float("nan")
    nsteps: int = 0
    error: float = float("nan")
    status: str = ""
    run_dir: Path | None = None
    step: dict = field(default_factory=dict)
    Omega: float | None = None
    warnings: tuple[str, ...] = ()
    deck: str = ""
    dump: str | None = None
    lammps_version: str = ""

    def ran(self) -> dict:
        """These as JSON-ready data, the keys every collision report that ran LAMMPS has."""
        return {"error_estimate": self.error, "status": self.status, "theory_kind": self.theory_kind,
                "theory_name": self.theory_name, "dt": self.dt, "nsteps": self.nsteps, "step": self.step,
                "Omega": self.Omega, "run_dir": None if self.run_dir is None else str(self.run_dir), "deck": self.deck,
                "dump": self.dump, "lammps_version": self.lammps_version, "warnings": list(self.warnings)}


@dataclass(frozen=True)
class CollisionReport(_Ran):
    """One wall collision in LAMMPS beside its theory. ``table``: one row per state column
    (initial, LAMMPS, theory, error); the rest says how it ran and how far from the truth it is."""

    table: pd.DataFrame
    contact_time: float = float("nan")

    def record(self) -> dict:
        """The report as JSON-ready data (``spinbounce collide --json``)."""
        return {**state_record(self.table), **self.ran(), "contact_time": self.contact_time}

    def __str__(self) -> str:
        head = (f"collision: theory {self.theory_name}; dt = {self.dt:.6g} ({self.nsteps} steps); "
                f"error {self.error:.2e} of the state's size; status {self.status}\n")
        return head + self.table.to_string(float_format=lambda x: f"{x:.10f}")


@dataclass(frozen=True)
class PairReport(_Ran):
    """One pair scene: both spheres' states in the paper's names and signs (sphere b's with ``_b``;
    the frame is the wall's, the line of centres from b to a its normal) initially, as LAMMPS ended
    them (if it ran), by the exact reference (``theory``), their difference (``error``) and by the
    planar theory (``table``); LAMMPS's error against the exact reference (the wall's measure:
    ``error``, in units of the pair's speed) and the planar theory's model error."""

    table: pd.DataFrame
    planar_error: float
    eps: float
    geometry: dict = field(default_factory=dict)

    def record(self) -> dict:
        """The report as JSON-ready data (``spinbounce pair --json``); without a run (``theory --scene
        pair``), the states, the theory they come from, the model error and the geometry only."""
        out = {**state_record(self.table), "planar_error": self.planar_error, **self.geometry}
        if self.run_dir is None:
            return {**out, "theory_kind": self.theory_kind, "theory_name": self.theory_name}
        return {**out, **self.ran()}

    def __str__(self) -> str:
        head = (f"pair: dt = {self.dt:.6g} ({self.nsteps} steps); LAMMPS vs exact {self.error:.2e}; planar theory's "
                f"model error {self.planar_error:.2e} (eps = {self.eps:.3g})\n")
        return head + self.table.to_string(float_format=lambda x: f"{x:.10f}")


@dataclass(frozen=True)
class ToleranceReport:
    """A collision run to a requested accuracy: the extrapolated state beside the theory
    (``table`` as :class:`CollisionReport`'s) and ``record`` (written to ``tolerance.json``)."""

    table: pd.DataFrame
    record: dict
    how: str
    path: Path
