"""The frozen contact of Section 3: one sphere held at a fixed height z < r, so v_n = 0 and
only the slip evolves; checked against Eq. 10 (or its exact damped form, theory.md; with a
Coulomb cap, a spring's stick-slip under the constant cap, :mod:`spinbounce.exact.frozen_capped`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...errors import ResultError
from ...exact import choose
from ...lammps.decks import wall_parameters
from ...model.contact import ContactModel
from ...model.parameters import SceneError, finite_number, positive_number
from ...model.timestep import ACCURACY, FROZEN_ACCURACY, SAFETY, check_steps, second_order_dt, steps_to

__all__ = ["Frozen", "FROZEN_DAMPING_ORDER_ONE"]

#: Frozen contact with tangential damping: first order, error about this times 2 zeta dt
#: (LAMMPS_FACTS section 5: 2e-5 to 8e-5 at dt = 1e-4 for gamma_t from 0.1 to 2).
FROZEN_DAMPING_ORDER_ONE = 0.5


@dataclass(frozen=True)
class Frozen:
    """One sphere held at height z (0 < z < r) with v_n = 0: the frozen contact of Section 3.

    ``dt = None`` takes the step of the default accuracy (:meth:`default_dt`), shortened so
    that ``t_end`` is a whole number of dump intervals; ``every`` is the dump cadence in steps
    (default: about 2000 frames). With a given dt the run goes on to the first dump at or
    after t_end (:attr:`t_final`).
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
        if m.mu is not None and m.style.tangential_contact_radius:
            raise SceneError("mu", m.mu, f"the capped frozen contact is checked against a spring under a constant "
                                         f"cap, which wall = {m.wall} is not (its form resets the history to the "
                                         "capped force over kt alone): give wall = granular, or leave mu out")
        z = finite_number("z", self.z)
        if not 0.0 < z < m.r:
            raise SceneError("z", self.z, f"must lie in (0, r) = (0, {m.r:g}) to hold the sphere in contact")
        set_(self, "z", z)
        if m.mu is not None and m.tangential_law.frozen_stiffness(m, m.r - z) == 0.0:
            raise SceneError("kt", m.kt, "must be > 0 with a cap (mu) in the frozen contact: LAMMPS resets a "
                                         "capped history to the force over the spring's stiffness")
        set_(self, "v_t", finite_number("v_t", self.v_t))
        set_(self, "omega", finite_number("omega", self.omega))
        set_(self, "t_end", positive_number("t_end", self.t_end))
        given = self.dt is not None
        set_(self, "dt", m.check_dt(self.dt if given else self.default_dt(), frozen=True,
                                        overlap=self.overlap))
        why = f"t_end = {self.t_end:g} at dt = {self.dt:.3g}" + ("" if given else ", the default accuracy's step")
        named = ("dt", self.dt) if given else ("t_end", self.t_end)
        steps = check_steps(steps_to(self.t_end, self.dt), *named, why)
        if self.every is None:
            set_(self, "every", max(1, steps // 2000))
        else:
            every = finite_number("every", self.every)
            if every < 1 or every != int(every):
                raise SceneError("every", self.every, "must be a whole number of steps >= 1")
            set_(self, "every", int(every))
        if steps % self.every:
            # LAMMPS dumps on multiples of `every`: a default step is shortened so that t_end is a
            # whole number of intervals; a given one runs on to the next dump (t_final says when)
            steps = check_steps(math.ceil(steps / self.every) * self.every, "every", self.every,
                                f"t_end = {self.t_end:g} rounded up to whole dump intervals")
            if not given:
                set_(self, "dt", self.t_end / steps)
        set_(self, "nsteps", steps)

    @property
    def steps_per_half_period(self) -> float:
        """How finely dt resolves the slip mode (its half-period over dt; inf if nothing moves)."""
        return self.model.steps_per_half_period(self.dt, frozen=True, overlap=self.overlap)

    @property
    def overlap(self) -> float:
        """r - z: how deep the sphere is held (a Mindlin spring's contact radius is sqrt(r overlap))."""
        return self.model.r - self.z

    @property
    def t_final(self) -> float:
        """When the run ends: t_end, or with a given dt the first dump at or after it."""
        return self.nsteps * self.dt

    @property
    def first_order_by_default(self) -> bool:
        """The classic spring's cap (reset by kt alone) saw-tooths, an error first order in dt whose constant no
        rule knows (measured: 1.1e-2 at the second-order rule's step, falling 4-fold over 4-fold finer steps):
        its default accuracy is reached by measurement against the exact theory, as a tolerance is."""
        return self.model.mu is not None and self.model.tangential_law.classic_cap

    def default_dt(self) -> float:
        """The step for the frozen contact's accuracy (FROZEN_ACCURACY, second order on the slip
        mode over t_end) and, with gamma_t, the first-order damping bound for the default one."""
        m = self.model
        w, c = m.modes(frozen=True, overlap=self.overlap)["slip"]
        if w == 0.0 and c == 0.0:  # kt = gamma_t = 0: nothing evolves; any dt is exact
            return self.t_end / 1000
        dt = second_order_dt([(w, c)], self.t_end, FROZEN_ACCURACY)
        if c > 0.0:
            dt = min(dt, SAFETY * ACCURACY / (FROZEN_DAMPING_ORDER_ONE * c))  # first order: the default target
        steps = check_steps(steps_to(self.t_end, dt), "t_end", self.t_end, "at the default accuracy's step")
        return self.t_end / max(1, steps)

    def predicted(self, t) -> tuple[np.ndarray, np.ndarray]:
        """(v_t(t), r omega(t)): Eq. 10, or its exact damped form when gamma_t > 0."""
        return choose.frozen(self.model, t, self.v_t, self.omega * self.model.r, self.z)

    # --- what the pipeline asks of a time-series scene (spinbounce.pipeline.run_series) ---

    kind = "frozen"

    def render(self):
        from .deck import render_frozen

        return render_frozen(self)

    def read(self, info, deck, folder: Path):
        """The dump's time series beside Eq. 10, checked: every frame finite, all of them there,
        the sphere at its held height."""
        from ...lammps.dumps import finite_frames, read_dump
        from .table import frozen_table

        dump = Path(folder) / deck.dump
        frames = finite_frames(read_dump(dump), dump)
        expected = self.nsteps // self.every + 1
        if frames["step"].nunique() != expected or frames["step"].max() != self.nsteps:
            raise ResultError(f"{dump}: expected {expected} frames ending at step {self.nsteps}")
        table = frozen_table(self, frames)
        if np.max(np.abs(table["z"] - self.z)) > 1e-12 * max(1.0, self.z):
            raise ResultError(f"{dump}: the sphere moved off its held height z = {self.z!r}")
        return table

    def record(self) -> dict:
        return {"model": self.model.as_record(), "z": self.z, "v_t": self.v_t, "omega": self.omega,
                "t_end": self.nsteps * self.dt, "dt": self.dt, "nsteps": self.nsteps, "every": self.every,
                "wall": wall_parameters(self.model)}

    @staticmethod
    def max_abs_error(table) -> float:
        """The largest deviation of v_t or r omega from Eq. 10 over the run."""
        return float(max(np.max(np.abs(table["v_t"] - table["v_t_theory"])),
                         np.max(np.abs(table["r_omega"] - table["r_omega_theory"]))))
