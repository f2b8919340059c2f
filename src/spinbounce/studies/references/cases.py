"""The reference cases: small scenes whose results must not drift, defined once here."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from ... import exact
from ...model.timestep import mid_step_dt
from ...scenes.collision import Collision
from ...model.contact import ContactModel
from ...scenes.frozen import Frozen
from ...records import json_ready
from .tolerances import COLLISION_MU_TOLERANCES, COLLISION_TOLERANCES, FROZEN_TOLERANCES, Tolerance

__all__ = ["CASES", "ReferenceCase", "case_by_name", "tolerances_for"]

#: Where the references live, relative to the repository's top folder.
DEFAULT_DIR = Path("tests") / "reference"


# (v_n, v_t, omega) per sphere: head-on, pure spin, mixed signs, near-rolling, glancing.
_STANDARD = (
    (-1.0, 1.0, 0.0),
    (-1.0, 0.0, 2.0),
    (-0.5, -0.7, 1.3),
    (-1.2, 0.3, -2.5),
    (-0.3, 2.0, 0.0),
    (-0.8, -1.5, -1.0),
)


#: The resolutions the references were made at, in steps per half-period of the fastest
#: contact mode: collisions mid-step (model.timestep), frozen contacts a whole number of steps.
REFERENCE_COLLISION_STEPS = 250
REFERENCE_FROZEN_STEPS = 1000


def reference_dt(model: ContactModel, kind: str, t_end: float | None) -> float:
    """The fixed step of a stored reference (the default step when they were made)."""
    rate = model.fastest_rate(frozen=kind == "frozen")
    if kind == "frozen":
        dt = math.pi / rate / REFERENCE_FROZEN_STEPS if rate > 0.0 else t_end / 1000
        return t_end / math.ceil(t_end / dt)
    return mid_step_dt(model.tau, math.ceil(REFERENCE_COLLISION_STEPS * rate * model.tau / math.pi - 1e-9))


@dataclass(frozen=True)
class ReferenceCase:
    """One stored reference: a scene kind, its model, its states and its step.

    ``states``: collision, one (v_n, v_t, omega) per sphere, all in one run; frozen, a
    single (z, v_t, omega). ``dt = None`` takes the resolution the references were made at
    (:func:`reference_dt`, recorded in the manifest), not today's default: a stored reference
    must not move when the default step is retuned. ``t_end`` and ``every`` (dump cadence, which subsamples the series) are for
    frozen cases only.
    """

    name: str
    kind: str  # "collision" or "frozen"
    description: str
    model: dict = field(default_factory=dict)  # ContactModel arguments that differ from the defaults
    states: tuple = ()
    dt: float | None = None
    t_end: float | None = None
    every: int | None = None

    def contact_model(self) -> ContactModel:
        return ContactModel(**self.model)

    def scene(self) -> Collision | Frozen:
        model = self.contact_model()
        dt = self.dt if self.dt is not None else reference_dt(model, self.kind, self.t_end)
        if self.kind == "collision":
            vn, vt, om = (list(column) for column in zip(*self.states, strict=True))
            return Collision(model, v_n=vn, v_t=vt, omega=om, dt=dt)
        if self.kind == "frozen":
            (z, vt, om), = self.states
            # as they were made: the run goes on to the first dump at or after t_end
            steps = math.ceil(self.t_end / dt - 1e-9)
            t_end = math.ceil(steps / self.every) * self.every * dt if self.every else self.t_end
            return Frozen(model, z=z, v_t=vt, omega=om, t_end=t_end, dt=dt, every=self.every)
        raise ValueError(f"case {self.name!r}: unknown kind {self.kind!r}")

    def rows(self, scene=None) -> int:
        scene = scene or self.scene()
        return scene.n if self.kind == "collision" else scene.nsteps // scene.every + 1

    def describe(self) -> dict:
        """The case as the manifest records it (JSON types; computable without LAMMPS)."""
        scene = self.scene()
        out = {
            "kind": self.kind,
            "description": self.description,
            "model": scene.model.as_record(),
            "states": [list(s) for s in self.states],
            "dt": scene.dt,
            "nsteps": scene.nsteps,
        }
        if self.kind == "frozen":
            out.update(t_end=self.t_end, every=scene.every)
        out.update(rows=self.rows(scene), table=f"{self.name}.csv")
        return json_ready(out)


_KN = ContactModel().kn

CASES: tuple[ReferenceCase, ...] = (
    ReferenceCase("defaults", "collision", "the paper's model: m = 1, r = 0.5, alpha = 2/5, kn = 10, kt = 1",
                  states=_STANDARD),
    ReferenceCase("magic_ratio", "collision", "kt/kn = alpha/(1 + alpha) = 2/7: Omega = -2, energy conserved",
                  model={"kt": _KN * exact.magic_kt_over_kn(0.4)}, states=_STANDARD),
    ReferenceCase("alpha_0.1", "collision", "alpha = 0.1: mass near the centre, the rigid-body route",
                  model={"alpha": 0.1}, states=_STANDARD),
    ReferenceCase("shell_magic", "collision", "alpha = 2/3 (thin shell) at its magic ratio kt/kn = 2/5",
                  model={"alpha": 2.0 / 3.0, "kt": _KN * exact.magic_kt_over_kn(2.0 / 3.0)}, states=_STANDARD),
    ReferenceCase("damped_tangential", "collision", "tangential damping gamma_t = 0.3, no normal damping",
                  model={"gamma_t": 0.3}, states=_STANDARD),
    ReferenceCase("damped_normal", "collision", "normal damping gamma_n = 1 (restitution 0.60) with gamma_t = 0.2",
                  model={"gamma_n": 1.0, "gamma_t": 0.2}, states=_STANDARD),
    ReferenceCase("overdamped_tangential", "collision",
                  "gamma_t = 2: the slip mode is overdamped (zeta = 3.5 > sqrt(Q) = 1.87); it sets dt",
                  model={"gamma_t": 2.0}, states=_STANDARD),
    ReferenceCase("grazing", "collision", "grazing incidence |v_n| = 1e-3 with large slip",
                  states=((-1e-3, 2.0, 0.0), (-1e-3, -3.0, 1.0), (-1e-3, 0.5, -6.0), (-1e-3, 0.0, 4.0))),
    ReferenceCase("near_tunnelling", "collision",
                  "|v_n| close to the tunnelling limit 1.58: overlap up to 0.49 of r = 0.5",
                  states=((-1.5, 1.0, 0.0), (-1.5, -0.5, 3.0), (-1.55, 0.2, -1.0), (-1.55, 0.0, 0.0))),
    ReferenceCase("soft_kt", "collision", "very soft tangential spring kt/kn = 1e-3",
                  model={"kt": 1e-3 * _KN}, states=_STANDARD),
    ReferenceCase("stiff_kt", "collision", "stiff tangential spring kt/kn = 5: the slip mode sets a smaller dt",
                  model={"kt": 5.0 * _KN}, states=_STANDARD),
    ReferenceCase("large_spin", "collision", "large spin |r omega| = 20 |v_n| (r = 0.5: |omega| = 40 |v_n|)",
                  states=((-1.0, 0.0, 40.0), (-0.5, 0.3, -20.0), (-0.1, -0.2, 4.0), (-1.2, 1.0, -48.0))),
    ReferenceCase("mu_0.1", "collision", "Coulomb limit mu = 0.1: the spheres slide (not the paper's model)",
                  model={"mu": 0.1}, states=_STANDARD),
    ReferenceCase("frozen_defaults", "frozen", "frozen contact at the paper's defaults (its Fig. 2), ~200 rows",
                  states=((0.1, 1.0, 0.0),), t_end=10.0, every=30),
    ReferenceCase("frozen_damped", "frozen", "frozen contact with tangential damping gamma_t = 0.3, ~200 rows",
                  model={"gamma_t": 0.3}, states=((0.1, 1.0, -1.0),), t_end=10.0, every=30),
)


def case_by_name(name: str) -> ReferenceCase:
    for case in CASES:
        if case.name == name:
            return case
    raise KeyError(f"no reference case {name!r}; known: {', '.join(c.name for c in CASES)}")


def tolerances_for(case: ReferenceCase) -> dict[str, Tolerance]:
    if case.kind != "collision":
        return FROZEN_TOLERANCES
    if case.model.get("mu") is not None:  # the theory columns are the oracle's
        return COLLISION_MU_TOLERANCES
    return COLLISION_TOLERANCES

