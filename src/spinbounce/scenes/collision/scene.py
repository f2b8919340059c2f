"""The wall collision: spheres that start touching the wall (centre at z = r) with given
(v_n, v_t, omega) and run until they have left it; checked against Eq. 18 (theory.md).

A scene is pure data, checked when it is built (:mod:`spinbounce.scenes`). The normal force is
the model's normal sub-model (:mod:`spinbounce.laws.normal`): the paper's Hookean spring, or a
force that grows with the contact radius (Hertz), whose contact time depends on v_n; the scene
asks the sub-model for the contact's times, overlap and mode.

One dt cannot end contacts of different lengths mid-step, and LAMMPS's error is first order
unless a contact ends mid-step. So an undamped batch of Hertzian speeds runs each sphere in
its own time units (:mod:`.time_scale`, as the pair batches do): every contact then lasts the
longest one's time in the deck, and one step ends them all mid-step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ... import checks
from ...exact import choose
from ...exact.choose import PLANE_COLUMNS, SPACE_COLUMNS
from ...model import parameters
from ...model.contact import ContactModel
from ...model.parameters import SceneError, positive_number
from ...model.stability import overlap_stretch
from ...model.timestep import (MAX_STEPS, align_mid_step, check_steps, mode_rate, second_order_dt, steps_per_contact,
                               steps_through)
from ...lammps.decks import wall_parameters
from ..jump import beyond_reach, near_the_jump, slow_start, warn_slow_start
from .time_scale import dashpot, scaled_contact_time

__all__ = ["Collision", "row_states", "HERTZ_STEPS_PER_HALF_PERIOD", "STATE", "STATE_3D", "STATE_ARGS"]

#: How many steps late, per unit of gamma_n/m t_exit/e, LAMMPS's damped sphere may leave the
#: wall (an upper bound on the measured 0.1 to 0.3).
EXIT_DELAY = 0.5
#: Default resolution of a Hertzian batch of several speeds that cannot be time-scaled (a
#: dashpot, :func:`scaled_contact_time`): steps per half-period of the fastest mode.
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


def _as_vector(name: str, value) -> np.ndarray:
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
    out = arr + 0.0  # a copy of its own (and -0.0 as 0.0), which no one may change
    out.flags.writeable = False
    return out


def row_states(m: ContactModel, names, columns: dict) -> checks.RowStates:
    """A wall table's rows as the checks read them: its ``{s}_initial``, ``{s}_lammps`` and ``{s}_theory``
    state columns; errors relative to the initial state's size."""
    initial, final, reference = (np.column_stack([columns[f"{s}_{when}"] for s in names])
                                 for when in ("initial", "lammps", "theory"))
    weights = m.m * np.array([1.0, 1.0, m.alpha, 1.0, m.alpha, m.alpha])[: len(names)]
    return checks.RowStates(initial, final, reference, weights, np.linalg.norm(initial, axis=1),
                            m.max_overlap(np.abs(initial[:, 0])), m.r)


@dataclass(frozen=True, eq=False)
class Collision:
    """Spheres that start touching the wall (centre at z = r) and bounce off it.

    ``v_n``, ``v_t`` and ``omega`` are numbers or equal-length sequences (one entry per
    sphere). ``omega`` is the angular velocity, positive anticlockwise (the paper's sign).
    Each is kept as a read-only float array and what is derived is computed once (compared by identity).

    In 3-D, ``v_s`` is the second tangential component (LAMMPS's y), ``omega_s`` the spin
    that rolls the sphere along it (LAMMPS's omega_x: that slip is v_s + r omega_s, the same
    form as the paper's) and ``omega_n`` the spin about the wall's normal (omega_z). A scene
    with any of them non-zero is 3-D: its states have six columns (:data:`STATE_3D`).
    ``dt = None`` takes the step of the default accuracy (:meth:`default_dt`, the contact's
    end mid-step; a run may refine it by a probe: :mod:`spinbounce.stepping`).

    ``deck_contact_time``: how long every contact lasts in the deck, each sphere time-scaled to
    it (:attr:`time_scales`). None at the default step takes :func:`scaled_contact_time` (a batch
    of Hertzian speeds without a dashpot: its longest contact); with a given dt, None runs every
    sphere at dt. The probe's scenes carry it (:meth:`rows`, :meth:`at_step`), and a sweep gives
    every chunk of a group its slowest possible sphere's: one step then ends every contact
    mid-step in all of them.
    """

    model: ContactModel = field(default_factory=ContactModel)
    v_n: np.ndarray = (-1.0,)
    v_t: np.ndarray = (1.0,)
    omega: np.ndarray = (0.0,)
    dt: float | None = None
    v_s: np.ndarray = (0.0,)
    omega_s: np.ndarray = (0.0,)
    omega_n: np.ndarray = (0.0,)
    deck_contact_time: float | None = None
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
            if len(values) == 1 and n > 1:
                values = np.full(n, values[0])
                values.flags.writeable = False
            set_(self, name, values)
        vn, m, speed = self.v_n, self.model, self.speed
        if self.dt is None:  # once, where the default step is chosen (a probe's scenes carry their dt)
            warn_slow_start(self.model, slow_start(self.model, self.initial), probed=self.needs_probe())
        away = np.flatnonzero(vn >= 0.0)
        if away.size:
            i = int(away[0])
            raise SceneError(f"v_n[{i}]" if n > 1 else "v_n", vn[i], "must be < 0 (towards the wall)")
        m.check_overlap_resolved(vn)
        reach = float(np.max(m.max_overlap(np.abs(vn))))
        if reach >= m.r:
            raise SceneError(
                "v_n",
                max(vn, key=abs),
                f"|v_n| must be below {m.normal_law.tunnelling_speed(m):.6g}: the overlap would reach {reach:.6g} "
                f">= r = {m.r:g}, the centre would cross the wall and the sphere tunnel through it",
            )
        self._check_scale()
        # refused before anything runs: more steps than one run may take; first the fewest any step takes (the fastest
        # sphere's contact at MIN_STEPS_PER_HALF_PERIOD of its fastest mode), before a step of rates beyond a float
        why = m.check_resolvable(float(np.min(m.contact_times(self.v_n))), speed, "against the contact time "
                                 f"{float(np.max(m.contact_times(self.v_n))):.3g}", self.n)
        set_(self, "dt", self._checked_dt(self.default_dt() if self.dt is None else self.dt))
        check_steps(self.nsteps, "dt", self.dt, f"dt = {self.dt:.3g}: {why}", spheres=self.n)
        # the step's stretch of the deepest overlap, each end sphere at its own step dt/s
        law = m.normal_law
        stretched = max(float(m.max_overlap(v)) * overlap_stretch(law.normal_mode(m, v)[0], self.dt / s)
                        for v, s in self._end_spheres())
        if stretched >= m.r:
            raise SceneError(
                "v_n",
                max(vn, key=abs),
                f"at dt = {self.dt:.6g} the step's own oscillation stretches the overlap to "
                f"{stretched:.6g} >= r = {m.r:g} (exact: {reach:.6g}): the sphere would tunnel "
                "through the wall; use a smaller dt or a slower |v_n|",
            )

    def _check_scale(self) -> None:
        """The deck's contact time: the default step's :func:`scaled_contact_time`, or a given one
        (positive, and only where the scale is exact: no dashpot)."""
        m, given = self.model, self.deck_contact_time
        if given is None:
            if self.dt is None:
                object.__setattr__(self, "deck_contact_time", scaled_contact_time(m, self.v_n))
            return
        object.__setattr__(self, "deck_contact_time", positive_number("deck_contact_time", given))
        if dashpot(m):
            raise SceneError("deck_contact_time", given, "must be None with a dashpot (gamma_n or gamma_t "
                             "> 0): a time-scaled sphere's damping would have to scale with it")

    def _end_spheres(self) -> list[tuple[float, float]]:
        """(|v_n|, time scale) of the fastest and the slowest sphere (the fastest alone unless the
        batch is time-scaled). In deck time a mode w of sphere i is w/s_i = w T_i/T*, and w T is a
        power of |v_n| for every law here (Hertz: the same at every speed; a fixed spring: T's,
        |v_n|^(-1/5)): the fastest mode in the deck is the fastest or the slowest sphere's."""
        if not self.time_scaled:
            return [(self.speed, 1.0)]
        speeds, scales = np.abs(self.v_n), self.time_scales
        return [(float(speeds[k]), float(scales[k])) for k in (np.argmax(speeds), np.argmin(speeds))]

    def deck_modes(self) -> list[tuple[float, float]]:
        """The contact's modes (w, c) as the deck integrates them: the fastest sphere's, and in a
        time-scaled batch each end sphere's rates over its time scale (:meth:`_end_spheres`)."""
        rates = [(s, self.model.modes(frozen=False, speed=v).values()) for v, s in self._end_spheres()]
        return [(w / s, c / s) for s, modes in rates for w, c in modes]

    def _checked_dt(self, dt) -> float:
        """dt, refused above the stability limit or too coarse for a contact mode: the fastest
        sphere's at dt, or in a time-scaled batch each end sphere's at its own step dt/s."""
        m = self.model
        if not self.time_scaled:
            return m.check_dt(dt, frozen=False, speed=self.speed)
        dt = positive_number("dt", dt)
        for v, s in self._end_spheres():
            try:
                m.check_dt(dt / s, frozen=False, speed=v)
            except SceneError as exc:
                raise SceneError("dt", dt, f"as the sphere at |v_n| = {v:.6g} runs it (time-scaled by "
                                 f"{s:.6g}: its step is dt/{s:.6g} = {dt / s:.6g}), {exc.limit}") from None
        return dt

    def default_dt(self) -> float:
        """The step of the default accuracy (:mod:`.timestep`): second order on every contact
        mode over the contact's length, the contact's end mid-step. A batch of Hertzian speeds is
        aligned so in deck time, each sphere time-scaled to the longest contact
        (:attr:`time_scales`), its modes those of :meth:`deck_modes`; one with a dashpot cannot be
        scaled exactly, its spheres end at different times, and it keeps a fixed first-order rule
        (:data:`HERTZ_STEPS_PER_HALF_PERIOD`). A single speed is aligned like a Hookean contact."""
        m = self.model
        times = self.deck_contact_times
        if np.ptp(times) > 0.0 and self.deck_contact_time is None:
            return math.pi / m.fastest_rate(frozen=False, speed=self.speed) / HERTZ_STEPS_PER_HALF_PERIOD
        return align_mid_step(self.force_time, second_order_dt(self.deck_modes(), float(np.max(times))))

    @cached_property
    def time_scales(self) -> np.ndarray:
        """Per sphere, how many times slower its time runs in the deck: T*/T_i, T* the deck's
        contact time (:func:`scaled_contact_time`); its mass is m s^2, its velocities and spins
        over s, and its final ones are LAMMPS's times s. All ones when not time-scaled."""
        if self.deck_contact_time is None:
            return np.ones(self.n)
        return self.deck_contact_time / self.model.contact_times(self.v_n)

    @property
    def time_scaled(self) -> bool:
        """Whether any sphere runs at a time scale other than 1 (its deck sets masses per sphere)."""
        return bool(np.any(self.time_scales != 1.0))

    @cached_property
    def deck_contact_times(self) -> np.ndarray:
        """Each sphere's contact time in the deck: T_i s_i (T* for every sphere of a scaled batch)."""
        return self.model.contact_times(self.v_n) * self.time_scales

    @cached_property
    def force_time(self) -> float:
        """When the last contact force ends in the deck (:meth:`NormalLaw.force_times`, in deck time)."""
        m = self.model
        return float(np.max(m.normal_law.force_times(m, self.v_n) * self.time_scales))

    @property
    def row_dt(self) -> np.ndarray:
        """The step each sphere ran at, in its own time: dt/s_i (dt unless time-scaled)."""
        return self.dt / self.time_scales

    @property
    def steps_per_half_period(self) -> float:
        """How finely dt resolves the fastest contact mode (its half-period over dt; in deck time)."""
        if not self.time_scaled:
            return self.model.steps_per_half_period(self.dt, frozen=False, speed=self.speed)
        return math.pi / max(mode_rate(w, c) for w, c in self.deck_modes()) / self.dt

    @cached_property
    def speed(self) -> float:
        """The fastest |v_n|: where a force that grows with the overlap is stiffest."""
        return float(np.max(np.abs(self.v_n)))

    @property
    def n(self) -> int:
        return len(self.v_n)

    @cached_property
    def is_3d(self) -> bool:
        """Whether any sphere moves or spins out of the paper's plane."""
        return any(np.any(getattr(self, name)) for name in STATE_ARGS[3:])

    @property
    def state_names(self) -> tuple[str, ...]:
        return STATE_3D if self.is_3d else STATE

    @cached_property
    def initial(self) -> np.ndarray:
        """(n, 3) initial states (v_n, v_t, r omega); (n, 6) in 3-D (:data:`STATE_3D`)."""
        r = self.model.r
        columns = [self.v_n, self.v_t, self.omega * r]
        if self.is_3d:
            columns += [self.v_s, self.omega_s * r, self.omega_n * r]
        out = np.column_stack(columns)
        out.flags.writeable = False  # computed once: a caller's change would change the scene
        return out

    @cached_property
    def nsteps(self) -> int:
        """Steps that end the contact: the step after tau, and one more for rounding; with
        strong normal damping more, as the sphere leaves slowly (:data:`EXIT_DELAY`)."""
        m = self.model
        t_exit = float(np.max(self.deck_contact_times))  # a speed-dependent contact: the slowest's
        # LAMMPS's first-order error in the overlap, about gamma_n/m dt |v_n| t_exit, is crossed
        # at the exit speed e |v_n|: the exit is late by that many steps, whatever dt is
        exit_speed = float(np.min(m.normal_law.restitutions(m, self.v_n))) if m.gamma_n else 1.0
        late = math.ceil(EXIT_DELAY * m.gamma_n / m.m * t_exit / exit_speed) if m.gamma_n else 0
        return steps_through(t_exit, self.dt) + max(0, late - 2)

    def predicted(self) -> np.ndarray:
        """Final states from the theory, shaped like :attr:`initial`: the scattering matrix
        (Eq. 18 with the exact damped Omega; its 6x6 block form in 3-D; one per sphere for a
        Hertzian wall, whose Omega depends on v_n), or with a finite mu the Coulomb oracle
        (:mod:`oracle`), sphere by sphere; NaN for a state whose LAMMPS outcome has no limit."""
        return choose.predict(self.model, self.initial, limitless="nan")

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
        if m.normal_law.contact_radius or m.tangential_law.contact_radius or m.normal_law.integrated(m):
            tau, omega = m.contact_times(self.v_n).tolist(), choose.omega_per_sphere(m, self.v_n).tolist()
        else:
            tau, omega = m.tau, m.Omega
        out = {"model": m.as_record(), "dt": self.dt, "nsteps": self.nsteps, "tau": tau, "Omega": omega,
               "wall": wall_parameters(m), "integrator": "rigid" if deck.rigid else "nve/sphere",
               "atoms": "library" if deck.atoms is not None else ("data_file" if deck.files else "inline")}
        if self.time_scaled:
            scales = self.time_scales
            out["time_scaled"] = {
                "deck_contact_time": self.deck_contact_time,
                "scales": [float(scales.min()), float(scales.max())],
                "row_dt": [float(self.row_dt.min()), float(self.row_dt.max())],
                "meaning": "sphere i ran in time units s_i times longer (mass m s_i^2, v and omega over "
                           "s_i): every contact lasted deck_contact_time at dt; its own step was dt/s_i"}
        return out

    def needs_probe(self) -> bool:
        """Whether the step must be measured: not the paper's linear contact, and not a
        Hertzian batch of several speeds that is not time-scaled (its ends cannot be aligned;
        it keeps its fixed rule) unless some state lies just above its law's jump
        (:meth:`near_the_jump`), where the fixed rule falls short."""
        if choose.which(self.model).kind == "linear":
            return False
        aligned = self.deck_contact_time is not None or not np.ptp(self.model.contact_times(self.v_n)) > 0.0
        return aligned or bool(np.any(self.near_the_jump()))

    def near_the_jump(self) -> np.ndarray:
        """Per state, whether its law's outcome jumps just below it (:func:`spinbounce.scenes.jump.near_the_jump`)."""
        return near_the_jump(self.model, self.initial)

    def beyond_reach(self) -> np.ndarray:  # per state, whether no affordable step reaches the target
        return beyond_reach(self.model, self.initial)

    def probe_time(self, sample: "Collision") -> float:
        """The contact's length the probe's steps count over: the force's, the longest (in deck time)."""
        return self.force_time

    def first_probe_steps(self, t_contact: float) -> int:
        return steps_per_contact(t_contact, self.dt)

    def step_limit(self, t_contact: float) -> float:
        """Steps per contact a probe may ask for: any (a step beyond a run's limit is refused with
        the probe's errors, stepping.tune), but a quarter of the limit with a state near its law's
        jump (:meth:`near_the_jump`), which falls back to the rule's step instead."""
        return MAX_STEPS // 4 if np.any(self.near_the_jump()) else math.inf

    def fallback(self):
        """The scene at the step a probe falls back to: with a state near its law's jump, where no
        affordable step may reach the target, this one (the rule's step), each row's error reported;
        else none, the wall's probe answers."""
        return self if np.any(self.near_the_jump()) else None

    def rows(self, index) -> "Collision":
        """The scene of the spheres ``index`` only."""
        return Collision(self.model, dt=self.dt, deck_contact_time=self.deck_contact_time,
                         **{n: getattr(self, n)[index] for n in STATE_ARGS})

    def at_step(self, dt: float) -> "Collision":
        return Collision(self.model, dt=dt, deck_contact_time=self.deck_contact_time,
                         **{n: getattr(self, n) for n in STATE_ARGS})
