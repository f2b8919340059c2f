"""The contact model: its fields come from the declaration (:mod:`.parameters`), its
physics from :mod:`spinbounce.exact`.

``ContactModel`` is a frozen dataclass built from :data:`.parameters.MODEL`: one field per
declared parameter, with the declared default, checked against the declared range when
the model is made. Checks that involve two parameters (critical damping, Hertz without a
damped theory) and the derived quantities of the paper (tau, Q, Omega, the matrices, the
contact's modes and the step's stability limit) live in :class:`ContactPhysics`.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np

from .. import exact
from ..exact import choose
from ..laws import (NORMAL, DampingLaw, NormalLaw, Style, TangentialLaw, damping_law, normal_law, own, settled, style,
                    tangential_law)
from .parameters import MODEL, SceneError, positive_number
from .stability import stability_limit
from .timestep import MIN_STEPS_PER_HALF_PERIOD, check_steps, mode_rate
from ..errors import PhysicsWarning

#: The fewest units in the last place of r a contact's deepest overlap may span (LAMMPS's positions
#: are doubles near r): below, the sphere cannot move far enough to be seen leaving the wall
#: (measured at the paper's defaults: runs fail from 9 units down, v_n = -3e-15, and end "grazing",
#: 87% off, at 28). A row above it but below checks.RESOLVABLE_OVERLAP_ULPS runs, status "grazing".
UNRESOLVED_ULPS = 100.0

__all__ = ["ContactModel", "ContactPhysics", "PhysicsWarning", "NORMAL_LAWS", "ALPHA_SHELL",
           "MIN_STEPS_PER_HALF_PERIOD"]

#: Normal force laws, as registered (:data:`spinbounce.laws.NORMAL`).
NORMAL_LAWS = tuple(NORMAL)
#: Below this normal restitution the sphere creeps out of the overlap so slowly that the
#: end of the contact cannot be located by a run (measured: e = 4e-3 runs, 8e-5 does not).
MIN_RESTITUTION = 1e-3
#: Above alpha = 2/3 part of the mass would sit outside the sphere (Section 3).
ALPHA_SHELL = 2.0 / 3.0


class ContactPhysics:
    """What a contact model means: cross-parameter checks and the paper's derived quantities."""

    def __post_init__(self):
        for parameter in MODEL:
            object.__setattr__(self, parameter.name, parameter.check(getattr(self, parameter.name)))
        values = {parameter.name: getattr(self, parameter.name) for parameter in MODEL}
        for name, value in settled(values).items():
            object.__setattr__(self, name, value)
        if self.alpha > ALPHA_SHELL:
            warnings.warn(
                f"alpha = {self.alpha:g} > 2/3: more than a thin shell's inertia, the sphere "
                "carries 'phantom' mass beyond its radius (paper, Section 3)",
                PhysicsWarning,
                stacklevel=4,
            )
        self.style.check(self)
        critical = 2.0 * math.sqrt(self.m * self.kn)
        if not self.normal_law.contact_radius and self.gamma_n >= critical:
            raise SceneError(
                "gamma_n",
                self.gamma_n,
                f"must be below critical normal damping 2*sqrt(m*kn) = {critical:.6g}: "
                "at or above it the sphere never leaves the wall",
            )

    def as_record(self) -> dict:
        """The model's parameters as every record, digest and run folder's name gives them: the
        coefficients of sub-models it does not use left out (:func:`spinbounce.laws.own`)."""
        return own(dataclasses.asdict(self))

    def replace(self, **changes):
        """A copy with some parameters changed (checked again); what the sub-models derive is
        derived anew unless it is changed too."""
        derived = {*self.normal_law.derived, *self.damping_law.derived, *self.tangential_law.derived}
        reset = {p.name: p.default for p in MODEL if p.name in derived and p.name not in changes}
        return dataclasses.replace(self, **reset, **changes)

    # -- the law -------------------------------------------------------------------
    @property
    def normal_law(self) -> NormalLaw:
        """The normal sub-model (:mod:`spinbounce.laws.normal`): asked for what it can do."""
        return normal_law(self.normal)

    @property
    def damping_law(self) -> DampingLaw:
        """The damping sub-model (:mod:`spinbounce.laws.damping`): asked for what it can do."""
        return damping_law(self.damping)

    @property
    def tangential_law(self) -> TangentialLaw:
        """The tangential sub-model (:mod:`spinbounce.laws.tangential`): asked for what it can do."""
        return tangential_law(self.tangential)

    @property
    def style(self) -> Style:
        """The wall command's style (:mod:`spinbounce.laws.styles`): granular, or a fixed assembly."""
        return style(self.wall)

    # -- derived quantities (theory, in the paper's names) -------------------------
    @property
    def inertia(self) -> float:
        return self.alpha * self.m * self.r**2

    def _hooke_only(self, what: str) -> None:
        if self.normal_law.contact_radius:
            raise SceneError("normal", self.normal, f"has no single {what}: it depends on v_n "
                             "(per-sphere values: Collision.predicted(), spinbounce.exact.hertz)")
        if self.normal_law.integrated(self):
            raise SceneError("damping", self.damping, f"has no single {what}: its dashpot grows with the contact "
                             "radius, so it depends on v_n (per-sphere values: Collision.predicted())")

    @property
    def tau(self) -> float:
        """Contact time, Eq. 16 (damped form when gamma_n > 0): how long the force acts."""
        self._hooke_only("contact time tau")
        return exact.collision_time(self.m, self.kn, self.gamma_n, not self.limit_damping)

    @property
    def t_exit(self) -> float:
        """When the sphere is out of the overlap (later than tau with limit_damping)."""
        self._hooke_only("exit time")
        return exact.exit_time(self.m, self.kn, self.gamma_n, not self.limit_damping)

    @property
    def Q(self) -> float:
        """(1 + alpha)/alpha kt/m: the slip's squared frequency (a spring that does not change)."""
        if self.tangential_law.contact_radius:
            raise SceneError("tangential", self.tangential, "has no single Q: its stiffness grows with the contact "
                                                            "radius (spinbounce.exact.mindlin)")
        return exact.Q(self.kt, self.m, self.alpha)

    @property
    def zeta(self) -> float:
        return exact.damping_rate(self.gamma_t, self.m, self.alpha)

    @property
    def Omega(self) -> float:
        """Exact Omega (Eq. 18's when undamped; a Mindlin contact's where it has one matrix)."""
        if self.tangential_law.contact_radius:
            choice = choose.which(self)
            if not choice.has_matrix:
                raise SceneError("tangential", self.tangential, f"has no single Omega: {choice.no_matrix_reason}")
            return float(choose.omega_per_sphere(self, -1.0)[0])
        self._hooke_only("Omega")
        return exact.Omega_exact(self.m, self.kn, self.kt, self.alpha, self.gamma_t, self.gamma_n,
                                  not self.limit_damping)

    @property
    def restitution(self) -> float:
        self._hooke_only("restitution")
        return exact.restitution(self.m, self.kn, self.gamma_n, not self.limit_damping)

    def matrix(self) -> np.ndarray:
        """The scattering matrix that applies (:func:`spinbounce.exact.choose.matrix`)."""
        return choose.matrix(self)

    def block_matrix(self) -> np.ndarray:
        """The 6x6 map of 3-D states (:data:`STATE_3D`)."""
        return choose.matrix(self, three_d=True)

    def matrices(self, v_n) -> np.ndarray:
        """(n, 3, 3): each sphere's scattering matrix (:func:`spinbounce.exact.choose.matrices`)."""
        return choose.matrices(self, v_n)

    def check_default_step(self) -> None:
        """Refuse what a run at the default step cannot resolve: a sphere that leaves the wall too
        slowly for a run to see it go (any other value is answered at the step its probe finds)."""
        # a restitution rounded a part in 1e15 below the limit (e_n = 1e-3 exactly) is the limit
        hookean = not self.normal_law.contact_radius and not self.normal_law.integrated(self)
        if hookean and self.restitution < MIN_RESTITUTION * (1.0 - 1e-12):
            limit = exact.gamma_n_for_restitution(MIN_RESTITUTION, self.m, self.kn)
            name = self.damping_law.normal_coefficient
            made = "" if name == "gamma_n" else f"makes gamma_n = {self.gamma_n:.6g}, which "
            raise SceneError(name, getattr(self, name),
                             f"{made}must be below {limit:.6g} (restitution {MIN_RESTITUTION:g}) at the default "
                             f"step: here the sphere leaves at {self.restitution:.3g} of its speed, too slowly for the step's "
                             "probe to see the contact end; give a dt of your own")

    def contact_times(self, v_n) -> np.ndarray:
        """Each sphere's time until it is out of the overlap (Hertz: tau(v_n); Hooke: t_exit)."""
        return self.normal_law.contact_times(self, v_n)

    def max_overlap(self, speed) -> np.ndarray:
        """The largest overlap of each contact that starts touching at |v_n| = ``speed``."""
        return self.normal_law.max_overlap(self, speed)

    def check_overlap_resolved(self, v_n) -> None:
        """Refuse speeds whose deepest overlap spans fewer than UNRESOLVED_ULPS units in the last place
        of r: LAMMPS's positions (doubles near r) cannot carry it, and the sphere would never leave the
        wall. Named: v_n if this model's defaults resolve it, else the sphere's or the spring's value."""
        slowest = float(np.min(np.abs(v_n)))
        floor = UNRESOLVED_ULPS * float(np.spacing(self.r))
        if float(self.max_overlap(slowest)) >= floor:
            return
        default = type(self)()
        blamed = next((name for name in ("m", "kn", "r") if getattr(self, name) != getattr(default, name)), "v_n")
        if float(default.max_overlap(slowest)) < float(np.spacing(default.r)) * UNRESOLVED_ULPS:
            blamed = "v_n"
        value = -slowest if blamed == "v_n" else getattr(self, blamed)
        deepest = float(self.max_overlap(slowest))
        raise SceneError(blamed, value, f"the deepest overlap at |v_n| = {slowest:.3g} (m = {self.m:g}, "
                                        f"kn = {self.kn:g}) would be {deepest:.3g}, fewer than "
                                        f"{UNRESOLVED_ULPS:g} units in the last place of r = {self.r:g}: LAMMPS's "
                                        "positions cannot resolve it and the sphere would never leave the wall")

    # -- numerics --------------------------------------------------------------------
    def modes(self, frozen: bool, speed: float | None = None,
              overlap: float | None = None) -> dict[str, tuple[float, float]]:
        """The linear contact modes a scene integrates: name -> (w, c) of x'' + c x' + w^2 x = 0.

        The Hertzian normal mode is nonlinear; it is represented by its stiffest point, the
        largest overlap of the fastest sphere, whose |v_n| is ``speed``.
        """
        law = self.tangential_law
        stiffness = law.frozen_stiffness(self, overlap) if frozen else law.slip_stiffness(self, speed)
        q = exact.Q(stiffness, self.m, self.alpha)
        s = self.damping_law.radius_power(self.normal_law)  # a dashpot gamma_t a^s: at its largest a
        depth = overlap if frozen else (float(self.max_overlap(speed)) if speed is not None else None)
        zeta = self.zeta * (math.sqrt(self.r * depth) ** s if s and depth is not None else 1.0)
        out = {"slip": (math.sqrt(q), 2.0 * zeta)}
        if not frozen:
            out["normal"] = self.normal_law.normal_mode(self, speed)
        return out

    def stiffest(self, frozen: bool, speed: float | None = None) -> tuple[str, str]:
        """The coefficient a user gives that sets the fastest integrated mode (its spring's, or its dashpot's where
        that decays faster than the spring turns: each law's declared coefficients), and that mode in words."""
        modes = self.modes(frozen, speed)
        mode = max(modes, key=lambda name: mode_rate(*modes[name]))
        w, c = modes[mode]
        if c / 2.0 >= w:
            name = self.damping_law.coefficients[1 if mode == "slip" else 0].name
        else:
            spring = (self.tangential_law if mode == "slip" else self.normal_law).coefficients
            name = spring[0].name if spring else ("kt" if mode == "slip" else "kn")
        if getattr(self, name) is None:  # a Mindlin spring's NULL stiffness: E's (and nu's)
            name = "youngs_modulus"
        parts = "its spring, dashpot and alpha" if mode == "slip" else "its spring and dashpot"
        return name, f"the {mode} mode ({parts})"

    def coarsest_dt(self, frozen: bool, speed: float | None = None, overlap: float | None = None) -> float:
        """The largest step every run must take at most (:meth:`check_dt`): MIN_STEPS_PER_HALF_PERIOD steps a
        half-period of the fastest mode (inf if nothing moves, 0 for rates beyond a float)."""
        rate = self.fastest_rate(frozen, speed, overlap)
        return math.pi / rate / MIN_STEPS_PER_HALF_PERIOD if rate > 0.0 else math.inf

    def fewest_steps(self, span: float, frozen: bool, speed: float | None = None) -> float:
        """The fewest steps any accepted step takes over ``span`` (a float: inf for rates beyond one)."""
        return span * self.fastest_rate(frozen, speed) * MIN_STEPS_PER_HALF_PERIOD / math.pi

    def check_resolvable(self, span: float, speed: float, against: str, spheres: int = 1, long=None) -> str:
        """Refuse a run of ``span`` (time) that no accepted step carries within a run's steps, before a step is
        computed from its rates (a float's end), naming the coefficient that sets its fastest mode
        (:meth:`stiffest`), or ``long`` (name, value) where that mode is the normal one (what makes a run long
        then: a gas's collisions); returns why, in words (the mode, fast ``against`` what)."""
        cause, mode = self.stiffest(False, speed)
        why = f"{mode} is fast {against}"
        named = long if long is not None and mode.startswith("the normal") else (cause, getattr(self, cause))
        check_steps(self.fewest_steps(span, False, speed), *named, why, spheres=spheres)
        return why

    def fastest_rate(self, frozen: bool, speed: float | None = None, overlap: float | None = None) -> float:
        """Largest rate (1/time) among the integrated modes: frequency or fast decay rate."""
        return max(mode_rate(w, c) for w, c in self.modes(frozen, speed, overlap).values())

    def steps_per_half_period(self, dt: float, frozen: bool, speed: float | None = None,
                              overlap: float | None = None) -> float:
        """How finely ``dt`` resolves the fastest integrated mode: its half-period over dt (inf if
        nothing moves)."""
        rate = self.fastest_rate(frozen, speed, overlap)
        return math.pi / rate / dt if rate > 0.0 else math.inf

    def dt_limit(self, frozen: bool, speed: float | None = None, overlap: float | None = None) -> tuple[float, str]:
        """Stability limit of LAMMPS's step and the mode that sets it."""
        limits = {name: stability_limit(w, c) for name, (w, c) in self.modes(frozen, speed, overlap).items()}
        name = min(limits, key=limits.get)
        return limits[name], name

    def check_dt(self, dt, frozen: bool, speed: float | None = None, overlap: float | None = None) -> float:
        dt = positive_number("dt", dt)
        limit, mode = self.dt_limit(frozen, speed, overlap)
        if dt >= limit:
            raise SceneError(
                "dt",
                dt,
                f"must be below the stability limit {limit:.6g} of the {mode} mode "
                "(LAMMPS's velocity-Verlet step diverges above it)",
            )
        steps = self.steps_per_half_period(dt, frozen, speed, overlap)
        if steps < MIN_STEPS_PER_HALF_PERIOD * (1.0 - 1e-9):  # a rung of exactly that many steps is accepted
            raise SceneError(
                "dt",
                dt,
                f"resolves the fastest contact mode with only {steps:.3g} steps per half-period: must be at most "
                f"{self.coarsest_dt(frozen, speed, overlap):.6g} "
                f"({MIN_STEPS_PER_HALF_PERIOD} steps; fewer "
                "give a caricature of the contact, whatever the target)",
            )
        return dt


ContactModel = dataclasses.make_dataclass(
    "ContactModel",
    [(p.name, object, dataclasses.field(default=p.default)) for p in MODEL],
    bases=(ContactPhysics,),
    frozen=True,
)
ContactModel.__module__ = __name__  # pickles (sweep workers) find it here
ContactModel.__doc__ = """The sphere and its wall contact (Eq. 1), in LAMMPS lj units.

Fields (declared in :data:`spinbounce.model.parameters.MODEL`): """ + ", ".join(
    f"``{p.name}`` ({p.meaning}; default {p.default!r})" for p in MODEL) + "."
