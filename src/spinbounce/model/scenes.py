"""Validated descriptions of what to simulate: the contact model and the scenes.

A scene is pure data: it knows nothing of files or LAMMPS. Every check happens when a
scene is built, so bad input is refused before any LAMMPS run, with a message that
names the parameter, its value and the limit it broke.

Two scenes:

* :class:`Collision`: spheres start touching the wall (centre at z = r) with given
  (v_n, v_t, omega) and run until they have left it; checked against Eq. 18.
* :class:`Frozen`: one sphere held at a fixed height z < r, so v_n = 0 and only the
  slip evolves; checked against Eq. 10 (or its exact damped form).

The normal force is the paper's Hookean spring or, with ``normal="hertz"``, LAMMPS's
Hertzian one (theory in :mod:`spinbounce.theory.hertz`), whose contact time depends on v_n.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..theory import hertz
from .. import theory
from .stability import stability_limit
from .timestep import mid_step_dt, steps_through

__all__ = [
    "SceneError",
    "PhysicsWarning",
    "ContactModel",
    "NORMAL_LAWS",
    "Collision",
    "Frozen",
    "COLLISION_STEPS_PER_HALF_PERIOD",
    "FROZEN_STEPS_PER_HALF_PERIOD",
    "HERTZ_STEPS_PER_HALF_PERIOD",
    "MIN_STEPS_PER_HALF_PERIOD",
    "STATE",
    "STATE_3D",
    "STATE_ARGS",
]

#: Default resolution of a collision: steps per half-period of the fastest contact mode,
#: with the contact's end placed mid-step. The error is then second order in dt; measured
#: over |v_n| <= 1.5, |v_t|, |r omega| <= 2 at the paper's defaults it is at most 3e-5
#: (1.7e-5 in v_t and r omega) at 250 steps, 7e-6 at 500 and 1.9e-6 at 1000 (README).
COLLISION_STEPS_PER_HALF_PERIOD = 250
#: Default resolution of a frozen contact. There is no contact end to align; velocity
#: Verlet's phase error grows with time, 5e-6 after 10 time units at this resolution.
FROZEN_STEPS_PER_HALF_PERIOD = 1000
#: Default resolution of a Hertzian collision: steps per half-period of the fastest mode.
#: Each sphere's contact ends at its own time, so no one dt puts every end mid-step and the
#: error is first order: cutting the tangential force off somewhere inside the last step
#: moves the final slip rate by at most sqrt(Q) dt |u'(0)|/2 (measured: 0.498 of
#: sqrt(Q) dt |u'(0)| at most, over 800 spheres). Since sqrt(Q) dt <= pi/N, N = 64000
#: keeps the error below pi/(2N) |u'(0)| <= 1e-4 for |v_t|, |r omega| <= 2, any alpha.
HERTZ_STEPS_PER_HALF_PERIOD = 64000
#: Normal force laws: LAMMPS's granular ``hooke`` (F = kn delta, the paper's) and ``hertz``
#: (F = kn sqrt(r) delta^(3/2) against a flat wall).
NORMAL_LAWS = ("hooke", "hertz")
#: Below this many steps per half-period a result is a caricature: warn.
MIN_STEPS_PER_HALF_PERIOD = 20
#: State columns, in order: the paper's plane, and in 3-D the second tangential pair and
#: the spin about the normal (each spin times r, with the sign that makes slip = v + r omega).
STATE = ("vn", "vt", "r_omega")
STATE_3D = STATE + ("vs", "r_omega_s", "r_omega_n")
#: Collision's per-sphere arguments, in the order of STATE_3D.
STATE_ARGS = ("v_n", "v_t", "omega", "v_s", "omega_s", "omega_n")
#: Above alpha = 2/3 part of the mass would sit outside the sphere (Section 3).
ALPHA_SHELL = 2.0 / 3.0


class SceneError(ValueError):
    """A scene parameter is out of its allowed range. Raised before LAMMPS starts."""

    def __init__(self, parameter: str, value, limit: str):
        self.parameter = parameter
        self.value = value
        self.limit = limit
        super().__init__(f"{parameter} = {value!r}: {limit}")


class PhysicsWarning(UserWarning):
    """A scene is allowed but physically unusual or numerically marginal."""


def _finite(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise SceneError(name, value, "must be a number") from None
    if not math.isfinite(v):
        raise SceneError(name, value, "must be finite")
    return v


def _positive(name: str, value) -> float:
    v = _finite(name, value)
    if v <= 0.0:
        raise SceneError(name, value, "must be > 0")
    return v


def _non_negative(name: str, value) -> float:
    v = _finite(name, value)
    if v < 0.0:
        raise SceneError(name, value, "must be >= 0")
    return v


@dataclass(frozen=True)
class ContactModel:
    """The sphere and its wall contact (Eq. 1), in LAMMPS lj units.

    ``mu = None`` is the paper's model: no Coulomb limit on the tangential force.
    ``normal = "hertz"`` replaces the Hookean normal spring by F = kn sqrt(r) delta^(3/2)
    (kn in force/length^2, LAMMPS's K); its v_n-dependent theory is in :mod:`spinbounce.theory.hertz`.
    """

    m: float = 1.0
    r: float = 0.5
    alpha: float = 0.4
    kn: float = 10.0
    kt: float = 1.0
    gamma_n: float = 0.0
    gamma_t: float = 0.0
    mu: float | None = None
    #: LAMMPS's ``limit_damping``: the normal force never pulls (it is cut at zero, and
    #: the tangential force with it, since |F_t| <= mu |F_n|). Default: tensile allowed.
    limit_damping: bool = False
    #: The normal force law, one of NORMAL_LAWS.
    normal: str = "hooke"

    def __post_init__(self):
        set_ = object.__setattr__
        if self.normal not in NORMAL_LAWS:
            raise SceneError("normal", self.normal, f"must be one of {', '.join(NORMAL_LAWS)}")
        if not isinstance(self.limit_damping, bool):
            raise SceneError("limit_damping", self.limit_damping, "must be true or false")
        for name in ("m", "r", "kn"):
            set_(self, name, _positive(name, getattr(self, name)))
        for name in ("kt", "gamma_n", "gamma_t"):
            set_(self, name, _non_negative(name, getattr(self, name)))
        alpha = _finite("alpha", self.alpha)
        if not 0.0 < alpha <= 1.0:
            raise SceneError("alpha", self.alpha, "must lie in (0, 1] (alpha = I/(m r^2))")
        if alpha > ALPHA_SHELL:
            warnings.warn(
                f"alpha = {alpha:g} > 2/3: more than a thin shell's inertia, the sphere "
                "carries 'phantom' mass beyond its radius (paper, Section 3)",
                PhysicsWarning,
                stacklevel=3,
            )
        set_(self, "alpha", alpha)
        if self.mu is not None:
            set_(self, "mu", _non_negative("mu", self.mu))
        if self.normal == "hertz" and self.gamma_n > 0.0:
            raise SceneError(
                "gamma_n",
                self.gamma_n,
                "must be 0 with normal = 'hertz': there is no exact theory here of the damped "
                "Hertzian contact to check it against",
            )
        critical = 2.0 * math.sqrt(self.m * self.kn)
        if self.gamma_n >= critical:
            raise SceneError(
                "gamma_n",
                self.gamma_n,
                f"must be below critical normal damping 2*sqrt(m*kn) = {critical:.6g}: "
                "at or above it the sphere never leaves the wall",
            )

    # -- derived quantities (theory, in the paper's names) -------------------------
    @property
    def inertia(self) -> float:
        return self.alpha * self.m * self.r**2

    def _hooke_only(self, what: str) -> None:
        if self.normal != "hooke":
            raise SceneError("normal", self.normal, f"has no single {what}: it depends on v_n "
                             "(per-sphere values: Collision.predicted(), spinbounce.theory.hertz)")

    @property
    def tau(self) -> float:
        """Contact time, Eq. 16 (damped form when gamma_n > 0): how long the force acts."""
        self._hooke_only("contact time tau")
        return theory.collision_time(self.m, self.kn, self.gamma_n, not self.limit_damping)

    @property
    def t_exit(self) -> float:
        """When the sphere is out of the overlap (later than tau with limit_damping)."""
        self._hooke_only("exit time")
        return theory.exit_time(self.m, self.kn, self.gamma_n, not self.limit_damping)

    @property
    def Q(self) -> float:
        return theory.Q(self.kt, self.m, self.alpha)

    @property
    def zeta(self) -> float:
        return theory.damping_rate(self.gamma_t, self.m, self.alpha)

    @property
    def Omega(self) -> float:
        """Exact Omega (Eq. 18's when undamped)."""
        self._hooke_only("Omega")
        return theory.Omega_exact(self.m, self.kn, self.kt, self.alpha, self.gamma_t, self.gamma_n,
                                  not self.limit_damping)

    @property
    def restitution(self) -> float:
        self._hooke_only("restitution")
        return theory.restitution(self.m, self.kn, self.gamma_n, not self.limit_damping)

    def matrix(self) -> np.ndarray:
        """The scattering matrix this model predicts (Eq. 18, exact damped Omega)."""
        return theory.scattering_matrix(self.alpha, self.Omega, self.restitution)

    def block_matrix(self) -> np.ndarray:
        """The 6x6 map of 3-D states (:data:`STATE_3D`)."""
        return theory.block_matrix(self.alpha, self.Omega, self.restitution)

    def contact_times(self, v_n) -> np.ndarray:
        """Each sphere's time until it is out of the overlap (Hertz: tau(v_n); Hooke: t_exit)."""
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        if self.normal == "hertz":
            return hertz.contact_time(v, self.m, self.kn, self.r)
        return np.full(v.shape, self.t_exit)

    def matrices(self, v_n) -> np.ndarray:
        """(n, 3, 3): each sphere's scattering matrix (Hooke: the one matrix, repeated)."""
        v = np.atleast_1d(np.asarray(v_n, dtype=float))
        if self.normal == "hertz":
            return hertz.scattering_matrices(v, self.m, self.kn, self.r, self.kt, self.alpha, self.gamma_t)
        return np.broadcast_to(self.matrix(), (v.size, 3, 3))

    # -- numerics --------------------------------------------------------------------
    def modes(self, frozen: bool, speed: float | None = None) -> dict[str, tuple[float, float]]:
        """The linear contact modes a scene integrates: name -> (w, c) of x'' + c x' + w^2 x = 0.

        The Hertzian normal mode is nonlinear; it is represented by its stiffest point, the
        largest overlap of the fastest sphere, whose |v_n| is ``speed``.
        """
        out = {"slip": (math.sqrt(self.Q), 2.0 * self.zeta)}
        if not frozen:
            if self.normal == "hertz":
                if speed is None:
                    raise ValueError("a Hertzian collision's normal mode needs the fastest |v_n| (speed)")
                out["normal"] = (float(hertz.normal_frequency(speed, self.m, self.kn, self.r)), 0.0)
            else:
                out["normal"] = (math.sqrt(self.kn / self.m), self.gamma_n / self.m)
        return out

    def fastest_rate(self, frozen: bool, speed: float | None = None) -> float:
        """Largest rate (1/time) among the integrated modes: frequency or fast decay rate."""
        rates = []
        for w, c in self.modes(frozen, speed).values():
            half = 0.5 * c
            rates.append(w if half < w else half + math.sqrt(half * half - w * w))
        return max(rates)

    def dt_limit(self, frozen: bool, speed: float | None = None) -> tuple[float, str]:
        """Stability limit of LAMMPS's step and the mode that sets it."""
        limits = {name: stability_limit(w, c) for name, (w, c) in self.modes(frozen, speed).items()}
        name = min(limits, key=limits.get)
        return limits[name], name

    def check_dt(self, dt, frozen: bool, speed: float | None = None) -> float:
        dt = _positive("dt", dt)
        limit, mode = self.dt_limit(frozen, speed)
        if dt >= limit:
            raise SceneError(
                "dt",
                dt,
                f"must be below the stability limit {limit:.6g} of the {mode} mode "
                "(LAMMPS's velocity-Verlet step diverges above it)",
            )
        rate = self.fastest_rate(frozen, speed)
        steps = math.pi / rate / dt if rate > 0.0 else math.inf
        if steps < MIN_STEPS_PER_HALF_PERIOD:
            warnings.warn(
                f"dt = {dt:g} resolves the fastest contact mode with only {steps:.1f} steps "
                f"per half-period (fewer than {MIN_STEPS_PER_HALF_PERIOD}): expect a large error",
                PhysicsWarning,
                stacklevel=3,
            )
        return dt


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


def _hertz_collision_dt(scene: "Collision") -> float:
    """Tunnelling and step checks of a Hertzian collision; returns its (checked) dt.

    Only the fastest sphere matters: its overlap is the deepest and the wall stiffest there.
    """
    m = scene.model
    fastest = max(scene.v_n, key=abs)
    speed = abs(fastest)
    reach = float(hertz.max_overlap(speed, m.m, m.kn, m.r))
    if reach >= m.r:
        raise SceneError(
            "v_n", fastest,
            f"|v_n| must be below {hertz.tunnelling_speed(m.m, m.kn, m.r):.6g} for the Hertzian wall: "
            f"the overlap would reach {reach:.6g} >= r = {m.r:g}, the centre would cross the wall "
            "and the sphere tunnel through it",
        )
    dt = m.check_dt(scene.default_dt() if scene.dt is None else scene.dt, frozen=False, speed=speed)
    # For a linear spring, LAMMPS's step stretches the largest overlap by 1/sqrt(1 - (w dt/2)^2).
    # Taking w at the Hertzian wall's stiffest point bounds its stretch: to leading order the
    # step's modified energy gives 1 + (w dt)^2/36 for the Hertzian wall, against 1 + (w dt)^2/8
    # (tests/test_hertz.py replays the step to check the bound).
    half_step = 0.5 * float(hertz.normal_frequency(speed, m.m, m.kn, m.r)) * dt
    stretch = 1.0 / math.sqrt(1.0 - half_step**2) if half_step < 1.0 else math.inf
    if reach * stretch >= m.r:
        raise SceneError(
            "v_n", fastest,
            f"at dt = {dt:.6g} the step may stretch the Hertzian overlap to {reach * stretch:.6g} >= "
            f"r = {m.r:g} (exact: {reach:.6g}): the sphere could tunnel through the wall; use a "
            "smaller dt or a slower |v_n|",
        )
    return dt


@dataclass(frozen=True)
class Collision:
    """Spheres that start touching the wall (centre at z = r) and bounce off it.

    ``v_n``, ``v_t`` and ``omega`` are numbers or equal-length sequences (one entry per
    sphere). ``omega`` is the angular velocity, positive anticlockwise (the paper's sign).

    In 3-D, ``v_s`` is the second tangential component (LAMMPS's y), ``omega_s`` the spin
    that rolls the sphere along it (LAMMPS's omega_x: that slip is v_s + r omega_s, the same
    form as the paper's) and ``omega_n`` the spin about the wall's normal (omega_z). A scene
    with any of them non-zero is 3-D: its states have six columns (:data:`STATE_3D`).
    ``dt = None`` picks ``tau/(N + 1/2)`` with N = COLLISION_STEPS_PER_HALF_PERIOD scaled by
    the fastest contact mode: the half step puts the end of the contact in the middle of
    a step, where the error made by cutting the tangential force off cancels to
    first order (README, "accuracy").
    """

    model: ContactModel = field(default_factory=ContactModel)
    v_n: tuple[float, ...] = (-1.0,)
    v_t: tuple[float, ...] = (1.0,)
    omega: tuple[float, ...] = (0.0,)
    dt: float | None = None
    v_s: tuple[float, ...] = (0.0,)
    omega_s: tuple[float, ...] = (0.0,)
    omega_n: tuple[float, ...] = (0.0,)

    def __post_init__(self):
        set_ = object.__setattr__
        columns = [_as_vector(name, getattr(self, name)) for name in STATE_ARGS]
        sizes = {len(c) for c in columns}
        if len(sizes - {1}) > 1:
            raise SceneError("/".join(STATE_ARGS), tuple(len(c) for c in columns), "lengths must match")
        n = max(sizes)
        for name, values in zip(STATE_ARGS, columns, strict=True):
            set_(self, name, values * n if len(values) == 1 else values)
        vn = self.v_n
        m = self.model
        away = np.flatnonzero(np.asarray(vn) >= 0.0)
        if away.size:
            i = int(away[0])
            raise SceneError(f"v_n[{i}]" if n > 1 else "v_n", vn[i], "must be < 0 (towards the wall)")
        if m.normal == "hertz":  # the contact depends on v_n: checks and step of its own
            set_(self, "dt", _hertz_collision_dt(self))
            return
        reach = float(np.max(theory.max_overlap(np.array(vn), m.m, m.kn, m.gamma_n)))
        if reach >= m.r:
            fastest = max(vn, key=abs)
            vmax = m.r / float(theory.max_overlap(1.0, m.m, m.kn, m.gamma_n))
            raise SceneError(
                "v_n",
                fastest,
                f"|v_n| must be below {vmax:.6g}: the overlap would reach {reach:.6g} >= r = {m.r:g}, "
                "the centre would cross the wall and the sphere tunnel through it",
            )
        dt = self.default_dt() if self.dt is None else self.dt
        set_(self, "dt", m.check_dt(dt, frozen=False))
        # LAMMPS's velocity Verlet keeps v^2 + w^2 x^2 (1 - (w dt/2)^2) constant in the
        # undamped normal spring, so its largest overlap exceeds the exact one by the factor
        # 1/sqrt(1 - (w dt/2)^2): a coarse step can tunnel where the exact motion would not
        half_step = 0.5 * math.sqrt(m.kn / m.m) * self.dt
        stretch = 1.0 / math.sqrt(1.0 - half_step**2) if half_step < 1.0 else math.inf
        if reach * stretch >= m.r:
            raise SceneError(
                "v_n",
                max(vn, key=abs),
                f"at dt = {self.dt:.6g} the step's own oscillation stretches the overlap to "
                f"{reach * stretch:.6g} >= r = {m.r:g} (exact: {reach:.6g}): the sphere would tunnel "
                "through the wall; use a smaller dt or a slower |v_n|",
            )

    def default_dt(self) -> float:
        m = self.model
        if m.normal == "hertz":  # first order: no mid-step alignment (see HERTZ_STEPS_PER_HALF_PERIOD)
            speed = max(abs(v) for v in self.v_n)
            return math.pi / m.fastest_rate(frozen=False, speed=speed) / HERTZ_STEPS_PER_HALF_PERIOD
        per_tau = COLLISION_STEPS_PER_HALF_PERIOD * m.fastest_rate(frozen=False) * m.tau / math.pi
        return mid_step_dt(m.tau, math.ceil(per_tau - 1e-9))

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
        """Steps that end the contact: the step after tau, and one more for rounding."""
        if self.model.normal == "hertz":  # the slowest sphere's contact is the longest
            return steps_through(float(np.max(self.model.contact_times(self.v_n))), self.dt)
        return steps_through(self.model.t_exit, self.dt)

    def predicted(self) -> np.ndarray:
        """Final states from the theory, shaped like :attr:`initial`: the scattering matrix
        (Eq. 18 with the exact damped Omega; its 6x6 block form in 3-D; one per sphere for a
        Hertzian wall, whose Omega depends on v_n), or with a finite mu the Coulomb oracle
        (:mod:`oracle`), sphere by sphere."""
        k = len(self.state_names)
        if self.model.mu is not None:
            from ..theory import oracle

            return oracle.bounce_many(self.model, self.v_n, self.v_t, self.omega,
                                      self.v_s, self.omega_s, self.omega_n)[:, :k]
        if self.model.normal == "hertz":  # Omega differs from sphere to sphere
            matrices = self.model.matrices(self.v_n)
            if k == 6:
                matrices = np.array([theory.block_from(m3) for m3 in matrices])
            return np.einsum("nij,nj->ni", matrices, self.initial)
        matrix = self.model.block_matrix() if k == 6 else self.model.matrix()
        return self.initial @ matrix.T


@dataclass(frozen=True)
class Frozen:
    """One sphere held at height z (0 < z < r) with v_n = 0: the frozen contact of Section 3.

    ``dt = None`` resolves the slip's fastest rate with FROZEN_STEPS_PER_HALF_PERIOD steps per
    half-period; ``every`` is the dump cadence in steps (default: about 2000 frames).
    The run ends on the first multiple of ``every`` at or after ``t_end``.
    """

    model: ContactModel = field(default_factory=ContactModel)
    z: float = 0.1
    v_t: float = 1.0
    omega: float = 0.0
    t_end: float = 10.0
    dt: float | None = None
    every: int | None = None
    nsteps: int = field(init=False, default=0)

    def __post_init__(self):
        set_ = object.__setattr__
        m = self.model
        z = _finite("z", self.z)
        if not 0.0 < z < m.r:
            raise SceneError("z", self.z, f"must lie in (0, r) = (0, {m.r:g}) to hold the sphere in contact")
        set_(self, "z", z)
        set_(self, "v_t", _finite("v_t", self.v_t))
        set_(self, "omega", _finite("omega", self.omega))
        set_(self, "t_end", _positive("t_end", self.t_end))
        if self.dt is None:
            rate = m.fastest_rate(frozen=True)
            # kt = gamma_t = 0: nothing evolves; any dt is exact.
            dt = math.pi / rate / FROZEN_STEPS_PER_HALF_PERIOD if rate > 0.0 else self.t_end / 1000
            dt = self.t_end / math.ceil(self.t_end / dt)
        else:
            dt = self.dt
        set_(self, "dt", m.check_dt(dt, frozen=True))
        steps = math.ceil(self.t_end / self.dt - 1e-9)
        if self.every is None:
            set_(self, "every", max(1, steps // 2000))
        else:
            every = _finite("every", self.every)
            if every < 1 or every != int(every):
                raise SceneError("every", self.every, "must be a whole number of steps >= 1")
            set_(self, "every", int(every))
        # LAMMPS dumps only on multiples of `every`: end the run on one
        set_(self, "nsteps", math.ceil(steps / self.every) * self.every)

    def predicted(self, t) -> tuple[np.ndarray, np.ndarray]:
        """(v_t(t), r omega(t)): Eq. 10, or its exact damped form when gamma_t > 0."""
        m = self.model
        return theory.frozen_velocities(t, self.v_t, self.omega * m.r, m.kt, m.m, m.alpha, m.gamma_t)
