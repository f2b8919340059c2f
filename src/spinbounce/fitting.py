"""Least-squares scattering matrices from sweep results, beside the theory that applies.

For each model group (every declared parameter that changes the outcome, and dt) the fit
first asks whether one matrix describes the group at all:

* without a Coulomb cap and with a Hookean contact, the theory is a matrix (Eq. 18, or its
  exact damped form): the fit gives the 3x3 matrix M (6x6 in 3-D) with final = M @ initial,
  each element's standard error, Omega from Eq. 19, and their differences from the theory;
* with a finite mu, a matrix applies only if every collision of the group sticks to the
  end, where the frictionless matrix holds; that is checked on the theory's own columns
  (they must equal the frictionless matrix's outcome within :data:`STICK_TOLERANCE`);
* otherwise (sliding collisions, or a Hertzian group with several v_n) no matrix is claimed:
  the group reports its per-collision deviation from the theory (worst and median);
* a pair scene's group (sphere b at rest instead of the wall; :mod:`spinbounce.scenes.pair.kind`)
  is checked against the exact reference; the planar theory's matrix of a's state is claimed
  only where its model error (the rows' ``planar_error``, the quantity of the validity map
  over eps and the centrifugal ratio, figures/pair_validity) stays within the accuracy
  :data:`~spinbounce.model.timestep.ACCURACY`; elsewhere the group's regime says by how much
  it misses, with the group's largest eps and centrifugal ratio.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from .scenes.collision import STATE, STATE_3D
from .model import parameters
from .model.contact import ContactModel
from .records import write_atomic_with
from .scenes.pair.kind import theory_kind
from .exact import choose
from .laws import own

__all__ = ["GROUP_KEYS", "model_of_group", "fit_matrix", "fit_omega", "fit_groups", "plot_groups", "STICK_TOLERANCE",
           "omega_gains", "regime", "PAIR_GEOMETRY"]

#: Columns that separate fit groups: every declared parameter that changes the outcome (the
#: scene's too: a wall sweep has none of them), and dt.
GROUP_KEYS = ([p.column for p in parameters.MODEL if p.changes_outcome] + [p.column for p in parameters.SCENE]
              + ["dt"])
#: A pair group's columns that decide its regime: the planar theory's model error and the geometry.
PAIR_GEOMETRY = ("planar_error", "eps", "centrifugal")
#: A group sticks throughout when its theory columns match the frictionless matrix's outcome
#: to this, relative to the largest initial speed: the oracle's own accuracy is ~1e-12, and
#: any slip, however brief, moves the outcome by far more than this.
STICK_TOLERANCE = 1e-9


def fit_matrix(initial: np.ndarray, final: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Least squares final ~ initial @ M.T; returns (M, standard errors of M, residuals)."""
    coef, *_ = np.linalg.lstsq(initial, final, rcond=None)
    residuals = final - initial @ coef
    dof = max(len(initial) - initial.shape[1], 1)
    sigma2 = (residuals**2).sum(axis=0) / dof  # one variance per output row of M
    cov = np.linalg.inv(initial.T @ initial)
    stderr = np.sqrt(np.outer(sigma2, np.diag(cov)))
    return coef.T, stderr, residuals


def omega_gains(params: dict) -> tuple[float, float]:
    """Eq. 19's coefficients (c_t, c_r): Delta v_t = c_t Omega u'(0) and r Delta omega = c_r Omega u'(0).

    The wall: alpha/(1 + alpha) and 1/(1 + alpha). A pair with b at rest (exact/pair.py):
    the impulse Omega u'(0)/K on a gives 1/(m K) and 1/(alpha m K), which are the wall's
    as m_b grows without bound.
    """
    m, r, alpha = params["m"], params["r"], params["alpha"]
    if params.get("scene") == "pair":
        from .exact.pair import slip_mobility

        mobility = slip_mobility(m, r, alpha, params["m_b"], params["r_b"], params["alpha_b"])
        return 1.0 / (m * mobility), 1.0 / (alpha * m * mobility)
    return alpha / (1 + alpha), 1.0 / (1 + alpha)


def slip_changes(initial: np.ndarray, final: np.ndarray, gains: tuple[float, float]) -> tuple:
    """Eq. 19 stacked over both tangential rows: x = (c_t, c_r) u'(0) and y = the changes of v_t, r omega."""
    slip = initial[:, 1] + initial[:, 2]
    return (np.concatenate([gains[0] * slip, gains[1] * slip]),
            np.concatenate([final[:, 1] - initial[:, 1], final[:, 2] - initial[:, 2]]))


def fit_omega(initial: np.ndarray, final: np.ndarray, alpha: float,
              gains: tuple[float, float] | None = None) -> tuple[float, float]:
    """Omega from Eq. 19 by least squares over both tangential rows; (Omega, its standard error).
    ``gains``: Eq. 19's coefficients where they are not the wall's of ``alpha`` (:func:`omega_gains`)."""
    x, y = slip_changes(initial, final, gains or (alpha / (1 + alpha), 1.0 / (1 + alpha)))
    xx = float(x @ x)
    if xx == 0.0:
        return math.nan, math.nan
    omega = float(x @ y) / xx
    dof = max(len(x) - 1, 1)
    return omega, math.sqrt(float(((y - omega * x) ** 2).sum()) / dof / xx)


#: The declared parameters by column, to read a group's values back.
by_column = {p.column: p for p in parameters.MODEL + parameters.SCENE}


def group_parameters(params: dict) -> dict:
    """A group's parameters as a fit reports them: NaN columns as None, and without the
    coefficients of normal laws the group does not use (:func:`spinbounce.laws.own`)."""
    return own({k: (by_column[k].from_column(v) if k in by_column else
                     None if isinstance(v, float) and math.isnan(v) else v) for k, v in params.items()})


def model_of_group(params: dict) -> ContactModel:
    """The group's contact model, from its columns (none as the column holds it; columns an older
    sweep lacks: default)."""
    values = {}
    for p in parameters.MODEL:
        if p.column in params:
            value = p.from_column(params[p.column])
            values[p.name] = bool(value) if p.kind == "flag" else value
    return ContactModel(**values)


def worst_and_median(parts: list) -> tuple[float, float]:
    """The largest and the median of a group's per-row values, kept batch by batch in ``parts``
    (emptied: the rows are held once, and partitioned in place, where np.median would copy them;
    the median is np.median's, the mean of the two middle values for an even count)."""
    values = np.concatenate(parts)
    parts.clear()
    n = len(values)
    middle = [n // 2 - 1, n // 2] if n % 2 == 0 else [n // 2]
    values.partition(middle)
    return float(values.max()), float(np.mean(values[middle]))


def regime(params: dict, three_d: bool, off_uncapped: float, scale: float, speeds,
           geometry: dict) -> tuple[np.ndarray | None, str]:
    """The matrix that describes every collision of a group, or None, and the regime's name.

    ``off_uncapped``: the largest |theory - frictionless matrix @ initial| over the group (a
    capped group sticks throughout where it is within STICK_TOLERANCE of ``scale``, its
    largest initial component); ``speeds``: its distinct v_n (a Hertzian group at one speed
    has one matrix). A pair group's planar matrix of a's state is None where the planar
    theory's model error (``geometry``: the group's largest planar_error, eps and centrifugal
    ratio) exceeds the accuracy."""
    model = model_of_group(params)
    if params.get("scene") == "pair":
        from .model.timestep import ACCURACY
        from .scenes.pair.kind import no_planar_matrix, planar_matrix, sphere_b

        where = f"eps up to {geometry['eps']:.2g}, centrifugal ratio up to {geometry['centrifugal']:.2g}"
        error = f"its model error {geometry['planar_error']:.1e}"
        if (why := no_planar_matrix(model)) is not None:
            return None, f"pair with a Coulomb cap: {why}" if model.mu is not None else f"pair: {why}"
        if geometry["planar_error"] > ACCURACY:
            return None, (f"pair, planar theory not exact here: {error} exceeds the accuracy {ACCURACY:g} "
                          f"({where}); no matrix is claimed, the rows' theory is the exact reference")
        b = sphere_b(*(params[name] for name in parameters.PAIR_SPHERE))
        valid = f"pair, planar matrix valid: {error} <= the accuracy {ACCURACY:g} ({where})"
        return planar_matrix(model, b, three_d), valid
    choice = choose.which(model)
    if choice.has_matrix:
        return choose.matrix(model, three_d=three_d), "matrix"
    if choice.kind == "coulomb" and not model.normal_law.contact_radius:
        if off_uncapped <= STICK_TOLERANCE * scale:
            return choose.matrix(model.replace(mu=None), three_d=three_d), \
                "sticks throughout: the frictionless matrix applies"
        return None, "stick and slip: no single matrix (outcomes are not linear in the initial state)"
    if choice.kind in ("hertzian", "mindlin") and len(speeds) == 1:
        return choose.matrix(model, v_n=float(next(iter(speeds))), three_d=three_d), "matrix at one v_n"
    return None, f"{choice.name}: no single matrix"


def off_uncapped(model: ContactModel, initial: np.ndarray, theory: np.ndarray) -> float:
    """A capped Hookean group's largest |theory - frictionless matrix @ initial| (0 otherwise)."""
    if choose.which(model).kind != "coulomb" or model.normal_law.contact_radius:
        return 0.0
    uncapped = choose.matrix(model.replace(mu=None), three_d=initial.shape[1] == 6)
    return float(np.abs(theory - initial @ uncapped.T).max())


@dataclass
class GroupFit:
    """One model group's sums, gathered batch by batch (:func:`accumulate`; then, once
    :func:`solve` has its matrix, :func:`add_residuals`) and reported by :func:`report`."""

    params: dict
    names: tuple
    n: int = 0
    xtx: np.ndarray | None = None  # the least-squares normal equations, X^T X and X^T Y
    xty: np.ndarray | None = None
    omega_xx: float = 0.0  # Eq. 19's sums for Omega (slip_changes)
    omega_xy: float = 0.0
    scale: float = 0.0
    off_uncapped: float = 0.0
    speeds: set = field(default_factory=set)
    errors: list = field(default_factory=list)
    relative: list = field(default_factory=list)
    status: dict = field(default_factory=dict)
    residual_ss: np.ndarray | None = None
    residual_max: np.ndarray | None = None
    omega_ss: float = 0.0
    #: A pair group's largest planar_error, eps and centrifugal ratio (:func:`regime`).
    geometry: dict = field(default_factory=dict)
    found: tuple = (None, "")  # regime's (the theory's matrix or None, the regime's name)
    coef: np.ndarray | None = None
    omega: float = math.nan

    def arrays(self, frame: pd.DataFrame) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return tuple(frame[[f"{s}_{x}" for s in self.names]].to_numpy()
                     for x in ("initial", "lammps", "theory"))


def accumulate(g: GroupFit, frame: pd.DataFrame) -> None:
    """Add a batch of the group's rows to its sums (pass one)."""
    initial, final, theory = g.arrays(frame)
    g.n += len(frame)
    g.xtx = initial.T @ initial + (0.0 if g.xtx is None else g.xtx)
    g.xty = initial.T @ final + (0.0 if g.xty is None else g.xty)
    x, y = slip_changes(initial[:, :3], final[:, :3], omega_gains(g.params))
    g.omega_xx += float(x @ x)
    g.omega_xy += float(x @ y)
    g.scale = max(g.scale, float(np.abs(initial).max()))
    g.off_uncapped = max(g.off_uncapped, off_uncapped(model_of_group(g.params), initial, theory))
    for key in PAIR_GEOMETRY:
        if key in frame:
            g.geometry[key] = max(g.geometry.get(key, 0.0), float(frame[key].max()))
    if len(g.speeds) < 2:
        g.speeds.update(np.unique(initial[:, 0])[:2].tolist())
    g.errors.append(np.abs(frame[[f"{s}_error" for s in g.names]].to_numpy()).max(axis=1))
    # a copy: a column's array is a view of the whole batch's block, which would stay alive
    g.relative.append(frame["error"].to_numpy().copy() if "error" in frame else
                      g.errors[-1] / np.linalg.norm(initial, axis=1))
    if "status" in frame:
        for name, count in frame["status"].value_counts().items():
            g.status[name] = g.status.get(name, 0) + int(count)


def solve(g: GroupFit, rows: tuple | None = None) -> None:
    """The group's regime and, where a matrix applies, its matrix: from the normal equations, or
    by :func:`numpy.linalg.lstsq` on ``rows`` held in memory, (initial, final)."""
    g.found = regime(g.params, len(g.names) == 6, g.off_uncapped, g.scale, g.speeds, g.geometry)
    if g.found[0] is not None:
        g.coef = np.linalg.solve(g.xtx, g.xty) if rows is None else np.linalg.lstsq(*rows, rcond=None)[0]
        g.omega = g.omega_xy / g.omega_xx if g.omega_xx else math.nan


def add_residuals(g: GroupFit, frame: pd.DataFrame) -> None:
    """Add a batch's residuals from the solved matrix and Omega (pass two)."""
    initial, final, _ = g.arrays(frame)
    residuals = final - initial @ g.coef
    g.residual_ss = (residuals**2).sum(axis=0) + (0.0 if g.residual_ss is None else g.residual_ss)
    worst = np.abs(residuals).max(axis=0)
    g.residual_max = worst if g.residual_max is None else np.maximum(g.residual_max, worst)
    x, y = slip_changes(initial[:, :3], final[:, :3], omega_gains(g.params))
    g.omega_ss += float(((y - g.omega * x) ** 2).sum())


def report(g: GroupFit) -> dict:
    """One group's record: its parameters, theory, regime and per-collision deviation (worst and
    median, absolute and over the size of the initial state: the rows' ``error`` column,
    :mod:`spinbounce.checks`); where a matrix applies, the fit beside the theory's."""
    matrix_theory, name = g.found
    model, pair = model_of_group(g.params), g.params.get("scene") == "pair"
    # the theory the rows are checked against: the exact pair reference, or choose's
    kind = theory_kind(model) if pair else choose.which(model).kind
    worst, median = worst_and_median(g.errors)
    worst_relative, median_relative = worst_and_median(g.relative)
    out = {"parameters": group_parameters(g.params), "n": g.n, "theory": kind, "regime": name,
           "has_matrix": matrix_theory is not None, "worst_deviation": worst, "median_deviation": median,
           "worst_relative_deviation": worst_relative, "median_relative_deviation": median_relative}
    if g.status:
        out["status"] = g.status
    if g.coef is None:
        return out
    dof = max(g.n - len(g.names), 1)
    stderr = np.sqrt(np.outer(g.residual_ss / dof, np.diag(np.linalg.inv(g.xtx))))
    omega_err = math.sqrt(g.omega_ss / max(2 * g.n - 1, 1) / g.omega_xx) if g.omega_xx else math.nan
    if pair:  # the planar theory's Omega; the wall's: Eq. 18's r omega row
        from .scenes.pair.kind import planar_Omega, sphere_b

        omega_theory = float(planar_Omega(model, sphere_b(*(g.params[k] for k in parameters.PAIR_SPHERE))))
    else:
        omega_theory = float((matrix_theory[2, 2] - 1.0) * (1.0 + g.params["alpha"]))
    out.update({
        "matrix": g.coef.T.tolist(), "matrix_stderr": stderr.tolist(),
        "matrix_theory": matrix_theory.tolist(),
        "max_element_diff": float(np.abs(g.coef.T - matrix_theory).max()),
        "Omega": g.omega, "Omega_stderr": omega_err, "Omega_theory": omega_theory,
        "Omega_diff": g.omega - omega_theory,
        "residual_rms": np.sqrt(g.residual_ss / g.n).tolist(), "residual_max": g.residual_max.tolist(),
    })
    return out


def fit_groups(rows: pd.DataFrame) -> list[dict]:
    """One fit (or, where no matrix applies, one per-collision report) per model group: the sums
    of :func:`spinbounce.fitting_stream.fit_dataset` over the rows at once, with the matrix by
    least squares on the rows themselves."""
    keys = [k for k in GROUP_KEYS if k in rows]
    names = STATE_3D if f"{STATE_3D[-1]}_initial" in rows else STATE  # a 3-D sweep fits the 6x6 map
    fits = []
    for values, group in rows.groupby(keys, dropna=False, sort=True):
        g = GroupFit(dict(zip(keys, values, strict=True)), names)
        accumulate(g, group)
        solve(g, g.arrays(group)[:2])
        if g.coef is not None:
            add_residuals(g, group)
        fits.append(report(g))
    return fits


def _group_title(params: dict) -> str:
    """Every model parameter of a group, by name (LAMMPS lj units), for a panel's title."""
    import textwrap

    shown = [f"{k} = {v:g}" if isinstance(v, float) else f"{k} = {v}" for k, v in params.items()
             if k != "dt" and not (isinstance(v, float) and math.isnan(v))]
    return "\n".join(textwrap.wrap(", ".join(shown), 110))


def plot_groups(rows: pd.DataFrame, path: Path) -> Path:
    """Draw Eq. 19 per model group: LAMMPS's changes (points, on top) and the theory's lines (or,
    with no single Omega, the theory sphere by sphere as rings around them).

    One row of two panels per group: Delta v_t and r Delta omega against the initial slip
    u_dot(0) = v_t(0) + r omega(0), in LAMMPS lj units; each title names every model parameter.
    The format follows the suffix (.png or .pdf).
    """
    # Imported here so that fits, and everything else, work without drawing anything;
    # a bare Figure on the Agg canvas leaves pyplot's global backend alone.
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    path = Path(path)
    keys = [k for k in GROUP_KEYS if k in rows]
    groups = list(rows.groupby(keys, dropna=False, sort=True))
    fig = Figure(figsize=(8.0, 3.6 * len(groups)), layout="constrained")
    FigureCanvasAgg(fig)
    rows_of = np.atleast_1d(fig.subfigures(len(groups), 1))  # one per group, titled by its parameters
    for (values, group), row in zip(groups, rows_of, strict=True):
        ax_vt, ax_rw = row.subplots(1, 2)
        params = dict(zip(keys, values, strict=True))
        omegas = group["Omega_theory"].to_numpy()
        one_omega = bool(np.all(omegas == omegas[0]))  # NaN (Coulomb) or several (Hertz): per sphere
        big_omega = float(omegas[0]) if one_omega else math.nan
        c_t, c_r = omega_gains(params)  # Eq. 19's (the pair's with b at rest)
        slip = (group["v_t_initial"] + group["r_omega_initial"]).to_numpy()
        line = np.array([slip.min(), slip.max()])
        omega_text = f"$\\Omega$ = {big_omega:.5f}" if one_omega else "no single $\\Omega$"
        row.suptitle(_group_title(params) + "; " + omega_text, fontsize="x-small")
        for ax, column, slope, name in ((ax_vt, "v_t", c_t * big_omega, r"$\Delta v_t$"),
                                        (ax_rw, "r_omega", c_r * big_omega, r"$r\,\Delta\omega$")):
            change = group[f"{column}_lammps"] - group[f"{column}_initial"]
            if math.isnan(slope):  # no single Omega (Coulomb, Hertz): the theory sphere by sphere, ringed
                expected = group[f"{column}_theory"] - group[f"{column}_initial"]
                ax.plot(slip, expected, "o", ms=4, mfc="none", mew=0.6, color="tab:red", rasterized=True,
                        label="theory", zorder=1)
            else:
                ax.plot(line, slope * line, "-", lw=1, color="tab:red", label="Eq. 19", zorder=1)
            ax.plot(slip, change, ".", ms=1.5, color="tab:blue", rasterized=True, label="LAMMPS", zorder=2)
            ax.set(xlabel=r"$\dot u(0)$ [length/time]", ylabel=name + " [length/time]")
        ax_vt.legend(loc="best", fontsize="small")
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic_with(path, lambda tmp: fig.savefig(tmp, format=path.suffix.lstrip(".").lower(), dpi=150))
    return path
