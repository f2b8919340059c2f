"""A wall contact's law as every exact reference of a capped or damped nonlinear contact reads it:
the normal force K delta^p, the tangential spring k a^q on a displacement or force history (rescaled
or not), the dashpots C a^s and the cap, with a = sqrt(r delta) the contact radius.

Pure numpy (no scipy): a scene asks it about its states before anything is integrated.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Law", "on_contact_radius", "can_hold"]


def can_hold(gamma: float, power: float, damping_power: float, tensile: bool = True) -> bool:
    """Whether a normal dashpot gamma a^damping_power can hold a contact of force K delta^power closed: near the
    surface its rate outgrows the force's frequency, (delta^(s/2)) / (delta^((p-1)/2)) -> infinity, where
    s < p - 1 (Hertz's force with a velocity dashpot; a Hookean force or a dashpot at a constant damping ratio,
    tsuji's, cannot; nor no dashpot, nor one limit_damping cuts where it would pull: ``tensile`` False)."""
    return gamma > 0.0 and tensile and damping_power < power - 1.0


def on_contact_radius(power: float, spring_power: float, damping_power: float) -> bool:
    """Whether a force K delta^power, a spring k a^spring_power or dashpots gamma a^damping_power
    grow with the contact radius: the references then start and end a hair inside the contact."""
    return power != 1.0 or spring_power != 0.0 or damping_power != 0.0


@dataclass(frozen=True)
class Law:
    """A wall contact's law: the normal force K delta^p, the spring k a^q on a displacement (or,
    ``force_history``, a force) history, rescaled or not, the dashpots C_n a^s and C_t a^s, the cap
    mu (inf: none); the sphere's m, r and alpha."""

    m: float
    r: float
    alpha: float
    K: float
    power: float
    k: float
    spring_power: float = 1.0
    force_history: bool = False
    rescale: bool = False
    mu: float = math.inf
    c_n: float = 0.0
    c_t: float = 0.0
    damping_power: float = 0.0
    #: The normal force may pull (False: limit_damping cuts it at zero, and the sphere coasts out).
    tensile: bool = True
    #: The cap resets the history by k alone, not k a^q (this build's ``linear_history_classic``):
    #: the next trial force is a^q of the cap plus (1 - a^q) of the dashpot's (:mod:`.oracle_classic`).
    classic_cap: bool = False

    @property
    def on_contact_radius(self) -> bool:
        """Whether its force, spring or dashpot grows with the contact radius (:func:`on_contact_radius`)."""
        return on_contact_radius(self.power, self.spring_power, self.damping_power)

    @property
    def first_touch_on_cap(self) -> bool:
        """A displacement history on a^q (q > 0) with a tangential dashpot a^s, s <= q, and a cap: a first
        trial force beyond the cap (:meth:`threshold_ratio` above 1) is set on it at LAMMPS's first step,
        a step whose contact radius is ~ sqrt(dt), and the contact's course is decided from there at the
        margin, so LAMMPS converges as sqrt(dt) or slower. With s = q (``viscoelastic`` with a Mindlin
        history) the outcome is smooth in the state, but every state above 1 converges so: r omega's
        error 7.3e-3, 2.4e-3 and 7.5e-4 at dt = 3e-4, 3e-5 and 3e-6 (Hooke, x_t |u'| = 2 mu |v_n|, and
        as much at 5 times); with s < q it jumps (:attr:`first_touch_runaway`)."""
        return (not self.force_history and not self.classic_cap and self.spring_power > 0.0
                and self.spring_power >= self.damping_power
                and self.c_t > 0.0 and math.isfinite(self.mu))

    @property
    def first_touch_runaway(self) -> bool:
        """A displacement history on a^q (q > 0) with a tangential dashpot a^s, s < q, and a cap: at first
        touch a trial force gamma_t u' beyond the cap sets the history against the slip, and it then
        grows faster than the cap (exact.oracle's first phase), so the friction pushes along the slip
        from first touch. With a normal dashpot the cap is led by it as the trial force is, and this
        happens above :meth:`threshold_ratio` 1, where the outcome jumps; without one the cap starts
        at zero, below any trial force, and it happens whenever there is slip."""
        return self.first_touch_on_cap and self.spring_power > self.damping_power

    def threshold_ratio(self, v_n, slip):
        """c_t |u'| / (mu c_n |v_n|) of each state: the first trial force over the cap, both led by
        their dashpots at first touch (LAMMPS's x_t |u'| / (mu |v_n|)); infinite without a normal
        dashpot (the cap starts at zero)."""
        if self.c_n == 0.0:
            return np.where(np.abs(slip) > 0.0, np.inf, 0.0)
        return self.c_t * np.abs(slip) / (self.mu * self.c_n * np.abs(v_n))

    @classmethod
    def of(cls, model, normal_only: bool = False) -> "Law":
        """A wall contact model's law (read through its fields and sub-models): the force
        kn r^(p - 1) delta^p, the spring, the dashpots gamma a^s and the cap (``normal_only``: no
        spring, no cap)."""
        normal, tangential = model.normal_law, model.tangential_law
        force, rescale = tangential.variant
        return cls(m=model.m, r=model.r, alpha=model.alpha, K=normal.wall_constant(model), power=normal.power,
                   k=0.0 if normal_only else tangential.stiffness(model),
                   spring_power=1.0 if tangential.contact_radius else 0.0, force_history=force, rescale=rescale,
                   mu=math.inf if normal_only or model.mu is None else model.mu, c_n=model.gamma_n,
                   c_t=0.0 if normal_only else model.gamma_t, damping_power=model.damping_law.radius_power(normal),
                   tensile=not model.limit_damping,
                   classic_cap=tangential.classic_cap and not normal_only and model.mu is not None)
