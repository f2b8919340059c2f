"""The one place that decides which theory answers a scene, and answers it.

Every consumer (collide, frozen, theory, sweeps, fit, figures, references, claims,
benchmarks) asks here; nothing else looks at a model's parameters to pick a theory.

============  =========================================================  ===============
kind          when                                                       one matrix?
============  =========================================================  ===============
classic_wall  a tangential spring on the contact radius (this build's    no (Omega(v_n))
              classic wall, kt sqrt(r delta); and linear_history_classic
              with a cap): :mod:`.classic`
coulomb       a finite mu: the contact sticks and slides in turn         no
              (:mod:`.coulomb`, exact and batched; checked against
              :mod:`.oracle`)
capped_       a finite mu with a spring, force or dashpot on the         no
nonlinear     contact radius: stick and slip in turn
              (:mod:`.contact_phases` in the plane without dashpots,
              else :mod:`.oracle`)
mindlin       a tangential stiffness on the contact radius (LAMMPS's     Hertzian,
              Mindlin variants), no cap, undamped normal force: Eq. 18   undamped: yes;
              with the Omega of :mod:`.mindlin`                          else Omega(v_n)
hertzian      a normal force on the contact radius (Hertzian), no cap:   no (Omega(v_n))
              Eq. 18 sphere by sphere with the Omega of each contact
              time (:mod:`.hertz`)
damped        Hookean with gamma_n or gamma_t, no cap: Eq. 18 with the   yes
              exact damped Omega and restitution (:mod:`.linear`)
linear        Hookean, no damping, no Coulomb cap: Eq. 18                yes
============  =========================================================  ===============

The first that applies is the choice. The model's sub-models are asked (its normal and
tangential laws' ``contact_radius``, its style's ``tangential_contact_radius``), never named.

States are rows of (v_n, v_t, r omega) or, in 3-D, (v_n, v_t, r omega, v_s, r omega_s,
r omega_n), as everywhere in spinbounce. The model is read through its fields only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import NoMatrix, SceneError
from . import hertz, linear, per_state

__all__ = ["Choice", "STATE_SECONDS", "which", "predict", "outcome", "matrix", "matrices", "omega_per_sphere", "frozen",
           "NoMatrix", "mindlin_theory"]


#: Seconds one state's theory takes on one core for the kinds that integrate each state on its own, the
#: slowest measured with room: on this project's 2-core machine, 11 states of ``spinbounce sweep``'s default
#: ranges each, both cores busy, the classic spring 75 ms a state uncapped and 375 to 590 ms capped (its
#: sawtooth's teeth, :mod:`.oracle_classic`), the capped Hertz-Mindlin contact 40 ms in the plane and 167 ms in
#: 3-D; a review measured 5 to 8 ms for a damped contact on the contact radius (contact_phases) and Mindlin's
#: with a tangential dashpot. With the oracle's forces and rates compiled (:mod:`.oracle_kernel`) the capped ones
#: took 3 to 4 times less, side by side on the same 11 states with both cores busy (the classic spring's 81 to
#: 162 ms a state then 28 to 45 ms; Hertz-Mindlin's in 3-D 32 to 42 ms then 10 to 11 ms), and their entries
#: are the slowest above over 3, with room. Keyed by kind and whether capped. A sweep's estimate counts them
#: (:mod:`spinbounce.sweeps.cost`): its chunk sizes, its cluster jobs' time and its refusal of long sweeps.
STATE_SECONDS = {("classic_wall", True): 0.25, ("classic_wall", False): 0.1, ("capped_nonlinear", True): 0.1,
                 ("capped_nonlinear", False): 0.2, ("damped_nonlinear", False): 0.01, ("mindlin", False): 0.01}


@dataclass(frozen=True)
class Choice:
    """Which theory applies: its ``kind``, a readable ``name``, and why no matrix if none."""

    kind: str
    name: str
    no_matrix_reason: str = ""

    @property
    def has_matrix(self) -> bool:
        return not self.no_matrix_reason


def which(model) -> Choice:
    """The theory that applies to collisions of ``model``."""
    if model.style.tangential_contact_radius:
        return Choice("classic_wall", "the classic wall as this LAMMPS build integrates it (tangential spring "
                                 "kt sqrt(r delta); exact.classic)",
                      "the classic wall's tangential spring grows with the overlap, so Omega depends on v_n "
                      "and on the length unit: give a state (v_n, v_t, omega) for its outcome")
    if model.mu is not None and model.tangential_law.classic_cap:
        return Choice("classic_wall", "the classic wall's spring as this LAMMPS build integrates it (kt sqrt(r delta), "
                                      "its cap reset by kt alone; exact.classic in the plane with Hooke's force and "
                                      "constant dashpots, else exact.oracle)",
                      f"with mu = {model.mu!r} the contact sticks and slides in turn: give a state (v_n, v_t, omega) "
                      "for its outcome")
    if (model.mu is not None and (model.tangential_law.contact_radius or damped_nonlinear(model))
            or damped_nonlinear(model) and model.limit_damping):  # the cap LAMMPS always has cuts friction
        return Choice("capped_nonlinear", "the Coulomb-capped contact on the contact radius (exact in each stick or "
                      "slip phase: exact.contact_phases, or exact.oracle with a dashpot or in 3-D)",
                      (f"with mu = {model.mu!r} the contact sticks and slides in turn" if model.mu is not None else
                       "limit_damping cuts the friction with the normal force at its turn (LAMMPS's cap, 1e12)")
                      + ", so the outcome is not linear in the initial state: give a state (v_n, v_t, omega) for its "
                      "outcome")
    if model.mu is not None:
        return Choice("coulomb", "Coulomb stick-slip solution (exact in each phase, switches to machine precision)",
                      f"with mu = {model.mu!r} the contact sticks and slides in turn, so the outcome is not "
                      "linear in the initial state: give a state (v_n, v_t, omega) for its outcome")
    if damped_nonlinear(model):
        name = "Eq. 18 with the Omega and restitution of the damped contact integrated in time (exact.contact_phases)"
        if _self_similar(model):
            return Choice("damped_nonlinear", name + ": self-similar, the same at every v_n")
        return Choice("damped_nonlinear", name + ", sphere by sphere",
                      "with normal damping on a contact whose force, spring or dashpot grows with the contact "
                      "radius, the restitution and Omega depend on v_n: give v_n for its matrix")
    if model.tangential_law.contact_radius:
        name = "Eq. 18 with the Omega of LAMMPS's Mindlin contact (exact.mindlin)"
        if _mindlin_speed_free(model):
            return Choice("mindlin", name + ": Hertzian and undamped, the same at every v_n")
        return Choice("mindlin", name + ", sphere by sphere",
                      f"with tangential = {model.tangential} and {_mindlin_speed_dependence(model)} Omega depends "
                      "on v_n: give v_n for its matrix")
    if model.normal_law.contact_radius:
        return Choice("hertzian", "Eq. 18 per sphere, Omega of the Hertzian contact time tau(v_n)",
                      "with normal = hertz the contact time, and with it Omega, depends on v_n: "
                      "give v_n for its matrix")
    if model.gamma_n > 0.0 or model.gamma_t > 0.0:
        return Choice("damped", "Eq. 18 with the exact damped Omega and restitution")
    return Choice("linear", "Eq. 18")


def damped_nonlinear(model) -> bool:
    """Normal damping on a contact whose force, spring or dashpot grows with the contact radius:
    its reference is the contact integrated in time (:mod:`.contact_phases`)."""
    normal = model.normal_law
    return model.gamma_n > 0.0 and (normal.contact_radius or model.tangential_law.contact_radius
                                    or model.damping_law.radius_power(normal) > 0.0)


def _self_similar(model) -> bool:
    """The Hertzian force, a spring on the contact radius and dashpots sqrt(m_eff F/delta) (tsuji,
    coeff_restitution): scaled to its own depth and time every contact is the same, so one
    restitution and one Omega hold at every v_n."""
    normal, tangential = model.normal_law, model.tangential_law
    return (normal.contact_radius and tangential.contact_radius
            and model.damping_law.radius_power(normal) == normal.power - 1.0)


def _capped_nonlinear(model, initial) -> np.ndarray:
    """Final states of a capped contact whose spring, force or dashpot grows with the contact radius:
    in the plane and without dashpots exact.contact_phases (its phases in sqrt(delta) near the ends,
    about 4x faster), else exact.oracle (3-D slides, dashpots, a tensile turn, limit_damping). The
    two meet to 1e-10 where both apply (tests/test_capped_nonlinear.py)."""
    if model.mu is None:  # limit_damping: the cap LAMMPS always has (1e12), cut to zero with the normal force
        model = model.replace(mu=model.tangential_law.cap(model)[0])
    if initial.shape[1] == 3 and model.gamma_n == 0.0 and model.gamma_t == 0.0:
        from . import contact_phases

        return contact_phases.bounce_many(contact_phases.Law.of(model), initial)[:, :3]
    return per_state.oracle(model, initial)


def _damped_matrices(model, v_n) -> np.ndarray:
    """(n, 3, 3): Eq. 18 per sphere with the restitution and Omega of its own damped contact, from
    one integration of a unit slip (the slip is linear in its initial rate)."""
    from . import contact_phases

    law = contact_phases.Law.of(model)
    out = []
    for v in np.atleast_1d(v_n):
        v_out, v_t, r_omega, _ = contact_phases.bounce(law, float(v), 1.0, 0.0)
        out.append(linear.scattering_matrix(model.alpha, v_t + r_omega - 1.0, v_out / abs(float(v))))
    return np.array(out)


def _mindlin_speed_free(model) -> bool:
    """A Mindlin contact's Omega is the same at every v_n: a Hertzian force and no dashpot
    (exact.mindlin: lam = (1 + alpha)/alpha k_t/kn, zeta = 0)."""
    return model.normal_law.contact_radius and model.gamma_t == 0.0


def _mindlin_speed_dependence(model) -> str:
    return "a tangential dashpot gamma_t" if model.normal_law.contact_radius else f"normal = {model.normal}"


def _mindlin_omega(model, v_n) -> np.ndarray:
    """Each sphere's Omega of a Mindlin contact (:mod:`.mindlin`, its scaled contact)."""
    from . import mindlin  # scipy's integrator: loaded when a Mindlin contact is asked

    v_n = np.atleast_1d(np.asarray(v_n, dtype=float))
    if _mindlin_speed_free(model):  # one contact answers every speed (its rounding aside)
        v_n = v_n[:1] * 0.0 - 1.0
    power, m, r, alpha = model.normal_law.power, model.m, model.r, model.alpha
    t0 = mindlin.time_unit(power, m, model.normal_law.wall_constant(model), v_n)
    k = model.tangential_law.stiffness(model)
    lam, zeta = mindlin.lam(k, alpha, m, r, v_n, t0), mindlin.zeta(model.gamma_t, m, alpha, t0)
    for name, value, scaled, limit in (("mindlin_kt", k, lam, mindlin.LAM_MAX), ("gamma_t", model.gamma_t, zeta,
                                                                                 mindlin.ZETA_MAX)):
        if np.max(scaled) > limit:
            raise SceneError(name, value, f"makes the slip {'turn' if name == 'mindlin_kt' else 'die out'} far "
                                          f"faster than the contact ({float(np.max(scaled)):.3g} > {limit:g} in its "
                                          "scaled time): beyond the reach of the Mindlin reference")
    return np.atleast_1d(mindlin.Omega(lam, zeta, model.tangential_law.variant, power))


def mindlin_theory(model) -> dict:
    """What the paper's theory becomes for a Mindlin contact that has one matrix (Hertzian,
    undamped): lam = (1 + alpha)/alpha k_t/kn sets Omega at every v_n; where the bounce conserves
    energy (Omega = -2, and Omega = 0) in k_t/kn and, with LAMMPS's NULL stiffness, in Poisson's
    ratio; and whether this model's bounce gains energy (|Omega + 1| > 1)."""
    from . import mindlin

    law, alpha = model.tangential_law, model.alpha
    k = law.stiffness(model)
    lam = mindlin.speed_free_lam(k, model.kn, alpha)
    ratio = float(_mindlin_omega(model, -1.0)[0]) + 1.0
    points = mindlin.unit_ratio_lams(mindlin.Variant(*law.variant))
    per_lam = alpha / (1.0 + alpha)  # k_t/kn = lam alpha/(1 + alpha)
    out = {"lam": lam, "k_t": k, "k_t_over_kn": k / model.kn, "Omega": ratio - 1.0,
           "Omega_depends_on": "alpha and k_t/kn only: the same at every v_n",
           "energy": "gained" if abs(ratio) > 1.0 + 1e-9 else "conserved" if abs(ratio) > 1.0 - 1e-9 else "lost",
           "energy_conserving_k_t_over_kn": {key: [x * per_lam for x in lams] for key, lams in points.items()},
           "energy_conserving_searched_to_k_t_over_kn": mindlin.LAM_SEARCHED * per_lam}
    if model.mindlin_kt is None:
        out["energy_conserving_poisson_ratio"] = {
            key: sorted(nu for nu in (mindlin.poisson_ratio_of(x * per_lam) for x in lams) if nu is not None)
            for key, lams in points.items()}
    return out


def _omega(model) -> float:
    """The exact damped Omega of a Hookean model without a cap (Eq. 18's when undamped)."""
    return linear.Omega_exact(model.m, model.kn, model.kt, model.alpha, model.gamma_t, model.gamma_n,
                              not model.limit_damping)


def _matrix3(model) -> np.ndarray:
    kind = which(model).kind
    if kind == "mindlin":  # undamped normal force: e = 1
        return linear.scattering_matrix(model.alpha, float(_mindlin_omega(model, -1.0)[0]), 1.0)
    if kind == "damped_nonlinear":  # self-similar: any speed's
        return _damped_matrices(model, -1.0)[0]
    e = linear.restitution(model.m, model.kn, model.gamma_n, not model.limit_damping)
    return linear.scattering_matrix(model.alpha, _omega(model), e)


def matrix(model, v_n: float | None = None, three_d: bool = False) -> np.ndarray:
    """The scattering matrix (3x3, or the 6x6 block form) that applies, or :class:`NoMatrix`.

    A Hertzian model has one matrix per v_n; a Coulomb-capped one has none.
    """
    choice = which(model)
    if choice.kind in ("coulomb", "capped_nonlinear"):
        raise NoMatrix(choice.no_matrix_reason)
    if not choice.has_matrix:  # one matrix per v_n
        if v_n is None:
            raise NoMatrix(choice.no_matrix_reason)
        m3 = matrices(model, v_n)[0]
    else:
        m3 = _matrix3(model)
    return linear.block_from(m3) if three_d else m3


def matrices(model, v_n) -> np.ndarray:
    """(n, 3, 3): each sphere's scattering matrix (one per v_n for a Hertzian model; the one
    matrix repeated otherwise); :class:`NoMatrix` with a Coulomb cap."""
    v_n = np.atleast_1d(np.asarray(v_n, dtype=float))
    choice = which(model)
    if choice.kind == "hertzian":
        return hertz.scattering_matrices(v_n, model.m, model.kn, model.r, model.kt, model.alpha,
                                         model.gamma_t)
    if choice.kind == "mindlin" and not choice.has_matrix:
        return np.stack([linear.scattering_matrix(model.alpha, float(w), 1.0) for w in _mindlin_omega(model, v_n)])
    if choice.kind == "damped_nonlinear":
        return np.broadcast_to(_damped_matrices(model, -1.0)[0], (v_n.size, 3, 3)) if choice.has_matrix \
            else _damped_matrices(model, v_n)
    return np.broadcast_to(matrix(model), (v_n.size, 3, 3))


def omega_per_sphere(model, v_n) -> np.ndarray:
    """Each sphere's Omega (Eq. 18's, exact damped or Hertzian); NaN where none exists (Coulomb)."""
    v_n = np.atleast_1d(np.asarray(v_n, dtype=float))
    kind = which(model).kind
    if kind == "classic_wall" and model.mu is None:  # the sticking contact's Omega, speed by speed
        from . import classic

        return np.array([classic.Omega_eff(v, model.kn, model.kt, model.alpha, model.r, model.m,
                                           model.gamma_n / model.m, model.gamma_t / model.m) for v in v_n])
    if kind in ("coulomb", "classic_wall", "capped_nonlinear"):
        return np.full(v_n.shape, np.nan)
    if kind == "hertzian":
        return np.atleast_1d(hertz.Omega(v_n, model.m, model.kn, model.r, model.kt, model.alpha, model.gamma_t))
    if kind == "mindlin":
        return np.broadcast_to(_mindlin_omega(model, v_n), v_n.shape).copy()
    if kind == "damped_nonlinear":  # one integration in all if self-similar, else one a sphere
        return linear.Omega_of_matrix(matrices(model, v_n), model.alpha)
    return np.full(v_n.shape, _omega(model))


def predict(model, initial, limitless: str = "raise") -> np.ndarray:
    """Final states for the initial states ``initial`` ((n, 3) or (n, 6)), from the theory that applies.
    A state whose LAMMPS outcome has no dt -> 0 limit (:class:`~spinbounce.errors.NoLimit`) is refused, or
    with ``limitless="nan"`` given as NaN, their number warned of (a scene's rows: status ``no_limit``)."""
    initial = np.atleast_2d(np.asarray(initial, dtype=float))
    width = initial.shape[1]
    kind = which(model).kind
    if kind == "classic_wall":
        return _classic(model, initial, limitless)
    if kind == "capped_nonlinear":
        return _capped_nonlinear(model, initial)
    if kind == "coulomb":  # the exact batched solver; the scipy oracle is its independent check
        from . import coulomb

        r = model.r
        columns = [initial[:, 0], initial[:, 1], initial[:, 2] / r]
        if width == 6:
            return coulomb.bounce_3d(model, *columns, initial[:, 3], initial[:, 4] / r, initial[:, 5] / r)
        return coulomb.bounce_2d(model, *columns)
    if kind in ("hertzian", "mindlin", "damped_nonlinear"):
        each = matrices(model, initial[:, 0])
        if width == 6:
            each = np.array([linear.block_from(m3) for m3 in each])
        return np.einsum("nij,nj->ni", each, initial)
    return initial @ matrix(model, three_d=width == 6).T


#: The columns of a state, in the plane and in 3-D (each spin times r).
PLANE_COLUMNS = ("v_n", "v_t", "r_omega")
SPACE_COLUMNS = PLANE_COLUMNS + ("v_s", "r_omega_s", "r_omega_n")


def outcome(model, v_n: float, v_t: float = 0.0, omega: float = 0.0, v_s: float = 0.0, omega_s: float = 0.0,
            omega_n: float = 0.0) -> tuple[dict, dict]:
    """One state's (initial, final) by column name, from the theory that applies: no run, so
    none of a run's limits (the default step's) apply."""
    r = model.r
    initial = [v_n, v_t, r * omega]
    names = PLANE_COLUMNS
    if v_s or omega_s or omega_n:
        initial += [v_s, r * omega_s, r * omega_n]
        names = SPACE_COLUMNS
    if not v_n < 0.0:
        raise NoMatrix(f"v_n = {v_n!r}: a collision needs v_n < 0 (towards the wall)")
    final = predict(model, np.array([initial]))[0]
    return dict(zip(names, map(float, initial), strict=True)), dict(zip(names, map(float, final), strict=True))


def _classic(model, initial, limitless: str) -> np.ndarray:
    """The classic spring's final states: exact.oracle with the classic cap (:mod:`.oracle_classic`, which refuses
    a state without a dt -> 0 limit), or exact.classic where the contact radius reaches one length unit, which
    only it follows (the paper's plane, Hooke's force, constant dashpots, a tensile normal force)."""
    from .oracle_classic import reaches_one

    fixed = model.style.tangential_contact_radius  # the classic wall's fixed assembly (its own coefficients)
    reach = (not model.normal_law.contact_radius and model.damping_law.radius_power(model.normal_law) == 0.0
             and not model.limit_damping)
    if initial.shape[1] == 3 and (fixed or reach) and (model.mu is None or reaches_one(model, initial[:, 0])):
        return per_state.classic(model, initial)
    if fixed:  # in 3-D: the same sub-models inside granular, the classic form's cap (mu none: its largest, 1e4)
        model = model.replace(wall="granular", tangential="linear_history_classic",
                              mu=model.style.coefficients(model)["mu"])
    return per_state.oracle(model, initial, limitless)


def frozen(model, t, v_t0: float, r_omega0: float, z: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(v_t(t), r omega(t)) of the frozen contact at height z: Eq. 10, or its exact damped form
    (the classic wall: with its spring kt sqrt(r (r - z))).

    Held at a fixed height the normal force is constant, so neither the normal law nor
    gamma_n nor limit_damping changes the slip; a Coulomb cap is then constant too, mu times that
    force, and the slip is a spring's stick-slip under it (:mod:`.frozen_capped`).
    """
    if model.mu is not None and (z is None or model.style.tangential_contact_radius):
        raise NoMatrix(f"mu = {model.mu!r}: the frozen contact's capped theory needs its height z, and is not "
                       "written for the classic form's own coefficients (its spring inside granular is: "
                       "--wall granular --tangential linear_history_classic)")
    if model.style.tangential_contact_radius:
        from . import classic

        return classic.frozen_velocities(t, v_t0, r_omega0, model.kt, model.alpha, model.r, model.r - z, model.m,
                                         model.gamma_t / model.m)
    overlap = None if z is None else model.r - z
    kt = model.tangential_law.frozen_stiffness(model, overlap)
    s = model.damping_law.radius_power(model.normal_law)  # a dashpot gamma_t a^s is constant when held
    gamma_t = model.gamma_t * math.sqrt(model.r * overlap) ** s if s and model.gamma_t else model.gamma_t
    if model.mu is not None:
        from . import frozen_capped

        law = model.normal_law
        cap = model.mu * law.wall_constant(model) * overlap**law.power  # mu F_n, constant at a fixed height
        reset = model.tangential_law.stiffness(model) if model.tangential_law.classic_cap else None  # kt alone
        return frozen_capped.frozen_velocities(t, v_t0, r_omega0, kt, model.m, model.alpha, gamma_t, cap, reset)
    return linear.frozen_velocities(t, v_t0, r_omega0, kt, model.m, model.alpha, gamma_t)
