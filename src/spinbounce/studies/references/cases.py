"""The reference cases, small scenes whose results must not drift, and how close a fresh run
must come to each stored column, and why."""

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


@dataclass(frozen=True)
class Tolerance:
    """Largest allowed |fresh - stored| for every row of one column, and why that much.

    ``name`` labels the reason, shared by the columns it covers (manifest key).
    """

    name: str
    atol: float
    why: str


# LAMMPS runs serially here and is deterministic (two runs on one build agree bit for bit); on
# another machine a libm call may differ in its last bit, which velocity Verlet carries along for
# these linear springs without amplifying it (the integration error itself is ~1e-5). The
# measurements behind each atol are in MEASUREMENTS and the reasons, both recorded in the manifest.
_EXACT = Tolerance(
    "case_input", 0.0,
    "an input of the case definition, written and read back exactly (repr): any difference means the "
    "case itself was changed")
_THEORY = Tolerance(
    "theory", 1e-12,
    "pure Python/numpy theory (sqrt, exp, sin, cos of O(10) arguments): another libm may differ in the "
    "last bit, ~1e-15; 1e-12 allows that, and any change of a formula or a parameter moves it by far more")
_ORACLE = Tolerance(
    "oracle", 1e-9,
    "the Coulomb oracle (finite mu): adaptive DOP853 at rtol 1e-12 with located events, whose steps "
    "depend on scipy's version and on rounding (two revisions of its event handling differed by 3.7e-12); "
    "1e-9 allows that, while mu*(1 + 1e-7) moves the outputs by 5e-8")
_LAMMPS_FINAL = Tolerance(
    "lammps_final_state", 1e-10,
    "LAMMPS final state after <= ~1050 steps: bit-identical on this build; a 1-ulp change of the inputs "
    "moves it by <= 7.1e-15, so rounding on another CPU stays far below 1e-10, while dt*(1 + 1e-9) moves "
    "it by >= 1.2e-9 and kt*(1 + 1e-8) by >= 4.9e-10")
_LAMMPS_SERIES = Tolerance(
    "lammps_series", 1e-10,
    "LAMMPS frozen series over ~6000 steps: bit-identical on this build; a rounding difference would "
    "drift in phase, linearly in time: a 1-ulp change of the inputs moves it by <= 1.1e-15 at the end, so "
    "1e-10 has a 10^5 margin, while dt*(1 + 1e-9) moves it by >= 9.6e-10 and kt*(1 + 1e-8) by >= 4.6e-9")
_HELD = Tolerance(
    "held", 1e-12,
    "held height and normal velocity of the frozen sphere: exactly constant in LAMMPS (normal force "
    "cancelled, v_n = 0); the pipeline itself allows 1e-12 in z")
_TIME = Tolerance(
    "time", 1e-12,
    "step * dt, with dt from arithmetic and sqrt only (correctly rounded): reproduced exactly; 1e-12 is "
    "far below one step")

#: Collision reference columns -> tolerance. ``omega_lammps`` carries the spin in the
#: paper's units; r*omega is r times it and adds nothing.
COLLISION_TOLERANCES: dict[str, Tolerance] = {
    **dict.fromkeys(("id", "v_n_initial", "v_t_initial", "omega_initial"), _EXACT),
    **dict.fromkeys(("v_n_lammps", "v_t_lammps", "omega_lammps", "z_lammps"), _LAMMPS_FINAL),
    **dict.fromkeys(("v_n_theory", "v_t_theory", "omega_theory"), _THEORY),
}

#: A collision with a finite mu: the same, with the oracle's tolerance on its theory columns.
COLLISION_MU_TOLERANCES = {k: (_ORACLE if v is _THEORY else v) for k, v in COLLISION_TOLERANCES.items()}

#: Frozen-contact reference columns -> tolerance.
FROZEN_TOLERANCES: dict[str, Tolerance] = {
    "t": _TIME,
    **dict.fromkeys(("v_t", "omega"), _LAMMPS_SERIES),
    **dict.fromkeys(("z", "v_n"), _HELD),
    **dict.fromkeys(("v_t_theory", "r_omega_theory"), _THEORY),
}

#: The measurements behind the tolerances, recorded in the manifest next to them.
MEASUREMENTS = {
    "rerun": "two fresh runs of every case: largest difference 0.0 in every column; the data-file and "
             "library atom routes and the lmp executable reproduce the inline route exactly",
    "rounding_stand_in": "every initial velocity moved by 1 ulp: collision outputs move by <= 7.1e-15, "
                         "frozen outputs by <= 1.1e-15",
    "real_changes": "dt*(1 + 1e-9): collisions move by 1.2e-9 to 5.9e-8, frozen series by 9.6e-10 and "
                    "2.5e-8; dt*(1 + 1e-6): 9.6e-7 to 5.9e-5; kt*(1 + 1e-8): collisions by 4.9e-10 to "
                    "2.8e-5, frozen series by 4.6e-9 and 1.2e-7",
}


def tolerance_record() -> dict:
    """Per scene kind, column -> atol and the name of its reason; then the reasons (manifest entry)."""
    tables = {"collision": COLLISION_TOLERANCES, "collision_finite_mu": COLLISION_MU_TOLERANCES,
              "frozen": FROZEN_TOLERANCES}
    record = {kind: {column: {"atol": tol.atol, "reason": tol.name} for column, tol in table.items()}
              for kind, table in tables.items()}
    record["reasons"] = {tol.name: tol.why for table in tables.values() for tol in table.values()}
    return record


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

