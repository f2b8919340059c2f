"""A sweep's description: a scene file (TOML) or the same content from flags, validated.

::

    seed = 1
    chunk_size = 25000          # spheres per LAMMPS run (default: at most 25000, and at most
                                # what is estimated to run in 5 minutes on one core)

    [model]                     # any declared model parameter (spinbounce parameters):
    kt = [1.0, 2.857142857142857]   # one value, or a list: every combination is a group
    alpha = 0.4
    mu = ["none", 0.3]          # "none": no Coulomb cap (the paper's model)
    normal = "hooke"            # or "hertz"; limit_damping = true/false
    # kt_over_kn = [...] instead of kt; dt = ... (or tolerance = ... at the top level)
    # scene = "pair" (one per sweep): sphere a (m, r, alpha) hits a free sphere b at rest
    # instead of the wall; m_b, r_b, alpha_b = b's (one value or a list each; scenes.pair.kind)

    [states]                    # seeded uniform samples over [low, high] ...
    n = 100000
    v_n = [-1.5, -0.1]
    v_t = [-2.0, 2.0]
    r_omega = [-2.0, 2.0]       # or omega = [low, high]
    # instead of v_n and v_t: speed = [low, high] and angle_deg = [low, high], the incidence
    # angle from the wall's normal in degrees (v_n = -speed cos, v_t = speed sin);
    # 3-D: v_s, omega_s (or r_omega_s) and omega_n (or r_omega_n), all three

    # ... or a grid: [states] mode = "grid" with lists of values (all combinations)

Every model group (one point of the model grid) gets the same sampled states. Two
descriptions that mean the same sweep (a file, or the flags) have the same digest.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import tomllib
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from ..laws import own, settled
from ..model import parameters
from ..model.contact import ContactModel
from ..model.parameters import SceneError
from ..scenes.pair.kind import scene_of
from .physics import SweepError, check_physics, fail as _fail

__all__ = ["SweepError", "SweepSpec", "load_spec", "spec_from_dict", "MODEL_KEYS", "DEFAULT_CHUNK", "CHUNK_SECONDS", "MAX_CHUNKS"]

#: Model keys of a scene file: every sweepable declared parameter, kt_over_kn and dt.
MODEL_KEYS = (tuple(p.name for p in parameters.MODEL if p.sweepable) + tuple(p.name for p in parameters.SCENE)
              + ("kt_over_kn", "dt", "contact"))
STATE_KEYS = ("v_n", "v_t", "speed", "angle_deg", "omega", "r_omega",
              "v_s", "omega_s", "r_omega_s", "omega_n", "r_omega_n")
#: Optional out-of-plane states (3-D): each given as an angular velocity or times r.
EXTRA_KEYS = (("v_s",), ("omega_s", "r_omega_s"), ("omega_n", "r_omega_n"))
#: The two ways to give the velocity: components, or speed and incidence angle (degrees
#: from the wall's normal; positive angles give v_t > 0). Spin: omega or r_omega.
VELOCITY_KEYS = {"components": ("v_n", "v_t"), "polar": ("speed", "angle_deg")}
TOP_KEYS = ("name", "seed", "chunk_size", "tolerance", "model", "states")
DEFAULT_CHUNK = 25_000
#: A sweep that does not set chunk_size gets, per model group, at most DEFAULT_CHUNK collisions a
#: chunk and at most what the cost model (sweeps.cost) estimates to run in this many seconds on
#: one core: a chunk job then asks for a quarter of an hour (the estimate times its margin of 3)
#: whatever the model, under the SLURM profile's limit (workflows/profiles/slurm/limits.yaml).
CHUNK_SECONDS = 300.0
#: The most chunks one sweep may have: each is a LAMMPS run, a Parquet file and a workflow job;
#: more is a listing no engine schedules well (a 1e12-row sweep in default chunks: 4e7 of them).
MAX_CHUNKS = 100_000
#: The scene's keys (wall or pair, and sphere b's): a wall sweep's groups have none of them.
SCENE_KEYS = tuple(p.name for p in parameters.SCENE)
#: Sphere b's state: a collision's, not a sweep's (refused with the reason).
B_STATE_KEYS = tuple(p.name for p in parameters.STATE_B)
#: How "no value" is written for an optional parameter (mu) in a scene file or a flag.
NONE = "none"


def _number(key: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        _fail(key, value, "must be a number")
    if not math.isfinite(value):
        _fail(key, value, "must be finite")
    return float(value)


def _numbers(key: str, value) -> list[float]:
    values = value if isinstance(value, list) else [value]
    if not values:
        _fail(key, value, "is an empty list")
    return [_number(key, v) for v in values]


def _integer(key: str, value, low: int) -> int:
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    if isinstance(value, bool) or not isinstance(value, int):
        _fail(key, value, "must be a whole number")
    if value < low:
        _fail(key, value, f"must be >= {low}")
    return value


def _model_values(key: str, value) -> list:
    """One model key's values (a grid axis), each checked against its declaration."""
    values = value if isinstance(value, list) else [value]
    if not values:
        _fail(f"model.{key}", value, "is an empty list")
    if key == "scene" and len(values) > 1:
        _fail("model.scene", value, "one scene per sweep (run a wall sweep and a pair sweep apart)")
    declared = parameters.by_name("kt" if key == "kt_over_kn" else key)
    out = []
    for v in values:
        if declared.optional and isinstance(v, str) and v.strip().lower() == NONE:
            out.append(None)
            continue
        if declared.kind == "number" and (isinstance(v, bool) or not isinstance(v, (int, float))):
            _fail(f"model.{key}", v, "must be a number" + (f" or {NONE!r}" if declared.optional else ""))
        try:
            out.append(declared.check(v, where=f"model.{key}"))
        except SceneError as exc:
            raise SweepError(str(exc)) from None
    return out


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: model groups and the initial states each of them runs.

    ``states["axes"]`` maps each sampled state key (v_n or speed, v_t or angle_deg, omega
    or r_omega, then the 3-D keys) to its range (random) or values (grid), in column order.
    """

    raw: dict
    groups: tuple[dict, ...]
    seed: int
    chunk_size: int | None  # None: per group, from the cost (chunk_sizes)
    mode: str
    n: int
    states: dict
    tolerance: float | None = None

    def canonical(self) -> dict:
        """What the sweep means, whatever way it was written (file or flags)."""
        sizes = self.chunk_sizes
        chunking = self.chunk_size or (DEFAULT_CHUNK if set(sizes) == {DEFAULT_CHUNK} else list(sizes))
        return {"groups": [own(group) for group in self.groups], "seed": self.seed, "chunk_size": chunking, "mode": self.mode,
                "n": self.n, "states": self.states, "tolerance": self.tolerance}

    @property
    def digest(self) -> str:
        return hashlib.sha256(json.dumps(self.canonical(), sort_keys=True).encode()).hexdigest()[:16]

    @property
    def is_3d(self) -> bool:
        return len(self.states["axes"]) == 6

    @property
    def scene(self) -> str:
        """``wall``, or ``pair`` (sphere b's parameters are then in every group)."""
        return self.groups[0].get("scene", "wall")

    def model(self, group: int) -> tuple[ContactModel, float | None]:
        params = {k: v for k, v in self.groups[group].items() if k not in SCENE_KEYS}
        dt = params.pop("dt", None)
        return ContactModel(**params), dt

    def sphere_b(self, group: int):
        """A pair group's sphere b (:func:`spinbounce.scenes.pair.kind.sphere_b`)."""
        from ..scenes.pair.kind import sphere_b

        return sphere_b(*(self.groups[group][name] for name in parameters.PAIR_SPHERE))

    def initial_states(self, group: int, start: int = 0, stop: int | None = None) -> np.ndarray:
        """States (v_n, v_t, omega) of rows [start, stop), then (v_s, omega_s, omega_n) for a
        3-D sweep: the same for every group, set by the seed.

        Random states are seeded uniform columns of n draws each; a chunk's rows are drawn
        alone by jumping the generator ahead (one 64-bit draw per number), so a chunk costs
        the same whatever its place in a long sweep.
        """
        axes = self.states["axes"]
        stop = self.n if stop is None else stop
        if self.mode == "grid":
            arr = np.array(list(itertools.product(*axes.values())), dtype=float)[start:stop]
        else:
            columns = []
            for k, (lo, hi) in enumerate(axes.values()):
                bits = np.random.PCG64(self.seed)
                bits.advance(k * self.n + start)
                columns.append(np.random.Generator(bits).uniform(lo, hi, stop - start))
            arr = np.column_stack(columns)
        if "speed" in axes:
            arr[:, 0], arr[:, 1] = parameters.velocity_from_polar(arr[:, 0], arr[:, 1])
        for k, key in enumerate(axes):
            if key.startswith("r_"):  # spins given times r
                arr[:, k] = arr[:, k] / self.groups[group]["r"]
        return arr

    def normal_speeds(self) -> tuple[float, float]:
        """The fastest and the slowest |v_n| the states can reach (sampled ranges: their bounds)."""
        axes = self.states["axes"]
        if "v_n" in axes:
            vn = np.abs(np.asarray(axes["v_n"]))
            return float(vn.max()), float(vn.min())
        speed, angle = np.asarray(axes["speed"]), np.asarray(axes["angle_deg"])
        cos = np.cos(np.radians(angle))
        top = 1.0 if (self.mode == "random" and angle[0] <= 0.0 <= angle[1]) or 0.0 in angle else cos.max()
        return float(speed.max() * top), float(speed.min() * cos.min())

    @cached_property
    def chunk_sizes(self) -> tuple[int, ...]:
        """Collisions per chunk of each model group: the scene file's chunk_size, or else the
        smaller of DEFAULT_CHUNK and what runs in CHUNK_SECONDS by the cost estimate."""
        if self.chunk_size is not None:
            return (self.chunk_size,) * len(self.groups)
        from .cost import collisions_within

        return tuple(min(DEFAULT_CHUNK, collisions_within(self, g, CHUNK_SECONDS)) for g in range(len(self.groups)))

    def chunks(self) -> list[tuple[int, int, int, int]]:
        """(group, chunk, start, stop) for every chunk, in order."""
        return [(g, c, start, min(start + size, self.n)) for g, size in enumerate(self.chunk_sizes)
                for c, start in enumerate(range(0, self.n, size))]


def load_spec(path: Path) -> SweepSpec:
    path = Path(path)
    try:
        raw = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise SweepError(f"{path}: not valid TOML: {exc}") from None
    except (OSError, UnicodeDecodeError) as exc:
        why = {FileNotFoundError: "does not exist", IsADirectoryError: "is a folder, not a TOML file",
               UnicodeDecodeError: "is not text (a TOML file is expected)",
               PermissionError: "cannot be read (permission denied)"}.get(type(exc))
        raise SweepError(f"scene file {path} {why or f'cannot be read ({exc.strerror or exc})'}") from None
    return spec_from_dict(raw)


def _groups(model: dict) -> list[dict]:
    if not isinstance(model, dict):
        _fail("model", model, "must be a table")
    for key in model:
        if key not in MODEL_KEYS:
            if key in B_STATE_KEYS:  # declared, but one collision's: refused with the reason
                _fail(f"model.{key}", model[key], "a sweep samples sphere a's state with b at rest (the planar "
                                                  "matrix and the fit assume it); give b's state to one collision: "
                                                  "collide --scene pair")
            _fail(f"model.{key}", model[key], f"unknown key (allowed: {', '.join(MODEL_KEYS)})")
    if "kt" in model and "kt_over_kn" in model:
        _fail("model.kt_over_kn", model["kt_over_kn"], "give kt or kt_over_kn, not both")
    contacts = _contacts(model)
    # declaration order, not the file's: the same sweep numbers its groups the same way
    axes = {key: (_numbers(f"model.{key}", model[key]) if key == "dt" else _model_values(key, model[key]))
            for key in MODEL_KEYS if key in model and key != "contact"}
    defaults = {p.name: p.default for p in parameters.MODEL}
    try:
        scene = scene_of({k: v[0] for k, v in axes.items()})
    except SceneError as exc:
        raise SweepError(f"model.{exc}") from None
    if scene == "pair":  # b's defaults too; a wall sweep's groups stay as they were
        defaults.update({p.name: p.default for p in parameters.SCENE}, scene="pair")
    groups = []
    for read, combo in itertools.product(contacts, itertools.product(*axes.values())):
        params = {**defaults, **read, **dict(zip(axes, combo, strict=True))}
        if "kt_over_kn" in params:  # over the kn the normal law settles on (it may derive it)
            try:
                kn = settled(params)["kn"]
            except SceneError as exc:
                raise SweepError(f"model.{exc}") from None
            params["kt"] = params.pop("kt_over_kn") * kn
        if params in groups:  # a value listed twice (0.0 and -0.0 alike) would be one model run as two groups
            _fail("model", {**read, **{k: params[k] for k in axes}}, f"is group {groups.index(params)}'s model again")
        groups.append(params)
    return groups


def _contacts(model: dict) -> list[dict]:
    """Each ``contact`` line of the model table (one, or a list: each a group) read into model
    values (:func:`spinbounce.laws.words.parse_contact`); a key given beside them is refused."""
    from ..laws.words import parse_contact

    lines, read = model.get("contact", []), []
    if lines and "kt_over_kn" in model:  # the line gives kt
        _fail("model.kt_over_kn", model["kt_over_kn"], "give kt in model.contact's line, not beside it")
    for line in lines if isinstance(lines, list) else [lines]:
        try:
            values = parse_contact(line)
        except SceneError as exc:
            raise SweepError(f"model.{exc}") from None
        for name in sorted(set(values) & set(model)):  # the first, named
            _fail(f"model.{name}", model[name], "is given by model.contact too: give it once")
        read.append(values)
    return read or [{}]


def _check_top(raw: dict) -> tuple[int, int | None, float | None]:
    if not isinstance(raw, dict):
        _fail("scene", raw, "must be a table of keys")
    for key in raw:
        if key not in TOP_KEYS:
            _fail(key, raw[key], f"unknown key (allowed: {', '.join(TOP_KEYS)})")
    seed = _integer("seed", raw.get("seed", 0), 0)
    chunk_size = _integer("chunk_size", raw["chunk_size"], 1) if "chunk_size" in raw else None
    tolerance = raw.get("tolerance")
    if tolerance is not None:
        from ..extrapolation import check_tolerance

        tolerance = _number("tolerance", tolerance)
        try:
            check_tolerance(tolerance)
        except SceneError as exc:
            raise SweepError(str(exc)) from None
        if "dt" in raw.get("model", {}):
            _fail("tolerance", tolerance, "give model.dt or tolerance, not both: a tolerance chooses the steps")
    return seed, chunk_size, tolerance


def spec_from_dict(raw: dict) -> SweepSpec:
    """Validate a sweep description; every error names the key and its value."""
    seed, chunk_size, tolerance = _check_top(raw)
    groups = _groups(raw.get("model", {}))
    mode, n, states = _parse_states(raw.get("states"))
    spec = SweepSpec(raw=raw, groups=tuple(groups), seed=seed, chunk_size=chunk_size, tolerance=tolerance,
                     mode=mode, n=n, states=states)
    check_physics(spec)  # first: the chunk sizes come from the cost of valid scenes
    chunks = sum(math.ceil(n / size) for size in spec.chunk_sizes)
    if chunks > MAX_CHUNKS:
        _fail("states.n", n, f"makes {chunks:.3g} chunks of up to {max(spec.chunk_sizes)} collisions over {len(groups)} "
                             f"model group(s), more than the limit of {MAX_CHUNKS} for one sweep: give a larger "
                             "chunk_size, or split the sweep")
    return spec


def _state_keys(states: dict) -> list[str]:
    """The sampled keys in column order: the two velocity keys, the spin, then any 3-D keys."""
    if "omega" in states and "r_omega" in states:
        _fail("states.r_omega", states["r_omega"], "give omega or r_omega, not both")
    polar = any(k in states for k in VELOCITY_KEYS["polar"])
    if polar and any(k in states for k in VELOCITY_KEYS["components"]):
        _fail("states.speed", states.get("speed"), "give v_n and v_t, or speed and angle_deg, not both")
    keys = [*VELOCITY_KEYS["polar" if polar else "components"], "r_omega" if "r_omega" in states else "omega"]
    if any(k in states for group in EXTRA_KEYS for k in group):  # 3-D: every out-of-plane axis
        for group in EXTRA_KEYS:
            given = [k for k in group if k in states]
            if len(given) != 1:
                _fail(f"states.{group[0]}", states.get(group[0]),
                      f"a 3-D sweep needs exactly one of {' or '.join(group)}")
            keys.append(given[0])
    return keys


def _declared_state(key: str, given, values: list[float]) -> list[float]:
    """Each value (a range's bounds, a grid's points) within the declared range of its state."""
    declared = {p.name: p for p in parameters.STATE}.get(key)
    for value in values if declared else ():
        try:
            declared.check(value)
        except SceneError as exc:
            _fail(f"states.{key}", given, f"{value:g} is outside the declared range of {key}: {exc.limit}")
    return values


def _parse_states(states) -> tuple[str, int, dict]:
    if not isinstance(states, dict):
        _fail("states", states, "a [states] table is required")
    mode = states.get("mode", "random")
    if mode not in ("random", "grid"):
        _fail("states.mode", mode, 'must be "random" or "grid"')
    allowed = ("mode", "n", *STATE_KEYS) if mode == "random" else ("mode", *STATE_KEYS)
    for key in states:
        if key not in allowed:
            _fail(f"states.{key}", states[key], f"unknown key for mode {mode!r} (allowed: {', '.join(allowed)})")
    axes = {}
    for key in _state_keys(states):
        if key not in states:
            _fail(f"states.{key}", None, "is required")
        values = _numbers(f"states.{key}", states[key])
        if mode == "random":
            if len(values) != 2:
                _fail(f"states.{key}", states[key], "must be a range [low, high]")
            if not (values[0] < values[1] and math.isfinite(values[1] - values[0])):
                _fail(f"states.{key}", states[key], "must be a range of low below high, its width a float")
        axes[key] = _declared_state(key, states[key], values)
    if "speed" in axes:
        if min(axes["speed"]) <= 0.0:
            _fail("states.speed", states["speed"], "must be > 0")
        if max(abs(a) for a in axes["angle_deg"]) >= 90.0:
            _fail("states.angle_deg", states["angle_deg"], "must lie in (-90, 90): 90 degrees never meets the wall")
    if mode == "random":
        n = _integer("states.n", states.get("n", 0), 1)
    else:
        n = math.prod(len(v) for v in axes.values())
    return mode, n, {"axes": axes}
