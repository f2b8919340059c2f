"""The wall collision: spheres that start touching the wall (centre at z = r) with given
(v_n, v_t, omega) and run until they have left it; checked against Eq. 18 (theory.md).

A scene is pure data, checked when it is built (:mod:`spinbounce.scenes`). The normal force is
the model's normal sub-model (:mod:`spinbounce.laws.normal`): the paper's Hookean spring, or a
force that grows with the contact radius (Hertz), whose contact time depends on v_n; the scene
asks the sub-model for the contact's times, overlap and mode.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ... import checks
from ...exact import choose
from ...exact.choose import PLANE_COLUMNS, SPACE_COLUMNS
from ...model import parameters
from ...model.contact import ContactModel
from ...model.parameters import SceneError
from ...model.stability import overlap_stretch
from ...model.timestep import align_mid_step, check_steps, second_order_dt, steps_through, steps_per_contact
from ...lammps.decks import wall_parameters

__all__ = ["Collision", "row_states", "HERTZ_STEPS_PER_HALF_PERIOD", "STATE", "STATE_3D", "STATE_ARGS"]

#: How many steps late, per unit of gamma_n/m t_exit/e, LAMMPS's damped sphere may leave the
#: wall (an upper bound on the measured 0.1 to 0.3).
EXIT_DELAY = 0.5
#: Default resolution of a Hertzian collision: steps per half-period of the fastest mode.
#: Each sphere's contact ends at its own time, so no one dt puts every end mid-step and the
#: error is first order: cutting the tangential force off somewhere inside the last step
#: moves the final slip rate by at most sqrt(Q) dt |u'(0)|/2 (measured: 0.498 of
#: sqrt(Q) dt |u'(0)| at most, over 800 spheres). Since sqrt(Q) dt <= pi/N, N = 64000
#: keeps the error below pi/(2N) |u'(0)| <= 1e-4 for |v_t|, |r omega| <= 2, any alpha.
HERTZ_STEPS_PER_HALF_PERIOD = 64000
#: State columns, in order: the paper's plane, and in 3-D the second tangential pair and
#: the spin about the normal (each spin times r, with the sign that makes slip = v + r omega);
#: declared with the exact references, which read and write states too.
STATE, STATE_3D = PLANE_COLUMNS, SPACE_COLUMNS
#: Collision's per-sphere arguments, in the order of STATE_3D: the declared state.
STATE_ARGS = tuple(p.name for p in parameters.STATE)


def _as_vector(name: str, value) -> tuple[float, ...]:
    try:
        arr = np.atleast_1d(np.asarray(value, dtype=float))
    except (TypeError, ValueError):
        raise SceneError(name, value, "must be a number or a non-empty list of numbers") from None
    if arr.ndim != 1 or arr.size == 0:
        raise SceneError(name, value, "must be a number or a non-empty list of numbers")
    bad = np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        i = int(bad[0])
        raise SceneError(f"{name}[{i}]" if arr.size > 1 else name, float(arr[i]), "must be finite")
    return tuple((arr + 0.0).tolist())


def row_states(m: ContactModel, names, columns: dict) -> checks.RowStates:
    """A wall table's rows as the checks read them: its ``{s}_initial``, ``{s}_lammps`` and ``{s}_theory``
    state columns; errors relative to the initial state's size."""
    initial, final, reference = (np.column_stack([columns[f"{s}_{when}"] for s in names])
                                 for when in ("initial", "lammps", "theory"))
    weights = m.m * np.array([1.0, 1.0, m.alpha, 1.0, m.alpha, m.alpha])[: len(names)]
    return checks.RowStates(initial, final, reference, weights, np.linalg.norm(initial, axis=1),
                            m.max_overlap(np.abs(initial[:, 0])), m.r)


@dataclass(frozen=True)
class Collision:
    """Spheres that start touching the wall (centre at z = r) and bounce off it.

    ``v_n``, ``v_t`` and ``omega`` are numbers or equal-length sequences (one entry per
    sphere). ``omega`` is the angular velocity, positive anticlockwise (the paper's sign).

    In 3-D, ``v_s`` is the second tangential component (LAMMPS's y), ``omega_s`` the spin
    that rolls the sphere along it (LAMMPS's omega_x: that slip is v_s + r omega_s, the same
    form as the paper's) and ``omega_n`` the spin about the wall's normal (omega_z). A scene
    with any of them non-zero is 3-D: its states have six columns (:data:`STATE_3D`).
    ``dt = None`` takes the step of the default accuracy (:meth:`default_dt`, the contact's
    end mid-step; a run may refine it by a probe: :mod:`spinbounce.stepping`).
    """

    model: ContactModel = field(default_factory=ContactModel)
    v_n: tuple[float, ...] = (-1.0,)
    v_t: tuple[float, ...] = (1.0,)
    omega: tuple[float, ...] = (0.0,)
    dt: float | None = None
    v_s: tuple[float, ...] = (0.0,)
    omega_s: tuple[float, ...] = (0.0,)
    omega_n: tuple[float, ...] = (0.0,)
    #: Whether dt came from the default rule (a run may then tune it: spinbounce.stepping).
    default_step: bool = field(init=False, default=False)

    def __post_init__(self):
        set_ = object.__setattr__
        set_(self, "default_step", self.dt is None)
        if self.dt is None:
            self.model.check_default_step()
        columns = [_as_vector(name, getattr(self, name)) for name in STATE_ARGS]
        sizes = {len(c) for c in columns}
        if len(sizes - {1}) > 1:
            raise SceneError("/".join(STATE_ARGS), tuple(len(c) for c in columns), "lengths must match")
        n = max(sizes)
        for name, values in zip(STATE_ARGS, columns, strict=True):
            set_(self, name, values * n if len(values) == 1 else values)
        vn, m, speed = self.v_n, self.model, self.speed
        if m.style.planar_only and self.is_3d:
            raise SceneError("wall", m.wall, f"the {m.wall} wall's theory is in the paper's plane: give no v_s, "
                                             f"omega_s or omega_n with wall = {m.wall}")
        if m.mu is not None and m.tangential_law.capped_planar_only and self.is_3d:
            raise SceneError("tangential", m.tangential, "with a Coulomb cap (mu) its exact reference is in the "
                                                         "paper's plane: give no v_s, omega_s or omega_n")
        away = np.flatnonzero(np.asarray(vn) >= 0.0)
        if away.size:
            i = int(away[0])
            raise SceneError(f"v_n[{i}]" if n > 1 else "v_n", vn[i], "must be < 0 (towards the wall)")
        reach = float(np.max(m.max_overlap(np.abs(vn))))
        if reach >= m.r:
            raise SceneError(
                "v_n",
                max(vn, key=abs),
                f"|v_n| must be below {m.normal_law.tunnelling_speed(m):.6g}: the overlap would reach {reach:.6g} "
                f">= r = {m.r:g}, the centre would cross the wall and the sphere tunnel through it",
            )
        dt = self.default_dt() if self.dt is None else self.dt
        set_(self, "dt", m.check_dt(dt, frozen=False, speed=speed))
        # refused before anything runs: a collision that needs more steps than one run may take
        modes = m.modes(frozen=False, speed=speed)
        mode = max(modes, key=lambda name: math.hypot(*modes[name]))
        causes = {"slip": "kt, alpha and gamma_t", "normal": "kn and gamma_n"}
        why = (f"dt = {self.dt:.3g}: the {mode} mode ({causes[mode]}) is fast against the contact time "
               f"{float(np.max(m.contact_times(self.v_n))):.3g}")
        check_steps(self.nsteps, "dt", self.dt, why, spheres=self.n)
        stretch = overlap_stretch(m.normal_law.normal_mode(m, speed)[0], self.dt)
        if reach * stretch >= m.r:
            raise SceneError(
                "v_n",
                max(vn, key=abs),
                f"at dt = {self.dt:.6g} the step's own oscillation stretches the overlap to "
                f"{reach * stretch:.6g} >= r = {m.r:g} (exact: {reach:.6g}): the sphere would tunnel "
                "through the wall; use a smaller dt or a slower |v_n|",
            )

    def default_dt(self) -> float:
        """The step of the default accuracy (:mod:`.timestep`): second order on every contact
        mode over the contact's length, the contact's end mid-step. A Hertzian batch whose
        spheres end at different times cannot be aligned and runs at first order
        (:data:`HERTZ_STEPS_PER_HALF_PERIOD`); a single speed is aligned like a Hookean contact."""
        m = self.model
        times = m.contact_times(self.v_n)
        if np.ptp(times) > 0.0:
            return math.pi / m.fastest_rate(frozen=False, speed=self.speed) / HERTZ_STEPS_PER_HALF_PERIOD
        t_force = float(m.normal_law.force_times(m, self.v_n)[0])
        modes = m.modes(frozen=False, speed=self.speed).values()
        return align_mid_step(t_force, second_order_dt(modes, float(times[0])))

    @property
    def steps_per_half_period(self) -> float:
        """How finely dt resolves the fastest contact mode (its half-period over dt)."""
        return self.model.steps_per_half_period(self.dt, frozen=False, speed=self.speed)

    @property
    def speed(self) -> float:
        """The fastest |v_n|: where a force that grows with the overlap is stiffest."""
        return max(abs(v) for v in self.v_n)

    @property
    def n(self) -> int:
        return len(self.v_n)

    @property
    def is_3d(self) -> bool:
        """Whether any sphere moves or spins out of the paper's plane."""
        return any(any(getattr(self, name)) for name in STATE_ARGS[3:])

    @property
    def state_names(self) -> tuple[str, ...]:
        return STATE_3D if self.is_3d else STATE

    @property
    def initial(self) -> np.ndarray:
        """(n, 3) initial states (v_n, v_t, r omega); (n, 6) in 3-D (:data:`STATE_3D`)."""
        r = self.model.r
        columns = [self.v_n, self.v_t, np.array(self.omega) * r]
        if self.is_3d:
            columns += [self.v_s, np.array(self.omega_s) * r, np.array(self.omega_n) * r]
        return np.column_stack(columns)

    @property
    def nsteps(self) -> int:
        """Steps that end the contact: the step after tau, and one more for rounding; with
        strong normal damping more, as the sphere leaves slowly (:data:`EXIT_DELAY`)."""
        m = self.model
        t_exit = float(np.max(m.contact_times(self.v_n)))  # a speed-dependent contact: the slowest's
        # LAMMPS's first-order error in the overlap, about gamma_n/m dt |v_n| t_exit, is crossed
        # at the exit speed e |v_n|: the exit is late by that many steps, whatever dt is
        late = math.ceil(EXIT_DELAY * m.gamma_n / m.m * t_exit / m.restitution) if m.gamma_n else 0
        return steps_through(t_exit, self.dt) + max(0, late - 2)

    def predicted(self) -> np.ndarray:
        """Final states from the theory, shaped like :attr:`initial`: the scattering matrix
        (Eq. 18 with the exact damped Omega; its 6x6 block form in 3-D; one per sphere for a
        Hertzian wall, whose Omega depends on v_n), or with a finite mu the Coulomb oracle
        (:mod:`oracle`), sphere by sphere."""
        return choose.predict(self.model, self.initial)

    # --- what the pipeline and the step probe ask of every scene (spinbounce.scenes) ---

    kind = "collision"

    def render(self, atoms: str | None = None, padding=None):
        """The deck (:func:`.deck.render_collision`)."""
        from .deck import render_collision

        return render_collision(self, atoms, padding)

    def read(self, info, deck, folder) -> dict:
        """The run's checked table columns (:func:`.table.read_collision`)."""
        from .table import read_collision

        return read_collision(self, info, deck, folder)

    def row_states(self, columns: dict) -> checks.RowStates:
        """The sphere's initial, LAMMPS and theory states, in the paper's columns."""
        return row_states(self.model, self.state_names, columns)

    def record(self, deck) -> dict:
        """The run's parameters, for its provenance record."""
        m = self.model
        if m.normal_law.contact_radius or m.tangential_law.contact_radius:  # per sphere: tau or Omega(v_n)
            tau, omega = m.contact_times(self.v_n).tolist(), choose.omega_per_sphere(m, self.v_n).tolist()
        else:
            tau, omega = m.tau, m.Omega
        return {"model": m.as_record(), "dt": self.dt, "nsteps": self.nsteps, "tau": tau, "Omega": omega,
                "wall": wall_parameters(m), "integrator": "rigid" if deck.rigid else "nve/sphere",
                "atoms": "library" if deck.atoms is not None else ("data_file" if deck.files else "inline")}

    def needs_probe(self) -> bool:
        """Whether the step must be measured: not the paper's linear contact, and not a
        Hertzian batch of several speeds (its end cannot be aligned; it keeps its fixed rule)."""
        if choose.which(self.model).kind == "linear":
            return False
        return not np.ptp(self.model.contact_times(self.v_n)) > 0.0

    def probe_time(self, sample: "Collision") -> float:
        """The contact's length the probe's steps are counted over: the force's, the longest."""
        return float(np.max(self.model.normal_law.force_times(self.model, self.v_n)))

    def first_probe_steps(self, t_contact: float) -> int:
        return steps_per_contact(t_contact, self.dt)

    def step_limit(self, t_contact: float) -> float:
        return math.inf

    def fallback(self):
        """The scene at the step a probe falls back to: none, the wall's probe always answers."""
        return None

    def rows(self, index) -> "Collision":
        """The scene of the spheres ``index`` only."""
        return Collision(self.model, dt=self.dt, **{n: np.asarray(getattr(self, n))[index] for n in STATE_ARGS})

    def at_step(self, dt: float) -> "Collision":
        return Collision(self.model, dt=dt, **{n: getattr(self, n) for n in STATE_ARGS})
