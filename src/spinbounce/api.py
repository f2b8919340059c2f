"""The Python API: the commands' work, callable from a script or a notebook.

Keywords are the declared parameter names (:data:`spinbounce.model.parameters.MODEL` and
``STATE``), with the declared defaults, as on the command line (``gamma_n`` is
``--gamma-n`` there). Results are plain objects and pandas DataFrames::

    import spinbounce
    result = spinbounce.collide(v_n=-1.0, v_t=1.0, omega=0.0, mu=0.3)
    print(result)                    # LAMMPS beside the theory, with the error
    spinbounce.theory(gamma_t=0.5)   # the scattering matrix that applies
    rows = spinbounce.sweep(n=2000, out="my-sweep", mu=[None, 0.3])
    spinbounce.fit("my-sweep")       # one row per model group
    spinbounce.collide(scene="pair", m_b=3.0, r_b=0.8)   # sphere a against a free sphere b at rest
    spinbounce.sweep(n=100, out="pairs", scene="pair", m_b=[1.0, 3.0])

A script needs no ``if __name__ == "__main__"`` guard: a sweep runs in this process by
default (``workers=1``); with more workers it forks them while LAMMPS is not loaded here,
and spawns them (which does need the guard) once it is.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from .model import parameters
from .model.contact import ContactModel
from .scenes.collision import Collision
from .exact import choose

__all__ = ["collide", "theory", "sweep", "fit", "CollisionReport", "PairReport", "model"]

_MODEL_NAMES = {p.name for p in parameters.MODEL}
#: The scene's keywords (wall or pair, sphere b's m_b, r_b, alpha_b): :data:`parameters.SCENE`.
_SCENE_NAMES = {p.name for p in parameters.SCENE}


def _split_scene(keywords: dict):
    """(model keywords, sphere b or None for the wall), b's keywords refused without scene="pair"."""
    from .scenes.pair.kind import scene_of, sphere_b

    scene = {k: keywords.pop(k) for k in list(keywords) if k in _SCENE_NAMES}
    if scene_of(scene) == "wall":
        return keywords, None
    return keywords, sphere_b(**{k: v for k, v in scene.items() if k != "scene"})


def model(**parameters_) -> ContactModel:
    """A checked contact model from declared parameter names (unknown names are refused)."""
    unknown = set(parameters_) - _MODEL_NAMES
    if unknown:
        raise TypeError(f"unknown model parameter(s) {sorted(unknown)}; declared: {sorted(_MODEL_NAMES)}")
    return ContactModel(**parameters_)


@dataclass(frozen=True)
class CollisionReport:
    """One LAMMPS collision beside its theory. ``table`` has one row per state column."""

    table: pd.DataFrame
    theory: str
    dt: float
    nsteps: int
    error: float
    status: str
    run_dir: Path

    def __str__(self) -> str:
        head = (f"collision: theory {self.theory}; dt = {self.dt:.6g} ({self.nsteps} steps); "
                f"error {self.error:.2e} of the state's size; status {self.status}\n")
        return head + self.table.to_string(float_format=lambda x: f"{x:.10f}")


@dataclass(frozen=True)
class PairReport:
    """One pair scene in LAMMPS: both spheres' final states (``table``: LAMMPS, exact reference,
    planar theory), LAMMPS's error against the exact reference and the planar theory's model error."""

    table: pd.DataFrame
    dt: float
    nsteps: int
    error: float
    planar_error: float
    eps: float
    run_dir: Path

    def __str__(self) -> str:
        head = (f"pair: dt = {self.dt:.6g} ({self.nsteps} steps); LAMMPS vs exact {self.error:.2e}; planar theory's "
                f"model error {self.planar_error:.2e} (eps = {self.eps:.3g})\n")
        return head + self.table.to_string(float_format=lambda x: f"{x:.10f}")


def _pair_batch(b, model_parameters: dict, state: dict, dt=None):
    from .scenes.pair.kind import pair_contact, pairs_from_states
    from .scenes.pair.scene import PairBatch

    contact = model(**model_parameters)
    row = [state[k] for k in ("v_n", "v_t", "omega", "v_s", "omega_s", "omega_n")]
    return PairBatch(pairs_from_states(contact, b, [row]), pair_contact(contact), dt)


def _collide_pair(b, model_parameters: dict, state: dict, dt, out) -> PairReport:
    from .scenes.pair import QUANTITIES
    from .pipeline import run_scene

    batch = _pair_batch(b, model_parameters, state, dt)
    out = Path(out) if out is not None else _run_folder("collide-pair", {"pairs": repr(batch.pairs), "dt": batch.dt})
    result = run_scene(batch, out)  # its batch carries the step the probe chose
    row = result.table.iloc[0]
    table = pd.DataFrame({label: [float(row[q + suffix]) for q in QUANTITIES] for label, suffix in
                          (("LAMMPS", ""), ("exact", "_exact"), ("planar", "_planar"))}, index=list(QUANTITIES))
    return PairReport(table, result.scene.dt, result.scene.nsteps, float(row["error"]), float(row["planar_error"]),
                      float(row["eps"]), out)


def _run_folder(kind: str, record: dict) -> Path:
    digest = hashlib.sha256(json.dumps(record, sort_keys=True, default=str).encode()).hexdigest()[:10]
    return Path("spinbounce-runs") / f"{kind}-{digest}"


def collide(v_n: float = -1.0, v_t: float = 1.0, omega: float = 0.0, v_s: float = 0.0, omega_s: float = 0.0,
            omega_n: float = 0.0, *, dt: float | None = None, out: str | Path | None = None,
            **model_parameters) -> CollisionReport | PairReport:
    """Bounce one sphere off the wall in LAMMPS and compare it with the theory that applies; with
    ``scene="pair"`` (and ``m_b``, ``r_b``, ``alpha_b``) against a free sphere b at rest instead."""
    from .pipeline import run_scene

    model_parameters, b = _split_scene(model_parameters)
    if b is not None:
        state = {"v_n": v_n, "v_t": v_t, "omega": omega, "v_s": v_s, "omega_s": omega_s, "omega_n": omega_n}
        return _collide_pair(b, model_parameters, state, dt, out)

    scene = Collision(model(**model_parameters), v_n=v_n, v_t=v_t, omega=omega, v_s=v_s, omega_s=omega_s,
                      omega_n=omega_n, dt=dt)
    out = Path(out) if out is not None else _run_folder("collide", {"scene": repr(scene)})
    result = run_scene(scene, out)
    row = result.table.iloc[0]
    names = result.scene.state_names
    table = pd.DataFrame({when: [float(row[f"{s}_{suffix}"]) for s in names]
                          for when, suffix in (("initial", "initial"), ("LAMMPS", "lammps"), ("theory", "theory"),
                                               ("error", "error"))}, index=list(names))
    return CollisionReport(table, choose.which(scene.model).name, result.scene.dt, result.scene.nsteps,
                           float(row["error"]), str(row["status"]), out)


def theory(v_n: float | None = None, v_t: float = 0.0, omega: float = 0.0, v_s: float = 0.0, omega_s: float = 0.0,
           omega_n: float = 0.0, **model_parameters) -> dict:
    """The theory that applies: with ``v_n`` the final state of that collision, else the
    scattering matrix (or, where none exists, why not). With ``scene="pair"``: the planar
    pair theory's matrix of sphere a (b at rest), or one state's exact and planar outcomes."""
    model_parameters, b = _split_scene(model_parameters)
    if b is not None:
        return _pair_theory(b, model_parameters, v_n, {"v_t": v_t, "omega": omega, "v_s": v_s, "omega_s": omega_s,
                                                       "omega_n": omega_n})
    contact = model(**model_parameters)
    choice = choose.which(contact)
    out = {"theory": choice.kind, "name": choice.name}
    if v_n is not None:
        out["initial"], out["theory"] = choose.outcome(contact, v_n, v_t, omega, v_s, omega_s, omega_n)
    elif choice.has_matrix:
        out["matrix"] = np.asarray(contact.matrix())
        out["Omega"] = contact.Omega
    else:
        out["why_no_matrix"] = choice.no_matrix_reason
    return out


def _pair_theory(b, model_parameters: dict, v_n, state: dict) -> dict:
    from .scenes.pair.kind import CAPPED_NO_MATRIX, planar_Omega, planar_matrix
    from .scenes.pair.table import pair_table

    contact = model(**model_parameters)
    out = {"theory": "pair", "name": "planar pair theory (exact only as eps -> 0) and the exact reference"}
    if contact.mu is None:
        out.update(matrix=planar_matrix(contact, b), Omega=planar_Omega(contact, b))
    else:
        out["why_no_matrix"] = f"mu = {contact.mu!r}: {CAPPED_NO_MATRIX}"
    if v_n is not None:
        out["outcome"] = pair_table(_pair_batch(b, model_parameters, {"v_n": v_n, **state}), None).iloc[0].to_dict()
    return out


def sweep(n: int, out: str | Path, *, v_n=(-1.5, -0.1), v_t=(-2.0, 2.0), r_omega=(-2.0, 2.0), seed: int = 0,
          workers: int = 1, dt: float | None = None, **model_grid) -> pd.DataFrame:
    """Sample ``n`` collisions for every combination of the model values given (a number or a
    list each; ``None`` in ``mu``'s list is the paper's uncapped model) into ``out``; return the rows.
    ``scene="pair"`` with ``m_b``, ``r_b``, ``alpha_b``: sphere a against a free sphere b at rest."""
    from .sweeps import read_results, run_sweep, spec_from_dict

    unknown = set(model_grid) - _MODEL_NAMES - _SCENE_NAMES - {"kt_over_kn"}
    if unknown:
        raise TypeError(f"unknown model parameter(s) {sorted(unknown)}")
    grid = {k: ["none" if v is None else v for v in (vals if isinstance(vals, (list, tuple)) else [vals])]
            for k, vals in model_grid.items()}
    if dt is not None:
        grid["dt"] = dt
    raw = {"seed": seed, "states": {"n": n, "v_n": list(v_n), "v_t": list(v_t), "r_omega": list(r_omega)}}
    if grid:
        raw["model"] = grid
    run_sweep(spec_from_dict(raw), Path(out), workers=workers, log=lambda *_: None)
    return read_results(out)


def fit(results: str | Path | pd.DataFrame) -> pd.DataFrame:
    """One row per model group: its parameters, regime, per-collision deviation and (where one
    matrix applies) the fitted Omega beside the theory's; ``matrix`` holds the fitted matrix."""
    from .fitting import fit_groups
    from .sweeps import read_results

    rows = results if isinstance(results, pd.DataFrame) else read_results(results)
    groups = fit_groups(rows)
    return pd.DataFrame([{**_as_columns(g["parameters"]), **{k: v for k, v in g.items() if k != "parameters"}}
                         for g in groups])


def _as_columns(values: dict) -> dict:
    """A group's parameters as the sweep's table holds them (mu none: inf), so that the fit's
    rows group and filter like the sweep's."""
    from .fitting import by_column

    return {k: by_column[k].to_column(v) if k in by_column else v for k, v in values.items()}
