"""The gas scene: N equal spheres in a periodic box, their two temperatures followed in LAMMPS.

The spheres are placed on a jittered cubic lattice (no overlaps), settle for SETTLE collisions per
sphere under their own law, then are given Maxwellian velocities at T_tr(0) and spins at T_rot(0)
(every temperature is 2 KE / (3 N)), and run BURN contact times more before the series starts: the
contacts open at the draw end first (their springs, loaded before it, lose energy no collision of the
gas would), so the series starts from what the gas then has: its energy within a few 1e-3 of the
asked, its ratio moved on by 0.05 collisions (0.013 for the magic ratio from T_rot = 0). LAMMPS
reports the translational and rotational kinetic energies at ``samples`` evenly spaced times, and the
open contacts averaged over each interval (sampled once every 1/CONTACT_SAMPLES contact times), from which
the collisions per sphere are counted.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ...exact import kinetic
from ...lammps.decks import ALPHA_NVE_SPHERE
from ...model.contact import ContactModel
from ...model.parameters import SceneError
from ...model.timestep import check_steps
from .parameters import DEFAULT, GAS, MIN_SPHERES

__all__ = ["Gas", "GAS", "STEPS_PER_CONTACT", "MIN_SPHERES", "SETTLE", "BURN", "LATTICE_GAP"]

#: The default step: the mean contact time over this many (the gas's collisions end mid-step at random
#: phases: LAMMPS's error per collision is first order in dt/t_c, and the pair-level theory carries it).
STEPS_PER_CONTACT = 50
#: Collisions per sphere run before the start (the lattice melts; each sphere has met others).
SETTLE = 2.0
#: Contact times run between the velocities' draw and the series' start: the contacts open at the draw
#: (about 2 omega t_c of the spheres), whose overlaps and springs were loaded before it, have ended.
BURN = 3.0
#: The smallest gap between neighbours on the starting lattice, in diameters.
LATTICE_GAP = 0.02
#: The fastest collision a gas is sized for, in units of its closing speed's scale sqrt(2 T_tr / m) (a gas of
#: 10^7 collisions meets one beyond about 5.7), and the deepest overlap it may press, over the radius.
HOTTEST = 6.0
DEEPEST = 0.25
#: Open-contact samples per contact time (their time average counts the collisions). Each sample is a
#: neighbour-list build of LAMMPS's contact/atom, about six steps' cost at 20,000 spheres: once a contact time
#: it cost 11 to 15% of the run (bench), once in three 1 to 4%. A contact is then seen with a chance of one in
#: three, so the count carries a noise (``collisions_noise``: 0.4% of 15 collisions per sphere of 20,000 spheres).
#: The interval is whole contact times, so the period is the nearest that splits it (t_c when it is 3 t_c).
CONTACT_SAMPLES = 1.0 / 3.0
_GAS = {p.name: p for p in GAS}


def _whole(name: str, value) -> int:
    number = _GAS[name].check(value)
    if number != int(number):
        raise SceneError(name, value, "must be a whole number")
    return int(number)


@dataclass(frozen=True)
class Gas:
    """A gas of ``spheres`` equal spheres (the model's m, r and alpha = 2/5) at ``packing``, from
    T_tr(0) = ``t_tr`` and T_rot(0) = ``t_rot`` for ``collisions`` collisions per sphere (at the
    starting Enskog rate). ``dt``: default the mean contact time (``contact_time``, the pair
    reference's at the start's temperature) over STEPS_PER_CONTACT, or the coarsest step its fastest
    collisions' fastest mode accepts where that is finer. ``contact_time`` None: the gas's values (a given
    dt too) checked, and no step chosen (what a run asks before it measures the contact time)."""

    model: ContactModel
    contact_time: float | None
    spheres: int = DEFAULT["spheres"]
    packing: float = DEFAULT["packing"]
    t_tr: float = DEFAULT["t_tr"]
    t_rot: float = DEFAULT["t_rot"]
    collisions: float = DEFAULT["collisions"]
    samples: int = DEFAULT["samples"]
    seed: int = DEFAULT["seed"]
    draws: int = DEFAULT["draws"]
    dt: float | None = None
    nsteps: int = field(init=False, default=0)
    interval: int = field(init=False, default=0)

    def __post_init__(self):
        set_ = object.__setattr__
        if self.model.alpha != ALPHA_NVE_SPHERE:
            raise SceneError("alpha", self.model.alpha, f"a gas runs fix nve/sphere: alpha = {ALPHA_NVE_SPHERE} "
                             "(spheres of another alpha as rigid bodies are not implemented for a gas)")
        if not self.model.style.pairs:
            raise SceneError("wall", self.model.wall, "must be granular: a gas's spheres meet through pair granular")
        if self.model.mu is not None and self.model.tangential_law.classic_cap:
            raise SceneError("mu", self.model.mu, f"must be none with tangential = {self.model.tangential} in a gas: "
                             "its cap (reset by kt alone) leaves some collisions without a dt -> 0 limit "
                             "(exact.oracle_classic), so the pair-level theory, an average over every "
                             "collision's outcome, has none")
        for name in ("spheres", "samples", "seed", "draws"):
            set_(self, name, _whole(name, getattr(self, name)))
        for name in ("packing", "t_tr", "t_rot", "collisions"):
            set_(self, name, float(_GAS[name].check(getattr(self, name))))
        self._check_lattice()
        self._check_overlap()
        wall, fastest = self._fastest()
        # the run's fewest steps (its fastest collisions' fastest mode at the steps every step must give it) and a
        # given step, refused before the contact time's sample: a long run is its collisions' doing where the
        # normal mode is the fastest, a stiff spring's or dashpot's where another is
        wall.check_resolvable(self.duration, fastest, f"in the gas's fastest collisions, closing at {fastest:.3g}, "
                              f"over its {self.collisions:g} collisions per sphere", self.spheres,
                              long=("collisions", self.collisions))
        if self.dt is not None:
            wall.check_dt(self.dt, False, fastest)
            check_steps(self.duration / self.dt, "dt", self.dt, "to run the gas", spheres=self.spheres)
        if self.contact_time is None:
            return
        # by default the mean contact over STEPS_PER_CONTACT, or finer where a mode of the fastest collisions is
        # faster than the normal one (a stiff tangential spring)
        dt = self.dt if self.dt is not None else min(self.contact_time / STEPS_PER_CONTACT,
                                                     wall.coarsest_dt(False, fastest))
        check_steps(self.duration / dt, "dt", dt, "to run the gas", spheres=self.spheres)  # before a count overflows
        set_(self, "dt", float(dt))
        every = self.contact_steps
        steps = math.ceil(self.duration / dt)
        # whole contact times, at least two: the open contacts are sampled at least twice an interval (with
        # one, LAMMPS's fix ave/time also reports step 0)
        interval = max(2 * every, math.ceil(steps / self.samples / every) * every)
        set_(self, "interval", interval)
        set_(self, "nsteps", interval * self.samples)
        check_steps(self.nsteps + self.settle_steps + self.burn_steps, "dt", dt, "to run the gas", spheres=self.spheres)

    @property
    def sigma(self) -> float:
        return 2.0 * self.model.r

    @property
    def box(self) -> float:
        """The periodic box's side."""
        return (self.spheres * math.pi * self.sigma**3 / (6.0 * self.packing)) ** (1.0 / 3.0)

    @property
    def lattice_side(self) -> int:
        return math.ceil(round(self.spheres ** (1.0 / 3.0), 9))

    def _check_lattice(self) -> None:
        side = self.lattice_side
        densest = self.spheres * math.pi / (6.0 * side**3 * (1.0 + LATTICE_GAP) ** 3)
        if self.packing > densest:
            raise SceneError("packing", self.packing, f"cannot be placed: {self.spheres} spheres on a cubic lattice of "
                             f"{side}^3 sites need packing <= {densest:.4g} (a gap of {LATTICE_GAP} diameters)")

    def _fastest(self) -> tuple[ContactModel, float]:
        """The wall equivalent to a pair of the gas's spheres, and the closing speed of its fastest collisions:
        HOTTEST times the scale of |g.n| at T_tr + T_rot (the most T_tr can reach, were rotation to give all its
        energy back)."""
        from ..pair.kind import equal_pair
        from ..pair.pairs import equivalent_wall

        sphere, contact = equal_pair(self.model)
        return (equivalent_wall(sphere, sphere, contact),
                HOTTEST * math.sqrt(2.0 * (self.t_tr + self.t_rot) / self.model.m))

    def _check_overlap(self) -> None:
        """The gas's fastest collisions (closing at HOTTEST times the scale of |g.n| at T_tr + T_rot) must not press the
        spheres together by more than DEEPEST of a radius: the contact law, and the pair theory's runs,
        hold for small overlaps."""
        m = self.model
        wall, fastest = self._fastest()
        hottest = self.t_tr + self.t_rot
        depth = float(wall.max_overlap(fastest))
        if depth >= DEEPEST * m.r:
            factor = (depth / (DEEPEST * m.r)) ** 2  # a Hookean overlap grows as v / sqrt(kn)
            raise SceneError("t_tr", self.t_tr, f"is too hot for the contact's stiffness: its fastest collisions "
                             f"(closing at {fastest:.3g}) would overlap by {depth:.3g}, more than {DEEPEST} of the "
                             f"radius {m.r:g} (with Hooke's spring: kn >= {m.kn * factor:.3g}, or t_tr + t_rot <= "
                             f"{hottest / factor:.3g})")

    def rate(self, t_tr: float) -> float:
        """The Enskog collision rate per sphere at ``t_tr``."""
        return float(kinetic.enskog_rate(t_tr, self.packing, self.sigma, self.model.m))

    @property
    def duration(self) -> float:
        return self.collisions / self.rate(self.t_tr)

    @property
    def contact_steps(self) -> int:
        """A contact time in whole steps."""
        return max(1, round(self.contact_time / self.dt)) if self.dt else 1

    @property
    def contact_every(self) -> int:
        """Steps between open-contact samples: the interval (whole contact times) split into the number of
        samples, at least two, nearest to one every 1/CONTACT_SAMPLES contact times."""
        whole = self.interval // self.contact_steps
        count = min((k for k in range(2, whole + 1) if whole % k == 0), key=lambda k: abs(k - whole * CONTACT_SAMPLES))
        return self.interval // count

    def collisions_noise(self, collisions: float) -> float:
        """The relative standard error of ``collisions`` per sphere counted from the open-contact samples: a
        contact of the mean contact time t_c, sampled every P, is seen floor(t_c/P) times or once more, so each
        adds (P/t_c)^2 f (1 - f) to the count's variance (f the fractional part of t_c/P; none when P = t_c)."""
        seen = self.contact_time / (self.contact_every * self.dt)
        part = seen - math.floor(seen)
        contacts = collisions * self.spheres / 2.0
        return math.sqrt(part * (1.0 - part) / contacts) / seen if contacts > 0 else math.nan

    @property
    def settle_steps(self) -> int:
        return max(1, math.ceil(SETTLE / self.rate(self.t_tr) / self.dt)) if self.dt else 1

    @property
    def burn_steps(self) -> int:
        """Steps between the draw and the series' start (BURN contact times)."""
        return max(1, math.ceil(BURN * self.contact_time / self.dt)) if self.dt else 1

    @property
    def judged(self) -> bool:
        """Whether binary-collision theory is held to this gas (packing up to kinetic.DILUTE)."""
        return self.packing <= kinetic.DILUTE

    def record(self) -> dict:
        return {"model": self.model.as_record(), "spheres": self.spheres, "packing": self.packing, "t_tr": self.t_tr,
                "t_rot": self.t_rot, "collisions": self.collisions, "samples": self.samples, "seed": self.seed,
                "draws": self.draws,
                "dt": self.dt, "contact_time": self.contact_time, "nsteps": self.nsteps, "interval": self.interval,
                "settle_steps": self.settle_steps, "burn_steps": self.burn_steps, "box": self.box}
