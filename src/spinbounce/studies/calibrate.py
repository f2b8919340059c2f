"""From what a bounce should do to the LAMMPS parameters that make it do so.

Targets: the normal restitution e, the contact time t_c, the contact point's tangential
restitution beta = -u'(out)/u'(in) of a sticking collision (Eq. 18's Omega = -(1 + beta)) and
mu, which is passed on. Unknowns: kn, gamma_n, kt, gamma_t, from the exact theory inverted
(docs/theory.md, section 5). Unreachable targets raise :class:`Unreachable` with the reachable range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from .. import exact
from ..lammps.decks import fix_line, wall_parameters
from ..model.contact import ContactModel
from ..model.parameters import SceneError, by_name
from .validation.materials import gamma_n_for_restitution_cut

__all__ = ["Targets", "Calibration", "Unreachable", "calibrate", "tangential_range", "fix_line", "pair_lines",
           "measure", "LIMIT_DAMPING_E_MIN"]

#: With limit_damping the restitution falls to exp(-2) at critical damping, and no lower.
LIMIT_DAMPING_E_MIN = math.exp(-2.0)
#: Points of the scan that brackets the tangential root and bounds the reachable range.
SCAN_POINTS = 400


class Unreachable(SceneError):
    """A target the linear model cannot reach with what is held fixed; names the reachable range."""


@dataclass(frozen=True)
class Targets:
    """What a bounce should do. ``beta`` is the contact point's tangential restitution,
    -u'(out)/u'(in), in [-1, 1] (1: the slip reverses, the rough sphere of Eq. 20; 0: it stops,
    the rolling collision of Eq. 23). Exactly one of ``gamma_t`` (default 0) and
    ``kt_over_kn`` is held; the other is solved for."""

    e: float
    contact_time: float
    beta: float
    mu: float | None = None
    m: float = 1.0
    r: float = 0.5
    alpha: float = 0.4
    limit_damping: bool = False
    gamma_t: float | None = 0.0
    kt_over_kn: float | None = None


@dataclass(frozen=True)
class Calibration:
    targets: Targets
    model: ContactModel

    def achieved_theory(self) -> dict:
        """e, beta and t_c of the calibrated model, from the exact theory."""
        m = self.model
        return {"e": m.restitution, "beta": -(1.0 + m.Omega), "contact_time": m.t_exit}


def _normal(t: Targets) -> tuple[float, float]:
    """(kn, gamma_n) that give restitution e and overlap time t_c, kn one the model takes (a contact time so short or
    so long against the mass that kn = m (pi/t_c)^2 leaves a float is refused, naming it)."""
    kn, gamma_n = _normal_law(t)
    try:
        by_name("kn").check(kn)
    except SceneError as exc:
        raise Unreachable("contact_time", t.contact_time, f"gives kn = {kn:.3g} for m = {t.m:g}: {exc.limit}") from None
    return kn, gamma_n


def _normal_law(t: Targets) -> tuple[float, float]:
    if not 0.0 < t.e <= 1.0:
        raise Unreachable("e", t.e, "must lie in (0, 1]")
    if not t.contact_time > 0.0:
        raise Unreachable("contact_time", t.contact_time, "must be > 0")
    if not t.limit_damping:  # e = exp(-b pi/w), t_c = pi/w: kn = m (w^2 + b^2), gamma_n = 2 m b
        w, b = math.pi / t.contact_time, -math.log(t.e) / t.contact_time
        return t.m * (w * w + b * b), 2.0 * t.m * b
    if t.e <= LIMIT_DAMPING_E_MIN:
        raise Unreachable("e", t.e, f"with limit_damping the restitution reachable lies in (exp(-2), 1] = "
                          f"({LIMIT_DAMPING_E_MIN:.6f}, 1]: critical damping still returns exp(-2) of v_n")
    ratio = gamma_n_for_restitution_cut(t.e, 1.0, 1.0) / 2.0  # gamma_n/(2 sqrt(m kn))
    unit_time = exact.exit_time(1.0, 1.0, 2.0 * ratio, tensile=False)  # t_c at m = kn = 1
    kn = t.m * (unit_time / t.contact_time) ** 2
    return kn, 2.0 * ratio * math.sqrt(t.m * kn)


def _slip_ratio(t: Targets, kn: float, gamma_n: float, kt: float, gamma_t: float) -> float:
    """u'(tau)/u'(0) = 1 + Omega (exact, damped)."""
    return exact.Omega_exact(t.m, kn, kt, t.alpha, gamma_t, gamma_n, not t.limit_damping) + 1.0


def _free_axis(t: Targets, kn: float, gamma_n: float):
    """(name, f(x) = slip ratio, scan grid of x >= 0) for the tangential parameter solved for."""
    tau = exact.collision_time(t.m, kn, gamma_n, not t.limit_damping)
    if t.kt_over_kn is not None:
        kt = t.kt_over_kn * kn
        # gamma_t up to a slip damping rate zeta = 1e7/tau, where the ratio is within about
        # Q tau/(2 zeta) ~ 1e-7 of its overdamped limit 0
        top = 1e7 / tau * 2.0 * t.alpha * t.m / (1.0 + t.alpha)
        grid = np.concatenate([[0.0], np.geomspace(top * 1e-13, top, SCAN_POINTS)])
        return "gamma_t", (lambda g: _slip_ratio(t, kn, gamma_n, kt, g)), grid
    # kt up to a slip phase sqrt(Q) tau of 2 pi: one full turn holds the first branch's extremes
    top = (2.0 * math.pi / tau) ** 2 * t.m * t.alpha / (1.0 + t.alpha)
    grid = np.linspace(0.0, top, SCAN_POINTS + 1)
    return "kt", (lambda k: _slip_ratio(t, kn, gamma_n, k, t.gamma_t)), grid


def _polished(f, grid: np.ndarray, values: np.ndarray, k: int, sign: float) -> float:
    """Where the scan's extreme at index k really is, between its neighbours."""
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    best = minimize_scalar(lambda x: sign * f(x), bounds=(lo, hi), method="bounded", options={"xatol": 1e-12 * hi})
    return float(best.x) if best.fun < sign * values[k] else float(grid[k])


def _scan(t: Targets):
    """(name, f, grid, f on the grid): the free parameter's scan, its two extremes polished and
    put in, so that the grid reaches every value the range names."""
    kn, gamma_n = _normal(t)
    name, f, grid = _free_axis(t, kn, gamma_n)
    values = np.array([f(x) for x in grid])
    extremes = [_polished(f, grid, values, int(np.argmin(values)), 1.0),
                _polished(f, grid, values, int(np.argmax(values)), -1.0)]
    grid = np.unique(np.concatenate([grid, extremes]))
    return name, f, grid, np.array([f(x) for x in grid])


def tangential_range(t: Targets) -> tuple[float, float, str]:
    """(lowest, highest) beta reachable with what ``t`` holds, and the parameter solved for:
    the slip ratio's extremes along the free parameter (beta = -ratio)."""
    name, _, _, values = _scan(t)
    low, high = float(values.min()), float(values.max())
    if name == "gamma_t":  # the overdamped limit: the slip rate dies out, ratio -> 0
        low, high = min(low, 0.0), max(high, 0.0)
    return -high, -low, name


def _tangential(t: Targets, kn: float, gamma_n: float) -> tuple[float, float]:
    """(kt, gamma_t) giving the slip ratio -beta: the first root along the free parameter."""
    if not -1.0 <= t.beta <= 1.0:
        raise Unreachable("beta", t.beta, "must lie in [-1, 1]: |u'(out)| <= |u'(in)| in a passive contact")
    target = -t.beta
    if t.kt_over_kn is None and t.gamma_t == 0.0:  # cos(sqrt(Q) tau) = -beta on the first branch
        tau = exact.collision_time(t.m, kn, gamma_n, not t.limit_damping)
        return t.m * t.alpha / (1.0 + t.alpha) * (math.acos(target) / tau) ** 2, 0.0
    name, f, grid, values = _scan(t)
    values = values - target
    crossing = np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) <= 0.0)
    if crossing.size == 0:
        low, high, _ = tangential_range(t)
        held = (f"kt/kn = {t.kt_over_kn:g}" if name == "gamma_t" else f"gamma_t = {t.gamma_t:g}")
        limit = " (beta = 0 only as gamma_t grows without bound)" if name == "gamma_t" else ""
        raise Unreachable("beta", t.beta, f"with {held} (e = {t.e:g}, t_c = {t.contact_time:g}) the linear model "
                          f"reaches beta in [{low:.6g}, {high:.6g}] by varying {name}{limit}")
    k = int(crossing[0])
    x = grid[k] if values[k] == 0.0 else brentq(lambda v: f(v) - target, grid[k], grid[k + 1], xtol=1e-15, rtol=1e-14)
    return (x, t.gamma_t) if name == "kt" else (t.kt_over_kn * kn, x)


def calibrate(t: Targets) -> Calibration:
    """The contact model whose exact theory meets ``t`` (:class:`Unreachable` if none does)."""
    if (t.gamma_t is None) == (t.kt_over_kn is None):
        raise SceneError("kt_over_kn", t.kt_over_kn, "hold exactly one of gamma_t and kt/kn; the other is solved for")
    kn, gamma_n = _normal(t)
    if t.mu is not None and gamma_n > 0.0 and not t.limit_damping:
        raise Unreachable("mu", t.mu, f"with e = {t.e:g} < 1 the normal force turns tensile before the sphere leaves, "
                          "and there the cap mu |F_n| passes through zero and wipes the tangential spring's "
                          "history (LAMMPS rescales it onto the cap): no matrix describes the bounce, sticking or "
                          "not. Give limit_damping, or leave mu out")
    kt, gamma_t = _tangential(t, kn, gamma_n)
    model = ContactModel(m=t.m, r=t.r, alpha=t.alpha, kn=kn, kt=kt, gamma_n=gamma_n, gamma_t=gamma_t, mu=t.mu,
                         limit_damping=t.limit_damping)
    return Calibration(t, model)


def pair_lines(model: ContactModel) -> tuple[str, str]:
    """``pair_style granular`` and ``pair_coeff`` for two equal spheres with the same e, beta and t_c:
    kn, gamma_n, kt and gamma_t halved (docs/theory.md, section 5)."""
    half = model.replace(kn=model.kn / 2.0, kt=model.kt / 2.0, gamma_n=model.gamma_n / 2.0,
                         gamma_t=model.gamma_t / 2.0)
    return "pair_style granular", f"pair_coeff * * {wall_parameters(half)['style'].removeprefix('granular ')}"


def measure(calibrations, out_dir, steps_per_half_period: int = 2000) -> list[dict]:
    """What LAMMPS achieves with each calibrated model: e, beta and t_c of one bounce.

    MAX_MODELS models per run (a wall pair per model, :mod:`.two_walls`, the first bounce only).
    Each sphere comes in at the |v_n| that presses it r/2 into the wall (far from tunnelling),
    with a slip u'(0) = |v_n|, or 1e-3 mu |v_n| with a cap, small enough to stick (docs/theory.md,
    section 5).
    """
    from ..scenes.two_walls import MAX_MODELS, TwoWalls, run_two_walls

    models = [c.model for c in calibrations]
    out = []
    for k, start in enumerate(range(0, len(models), MAX_MODELS)):
        chunk = tuple(models[start:start + MAX_MODELS])
        speeds = [0.5 * m.r / float(exact.max_overlap(1.0, m.m, m.kn, m.gamma_n)) for m in chunk]
        slips = [v if m.mu is None else 1e-3 * m.mu * v for v, m in zip(speeds, chunk, strict=True)]
        initial = np.array([[-v, s, 0.0] for v, s in zip(speeds, slips, strict=True)])
        scene = TwoWalls(chunk, initial, bounces=1, steps_per_half_period=steps_per_half_period)
        result = run_two_walls(scene, Path(out_dir) / f"batch{k + 1}")
        after, durations = result.states[1], result.contact_durations()[:, 0]
        out += [{"e": float(after[i, 0] / -initial[i, 0]),
                 "beta": float(-(after[i, 1] + after[i, 2]) / slips[i]),
                 "contact_time": float(durations[i]), "deck": str(result.deck)} for i in range(len(chunk))]
    return out
