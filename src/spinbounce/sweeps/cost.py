"""What one sweep chunk costs on one core, known before it runs: its cluster job's requests.

A chunk is one serial LAMMPS run of its spheres followed by the theory columns
(:func:`spinbounce.sweeps.run_chunk`). On one core it takes

    seconds = START_SECONDS + PROBE_SECONDS + n * (steps * SPHERE_STEP_SECONDS + theory)

(a pair chunk: two spheres a collision at the fine rule's steps, plus the pair references'
PAIR_BATCHED_SECONDS or PairContact.one_pair_seconds),

where ``steps`` is the run's LAMMPS steps per collision (the contact's exit time over the
model's step, as :attr:`Collision.nsteps` counts them) and ``theory`` a collision's theory
(CAPPED_THEORY_SECONDS for the batched stick-slip solver with a finite mu; hundredths to tenths
of a second where the theory integrates each state on its own, the classic spring's, the capped
contacts on the contact radius and the damped ones sphere by sphere:
:data:`spinbounce.exact.choose.STATE_SECONDS`), and it peaks at

    mb = BASE_MB + SCIPY_MB [finite mu] + n * KB_PER_SPHERE / 1024.

A scene whose step is probed has its steps per collision estimated a priori
(:func:`spinbounce.stepping.expected_steps`). A batch of Hertzian speeds without a dashpot
runs time-scaled to its slowest sphere's contact (:attr:`Collision.time_scales`): about as
many steps as that speed alone (284 for |v_n| from 0.1 to 0.8 at kn = 10, 555 for
Hertz-Mindlin on hertz/material, E = 1e4, nu = 0.3; estimated 426 and 833); with a dashpot
it keeps the fixed first-order rule (124,000 steps there).

A job asks for the estimate times a margin (TIME_MARGIN, MEM_MARGIN), which must stay
under the site's limits; the same numbers size chunks (:func:`largest_chunk_size`). A pair chunk's
bound is far above what it takes (its fine rule's steps, which its probe shortens ~20-fold): a local
sweep's estimate, and its refusal past MAX_CORE_HOURS, take :attr:`ChunkCost.likely_seconds` instead,
LAMMPS's start-up paid once a process (:func:`sweep_seconds`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..scenes.collision import Collision
from ..model.timestep import SPHERE_STEP_SECONDS
from ..stepping import expected_steps
from .ladder import tolerance_of

__all__ = ["CostError", "ChunkCost", "JobRequest", "chunk_cost", "job_request", "chunk_requests",
           "check_fits", "largest_chunk_size", "collisions_within"]

#: Measured on this project's 2-core Debian machine (Python 3.11, LAMMPS 2025.7.22), one
#: chunk per core, by `spinbounce sweep SCENE --chunk 0` under /usr/bin/time:
#: a 100-sphere chunk took 1.16 s and 158 MB (157 MB, 197 MB with mu = 0.3); 20,000
#: spheres took 1.85 s and 181 MB without mu, so 0.69 s for 20,000 x 252 sphere-steps.
START_SECONDS = 1.2
#: A further chunk in a process that has started (a local sweep's): its LAMMPS instance, deck and
#: table, about 0.09 s a 25,000-sphere chunk (a 200,000-collision frictionless sweep, profiled).
NEXT_CHUNK_SECONDS = 0.1
#: exact.coulomb's exact batched solver, per collision: 150,000 to 400,000 a second on one
#: core (studies/solver_speed), so 1e-5 s with room.
CAPPED_THEORY_SECONDS = 1e-5
#: A chunk whose step is probed (stepping.tune) runs two small LAMMPS runs first (measured
#: 0.2 s for a finite-mu chunk, `spinbounce bench`).
PROBE_SECONDS = 0.3
#: A batch whose references are solved together (PairContact.batched: Hooke's law, capped or not) spends about
#: 0.1 ms a pair on everything outside LAMMPS (a 20,000-pair sweep, `spinbounce bench`; a capped pair in 3-D up
#: to 1 ms, its reference alone): PAIR_BATCHED_SECONDS, with room. Pairs solved one at a time cost
#: :meth:`.PairContact.one_pair_seconds`.
PAIR_BATCHED_SECONDS = 2e-3
#: A pair chunk's probe (stepping.tune): up to five LAMMPS runs of at most
#: PROBE_SPHERES pairs, each at up to the fine rule's steps.
PAIR_PROBE_SECONDS = 5.0
#: What a batched pair sweep is expected to cost, for a local sweep's estimate and its refusal (a cluster job
#: asks for the bounds above): a pair probe settles on about PAIR_PROBED_STEPS a contact (`spinbounce bench`'s
#: 20,000-pair sweeps: 182 uncapped, 362 capped), the references and table about PAIR_BATCHED_EXPECTED a pair
#: (0.05 to 0.2 ms there), the probe about PAIR_PROBE_EXPECTED (two to five runs of PROBE_SPHERES pairs).
PAIR_PROBED_STEPS = 400
PAIR_BATCHED_EXPECTED = 1.5e-4
PAIR_PROBE_EXPECTED = 1.0
BASE_MB = 160
SCIPY_MB = 40  # scipy, loaded for the capped theory
KB_PER_SPHERE = 1.5  # 1.1 (no mu) to 1.4 (mu) kB measured between 100 and 20,000 spheres
#: A job asks for three times the estimate: with both cores busy a chunk ran 1.9 times
#: slower than on an idle machine, and cluster nodes may be slower than this one.
TIME_MARGIN = 3.0
#: Memory was measured to the megabyte; twice that covers other Python and library builds.
MEM_MARGIN = 2.0
#: A chunk is one serial LAMMPS run in one process: a second core would sit idle.
CPUS_PER_CHUNK = 1
#: Rungs a tolerance sweep's ladder is assumed to climb (extrapolation.py measured three
#: at a tolerance of 1e-6); a ladder that climbs further runs past the estimate.
LADDER_RUNGS = 4


class CostError(ValueError):
    """A chunk's job cannot fit the limits it must run under."""


@dataclass(frozen=True)
class ChunkCost:
    """The estimate for one chunk on one core: wall seconds and peak memory (MB)."""

    collisions: int
    steps: int  # LAMMPS steps per collision, summed over a tolerance ladder's runs
    seconds: float
    mem_mb: float
    cpus: int = CPUS_PER_CHUNK
    expected_seconds: float | None = None  # what it likely takes, where the bound above runs far past it

    @property
    def likely_seconds(self) -> float:
        """What the chunk is expected to take on one core (a local sweep's estimate)."""
        return self.seconds if self.expected_seconds is None else self.expected_seconds


@dataclass(frozen=True)
class JobRequest:
    """What a job asks the scheduler for: minutes of run time, MB of memory, cores."""

    runtime: int
    mem_mb: int
    cpus_per_task: int = CPUS_PER_CHUNK


def _pair_cost(spec, group: int, collisions: int) -> ChunkCost:
    """A pair chunk: two spheres a collision for at most the fine rule's steps (what a batch
    whose probe fails runs), and the pair references, which outweigh LAMMPS here; expected: the
    steps a probe settles on and the batched references' measured cost."""
    from ..model.timestep import mid_step_dt
    from ..scenes.pair.kind import pair_contact, pairs_from_states
    from ..scenes.pair.scene import PairBatch

    model, dt = spec.model(group)
    fast, _ = spec.normal_speeds()
    b = spec.sphere_b(group)
    contact = pair_contact(model, b)
    batch = PairBatch(pairs_from_states(model, b, [[-fast, 0.0, 0.0]]), contact, dt)
    one = contact.one_pair_seconds()
    mem_mb = BASE_MB + SCIPY_MB + 2 * collisions * KB_PER_SPHERE / 1024
    probe = PAIR_PROBE_SECONDS if dt is None else 0.0
    bound = _pair_seconds(collisions, batch.nsteps, one or PAIR_BATCHED_SECONDS, probe)
    if dt is not None:
        return ChunkCost(collisions, batch.nsteps, bound, mem_mb)
    probed = batch.at_step(mid_step_dt(float(batch.contact_times.max()), PAIR_PROBED_STEPS)).nsteps
    expected = _pair_seconds(collisions, min(probed, batch.nsteps), one or PAIR_BATCHED_EXPECTED, PAIR_PROBE_EXPECTED)
    return ChunkCost(collisions, batch.nsteps, bound, mem_mb, expected_seconds=expected)


def _pair_seconds(collisions: int, steps: int, theory: float, probe: float) -> float:
    return START_SECONDS + probe + collisions * (2 * steps * SPHERE_STEP_SECONDS + theory)


def _theory_seconds(model) -> float:
    """A collision's theory, by the kind that answers it (:func:`spinbounce.exact.choose.which`): the seconds a
    state of a kind without one matrix that integrates each state on its own
    (:data:`spinbounce.exact.choose.STATE_SECONDS`), the batched stick-slip solver's, or none (a matrix)."""
    from ..exact.choose import STATE_SECONDS, which

    choice = which(model)
    each = STATE_SECONDS.get((choice.kind, model.mu is not None))
    if each is not None and not choice.has_matrix:
        return each
    return CAPPED_THEORY_SECONDS if choice.kind == "coulomb" else 0.0


def chunk_cost(spec, group: int, collisions: int) -> ChunkCost:
    """The estimate for a chunk of ``collisions`` spheres of model group ``group`` of ``spec``."""
    if spec.scene == "pair":
        return _pair_cost(spec, group, collisions)
    # LAMMPS steps a collision runs for: its slowest sphere's (Hertz: time-scaled, the sweep's
    # T*) or the one contact's, at the step its probe will choose (stepping.expected_steps);
    # with a tolerance (a damped wall's default among them, .ladder), over the ladder's rungs
    fast, slow = spec.normal_speeds()
    model, dt = spec.model(group)
    scene = Collision(model, v_n=[-fast, -slow], v_t=0.0, omega=0.0, dt=dt)
    if tolerance_of(spec, group) is None:
        steps, probe = expected_steps(scene), (PROBE_SECONDS if scene.needs_probe() else 0.0)
    else:
        from ..extrapolation import START_STEPS, collision_rung_dt

        rungs = (START_STEPS * 2**k for k in range(LADDER_RUNGS))
        steps = sum(Collision(model, v_n=[-fast], dt=collision_rung_dt(model, n)).nsteps for n in rungs)
        probe = 0.0
    finite_mu = spec.groups[group].get("mu") is not None
    per_collision = steps * SPHERE_STEP_SECONDS + _theory_seconds(model)
    mem_mb = BASE_MB + (SCIPY_MB if finite_mu else 0) + collisions * KB_PER_SPHERE / 1024
    return ChunkCost(collisions, steps, START_SECONDS + probe + collisions * per_collision, mem_mb)


def collisions_within(spec, group: int, seconds: float) -> int:
    """The most collisions of ``group`` one chunk may hold and be estimated at ``seconds`` or
    less on one core (at least one: a single collision is the smallest chunk there is)."""
    one = chunk_cost(spec, group, 1).seconds
    per_collision = chunk_cost(spec, group, 2).seconds - one  # the estimate is linear in the chunk
    return max(1, math.floor((seconds - one) / per_collision) + 1)


def job_request(cost: ChunkCost) -> JobRequest:
    """The estimate with its margins, in the scheduler's units (whole minutes, whole MB)."""
    minutes = max(1, math.ceil(cost.seconds * TIME_MARGIN / 60.0))
    return JobRequest(minutes, math.ceil(cost.mem_mb * MEM_MARGIN), cost.cpus)


def chunk_requests(spec) -> list[JobRequest]:
    """Every chunk's request, in chunk order (the K of ``spinbounce sweep --chunk K``)."""
    return [job_request(chunk_cost(spec, group, stop - start)) for group, _, start, stop in spec.chunks()]


def _fits(request: JobRequest, limit: JobRequest) -> bool:
    return (request.runtime <= limit.runtime and request.mem_mb <= limit.mem_mb
            and request.cpus_per_task <= limit.cpus_per_task)


def largest_chunk_size(spec, group: int, limit: JobRequest) -> int:
    """The most collisions of ``group`` one chunk may hold and still fit ``limit`` (0: none fits)."""
    if not _fits(job_request(chunk_cost(spec, group, 1)), limit):
        return 0
    low, high = 1, max(1, spec.n)
    if _fits(job_request(chunk_cost(spec, group, high)), limit):
        return high
    while high - low > 1:  # the cost grows with the chunk: bisect for the last size that fits
        middle = (low + high) // 2
        low, high = (middle, high) if _fits(job_request(chunk_cost(spec, group, middle)), limit) else (low, middle)
    return low


def check_fits(spec, limit: JobRequest) -> list[JobRequest]:
    """Every chunk's request; :class:`CostError` naming the first chunk that exceeds ``limit``."""
    requests = chunk_requests(spec)
    for k, ((group, _, start, stop), request) in enumerate(zip(spec.chunks(), requests, strict=True)):
        if not _fits(request, limit):
            size = largest_chunk_size(spec, group, limit)
            advice = f"chunk_size <= {size} would fit" if size else "no chunk of this model fits"
            raise CostError(
                f"chunk {k} ({stop - start} collisions of group {group}) would ask for {request.runtime} min, "
                f"{request.mem_mb} MB and {request.cpus_per_task} core(s) (the estimate times "
                f"{TIME_MARGIN:g} in time, {MEM_MARGIN:g} in memory), over the limit of {limit.runtime} min, "
                f"{limit.mem_mb} MB and {limit.cpus_per_task} core(s): {advice}"
            )
    return requests


def sweep_seconds(spec, processes: int | None = None) -> float:
    """The whole sweep on one core, without listing its chunks: each chunk's bound (what a cluster job
    asks for), or, run in ``processes`` processes (a local sweep's workers), what each is expected to
    take, LAMMPS's start-up paid once a process and NEXT_CHUNK_SECONDS by each further chunk."""
    total, chunks = 0.0, 0
    for group, size in enumerate(spec.chunk_sizes):
        full, rest = divmod(spec.n, size)
        for count, collisions in ((full, size), (1 if rest else 0, rest)):
            if count:
                cost = chunk_cost(spec, group, collisions)
                total += count * (cost.seconds if processes is None else cost.likely_seconds)
                chunks += count
    if processes is None:
        return total
    return total - (chunks - min(processes, chunks)) * (START_SECONDS - NEXT_CHUNK_SECONDS)
