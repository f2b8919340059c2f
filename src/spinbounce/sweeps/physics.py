"""How a sweep refuses to start (one error, naming the key, its value and why), and its physics,
checked before anything runs: every model group's model, and its most demanding collision (the
fastest and slowest |v_n| the states reach) or, for a pair sweep, its fastest head-on impact,
built as the runs will build them."""

from __future__ import annotations

import warnings

from ..errors import SweepError
from ..model.parameters import SceneError
from ..scenes.collision import Collision

__all__ = ["SweepError", "check_physics", "fail"]


def fail(key: str, value, why: str):
    raise SweepError(f"{key} = {value!r}: {why}")


def check_physics(spec) -> None:
    """Build every group's model and its most demanding collision now, before any run (``spec``:
    the :class:`.spec.SweepSpec` being validated, which calls this; it is not imported here)."""
    if spec.scene == "pair":
        _check_pairs(spec)
        return
    fast, slow = spec.normal_speeds()
    for g in range(len(spec.groups)):
        try:
            with warnings.catch_warnings(action="ignore"):
                model, dt = spec.model(g)
        except SceneError as exc:
            ratio = exc.parameter == "kt" and "kt_over_kn" in spec.raw.get("model", {})
            raise SweepError(f"{'model.kt_over_kn' if ratio else f'model.{exc.parameter}'}: {exc}") from None
        if spec.tolerance is not None and (model.normal_law.contact_radius or model.tangential_law.contact_radius
                                           or model.normal_law.integrated(model)):
            fail("tolerance", spec.tolerance, "is refused for a contact whose force, spring or dashpot grows with "
                                              "the contact radius (its steps depend on each speed and its error is "
                                              "not smooth in dt): give model.dt, or the default step")
        try:
            Collision(model, v_n=[-fast, -slow], v_t=0.0, omega=0.0, dt=dt)
        except SceneError as exc:
            raise SweepError(f"{_key(spec, exc.parameter)}: {exc}") from None


def _key(spec, parameter: str) -> str:
    """The scene file's key a refusal of ``parameter`` names: the states' speed (v_n, or a polar scene's speed)
    where it refuses an impact (a wall's v_n, a pair's pairs[k].v_n), else the model's key."""
    if "v_n" in parameter:
        return "states.v_n" if "v_n" in spec.states["axes"] else "states.speed"
    return f"model.{parameter}"


def _check_pairs(spec) -> None:
    """A pair sweep: what the pair deck can run, its fastest impact's overlap and step, and its slowest's end."""
    from ..scenes.pair.kind import pair_contact, pairs_from_states
    from ..scenes.pair.scene import PairBatch

    if spec.tolerance is not None:
        fail("tolerance", spec.tolerance, "is for the wall only: a pair sweep takes model.dt or the default step")
    fast, slow = spec.normal_speeds()
    for g in range(len(spec.groups)):
        try:
            with warnings.catch_warnings(action="ignore"):
                model, dt = spec.model(g)
                b = spec.sphere_b(g)
                contact = pair_contact(model, b)
        except SceneError as exc:
            raise SweepError(f"model.{exc.parameter}: {exc}") from None
        try:  # head-on at the fastest |v_n|: the deepest overlap (the step's checks are per pair); at the slowest,
            # a contact its normal dashpot may hold closed
            for speed in (fast, slow):
                PairBatch(pairs_from_states(model, b, [[-speed, 0.0, 0.0]]), contact, dt)
        except SceneError as exc:
            raise SweepError(f"{_key(spec, exc.parameter)}: {exc}") from None
