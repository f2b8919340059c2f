"""Run a gas and judge it: LAMMPS's series beside the theories, written with its record (the API's
``spinbounce.gas``, the gas figure and the gas claims all run through :func:`run_gas`)."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...errors import SceneError
from ...exact.kinetic import Averages
from ...lammps.decks import prepare_run_dir
from ...lammps.runner import run_deck, run_deck_lmp
from ...model.contact import ContactModel
from ...records import check_run_folder, locked, run_folder, software, source_digest, to_json, write_atomic
from ...workers import cores
from ..pair.kind import equal_pair
from . import collisions as pair_draws
from . import closure, predict
from .deck import render_gas
from .parameters import DEFAULT
from .scene import Gas
from .table import read_series

__all__ = ["run_gas", "shared_gas", "GasReport", "GAS_SERIES", "GASES", "GAS_SPHERE_STEP_SECONDS"]

#: The series a gas run writes into its folder (its record: result.json).
GAS_SERIES = "gas.csv"
#: The folder, beside a command's run folders, of the gases it shares by content (:func:`shared_gas`).
GASES = "gases"
#: LAMMPS's cost of one sphere's step in a dilute gas on one core (measured here: 1.7e7 to 3.9e7
#: sphere-steps a second; the slower end, so that an estimate is not short).
GAS_SPHERE_STEP_SECONDS = 6e-8
#: The pair-level theory's cost of one drawn collision at one temperature: three runs (still, spun, reversed),
#: each an exact reference and a LAMMPS pair (measured about 45 us in all), and half an encounter's three
#: variants of seven spheres in LAMMPS (about 130 us each); rounded up.
THEORY_SECONDS_PER_DRAW = 1.2e-4
#: The collisions (without spin) whose mean exact contact time sets the step.
CONTACT_SAMPLE = 2000
#: How close (relative) a theory's late ratio must be to its fixed point for the closure's error, a steady state's,
#: to be added to it (the claims' kt/kn = 0.1 gas ends 1% short).
NEAR_STEADY = 0.02
#: Runs estimated longer than this (seconds) need force.
LONGEST_UNFORCED = 3600.0


@dataclass(frozen=True)
class GasReport:
    """A gas in LAMMPS beside its theories: ``series`` (time, temperatures, energy, collisions per sphere,
    and each theory's ratio and energy at the same collisions), ``record`` (parameters, comparisons,
    accuracy, provenance) and the files they were written to."""

    series: dict
    record: dict
    csv: Path
    record_path: Path


def run_gas(m: ContactModel, *, spheres: int = DEFAULT["spheres"], packing: float = DEFAULT["packing"],
            t_tr: float = DEFAULT["t_tr"], t_rot: float = DEFAULT["t_rot"], collisions: float = DEFAULT["collisions"],
            samples: int = DEFAULT["samples"], seed: int = DEFAULT["seed"], draws: int = DEFAULT["draws"],
            dt: float | None = None, ranks: int = 1, out: str | Path | None = None, force: bool = False,
            log=None, reuse: bool = False) -> GasReport:
    """Run a gas of ``spheres`` spheres of model ``m`` at ``packing`` from T_tr(0) = ``t_tr`` and
    T_rot(0) = ``t_rot`` for ``collisions`` collisions per sphere (at the starting rate), in this process
    or (``ranks`` > 1) under ``mpiexec -np ranks``, and set its temperatures beside the theories
    (:mod:`spinbounce.scenes.gas.predict`). A run estimated beyond an hour needs ``force``; a named
    ``out`` holding an earlier run is refused unless ``force``; with ``reuse``, one holding this very run,
    finished by the same software from the same sources (their digest), is read back instead of run again
    (:func:`_finished`)."""
    if isinstance(ranks, bool) or int(ranks) != ranks or ranks < 1:
        raise SceneError("ranks", ranks, "must be a whole number >= 1")
    values = Gas(m, None, spheres, packing, t_tr, t_rot, collisions, samples, seed, draws, dt)  # checked, not run
    _check_cost(values, theory_seconds(values), ranks, force)  # the theory alone: before the contact time's
    if log is not None and one_pair_seconds(m):
        log(f"gas: the step from the mean contact time of {CONTACT_SAMPLE} collisions, each solved on its own (about "
            f"{CONTACT_SAMPLE * one_pair_seconds(m):.0f} s)")
    tc = pair_draws.mean_contact_time(m, values.t_tr, pair_draws.draws(CONTACT_SAMPLE, values.seed))
    scene = Gas(m, tc, spheres, packing, t_tr, t_rot, collisions, samples, seed, draws, dt)
    folder = Path(out) if out is not None else run_folder("gas", scene.record() | {"ranks": ranks})
    if reuse and (done := _finished(folder, scene, ranks)) is not None:
        if log is not None:
            log(f"gas: {scene.spheres} spheres, read back from {folder} (this run, finished earlier)")
        return done
    check_run_folder(out, force)
    steps = scene.nsteps + scene.settle_steps + scene.burn_steps
    cost = scene.spheres * steps * GAS_SPHERE_STEP_SECONDS / min(ranks, cores()) + theory_seconds(scene)
    _check_cost(scene, cost, ranks, force, steps)
    if log is not None:
        log(f"gas: {scene.spheres} spheres, {steps} steps of dt = {scene.dt:.4g}, the theory from {scene.draws} draws "
            f"(about {cost:.0f} s in all on {ranks} rank(s))")
    deck_path = prepare_run_dir(folder, render_gas(scene))
    (folder / GAS_SERIES).unlink(missing_ok=True)  # an earlier run's series never stands beside this run's deck
    info = run_deck(deck_path) if ranks == 1 else run_deck_lmp(deck_path, ranks=ranks)
    return _judged(scene, folder, info, ranks, log)


def shared_gas(root: str | Path, m: ContactModel, log=None, **settings) -> GasReport:
    """:func:`run_gas` of ``m`` and ``settings`` in ``root``/gas-<digest of both>, read back where that folder
    holds it finished: one run for every product of a ``reproduce`` that shows the same gas (the claims' and the
    gas figure's), and none again when ``reproduce`` runs again. Products made side by side take turns: one
    waits on the folder's lock while another runs it, then reads it back."""
    folder = Path(root) / run_folder("gas", {"model": m.as_record(), **settings}).name
    folder.parent.mkdir(parents=True, exist_ok=True)
    with locked(folder.parent / f".{folder.name}.lock"):
        return run_gas(m, out=folder, force=True, reuse=True, log=log, **settings)


def declared_gas(root: str | Path, g: dict, kt_over_kn: float, log=None) -> GasReport:
    """:func:`shared_gas` of a product's declared gas: Hookean spheres of kn ``g["kn"]`` at ``kt_over_kn``, run
    with ``g``'s spheres, packing, collisions, samples and draws. Products showing the same declared gas (the
    gas figure's kt/kn = 0.1 case and the claims' soft gas) call this with the same numbers, so they share
    one run by construction."""
    settings = {name: g[name] for name in ("spheres", "packing", "collisions", "samples", "draws")}
    return shared_gas(root, ContactModel(kn=g["kn"], kt=kt_over_kn * g["kn"]), log=log, **settings)


def _finished(folder: Path, scene, ranks: int) -> GasReport | None:
    """The run in ``folder`` if it is this one finished: its record's parameters and rank count this scene's, and
    every version it records this software's (its series and record are written last, each atomically)."""
    import pandas as pd

    record_path, csv = folder / "result.json", folder / GAS_SERIES
    if not (record_path.is_file() and csv.is_file()):
        return None
    record = json.loads(record_path.read_text())
    versions = {k: v for k, v in software().items() if k.endswith("_version") or k == "python"}
    versions["spinbounce_source"] = source_digest()  # the code itself: an editable install keeps its version
    if (record.get("parameters") != json.loads(to_json(scene.record())) or record.get("ranks") != ranks
            or any(record.get(k) != v for k, v in versions.items())):
        return None
    table = pd.read_csv(csv)
    record |= {"csv": str(csv), "deck": str(folder / Path(record["deck"]).name)}  # where it is now
    return GasReport({name: table[name].to_numpy() for name in table.columns}, record, csv, record_path)


def one_pair_seconds(model: ContactModel) -> float:
    """What one collision of the theories costs beside a compiled batch's: the law's in a gas's hot collisions
    (:meth:`.PairContact.one_pair_seconds`, none where its exact pair references are compiled)."""
    return equal_pair(model)[1].one_pair_seconds(slow_impacts=False)


def theory_seconds(scene) -> float:
    """About how long the pair-level theories take: every draw at up to predict.MAX_TEMPERATURES temperatures,
    and where the law's exact references are solved one pair at a time, each of those draws' three collisions
    (still, spun, reversed) and the contact time's sample on its own (:func:`one_pair_seconds`)."""
    per_pair = one_pair_seconds(scene.model)
    per_draw = THEORY_SECONDS_PER_DRAW + 3 * per_pair
    return scene.draws * predict.MAX_TEMPERATURES * per_draw + CONTACT_SAMPLE * per_pair


def _check_cost(scene, seconds: float, ranks: int, force: bool, steps: int | None = None) -> None:
    """Refuse a run estimated at ``seconds`` beyond LONGEST_UNFORCED unless ``force``: LAMMPS's ``steps`` and the
    theory's draws, or (``steps`` None) the theory alone."""
    if seconds <= LONGEST_UNFORCED or force:
        return
    counted = f"{scene.draws} draws for the theory alone" if steps is None else (
        f"with {steps} steps and {scene.draws} draws for the theory")
    if one_pair_seconds(scene.model):
        counted += (" (this law's exact pair references are solved one pair at a time: about "
                    f"{one_pair_seconds(scene.model):g} s a pair in a gas's collisions)")
    name = "spheres" if steps is not None else "draws"
    raise SceneError(name, getattr(scene, name), f"{counted}: the run is estimated at {seconds / 3600:.2g} hours on "
                     f"{ranks} rank(s), more than one: give force (--force) to run it")


def _judged(scene, folder: Path, info, ranks: int, log) -> GasReport:
    """The run's series beside the theories, written to gas.csv and result.json."""
    import pandas as pd

    theories, errors, why, overlaps = predict.theories(scene, folder / "pairs", log)
    beyond = closure.boltzmann(scene.model, scene.seed, log)
    series = read_series(scene, folder, theories["pairs"].contact_time)
    compared = {name: predict.compare(series, averages, scene) for name, averages in theories.items()}
    table = dict(series)
    for name, c in compared.items():
        table |= {f"{q}_{name}": c[q] for q in ("t_tr", "t_rot", "ratio", "energy")}
    table["t_enskog_pairs"] = compared["pairs"]["t_enskog"]
    csv = folder / GAS_SERIES
    write_atomic(csv, pd.DataFrame(table).to_csv(index=False, float_format="%.17g"))
    drift = _drift_closure(scene, series, theories["exact_pairs"], overlaps[0], log)
    record = {"scene": "gas", "parameters": scene.record(), "ranks": ranks, "judged": scene.judged,
              "lammps": _lammps_summary(series),
              "theories": {n: _summary(c, beyond, None if n == "matrix" else drift) | _matrices(theories[n])
                           for n, c in compared.items()},
              "closure": beyond, "closure_drift": drift,
              "overlaps": _overlaps(series, scene, theories["pairs"], overlaps, compared["pairs"]),
              "no_matrix": why, "accuracy": _accuracy(scene, series, errors),
              "csv": str(csv),
              "deck": str(info.deck), "loop_seconds": info.loop_seconds, "wall_seconds": info.wall_seconds,
              **software(), "spinbounce_source": source_digest()}
    record_path = folder / "result.json"
    text = to_json(record)
    write_atomic(record_path, text)
    return GasReport(table, json.loads(text), csv, record_path)  # as written (a NaN as None): as it is read back


def _lammps_summary(series: dict) -> dict:
    late = series["ratio"][predict.late_samples(series["collisions"])]
    steady = float(np.mean(late))
    return {"late_ratio": steady, "late_ratio_spread": float(np.std(late)),
            "energy_drift": float(series["energy"][-1] / series["energy"][0] - 1.0),
            "collisions_per_sphere": float(series["collisions"][-1]),
            "relaxation_collisions": predict.relaxation(series["collisions"], series["ratio"], steady)}


def _summary(compared: dict, beyond: dict | None, drift: dict | None) -> dict:
    """A theory's comparison with LAMMPS, its steady and late ratios with the closure's error (the late one over
    LAMMPS's late samples: a cooling run may end a little short of the fixed point; the closure's error belongs to
    the steady state, so a late ratio further than NEAR_STEADY from it has none), and its energy drift with its
    isolated pairs' part by DSMC (:mod:`.closure`, :func:`_drift_closure`; None where the law has no planar rule,
    or no compiled pair reference; the drift's only for the pair-level theories: the matrix conserves energy
    whatever the distribution)."""
    keys = ("max_ratio_difference", "energy_drift", "drift_difference", "steady_ratio", "relaxation_collisions",
            "late_ratio", "relaxation_collisions_late")
    error = None if beyond is None else beyond["closure_error"]
    near = abs(compared["late_ratio"] / compared["steady_ratio"] - 1.0) <= NEAR_STEADY  # False if either is NaN
    energy = None if drift is None else compared["energy_drift"]["theory"] + drift["dsmc_less_equations"]
    return {k: compared[k] for k in keys} | {
        "steady_ratio_boltzmann": None if error is None else compared["steady_ratio"] + error,
        "late_ratio_boltzmann": None if error is None or not near else compared["late_ratio"] + error,
        "energy_drift_boltzmann": energy}


def _drift_closure(scene, series: dict, exact: Averages, share: Averages, log) -> dict | None:
    """The isolated pairs' energy drift over the run by DSMC with the exact pair references' outcomes
    (:func:`.closure.pair_path`, from the series' start to its collisions per sphere), and by the two-temperature
    equations with the same pairs (the exact theory without its overlapping contacts). Their difference replaces
    the equations' part in the pair-level drifts: it is the closure's error and the equations' own draws' noise
    (a drawn collision's loss is heavy-tailed: over 12 collisions at the magic ratio, 20,000 draws leave about
    0.08 points; four DSMC seeds span 0.043). None where the compiled references do not take the law."""
    tau = float(series["collisions"][-1])
    path = closure.pair_path(scene.model, float(series["t_tr"][0]), float(series["t_rot"][0]), tau, scene.seed, log)
    if path is None:
        return None
    closed = _isolated_drift(series, scene, exact, share)
    dsmc = float(np.interp(tau, path.tau, path.energy) / path.energy[0] - 1.0)
    return {"energy_drift_dsmc": dsmc, "energy_drift_equations": closed, "dsmc_less_equations": dsmc - closed,
            "spheres": closure.SPHERES, "collisions_per_sphere": tau}


def _isolated_drift(series: dict, scene, theory: Averages, share: Averages) -> float:
    """A pair-level theory's energy drift over the run without its overlapping contacts (their ``share`` of L)."""
    alone = Averages(theory.t_tr, theory.matrices - share.matrices, theory.contact_times)
    return predict.compare(series, alone, scene)["energy_drift"]["theory"]


def _overlaps(series: dict, scene, pairs, overlaps: tuple, compared: dict) -> dict:
    """The overlapping contacts' share of the pair-level L, and of its energy drift over the run (the drift less
    that of the isolated pairs alone), with the latter's standard error (the largest of an energy change's,
    carried over the run's collisions)."""
    share, errors = overlaps
    drift = compared["energy_drift"]["theory"] - _isolated_drift(series, scene, pairs, share)
    return _matrices(share) | {"energy_drift": drift,
                               "energy_drift_standard_error": float(np.max(errors[2]) * series["collisions"][-1])}


def _matrices(averages) -> dict:
    """A theory's L (d(T_tr, T_rot)/dtau = L (T_tr, T_rot)) at the T_tr's it was measured at."""
    return {"L_at_t_tr": averages.t_tr.tolist(), "L": averages.matrices.tolist()}


def energy_noise(energy: np.ndarray) -> float:
    """A sample's own relative noise in the kinetic energy (spring energy comes and goes with the contacts, and
    samples many contact times apart are independent): from the second differences of ln E, which a smooth
    cooling all but cancels, sqrt(<d2^2> / 6); NaN below four samples."""
    if len(energy) < 4:
        return math.nan
    return float(np.sqrt(np.mean(np.diff(np.log(energy), 2) ** 2) / 6.0))


def _accuracy(scene, series: dict, errors: np.ndarray) -> dict:
    """How far each number may be from the truth: a temperature's own noise (sqrt(2/(3N)) of it); the count of
    collisions per sphere's relative noise (the open contacts are sampled, not tallied); the kinetic
    energy's noise a sample (a drift's between two seeds is larger: 0.18 points at 20,000 spheres, kn = 1e4,
    packing 0.05, the early collisions' doing); the pair-level L's standard errors, the largest of its entries
    and of its columns' sums, and the latter carried over the run's collisions (the standard error of the
    theory's energy drift, at most)."""
    return {"temperature_noise": math.sqrt(2.0 / (3.0 * scene.spheres)),
            "energy_sample_noise": energy_noise(series["energy"]),
            "collisions_noise": scene.collisions_noise(float(series["collisions"][-1])),
            "pair_level_standard_error": float(np.max(errors[:2])),
            "pair_level_energy_standard_error": float(np.max(errors[2])),
            "pair_level_drift_standard_error": float(np.max(errors[2]) * series["collisions"][-1])}
