"""A gas's two theories, and how far LAMMPS is from each.

- ``matrix``: the rough-sphere equations (:func:`spinbounce.exact.kinetic.rough_sphere_matrix`) with
  the restitutions of the paper's planar theory for the pair (e_n and beta of its matrix: the line of
  centres held, dt -> 0); none for a law without one (a cap, a law on the contact radius).
- ``pairs``: L measured from LAMMPS's own isolated pair collisions at the gas's step
  (:mod:`.collisions`), at temperatures spanning the run's: the turning line of centres and the step's
  errors are in the prediction; and what the gas's overlapping contacts add (:mod:`.encounters`: three
  spheres at a time in LAMMPS, at the gas's packing).
- ``exact pairs``: the same with the pairs from the exact pair references (dt -> 0), which separates the
  two (the overlapping contacts are LAMMPS's in both: there is no exact three-sphere reference).

Each is compared with LAMMPS at LAMMPS's own collisions per sphere (the theory's clock: its rates per
collision do not depend on the Enskog rate, which a soft gas meets only to a few per cent).
"""

from __future__ import annotations

import math

import numpy as np

from ...exact import kinetic
from ..pair.kind import no_planar_matrix
from . import collisions, encounters
from .rule import restitutions

__all__ = ["restitutions", "matrix_averages", "temperature_grid", "compare", "relaxation", "theories", "late_mean",
           "late_samples", "LATE_SHARE"]

#: The share of a run whose mean ratio is its late ratio (LAMMPS's and each theory's, over the same samples).
LATE_SHARE = 0.25


def late_samples(tau: np.ndarray) -> np.ndarray:
    """Which samples at collisions per sphere ``tau`` are in the run's last LATE_SHARE."""
    return tau >= (1.0 - LATE_SHARE) * tau[-1]


def late_mean(tau: np.ndarray, ratio: np.ndarray) -> float:
    """The mean of ``ratio`` over the samples in the last LATE_SHARE of the collisions ``tau``."""
    return float(np.mean(ratio[late_samples(tau)]))


def matrix_averages(model) -> tuple[kinetic.Averages | None, str | None]:
    """The ``matrix`` theory's L, or None and why the law has none."""
    why = no_planar_matrix(model)
    if why is not None:
        return None, why
    e_n, beta = restitutions(model)
    # no contact time: the matrix theory counts no collisions (LAMMPS's count uses the pair references')
    return kinetic.Averages(np.array([1.0]), kinetic.rough_sphere_matrix(e_n, beta, model.alpha)[None],
                            np.array([math.nan])), None


#: The most temperatures L is measured at (a gas cooling a hundredfold: factors of 3.2 apart; L changes with the
#: speed through the turning angle, a few per cent of itself over that range).
MAX_TEMPERATURES = 5


def temperature_grid(averages: kinetic.Averages, gas) -> np.ndarray:
    """T_tr's the pair-level L is measured at: from the range a first evolution (by ``averages``) crosses in the
    run's time (its collisions slow as it cools: the nominal count at the starting rate overshoots them), one a
    factor of two apart (at least two, at most MAX_TEMPERATURES; one where T_tr stays within 5%)."""
    # a gas heating (T_rot(0) > T_tr(0)) meets more collisions than the nominal: at most as many more as its
    # rate grows, to T_tr = T_tr(0) + T_rot(0)
    most = gas.collisions * math.sqrt((gas.t_tr + gas.t_rot) / gas.t_tr)
    path = kinetic.evolve(averages, gas.t_tr, gas.t_rot, most, gas.packing, gas.sigma, gas.model.m, points=401)
    within = path.t <= gas.nsteps * gas.dt if gas.dt else np.ones_like(path.t, dtype=bool)
    low, high = float(path.t_tr[within].min()), float(path.t_tr[within].max())
    if high / low < 1.05:
        return np.array([gas.t_tr])
    return np.geomspace(low, high, min(MAX_TEMPERATURES, max(2, 1 + math.ceil(math.log2(high / low)))))


def relaxation(tau: np.ndarray, ratio: np.ndarray, steady: float, share: float = 0.9) -> float:
    """The collisions per sphere at which ``ratio`` first reaches ``share`` of ``steady`` (from below;
    linear between points), or NaN if it does not."""
    target = share * steady
    above = np.nonzero(ratio >= target)[0]
    if len(above) == 0 or above[0] == 0:
        return float("nan")
    k = above[0]
    return float(tau[k - 1] + (target - ratio[k - 1]) * (tau[k] - tau[k - 1]) / (ratio[k] - ratio[k - 1]))


def compare(series: dict, averages: kinetic.Averages, gas) -> dict:
    """One theory from LAMMPS's start, at LAMMPS's collisions per sphere: its series and the differences."""
    tau = series["collisions"]
    path = kinetic.evolve(averages, series["t_tr"][0], series["t_rot"][0], float(tau[-1]), gas.packing, gas.sigma,
                          gas.model.m, points=max(401, 4 * len(tau)))
    t_tr, t_rot = (np.interp(tau, path.tau, x) for x in (path.t_tr, path.t_rot))
    energy = 1.5 * (t_tr + t_rot)
    steady = kinetic.steady_ratio(averages.at(float(t_tr[-1])))
    late = late_mean(tau, t_rot / t_tr)  # over LAMMPS's late samples, as LAMMPS's: a run may end short of the fixed
    # point, so its late ratio and the time to 90% of it are what compare with LAMMPS's like with like
    drift = {"lammps": float(series["energy"][-1] / series["energy"][0] - 1.0),
             "theory": float(energy[-1] / energy[0] - 1.0)}
    return {"t_tr": t_tr, "t_rot": t_rot, "ratio": t_rot / t_tr, "energy": energy * series["energy"][0] / energy[0],
            "t_enskog": np.interp(tau, path.tau, path.t),
            "max_ratio_difference": float(np.max(np.abs(series["ratio"] - t_rot / t_tr))),
            "energy_drift": drift, "drift_difference": drift["lammps"] - drift["theory"],
            "steady_ratio": steady, "relaxation_collisions": relaxation(path.tau, path.ratio, steady),
            "late_ratio": late, "relaxation_collisions_late": relaxation(path.tau, path.ratio, late)}


def theories(gas, folder, log=None) -> tuple[dict, np.ndarray, str | None, tuple]:
    """The gas's theories by name ("pairs", "exact_pairs" and, where the law has one, "matrix": their L), the
    largest standard error of the pair-level L, why there is no matrix theory (or None), and the overlapping
    contacts' share of the pair-level L with its largest standard errors."""
    count = gas.draws
    matrix, why = matrix_averages(gas.model)
    sample = collisions.draws(count, gas.seed)
    first = collisions.averages(gas.model, [gas.t_tr], collisions.draws(max(1000, count // 8), gas.seed))["exact"][0]
    grid = temperature_grid(first, gas)
    if log is not None:
        log(f"pair-level theory: {count} collisions and {encounters.encounter_count(count)} three-sphere encounters at "
            f"{len(grid)} temperature(s), in LAMMPS at dt = {gas.dt:.4g}")
    crowd = encounters.Crowd(gas.packing, encounters.encounter_draws(encounters.encounter_count(count), gas.seed))
    found = collisions.averages(gas.model, grid, sample, gas.dt, folder, crowd)
    out = {"pairs": found["lammps"][0], "exact_pairs": found["exact"][0]}
    if matrix is not None:
        out["matrix"] = matrix
    return out, found["lammps"][1], why, found["overlaps"]
