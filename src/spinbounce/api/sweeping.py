"""Many collisions from Python: ``sweep`` (and ``run_sweep``, what the command runs), ``fit`` and
``fit_groups``."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING


from ..model import parameters
from .collisions import _MODEL_NAMES

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["sweep", "run_sweep", "SweepReport", "fit", "fit_groups"]


@dataclass(frozen=True)
class SweepReport:
    """A finished sweep: its dataset (one Parquet file per chunk), how many rows got each status,
    and what it was."""

    dataset: Path
    counts: dict
    scene: str
    collisions: int
    estimated_seconds: float
    scene_hash: str = ""  # the digest of the sweep as it ran (its chunks included), as its sweep.json records


def run_sweep(spec, out: str | Path, *, workers: int = 1, force: bool = False, log=None,
              size_name: str = "n") -> SweepReport:
    """Run a sweep (``spec``: a scene file's path, its content as a dict, or a SweepSpec) into
    ``out``, resuming what an earlier run there finished. One estimated at more than
    :data:`~spinbounce.model.timestep.MAX_CORE_HOURS` on one core is refused unless ``force``d (``size_name``: what the
    refusal calls the number of collisions). ``log(line)``: told what runs."""
    from ..errors import SweepError
    from ..model.timestep import MAX_CORE_HOURS, duration_text
    from ..sweeps import load_spec, spec_from_dict, status_counts
    from ..sweeps import run_sweep as run_chunks
    from ..sweeps.cost import sweep_seconds

    from ..sweeps.run import spread_over
    from ..workers import checked_count

    try:
        workers = checked_count(workers)
    except ValueError as exc:
        raise SweepError(str(exc)) from None
    if isinstance(spec, (str, Path)):
        spec = load_spec(spec)
    elif isinstance(spec, dict):
        spec = spec_from_dict(spec)
    spec = spread_over(spec, workers, Path(out))  # chunks enough for the workers; a begun sweep's own
    seconds = sweep_seconds(spec, processes=workers)
    collisions = spec.n * len(spec.groups)
    if seconds > MAX_CORE_HOURS * 3600 and not force:
        raise SweepError(f"{size_name} = {spec.n}: {collisions} collisions are estimated at {duration_text(seconds)} on "
                         f"one core, more than the limit of {MAX_CORE_HOURS:g} core-hour(s) for one machine: run it as "
                         "chunks on a cluster (workflows/Snakefile, docs/how-to/cluster.md), or force it to run here "
                         "(--force; force=True in Python)")
    if log is not None:
        log(f"sweep {spec.digest}: {collisions} collisions in {len(spec.chunks())} chunks, {len(spec.groups)} model "
            f"group(s), {workers} worker(s); estimated {duration_text(seconds)} on one core")
    dataset = run_chunks(spec, Path(out), workers=workers, log=log or (lambda *_: None))
    return SweepReport(Path(dataset), status_counts(dataset), spec.scene, collisions, seconds, spec.digest)


#: A sweep's default ranges of the states, (low, high): taken for what is not given.
DEFAULT_STATES = {"v_n": (-1.5, -0.1), "v_t": (-2.0, 2.0), "r_omega": (-2.0, 2.0)}


def sweep(n: int, out: str | Path, *, seed: int = 0, workers: int = 1, dt: float | None = None, force: bool = False,
          **grid) -> pd.DataFrame:
    """Sample ``n`` collisions for every combination of the model values given (a number or a
    list each; ``None`` in ``mu``'s list is the paper's uncapped model) into ``out``; return the rows.
    The states are ranges (low, high), as a scene file's: ``v_n`` and ``v_t``, or ``speed`` and
    ``angle_deg``; ``omega`` or ``r_omega``; in 3-D ``v_s``, ``omega_s``, ``omega_n`` (or r times them).
    Defaults: :data:`DEFAULT_STATES`. ``scene="pair"`` with ``m_b``, ``r_b``, ``alpha_b``: sphere a
    against a free sphere b at rest. A sweep beyond an hour on one core needs ``force`` (:func:`run_sweep`)."""
    from ..sweeps import read_results
    from ..sweeps.spec import STATE_KEYS, VELOCITY_KEYS

    states = {k: list(grid.pop(k)) for k in STATE_KEYS if k in grid}
    # sphere b's state passes on, to be refused by the spec with the reason
    scene = {p.name for p in parameters.SCENE + parameters.STATE_B}
    unknown = set(grid) - _MODEL_NAMES - scene - {"kt_over_kn", "contact"}
    if unknown:
        raise TypeError(f"unknown parameter(s) {sorted(unknown)}: a sweep takes the states {', '.join(STATE_KEYS)} "
                        f"(ranges) and the model's parameters {', '.join(sorted(_MODEL_NAMES))}")
    polar = any(k in states for k in VELOCITY_KEYS["polar"])
    spun = "omega" in states or "r_omega" in states
    states = {**{k: list(v) for k, v in DEFAULT_STATES.items() if not (polar and k != "r_omega")
                 and not (spun and k == "r_omega")}, **states}
    grid = {k: ["none" if v is None else v for v in (vals if isinstance(vals, (list, tuple)) else [vals])]
            for k, vals in grid.items() if not (k == "contact" and vals is None)}
    if dt is not None:
        grid["dt"] = dt
    raw = {"seed": seed, "states": {"n": n, **states}}
    if grid:
        raw["model"] = grid
    run_sweep(raw, out, workers=workers, force=force)
    return read_results(out)


def fit_groups(results: str | Path | pd.DataFrame, *, plot: str | Path | None = None, force: bool = False,
               **selection) -> list[dict]:
    """The fit of a sweep's groups, one record each (what ``spinbounce fit --json`` prints): where
    one matrix applies the fitted matrix and Omega beside the theory's, else each collision's
    deviation from its theory. ``selection``: declared parameters (model or scene) and the value a
    group must have (``mu=None``: the uncapped ones). ``plot``: also draw the slip figure there (a
    file that exists is refused unless ``force``).
    A sweep's folder with no selection and no plot is fitted streamed (memory bounded)."""
    import pandas as pd

    from ..fitting import fit_groups as fit_rows
    from ..records import check_new_file
    from ..fitting import plot_groups
    from ..fitting_stream import fit_dataset
    from ..sweeps import read_results
    from ..sweeps.dataset import check_complete

    check_new_file(plot, force, "plot")
    if not isinstance(results, pd.DataFrame):
        check_complete(results)
    selectable = {p.name for p in parameters.MODEL + parameters.SCENE}
    unknown = sorted(set(selection) - selectable)
    if unknown:
        raise TypeError(f"unknown parameter(s) {unknown} to select groups by; declared: {sorted(selectable)}")
    if not selection and plot is None and not isinstance(results, pd.DataFrame):
        return fit_dataset(results)
    rows = _selected(results if isinstance(results, pd.DataFrame) else read_results(results), selection)
    if plot is not None:
        plot_groups(rows, plot)
    return fit_rows(rows)


def _selected(rows: pd.DataFrame, selection: dict) -> pd.DataFrame:
    """Only the rows of groups whose parameters equal the values selected (by declared name)."""
    from ..errors import SweepError

    for name, value in selection.items():
        parameter = parameters.by_name(name)
        if parameter.column not in rows:
            raise SweepError(f"{name} = {value!r}: this sweep has no column {parameter.column!r}")
        column = rows[parameter.column]
        none = column.isna() | (column == parameter.none_value)  # a sweep older than inf held NaN
        rows = rows[none] if value is None else rows[column == value]
    if rows.empty:
        raise SweepError(f"{', '.join(f'{k} = {v!r}' for k, v in selection.items())}: no group of this sweep has "
                         "these parameters")
    return rows


def fit(results: str | Path | pd.DataFrame, **selection) -> pd.DataFrame:
    """One row per model group: its parameters, regime, per-collision deviation and (where one
    matrix applies) the fitted Omega beside the theory's; ``matrix`` holds the fitted matrix.
    ``selection``: as :func:`fit_groups`'s."""
    import pandas as pd

    return pd.DataFrame([{**_as_columns(g["parameters"]), **{k: v for k, v in g.items() if k != "parameters"}}
                         for g in fit_groups(results, **selection)])


def _as_columns(values: dict) -> dict:
    """A group's parameters as the sweep's table holds them (mu none: inf), so that the fit's
    rows group and filter like the sweep's."""
    from ..fitting import by_column

    return {k: by_column[k].to_column(v) if k in by_column else v for k, v in values.items()}
