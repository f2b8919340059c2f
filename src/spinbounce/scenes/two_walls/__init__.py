"""A sphere between two parallel walls: many successive collisions against the product of
scattering matrices (theory.md; docs/theory.md, "Two parallel walls").

The bottom wall is z = 0 with normal +z (the single-wall scene's), the top wall z = H with
normal -z; a state is the bottom wall's (:func:`~spinbounce.lammps.decks.wall_frame`). The
mirror z -> -z changes the sign of v_z, omega_x and omega_y, so the top wall's map is R M R
with R = diag(-1, 1, -1) (3-D: diag(-1, 1, -1, 1, -1, 1)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ... import exact
from ...errors import ResultError
from ...exact import choose
from ...lammps.decks import (ALPHA_NVE_SPHERE, Deck, lammps_vectors, prepare_run_dir, render_template, wall_frame,
                             wall_parameters)
from ...lammps.dumps import finite_frames, read_dump
from ...lammps.runner import run_deck
from ...model.contact import ContactModel
from ...model.parameters import SceneError
from ...model.timestep import mid_step_dt

__all__ = ["TwoWalls", "TwoWallsResult", "mirror", "matrix_product", "theory_path", "run_two_walls",
           "FLIGHT_STEPS"]

#: Steps of the first flight between the walls in the default gap: long enough for several
#: dumped frames, short enough that flights cost less than contacts.
FLIGHT_STEPS = 40
#: Where in a step each contact starts (the first: spheres start START_PHASE steps of flight
#: above the wall; the later ones, with e = 1, through the default gap's flight of a whole
#: number of steps and a half, which makes up for the contact's own half step). The tangential outcome
#: depends on how many steps see an overlap: a contact of tau = (N + 1/2) dt that starts at
#: phase phi sees N of them for 0 < phi < 1/2 (as a single collision, started on a step
#: with zero overlap, does) and N + 1 for phi >= 1/2, a first-order error (3e-3 at the
#: default step, measured). The normal error is first order in 1/2 - phi (4e-5 at phi = 0,
#: 3e-7 at 1/2, measured): 0.45 keeps it small and stays far (5e-2 of a step against a drift
#: of about 1e-5 steps per flight) from the switch at 1/2.
START_PHASE = 0.45
#: Frames per flight (at least) and per contact: each flight must show in the dump.
FRAMES_PER_FLIGHT = 4
DUMP_NAME = "walls.dump"
#: LAMMPS allows 32 groups, "all" included: one group per distinct model, 31 at most.
MAX_MODELS = 31


def mirror(width: int = 3) -> np.ndarray:
    """R: the reflection z -> -z on a state (v_n, v_t, r omega[, v_s, r omega_s, r omega_n])."""
    return np.diag([-1.0, 1.0, -1.0, 1.0, -1.0, 1.0][:width])


def matrix_product(model: ContactModel, bounces: int, width: int = 3) -> np.ndarray:
    """The map of ``bounces`` successive collisions, bottom wall first: ... M_top M_bottom.

    M_top = R M R (R: :func:`mirror`); only for models with one matrix (Eq. 18 or its exact
    damped form), else :class:`~spinbounce.errors.NoMatrix`.
    """
    bottom = choose.matrix(model, three_d=width == 6)
    r = mirror(width)
    top = r @ bottom @ r
    product = np.eye(width)
    for k in range(bounces):
        product = (bottom if k % 2 == 0 else top) @ product
    return product


def theory_path(model: ContactModel, initial, bounces: int) -> np.ndarray:
    """(bounces + 1, n, width) states after 0..bounces collisions, from :func:`choose.predict`
    applied bounce by bounce (the top wall's in the mirrored frame): the oracle with a finite mu."""
    state = np.atleast_2d(np.asarray(initial, dtype=float))
    r = mirror(state.shape[1])
    path = [state]
    for k in range(bounces):
        state = choose.predict(model, state) if k % 2 == 0 else choose.predict(model, state @ r) @ r
        path.append(state)
    return np.array(path)


#: Two walls' default resolution: every bounce's error adds up, and each later contact starts
#: only near a step's middle. Measured over 20 bounces of the paper's model: 3.4e-4 at 250
#: steps per half-period, 2.0e-5 at 1000 (the 1e-4 target needs this).
TWO_WALL_STEPS_PER_HALF_PERIOD = 1000


@dataclass(frozen=True)
class TwoWalls:
    """Spheres falling onto the bottom wall (from START_PHASE steps above it), bouncing ``bounces`` times between the walls.

    ``models`` holds one contact model per sphere (each distinct model gets its own pair of
    wall fixes); ``initial`` the (n, 3) or (n, 6) states. ``gap`` (H) defaults to the one
    whose first flight at the slowest sphere's speed makes
    each later contact start at START_PHASE of a step (with e = 1), so that LAMMPS resolves it
    as it resolves a single collision (model/timestep.py). ``steps_per_half_period`` resolves the fastest contact mode.
    """

    models: tuple[ContactModel, ...]
    initial: np.ndarray = field(repr=False)
    bounces: int = 20
    gap: float | None = None
    steps_per_half_period: int = TWO_WALL_STEPS_PER_HALF_PERIOD
    dt: float = field(init=False, default=0.0)

    def __post_init__(self):
        set_ = object.__setattr__
        states = np.atleast_2d(np.asarray(self.initial, dtype=float))
        if states.shape[1] not in (3, 6) or not np.all(np.isfinite(states)):
            raise SceneError("initial", states.shape,
                             "must be finite rows of 3 or 6 numbers (v_n, v_t, r omega, ...)")
        if np.any(states[:, 0] >= 0.0):
            raise SceneError("v_n", float(states[:, 0].max()), "must be < 0 (towards the bottom wall)")
        set_(self, "initial", states)
        models = tuple(self.models)
        if len(models) != len(self.initial):
            raise SceneError("models", len(models), f"must give one model per sphere ({len(self.initial)})")
        for model in models:
            if model.normal_law.contact_radius or model.style.tangential_contact_radius \
                    or model.tangential_law.contact_radius or model.alpha != ALPHA_NVE_SPHERE:
                raise SceneError("model", model, "two walls run Hookean spheres with alpha = 2/5 (fix nve/sphere) "
                                 "on granular walls; a Hertzian, Mindlin or classic wall or another alpha is not "
                                 "implemented here")
        if len(set(models)) > MAX_MODELS:
            raise SceneError("models", len(set(models)), f"at most {MAX_MODELS} distinct models in one run "
                             "(LAMMPS allows 32 groups): split the spheres over several runs")
        set_(self, "models", models)
        if int(self.bounces) != self.bounces or self.bounces < 1:
            raise SceneError("bounces", self.bounces, "must be a whole number >= 1")
        # each model's exit mid-step, at steps_per_half_period of its fastest mode or finer
        per_tau = [self.steps_per_half_period * m.fastest_rate(frozen=False) * m.t_exit / math.pi
                   for m in models]
        set_(self, "dt", min(mid_step_dt(m.t_exit, math.ceil(n - 1e-9)) for m, n in zip(models, per_tau)))
        r = models[0].r
        if any(m.r != r or m.m != models[0].m for m in models):
            raise SceneError("r", r, "every sphere of a two-wall scene has the same m and r (one atom type)")
        if self.gap is None:
            slowest = float(np.min(np.abs(self.initial[:, 0])))
            # a contact of (N + 1/2) steps and a flight of (K + 1/2) steps: the next contact starts
            # at the same phase of a step as this one
            set_(self, "gap", 2.0 * r + slowest * (FLIGHT_STEPS + 0.5) * self.dt)
        reach = max(float(exact.max_overlap(v, m.m, m.kn, m.gamma_n))
                    for v, m in zip(self.initial[:, 0], models, strict=True))
        if reach >= r:
            raise SceneError("v_n", float(self.initial[:, 0].min()), f"the overlap would reach {reach:.6g} >= r: "
                             "the sphere would tunnel through the wall")
        if not self.gap > 2.0 * r:
            raise SceneError("gap", self.gap, f"must exceed the diameter 2 r = {2 * r:g}")

    @property
    def r(self) -> float:
        return self.models[0].r

    @property
    def lift(self) -> np.ndarray:
        """Each sphere's start above touching: START_PHASE steps of flight."""
        return np.abs(self.initial[:, 0]) * START_PHASE * self.dt

    def contact_times(self) -> np.ndarray:
        """(n, bounces): when each sphere leaves each wall (exact normal motion; e per bounce)."""
        out = np.empty((len(self.initial), self.bounces))
        for i, (model, v_n) in enumerate(zip(self.models, self.initial[:, 0], strict=True)):
            t, speed = START_PHASE * self.dt, abs(v_n)
            for k in range(self.bounces):
                t += model.t_exit
                speed *= model.restitution
                out[i, k] = t
                t += (self.gap - 2.0 * self.r) / speed
        return out

    def flights(self) -> tuple[float, float]:
        """(the run's end: the middle of every sphere's last flight or later, the shortest flight)."""
        exits = self.contact_times()
        speeds = np.array([[abs(v) * m.restitution ** (k + 1) for k in range(self.bounces)]
                           for m, v in zip(self.models, self.initial[:, 0], strict=True)])
        flight = (self.gap - 2.0 * self.r) / speeds
        return float(np.max(exits[:, -1] + 0.5 * flight[:, -1])), float(flight.min())


def render_two_walls(scene: TwoWalls) -> Deck:
    """The deck: spheres at (0, 0, r) with their LAMMPS velocities, a pair of walls per model."""
    r, s = scene.r, scene.initial
    extra = s[:, 3:] if s.shape[1] == 6 else np.zeros((len(s), 3))
    v, w = lammps_vectors(s[:, 0], s[:, 1], s[:, 2] / r, extra[:, 0], extra[:, 1] / r, extra[:, 2] / r)
    spheres = [{"id": i + 1, "x": 0.0, "y": 0.0, "z": r + scene.lift[i], **dict(zip(("vx", "vy", "vz"), v[i])),
                **dict(zip(("wx", "wy", "wz"), w[i]))} for i in range(len(s))]
    distinct = list(dict.fromkeys(scene.models))
    groups = [{"name": f"model{j + 1}", "model": model, "wall": wall_parameters(model),
               "ids": " ".join(str(i + 1) for i, m in enumerate(scene.models) if m == model)}
              for j, model in enumerate(distinct)]
    end, shortest = scene.flights()
    contact_steps = min(m.t_exit for m in distinct) / scene.dt
    every = math.floor(min(shortest / scene.dt, contact_steps) / FRAMES_PER_FLIGHT)
    if every < 1:
        raise SceneError("gap", scene.gap, f"the shortest flight lasts {shortest / scene.dt:.3g} steps: widen the gap "
                         f"to at least {FRAMES_PER_FLIGHT} steps of flight")
    span = 10.0 * r
    ctx = {"deck_name": "in.lammps", "n": len(s), "gap": scene.gap,
           "bounces": scene.bounces, "spheres": spheres, "r": r, "m": scene.models[0].m, "groups": groups,
           "box": {"xlo": -span, "xhi": span, "ylo": -span, "yhi": span, "zlo": 0.0, "zhi": scene.gap},
           "every": every, "dump_name": DUMP_NAME, "dt": scene.dt, "run_steps": math.ceil(end / scene.dt)}
    return Deck(text=render_template(Path(__file__).parent, "two_walls.lmp.j2", **ctx), dump=DUMP_NAME)


@dataclass(frozen=True)
class TwoWallsResult:
    """LAMMPS's states after 0..bounces collisions, (bounces + 1, n, width), and the time each
    contact ended, (n, bounces), extrapolated back from a frame in the flight after it."""

    scene: TwoWalls
    states: np.ndarray
    exit_times: np.ndarray
    deck: Path

    def contact_durations(self) -> np.ndarray:
        """(n, bounces): each contact's length, from its exit and the previous flight."""
        exits = self.exit_times
        speeds = np.abs(self.states[1:-1, :, 0]).T  # after bounce k, before k + 1
        first = np.full((exits.shape[0], 1), START_PHASE * self.scene.dt)
        starts = np.concatenate([first,
                                 exits[:, :-1] + (self.scene.gap - 2.0 * self.scene.r) / speeds], axis=1)
        return exits - starts


def _flight_frames(rows, scene: TwoWalls) -> list[int]:
    """Index of the last frame of each flight after the first contact, in order (a flight:
    frames clear of both walls with one sign of v_z)."""
    r = scene.r
    clear = (rows["z"] > r) & (rows["z"] < scene.gap - r)
    last, previous_sign, previous_clear = [], 0.0, False
    touched = int(np.argmin(clear))  # the fall onto the bottom wall is no flight
    for k in range(touched, len(clear)):
        sign = math.copysign(1.0, rows["vz"][k])
        if clear[k]:
            if previous_clear and sign == previous_sign:
                last[-1] = k
            else:
                last.append(k)
        previous_clear, previous_sign = bool(clear[k]), sign
    return last


def run_two_walls(scene: TwoWalls, out_dir: Path) -> TwoWallsResult:
    """Run ``scene`` in ``out_dir``; each sphere's state after every bounce, read in flight."""
    deck = render_two_walls(scene)
    deck_path = prepare_run_dir(out_dir, deck)
    run_deck(deck_path)
    frames = finite_frames(read_dump(deck_path.parent / DUMP_NAME), deck_path)
    n, width = scene.initial.shape
    states = np.empty((scene.bounces + 1, n, width))
    states[0] = scene.initial
    exits = np.empty((n, scene.bounces))
    for i in range(n):
        mine = frames[frames["id"] == i + 1]
        rows = {c: mine[c].to_numpy() for c in ("step", "z", "vx", "vy", "vz", "omegax", "omegay", "omegaz")}
        last = _flight_frames(rows, scene)
        if len(last) < scene.bounces:
            raise ResultError(f"{deck_path}: sphere {i + 1} made {len(last)} of {scene.bounces} flights")
        picked = {c: v[last[:scene.bounces]] for c, v in rows.items()}
        v, w = (np.column_stack([picked[f"{q}{axis}"] for axis in "xyz"]) for q in ("v", "omega"))
        states[1:, i] = wall_frame(v, w, scene.r)[:, :width]
        wall_side = np.where(picked["vz"] > 0.0, scene.r, scene.gap - scene.r)
        exits[i] = picked["step"] * scene.dt - (picked["z"] - wall_side) / picked["vz"]
    return TwoWallsResult(scene, states, exits, deck_path)
