"""One collision and the theory that applies: ``collide`` and ``theory``, wall or pair, and their
reports."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..model import parameters
from ..model.contact import ContactModel
from ..exact import choose, linear
from ..laws.words import expand_contact
from ..records import run_folder
from .reports import CollisionReport, PairReport, ToleranceReport, state_record, state_table

__all__ = ["collide", "theory", "model", "CollisionReport", "PairReport", "ToleranceReport"]

_MODEL_NAMES = {p.name for p in parameters.MODEL}
#: The scene's keywords (wall or pair, sphere b's m_b, r_b, alpha_b and its state): a pair's only.
_SCENE_NAMES = {p.name for p in parameters.SCENE} | {p.name for p in parameters.STATE_B}
#: The state's keywords, in order (spins as angular velocities).
_STATE_NAMES = tuple(p.name for p in parameters.STATE)


@dataclass(frozen=True)
class _Pair:
    """A pair scene's sphere b and its state at first touch (a's frame and sign)."""

    b: object
    state: np.ndarray


def _contact_and_pair(keywords: dict):
    """(the contact model, None for the wall or the pair's sphere b and its state); b's keywords are
    refused without scene="pair"."""
    from ..scenes.pair.kind import scene_of, sphere_b, state_b

    scene = {k: keywords.pop(k) for k in list(keywords) if k in _SCENE_NAMES}
    pair = None
    if scene_of(scene) != "wall":
        sphere = sphere_b(**{k: v for k, v in scene.items() if k in parameters.PAIR_SPHERE and v is not None})
        pair = _Pair(sphere, state_b(scene))
    return model(**keywords), pair


def model(**parameters_) -> ContactModel:
    """A checked contact model from declared parameter names (unknown names are refused); a
    ``contact`` line (LAMMPS's granular words, :func:`spinbounce.laws.words.parse_contact`) is
    read into them."""
    parameters_ = expand_contact(parameters_)
    unknown = set(parameters_) - _MODEL_NAMES
    if unknown:
        raise TypeError(f"unknown model parameter(s) {sorted(unknown)}; declared: {sorted(_MODEL_NAMES)}")
    return ContactModel(**parameters_)


def _pair_batch(pair: _Pair, contact: ContactModel, state: dict, dt=None):
    from ..scenes.pair.kind import pair_contact, pairs_from_states
    from ..scenes.pair.scene import PairBatch

    row = [state[k] for k in _STATE_NAMES]
    return PairBatch(pairs_from_states(contact, pair.b, [row], pair.state), pair_contact(contact, pair.b), dt)


#: A pair row's geometry and spheres, reported beside the states.
_PAIR_GEOMETRY = ("m_a", "r_a", "alpha_a", "m_b", "r_b", "alpha_b", "v_n_relative", "v_t_relative", "speed", "tau",
                  "contact_time", "eps", "centrifugal", "turn")


def _pair_report(row: dict, batch, run=None, run_dir=None, Omega=None, kind: str = "pair_exact") -> PairReport:
    """A pair's row in the paper's names and signs: LAMMPS's frame (the line of centres along z)
    is the wall's, so each sphere's velocity and spin map as the wall's sphere's do. ``run``: the
    pipeline's result, where LAMMPS ran (in ``run_dir``)."""
    from ..exact.choose import SPACE_COLUMNS
    from ..scenes.pair.kind import THEORIES, wall_frame

    pair = batch.pairs[0]

    def states(suffix: str) -> np.ndarray:
        out = []
        for side, sphere in (("a", pair.a), ("b", pair.b)):
            v, w = (np.array([row[f"{side}_{q}{x}{suffix}"] for x in "xyz"]) for q in "vw")
            out += wall_frame(v, w, sphere.r)[0].tolist()
        return np.array(out)

    initial = wall_frame(np.array(pair.v_a), np.array(pair.w_a), pair.a.r)[0].tolist() + \
        wall_frame(np.array(pair.v_b), np.array(pair.w_b), pair.b.r)[0].tolist()
    theory, lammps = states("_theory"), None if run is None else states("")
    columns = {"initial": initial, "LAMMPS": lammps, "theory": theory,
               "error": None if lammps is None else lammps - theory, "planar": states("_planar")}
    import pandas as pd

    table = pd.DataFrame({k: v for k, v in columns.items() if v is not None},
                         index=list(SPACE_COLUMNS) + [f"{s}_b" for s in SPACE_COLUMNS])
    table.attrs.update(r=pair.a.r, r_b=pair.b.r)
    geometry = {k: float(row[k]) for k in _PAIR_GEOMETRY}
    report = PairReport(table, float(row["planar_error"]), float(row["eps"]), geometry, dt=batch.dt,
                        nsteps=batch.nsteps, error=float(row.get("error", float("nan"))),
                        status=str(row.get("status", "")), theory_kind=kind, theory_name=THEORIES[kind])
    if run is None:
        return report
    return dataclasses.replace(report, run_dir=run_dir, step=run.step.record(), Omega=Omega,
                               warnings=tuple(run.warnings), deck=str(run.info.deck),
                               dump=None if run.dump is None else str(run.dump), lammps_version=run.info.lammps_version)


def _collide_pair(pair: _Pair, contact: ContactModel, state: dict, dt, tolerance, out) -> PairReport:
    from ..errors import SceneError
    from ..pipeline import run_scene
    from ..scenes.pair.kind import no_planar_matrix, planar_Omega, theory_kind

    if tolerance is not None:
        raise SceneError("tolerance", tolerance, "is for the wall only: a pair runs at dt or its default step, and "
                                                 "reports its error against the exact reference")
    batch = _pair_batch(pair, contact, state, dt)
    out = Path(out) if out is not None else run_folder("collide-pair", {"model": contact.as_record(), "pairs": repr(batch.pairs),
                                                                         "dt": batch.dt})
    result = run_scene(batch, out)  # its batch carries the step the probe chose
    # the planar theory's Omega, as the sweep's Omega_theory; none where it has no matrix (as the wall's: a cap)
    Omega = None if no_planar_matrix(contact) is not None else planar_Omega(contact, pair.b)
    return _pair_report(result.table.iloc[0].to_dict(), result.scene, result, out, Omega, theory_kind(contact))


def collide(v_n: float | None = None, v_t: float | None = None, omega: float = 0.0, v_s: float = 0.0,
            omega_s: float = 0.0, omega_n: float = 0.0, *, speed: float | None = None, angle_deg: float | None = None,
            dt: float | None = None, tolerance: float | None = None, out: str | Path | None = None,
            force: bool = False, log=None, **model_parameters) -> CollisionReport | PairReport:
    """Bounce one sphere off the wall in LAMMPS and compare it with the theory that applies. Its velocity:
    ``v_n`` and ``v_t`` (default -1 and 1), or ``speed`` and ``angle_deg`` from the wall's normal. With
    ``scene="pair"`` (and ``m_b``, ``r_b``, ``alpha_b``, b's state ``v_n_b`` ... ``omega_n_b``: at rest by
    default) against a free sphere b instead. ``tolerance``: ask for an accuracy instead of a step
    (:mod:`spinbounce.extrapolation`); a damped wall collision's default is such a ladder asked for
    the default accuracy (its ``step`` record says so, with the estimate). ``log(line)``: told, before
    a long run starts, how long it will take, and how a run to a tolerance proceeds. A named ``out``
    holding an earlier run is refused unless ``force``."""
    from ..pipeline import run_scene
    from ..records import check_run_folder
    from ..scenes.collision import Collision
    from ..model.timestep import cost_notice
    from ..stepping import expected_steps
    from ..extrapolation import default_tolerance

    check_run_folder(out, force)
    v_n, v_t = parameters.velocity(v_n, v_t, speed, angle_deg, (-1.0, 1.0))
    state = dict(zip(_STATE_NAMES, (v_n, v_t, omega, v_s, omega_s, omega_n), strict=True))
    contact, pair = _contact_and_pair(model_parameters)
    if pair is not None:
        return _collide_pair(pair, contact, state, dt, tolerance, out)
    if tolerance is not None:
        return _collide_to_tolerance(contact, state, tolerance, out, log)
    scene = Collision(contact, dt=dt, **state)
    out = Path(out) if out is not None else run_folder("collide", {"model": contact.as_record(), **state,
                                                                    "dt": scene.dt})
    if dt is None and default_tolerance(contact) is not None:
        report = _collide_extrapolated(scene, out)
        if report is not None:  # else a rung failed: one probed run instead
            return report
    notice = cost_notice(expected_steps(scene), scene.n)
    if log is not None and notice:
        log(notice)
    result = run_scene(scene, out)
    scene, row = result.scene, result.table.iloc[0]  # at the step its accuracy needed
    choice = choose.which(scene.model)
    omega = float(choose.omega_per_sphere(scene.model, scene.v_n)[0])
    return CollisionReport(state_table(row, scene.state_names, scene.model.r),
                           float(np.max(scene.model.contact_times(scene.v_n))), theory_name=choice.name,
                           theory_kind=choice.kind, dt=scene.dt, nsteps=scene.nsteps, error=float(row["error"]),
                           status=str(row["status"]), run_dir=out, Omega=None if np.isnan(omega) else omega,
                           step=result.step.record(), warnings=result.warnings, deck=str(result.info.deck),
                           dump=None if result.dump is None else str(result.dump),
                           lammps_version=result.info.lammps_version)


def _collide_extrapolated(scene, out: Path) -> CollisionReport | None:
    """A damped collision at the default accuracy: the ladder's runs extrapolated to dt = 0
    (:func:`spinbounce.sweeps.ladder.extrapolate_default`), reported as one collision whose step record
    says so (``method`` "extrapolated", the runs, the estimate over the state's size, as ``error``);
    ``dt``: the finest run's, ``nsteps``: all runs' together. None where a rung failed."""
    from .. import checks
    from ..extrapolation import collision_frame, default_tolerance
    from ..pipeline import write_record
    from ..records import lammps_version
    from ..sweeps.ladder import extrapolate_default

    ladder = extrapolate_default(scene, out)  # quietly: a level's progress is told for --tolerance runs
    if ladder is None:
        return None
    (result, finest), target, contact = ladder, default_tolerance(scene.model), scene.model
    choice = choose.which(contact)
    table = collision_frame(result, finest, target)
    row = table.iloc[0]
    deviation = float(np.abs(table[[f"{s}_error" for s in finest.state_names]].to_numpy()).max())
    step = {"dt": finest.dt, "method": f"extrapolated to dt = 0 from {len(result.levels)} runs", "target": target,
            "estimate": result.relative_estimate(finest.initial), "observed_order": None, "raw_order": result.order,
            "levels": result.levels}
    run = result.finest  # the record: the finest run's provenance, the extrapolated rows and how
    write_record(out, run.info, finest.kind, {**finest.record(run.deck), "nsteps": result.steps}, dump=None,
                 warnings=[], max_abs_error=deviation, max_error=float(table["error"].max()), step=step,
                 status=checks.summary(table["status"]), table=table)
    v_n = float(scene.v_n[0])
    return CollisionReport(state_table(row, finest.state_names, contact.r), float(contact.contact_times(v_n)[0]),
                           theory_name=choice.name, theory_kind=choice.kind, dt=finest.dt, nsteps=result.steps,
                           error=float(row["error"]), status=str(row["status"]), run_dir=out, Omega=contact.Omega,
                           step=step, deck=str(result.levels[-1]["deck"]), lammps_version=lammps_version())


def _collide_to_tolerance(contact: ContactModel, state: dict, tolerance: float, out, log) -> ToleranceReport:
    from ..extrapolation import collide_to_tolerance, collision_frame
    from ..records import software, to_json, write_atomic

    out = Path(out) if out is not None else run_folder("collide", {"model": contact.as_record(), **state,
                                                                    "tolerance": tolerance})
    out_of_plane = {k: v for k, v in state.items() if k in ("v_s", "omega_s", "omega_n") and v}
    result, scene = collide_to_tolerance(contact, state["v_n"], state["v_t"], state["omega"], tolerance, out,
                                         log=log or (lambda *_: None), **out_of_plane)
    row = collision_frame(result, scene).iloc[0]
    table = state_table(row, scene.state_names, contact.r)
    record = {**state_record(table), "estimate": result.max_estimate, "theory_kind": choose.which(contact).kind,
              "tolerance": result.tolerance, "steps": result.steps,
              "plain_steps_for_same_estimate": result.plain_steps_for(result.max_estimate),
              "levels": result.levels, "Omega": _tolerance_omega(contact, state["v_n"]), **software()}
    path = Path(out) / "tolerance.json"
    write_atomic(path, to_json(record))
    return ToleranceReport(table, record, result.how, path)


def _tolerance_omega(contact: ContactModel, v_n: float) -> float | None:
    """The Omega a tolerance run's record gives: the model's where it has one (a capped model's
    uncapped Omega, as it always gave), else this speed's (its theory's per sphere), else None."""
    if not (contact.normal_law.contact_radius or contact.tangential_law.contact_radius
            or contact.normal_law.integrated(contact)):
        return contact.Omega
    omega = float(choose.omega_per_sphere(contact, v_n)[0])
    return omega if np.isfinite(omega) else None


def theory(v_n: float | None = None, v_t: float | None = None, omega: float = 0.0, v_s: float = 0.0,
           omega_s: float = 0.0, omega_n: float = 0.0, *, speed: float | None = None, angle_deg: float | None = None,
           **model_parameters) -> dict:
    """The theory that applies: with a state (``v_n``, and ``v_t`` default 0; or ``speed`` and
    ``angle_deg``) the final state of that collision (``theory``), else the scattering matrix and what
    it rests on (or, where none exists, why not). With ``scene="pair"``: the planar pair theory's
    matrix of sphere a (b at rest), or one state's outcome by the exact reference (``theory``) and by the
    planar theory (``planar``), in ``pair --json``'s keys."""
    v_n, v_t = parameters.velocity(v_n, v_t, speed, angle_deg, (v_n, 0.0))
    contact, pair = _contact_and_pair(model_parameters)
    state = dict(zip(_STATE_NAMES, (v_n, v_t, omega, v_s, omega_s, omega_n), strict=True))
    if pair is not None:
        return _pair_theory(pair, contact, state)
    choice = choose.which(contact)
    out = {"theory_kind": choice.kind, "theory_name": choice.name}
    if v_n is not None:
        out["initial"], out["theory"] = choose.outcome(contact, **state)
        out["contact_time"] = float(contact.contact_times(v_n)[0])
    elif choice.kind == "damped_nonlinear" and choice.has_matrix:
        m3 = np.asarray(contact.matrix())
        out.update(Omega=float(linear.Omega_of_matrix(m3, contact.alpha)), restitution=float(-m3[0, 0]),
                   matrix=m3, order=["v_n", "v_t", "r_omega"], Omega_depends_on="the same at every v_n (self-similar)")
    elif choice.kind == "mindlin" and choice.has_matrix:
        out.update(choose.mindlin_theory(contact), restitution=1.0, matrix=np.asarray(contact.matrix()),
                   order=["v_n", "v_t", "r_omega"])
    elif choice.has_matrix:
        from .. import exact

        out.update(tau=contact.tau, Q=contact.Q, Omega=contact.Omega, restitution=contact.restitution,
                   matrix=np.asarray(contact.matrix()), order=["v_n", "v_t", "r_omega"],
                   Omega_paper=exact.Omega(contact.kn, contact.kt, contact.alpha),
                   Omega_paper_damped=exact.Omega_paper_damped(contact.m, contact.kn, contact.kt, contact.alpha,
                                                               contact.gamma_t),
                   magic_kt_over_kn=exact.magic_kt_over_kn(contact.alpha))
    else:
        out.update(matrix=None, why_no_matrix=choice.no_matrix_reason)
    return out


def _pair_theory(pair: _Pair, contact: ContactModel, state: dict) -> dict:
    from ..exact import pair as planar
    from ..scenes.pair.kind import no_planar_matrix, pair_contact, planar_matrix, planar_Omega, theory_kind
    from ..scenes.pair.table import pair_table

    pair_law = pair_contact(contact, pair.b)
    law = pair_law.law()
    tau = None if pair_law.on_contact_radius else float(planar.contact_time(contact.m, pair.b.m, law["kn"],
                                                                                law["gamma_n"]))
    out = {"theory_kind": "pair planar", "theory_name": "planar pair theory (exact only as eps -> 0) and the exact "
                                                        "reference",
           "alpha_equivalent": planar.equivalent_alpha(contact.m, contact.alpha, pair.b.m, pair.b.alpha),
           "tau": tau,
           "model_error": "the planar theory holds the line of centres fixed: it is exact only as "
                          "eps = v_t tau/(r + r_b) -> 0 (figures/pair_validity); give a state for the exact reference"}
    if state["v_n"] is not None:
        batch = _pair_batch(pair, contact, state)
        # the state's theory is the exact reference (its kind named), the planar one beside it
        out.update(_pair_report(pair_table(batch, None).iloc[0].to_dict(), batch, kind=theory_kind(contact)).record())
    elif (why := no_planar_matrix(contact)) is not None:
        out.update(matrix=None, why_no_matrix=f"mu = {contact.mu!r}: {why}" if contact.mu is not None else why)
    elif np.any(pair.state):
        out.update(matrix=None, why_no_matrix="sphere b moves: the planar matrix maps a's state with b at rest")
    else:
        out.update(matrix=planar_matrix(contact, pair.b), order=["v_n", "v_t", "r_omega"],
                   Omega=planar_Omega(contact, pair.b))
    return out
