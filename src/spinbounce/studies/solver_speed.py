"""The closed-form Coulomb solver (:mod:`spinbounce.exact.coulomb`) measured: its agreement
with the scipy oracle over random models and states, and its throughput on one core.

Both are measurements, not checks; tests/test_coulomb_fast.py holds the checks.
``python -m spinbounce.studies.solver_speed`` prints the throughput;
``python -m spinbounce.studies.solver_speed agreement [N]`` the agreement over N random
cases in the plane and N/10 each in 3-D and with the Hertzian force.
"""

from __future__ import annotations

import math
import sys
import warnings

import numpy as np

from ..laws import normal_law
from ..model.contact import ContactModel
from ..errors import PhysicsWarning
from ..exact import coulomb, oracle

__all__ = ["random_case", "random_cases", "random_cases_3d", "agreement",
           "KINDS", "print_agreement", "measure_throughput", "main"]

#: kt/kn values sampled: soft, the magic ratio of alpha = 2/5 (2/7), stiff, stiffer than kn.
KT_OVER_KN = (0.05, 2.0 / 7.0, 0.5, 1.0, 2.0)
ALPHAS = (0.1, 0.25, 0.4, 2.0 / 3.0, 1.0)


def random_case(rng: np.random.Generator,
                normal: str = "hooke") -> tuple[ContactModel, tuple[float, float, float]]:
    """One model and one state (v_n, v_t, omega) from the ranges the solver must cover.

    mu log-uniform on [1e-3, 1e3]; gamma_n zero or up to 0.99 of critical 2 sqrt(m kn);
    gamma_t zero or up to twice the tangential critical 2 sqrt(kt m alpha/(1 + alpha));
    limit_damping on or off; incidence from head-on to 89 degrees; r omega zero or up to
    30 |v| either way. ``normal = "hertz"`` draws the same numbers and drops gamma_n
    (the batched solver takes the Hertzian force undamped; with a dashpot it is the oracle's alone).
    """
    kn = 10.0
    alpha = float(rng.choice(ALPHAS))
    kt = kn * float(rng.choice(KT_OVER_KN))
    critical_t = 2.0 * math.sqrt(kt * alpha / (1.0 + alpha))
    gamma_n = 0.0 if rng.random() < 0.3 else 0.99 * rng.random() * 2.0 * math.sqrt(kn)
    gamma_t = 0.0 if rng.random() < 0.3 else 2.0 * rng.random() * critical_t
    with warnings.catch_warnings():  # alpha = 1 is a thin shell's inertia, on purpose
        warnings.simplefilter("ignore", PhysicsWarning)
        damped = not normal_law(normal).contact_radius  # the batched solver's Hertzian force is undamped
        model = ContactModel(kn=kn, kt=kt, alpha=alpha, gamma_t=gamma_t, normal=normal,
                             gamma_n=gamma_n if damped else 0.0,
                             mu=float(10.0 ** rng.uniform(-3.0, 3.0)),
                             limit_damping=bool(rng.random() < 0.5))
    speed = rng.uniform(0.1, 2.0)
    angle = math.radians(rng.uniform(0.0, 89.0))
    spin = (0.0 if rng.random() < 0.2
            else speed * 10.0 ** rng.uniform(-2.0, 1.5) * rng.choice([-1.0, 1.0]))
    return model, (-speed * math.cos(angle), speed * math.sin(angle), spin / model.r)


def random_cases(n: int, seed: int, normal: str = "hooke"):
    rng = np.random.default_rng(seed)
    return [random_case(rng, normal) for _ in range(n)]


def random_cases_3d(n: int, seed: int):
    """Hookean cases of :func:`random_case` turned out of the plane: the tangential velocity
    along an angle drawn uniformly, the spin's axis along another (so the slip is not
    parallel to either), and a spin about the normal up to |v| / r either way."""
    rng = np.random.default_rng(seed)
    cases = []
    for model, (v_n, v_t, omega) in random_cases(n, seed):
        speed = math.hypot(v_n, v_t)
        along, spin_axis = rng.uniform(0.0, 2.0 * math.pi, 2)
        state = (v_n, v_t * math.cos(along), omega * math.cos(spin_axis), v_t * math.sin(along),
                 omega * math.sin(spin_axis), rng.uniform(-1.0, 1.0) * speed / model.r)
        cases.append((model, state))
    return cases


#: kind -> (its cases, the oracle's tolerance there in the acceptance line)
KINDS = {"2-D": (random_cases, 1e-9), "3-D": (random_cases_3d, 1e-8),
         "Hertz": (lambda n, seed: random_cases(n, seed, "hertz"), 1e-8)}


def _deviation(model, state) -> float:
    """|solver - oracle| over the final state (2-D or 3-D, as the state), per unit impact speed |v|."""
    out_of_plane = dict(zip(("v_s", "omega_s", "omega_n"), state[3:]))
    slow = oracle.bounce(model, *state[:3], **out_of_plane).final[:len(state)]
    fast = (coulomb.bounce_2d if len(state) == 3 else coulomb.bounce_3d)(model, *state)[0]
    speed = math.hypot(state[0], state[1], *state[3:4])  # v_s too, in 3-D
    return float(np.abs(fast - slow).max() / speed)


def agreement(n: int, seed: int, kind: str = "2-D") -> dict:
    """The solver against the oracle over n random cases of a kind (``KINDS``): how many the
    oracle refused (its regimes chatter beyond its switch limit: left out of the worst), the
    largest and median |solver - oracle| per unit |v|, the worst case's index, and how many
    exceed the kind's tolerance."""
    make, tolerance = KINDS[kind]
    deviations = np.full(n, np.nan)
    for i, (model, state) in enumerate(make(n, seed)):
        try:
            deviations[i] = _deviation(model, state)
        except RuntimeError:
            continue
    worst = int(np.nanargmax(deviations))
    return {"kind": kind, "cases": n, "refused": int(np.isnan(deviations).sum()),
            "worst": float(deviations[worst]), "worst_case": worst, "median": float(np.nanmedian(deviations)),
            "tolerance": tolerance, "above": int((deviations > tolerance).sum())}


def measure_throughput(n: int = 200_000, seed: int = 0, repeats: int = 3, three_d: bool = False,
                       **model) -> float:
    """Collisions per second of :func:`coulomb.bounce_2d` (or ``bounce_3d``) on one batch
    of n spheres.

    Default model: the paper's (kn = 10, kt = 1, alpha = 0.4) with mu = 0.3; states over
    the acceptance sweep's ranges (|v_n| in [0.1, 1.5], v_t and r omega in [-2, 2]; in
    3-D v_s, r omega_s and r omega_n too).
    The best of ``repeats`` runs (the machine is shared).
    """
    from .speed import _timed

    rng = np.random.default_rng(seed)
    contact = ContactModel(**({"mu": 0.3} | model))
    states = [-rng.uniform(0.1, 1.5, n), rng.uniform(-2.0, 2.0, n), rng.uniform(-2.0, 2.0, n) / contact.r]
    if three_d:
        states += [rng.uniform(-2.0, 2.0, n), rng.uniform(-2.0, 2.0, n) / contact.r,
                   rng.uniform(-2.0, 2.0, n) / contact.r]
    bounce = coulomb.bounce_3d if three_d else coulomb.bounce_2d
    return n / min(_timed(lambda: bounce(contact, *states)) for _ in range(repeats))


#: Models the throughput is reported for: the paper's, damped, and Hertzian.
SPEED_MODELS = {
    "Hooke, mu = 0.3": {},
    "Hooke, mu = 0.05, gamma_n = 1, gamma_t = 0.5": {"mu": 0.05, "gamma_n": 1.0, "gamma_t": 0.5},
    "Hooke, mu = 3, kt = 8, gamma_n = 2, limit_damping": {"mu": 3.0, "kt": 8.0, "gamma_n": 2.0,
                                                          "limit_damping": True},
    "Hertz, mu = 0.3": {"normal": "hertz"},
    "3-D Hooke, mu = 0.3": {"three_d": True},
}


def print_agreement(n: int = 10_000, seed: int = 2026) -> None:
    """n random cases in the plane, n/10 in 3-D and n/10 Hertzian, as one table."""
    for kind in KINDS:
        row = agreement(n if kind == "2-D" else max(1, n // 10), seed, kind)
        print(f"{kind}: {row['cases']} cases ({row['refused']} refused), worst "
              f"{row['worst']:.2e} (case {row['worst_case']}), median {row['median']:.2e}, "
              f"{row['above']} above {row['tolerance']:g}")


def main(argv: list[str] | None = None) -> None:
    """Print the throughput, or with ``agreement [N]`` the agreement with the oracle."""
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["agreement"]:
        print_agreement(*(int(a) for a in argv[1:2]))
        return
    for label, model in SPEED_MODELS.items():
        print(f"{label}: {measure_throughput(**model):,.0f} collisions/s")


if __name__ == "__main__":
    main()
