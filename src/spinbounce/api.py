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
from .model.scenes import Collision
from .theory import choose

__all__ = ["collide", "theory", "sweep", "fit", "CollisionReport", "model"]

_MODEL_NAMES = {p.name for p in parameters.MODEL}


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


def _run_folder(kind: str, record: dict) -> Path:
    digest = hashlib.sha256(json.dumps(record, sort_keys=True, default=str).encode()).hexdigest()[:10]
    return Path("spinbounce-runs") / f"{kind}-{digest}"


def collide(v_n: float = -1.0, v_t: float = 1.0, omega: float = 0.0, v_s: float = 0.0, omega_s: float = 0.0,
            omega_n: float = 0.0, *, dt: float | None = None, out: str | Path | None = None,
            **model_parameters) -> CollisionReport:
    """Bounce one sphere off the wall in LAMMPS and compare it with the theory that applies."""
    from .pipeline import run_collision

    scene = Collision(model(**model_parameters), v_n=v_n, v_t=v_t, omega=omega, v_s=v_s, omega_s=omega_s,
                      omega_n=omega_n, dt=dt)
    out = Path(out) if out is not None else _run_folder("collide", {"scene": repr(scene)})
    result = run_collision(scene, out)
    row = result.table.iloc[0]
    names = result.scene.state_names
    table = pd.DataFrame({when: [float(row[f"{s}_{suffix}"]) for s in names]
                          for when, suffix in (("initial", "0"), ("LAMMPS", "final"), ("theory", "theory"),
                                               ("error", "error"))}, index=list(names))
    return CollisionReport(table, choose.which(scene.model).name, result.scene.dt, result.scene.nsteps,
                           float(row["error"]), str(row["status"]), out)


def theory(v_n: float | None = None, v_t: float = 0.0, omega: float = 0.0, v_s: float = 0.0, omega_s: float = 0.0,
           omega_n: float = 0.0, **model_parameters) -> dict:
    """The theory that applies: with ``v_n`` the final state of that collision, else the
    scattering matrix (or, where none exists, why not)."""
    contact = model(**model_parameters)
    choice = choose.which(contact)
    out = {"theory": choice.kind, "name": choice.name}
    if v_n is not None:
        out["initial"], out["final"] = choose.outcome(contact, v_n, v_t, omega, v_s, omega_s, omega_n)
    elif choice.has_matrix:
        out["matrix"] = np.asarray(contact.matrix())
        out["Omega"] = contact.Omega
    else:
        out["why_no_matrix"] = choice.no_matrix_reason
    return out


def sweep(n: int, out: str | Path, *, v_n=(-1.5, -0.1), v_t=(-2.0, 2.0), r_omega=(-2.0, 2.0), seed: int = 0,
          workers: int = 1, dt: float | None = None, **model_grid) -> pd.DataFrame:
    """Sample ``n`` collisions for every combination of the model values given (a number or a
    list each; ``None`` in ``mu``'s list is the paper's uncapped model) into ``out``; return the rows."""
    from .sweeps import read_results, run_sweep, spec_from_dict

    unknown = set(model_grid) - _MODEL_NAMES - {"kt_over_kn"}
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
    return pd.DataFrame([{**g["parameters"], **{k: v for k, v in g.items() if k != "parameters"}} for g in groups])
