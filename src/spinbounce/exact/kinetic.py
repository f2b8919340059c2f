"""The two temperatures of a dilute gas of rough spheres (homogeneous cooling), from its collisions.

In a homogeneous gas under molecular chaos, with T_tr = m <v_x^2> and T_rot = I <omega_x^2> (three
degrees of freedom each), collisions change the temperatures at the rate

    dT_tr/dtau = <dE_tr>/3,    dT_rot/dtau = <dE_rot>/3,

with tau the collisions per sphere and <dE> a pair's kinetic energy change per collision, averaged
over the collisions of a Maxwellian gas (each pair weighted by its closing speed |g.n|). Where a
collision is linear in the velocities (no cap), the averages are linear in the temperatures:

    d/dtau (T_tr, T_rot) = L (T_tr, T_rot),

a 2 x 2 matrix L per gas (:class:`Averages`: L may change with T_tr, where the contact's shape does,
as the turning line of centres does). For the rough-sphere rule (normal restitution e_n, tangential
restitution beta of the contact point's slip, I = q m r^2), L is the closed form of homogeneous
cooling (:func:`rough_sphere_matrix`); from the project's pair outcomes it is measured
(:mod:`spinbounce.scenes.gas.collisions`). Real time follows the Enskog collision rate
omega_E = 4 n sigma^2 chi sqrt(pi T_tr / m), with chi the contact value of the pair correlation
(Carnahan-Starling), valid for a dilute gas (packing up to about 0.1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["rough_sphere_matrix", "enskog_rate", "contact_value", "Averages", "Evolution", "evolve",
           "steady_ratio", "DILUTE"]

#: The packing fraction up to which binary-collision theory is held to a gas (denser gases are run, not judged).
DILUTE = 0.1


def rough_sphere_matrix(e_n: float, beta: float, q: float) -> np.ndarray:
    """L of rough spheres: collisions that multiply the closing speed by -e_n and the contact point's
    slip by -beta, between equal spheres of I = q m r^2.

    With eta = q (1 + beta) / (2 (1 + q)): dT_tr/dtau = (4/3)(-A T_tr + B T_rot) and
    dT_rot/dtau = (4/3)(B T_tr - C T_rot), A = (1 - e_n^2)/4 + eta (1 - eta), B = eta^2/q,
    C = (eta/q)(1 - eta/q) (the factor 4/3: a collision's mean closing speed squared is 4 T_tr/m).
    """
    eta = q * (1.0 + beta) / (2.0 * (1.0 + q))
    a = (1.0 - e_n**2) / 4.0 + eta * (1.0 - eta)
    b = eta**2 / q
    c = eta / q * (1.0 - eta / q)
    return 4.0 / 3.0 * np.array([[-a, b], [b, -c]])


def contact_value(packing: float) -> float:
    """chi: the pair correlation at contact of hard spheres (Carnahan-Starling)."""
    return (1.0 - packing / 2.0) / (1.0 - packing) ** 3


def enskog_rate(t_tr, packing: float, sigma: float, m: float):
    """omega_E: collisions per sphere per unit time at translational temperature ``t_tr``."""
    density = 6.0 * packing / (math.pi * sigma**3)
    return 4.0 * density * sigma**2 * contact_value(packing) * np.sqrt(math.pi * np.asarray(t_tr) / m)


@dataclass(frozen=True)
class Averages:
    """L at each of ``t_tr`` (increasing; one value: L everywhere), and the mean contact time there
    (collision-weighted). Between the temperatures L is interpolated linearly in sqrt(T_tr) (the
    line of centres turns by an angle proportional to the speed); beyond them it is held."""

    t_tr: np.ndarray
    matrices: np.ndarray
    contact_times: np.ndarray

    def at(self, t_tr: float) -> np.ndarray:
        if len(self.t_tr) == 1:
            return self.matrices[0]
        x = np.sqrt(np.clip(t_tr, self.t_tr[0], self.t_tr[-1]))
        grid = np.sqrt(self.t_tr)
        return np.array([[np.interp(x, grid, self.matrices[:, i, j]) for j in range(2)] for i in range(2)])

    def contact_time(self, t_tr: float) -> float:
        if len(self.t_tr) == 1:
            return float(self.contact_times[0])
        return float(np.interp(math.sqrt(t_tr), np.sqrt(self.t_tr), self.contact_times))


@dataclass(frozen=True)
class Evolution:
    """The temperatures at collisions per sphere ``tau``, and the time ``t`` at which the Enskog rate reaches them."""

    tau: np.ndarray
    t: np.ndarray
    t_tr: np.ndarray
    t_rot: np.ndarray

    @property
    def ratio(self) -> np.ndarray:
        return self.t_rot / self.t_tr

    @property
    def energy(self) -> np.ndarray:
        """The kinetic energy per sphere, (3/2)(T_tr + T_rot)."""
        return 1.5 * (self.t_tr + self.t_rot)


def evolve(averages: Averages, t_tr0: float, t_rot0: float, tau_end: float, packing: float, sigma: float,
           m: float, points: int = 401) -> Evolution:
    """The temperatures from (t_tr0, t_rot0) over ``tau_end`` collisions per sphere (DOP853, rtol 1e-11),
    with the time t(tau) = integral of dtau / omega_E(T_tr)."""
    from scipy.integrate import solve_ivp

    def rates(_, y):
        temperatures = averages.at(y[0]) @ y[:2]
        return [*temperatures, 1.0 / float(enskog_rate(max(y[0], 1e-300), packing, sigma, m))]

    tau = np.linspace(0.0, tau_end, points)
    solution = solve_ivp(rates, (0.0, tau_end), [t_tr0, t_rot0, 0.0], method="DOP853", t_eval=tau, rtol=1e-11,
                         atol=1e-14 * (t_tr0 + t_rot0))
    if not solution.success:
        raise ArithmeticError(f"the temperature equations failed: {solution.message}")
    return Evolution(tau, solution.y[2], solution.y[0], solution.y[1])


def steady_ratio(matrix: np.ndarray) -> float:
    """The ratio T_rot/T_tr that L keeps: d(T_rot/T_tr)/dtau = 0, the positive root of
    L01 r^2 + (L00 - L11) r - L10 = 0 (NaN where translation and rotation do not exchange energy)."""
    (l00, l01), (l10, l11) = matrix
    scale = float(np.max(np.abs(matrix)))
    if scale == 0.0 or (abs(l01) <= 1e-12 * scale and abs(l10) <= 1e-12 * scale):
        return math.nan
    if abs(l01) <= 1e-12 * scale:  # no energy back from rotation: the linear equation
        return l10 / (l00 - l11) if l00 != l11 else math.nan
    roots = np.roots([l01, l00 - l11, -l10])
    positive = [float(r.real) for r in roots if abs(r.imag) <= 1e-12 * abs(r) and r.real > 0.0]
    return min(positive) if positive else math.nan
