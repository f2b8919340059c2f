"""The claims ledger: one record per claim, the verdict kinds, and what every claim shares.

A claim's function runs what it needs (batched collisions or one frozen contact) through
:class:`Runs` and returns a :class:`Claim` whose verdict is computed from its numbers; where
LAMMPS and the exact theory disagree, it is ``unresolved``, never quietly passed.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy import optimize

from ...scenes.collision import Collision
from ...model.contact import ContactModel
from ...scenes.frozen import Frozen
from ...model.timestep import refine_mid_step
from ...pipeline import run_scene, run_series

__all__ = ["VERDICTS", "COLLISION_TOL", "FROZEN_TOL", "DAMPED_REFINE", "Claim", "Runs", "verdict", "checked",
           "damped_dt", "random_states", "initial", "final", "contact_time", "maximise", "g"]

#: Every verdict a claim can get, and what it means.
VERDICTS: dict[str, str] = {
    "reproduced": "the paper's value agrees with the exact theory to the precision it was printed with, "
                  "and LAMMPS agrees with both",
    "approximate": "the paper's value is close but off by more than its precision (the size is stated)",
    "contradicted": "the paper's value or statement is wrong; the evidence says what holds instead",
    "inconsistent": "the paper defines the quantity twice and the two definitions give opposite answers; "
                    "the evidence says which definition gives which",
    "ill-posed": "the statement names a limit the model does not have in the stated form; the evidence "
                 "says what the model's limit is",
    "unresolved": "LAMMPS and the exact theory disagree beyond the run's tolerance, so no verdict on the "
                  "paper can be drawn",
}

#: The collision runs' integration error at the default (mid-step) dt is below 1e-4 (3e-5
#: measured at the defaults, 9e-5 at kt/kn = 1); ratios of such numbers are good to ~1e-4 too.
COLLISION_TOL = 2e-4
#: Frozen runs at the default dt: 5e-6 after 10 time units; fits of rates and slopes to a
#: whole series are good to ~1e-5.
FROZEN_TOL = 5e-5
#: With damping, LAMMPS's step is only first order in dt (the damping force uses the
#: half-step velocity): damped runs take a mid-step dt this many times finer.
DAMPED_REFINE = 32


@dataclass
class Claim:
    """One quantitative claim of the paper and what became of it."""

    key: str
    statement: str
    where: str
    paper: float | str
    lammps: float | str
    exact: float | str
    verdict: str = ""
    evidence: str = ""
    #: its runs' folders: under the claims' run folder; a gas's, named by its content, under the gases' (Runs.gases)
    runs: list[str] = field(default_factory=list)


def verdict(paper: float, lammps: float, exact: float, precision: float, lammps_tol: float,
            approx_tol: float = 0.0) -> str:
    """``reproduced`` / ``approximate`` / ``contradicted`` from the paper's distance to the
    exact value (or ``unresolved`` if LAMMPS and the exact theory disagree)."""
    if not abs(lammps - exact) <= lammps_tol:
        return "unresolved"
    gap = abs(paper - exact)
    if gap <= precision:
        return "reproduced"
    if gap <= approx_tol:
        return "approximate"
    return "contradicted"


def checked(lammps_agrees: bool, kind: str) -> str:
    """``kind`` if LAMMPS agreed with the exact theory, else ``unresolved``."""
    if kind not in VERDICTS:
        raise ValueError(f"unknown verdict {kind!r} (choose from {', '.join(VERDICTS)})")
    return kind if lammps_agrees else "unresolved"


def g(x: float, digits: int = 6) -> str:
    """A number in ``digits`` significant figures."""
    return f"{x:.{digits}g}"


def damped_dt(model: ContactModel) -> float:
    """The default mid-step dt refined DAMPED_REFINE times, keeping the contact's end mid-step."""
    return refine_mid_step(model.tau, Collision(model).dt, DAMPED_REFINE)


class Runs:
    """Where the claims' LAMMPS runs go, one folder per run; a run named twice is run once. Gases go to
    ``gases`` (by default the gases' folder under ``root``), by content: one finished there before is read back."""

    def __init__(self, root: Path, gases: Path | None = None):
        from ...scenes.gas.run import GASES

        self.root = Path(root)
        self.gases = Path(gases) if gases is not None else self.root / GASES
        self._done: dict[str, tuple] = {}

    def collide(self, name: str, model: ContactModel, vn, vt, omega, dt=None):
        """(scene, result table) of a batch of collisions: the scene as it ran (a default step's
        probe may have refined its dt)."""
        if name not in self._done:
            result = run_scene(Collision(model, v_n=vn, v_t=vt, omega=omega, dt=dt), self.root / name,
                               atoms="library")
            self._done[name] = result.scene, result.table
        return self._done[name]

    def frozen(self, name: str, model: ContactModel, **kwargs):
        """(scene, result table) of one frozen contact."""
        if name not in self._done:
            scene = Frozen(model, **kwargs)
            self._done[name] = scene, run_series(scene, self.root / name).table
        return self._done[name]


def random_states(n: int, seed: int, r: float = 0.5):
    """(v_n, v_t, omega) of n collisions: |v_n| in [0.1, 1.5], v_t and r omega in [-2, 2]."""
    rng = np.random.default_rng(seed)
    return rng.uniform(-1.5, -0.1, n), rng.uniform(-2.0, 2.0, n), rng.uniform(-2.0, 2.0, n) / r


def initial(t) -> np.ndarray:
    """(n, 3) initial states (v_n, v_t, r omega) of a result table."""
    return t[["v_n_initial", "v_t_initial", "r_omega_initial"]].to_numpy()


def final(t) -> np.ndarray:
    """(n, 3) final states (v_n, v_t, r omega) of a result table."""
    return t[["v_n_lammps", "v_t_lammps", "r_omega_lammps"]].to_numpy()


def contact_time(scene: Collision, t) -> np.ndarray:
    """When each sphere left the wall: the run's end minus its free flight from z = r, in the
    sphere's own time (a time-scaled sphere's step is dt over its scale: Collision.row_dt)."""
    end = scene.nsteps * scene.row_dt
    return end - (t["z_lammps"].to_numpy() - scene.model.r) / t["v_n_lammps"].to_numpy()


def maximise(fn, lo: float, hi: float, seeds: int = 200) -> tuple[float, float]:
    """(x, fn(x)) at the largest value of ``fn`` on [lo, hi].

    A grid of ``seeds`` points finds the best basin (the functions here have several
    local maxima); a bounded Brent search then pins it down to ~1e-10 in x.
    """
    grid = np.linspace(lo, hi, seeds)
    best = int(np.argmax([fn(x) for x in grid]))
    left, right = grid[max(best - 1, 0)], grid[min(best + 1, seeds - 1)]
    found = optimize.minimize_scalar(lambda x: -fn(x), bounds=(left, right), method="bounded",
                                     options={"xatol": 1e-10})
    return float(found.x), float(fn(found.x))
