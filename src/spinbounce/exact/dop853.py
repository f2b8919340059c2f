"""scipy's DOP853 step, compiled: the one integrator step the batched pair references take.

The tableau, the error norm and the accept and reject rule are scipy's own (``scipy.integrate.DOP853``),
compiled by numba so that each pair advances on its own step without numpy's per-call cost (numpy
spends about a microsecond per pair and step on a batch; compiled, a step of an 18-component state
takes a fraction of that). ``rates(y, p, n0, planar, mode, out)`` is the one right-hand side of the
pair equations (:mod:`.pair_batch`), ``mode`` the phase of a capped contact (0 where there is no cap).

Compiled once per machine and version of these modules (numba's cache, in a folder named by their
digest: :func:`.vec3.compiled`): the first batched pair reference after an install or an edit waits
about ten seconds for it.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .vec3 import compiled, kernel

__all__ = ["STAGES", "RTOL", "new_scratch", "make_step", "make_dense", "accept", "interpolate", "error_norm",
           "step_factor"]

#: scipy's DOP853 tableau (dop853_tableau.json, written from scipy.integrate.DOP853 and held equal to it by
#: tests/test_pair_batch.py: importing scipy.integrate costs a pair sweep half a second): 12 stages, its
#: weights, its 5th and 3rd order error estimates (13 entries: the last for the step's end), and its
#: step-size controller's constants.
_TABLEAU = json.loads((Path(__file__).parent / "dop853_tableau.json").read_text())
STAGES = _TABLEAU["n_stages"]
_A = np.ascontiguousarray(np.array(_TABLEAU["A"])[:STAGES, :STAGES])
_B = np.array(_TABLEAU["B"])
_E3, _E5 = np.array(_TABLEAU["E3"]), np.array(_TABLEAU["E5"])
#: Its dense output: three more stages and the interpolant's coefficients, of order 7 inside a step.
_A_EXTRA, _D = np.array(_TABLEAU["A_EXTRA"]), np.array(_TABLEAU["D"])
EXTENDED = STAGES + 1 + _A_EXTRA.shape[0]
INTERPOLATOR_POWER = 7
_EXPONENT = -1.0 / (_TABLEAU["error_estimator_order"] + 1)
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0
#: Relative tolerance of the pair references (as :data:`.pair_exact.RTOL`).
RTOL = 1e-12


@compiled
def new_scratch(size):
    """(stages, one state) of scratch for a step and its dense output of a state of ``size`` components."""
    return np.empty((EXTENDED, size)), np.empty(size)


def make_step(rates):
    """The compiled DOP853 step of the right-hand side ``rates``: ``step(y, f, h, p, n0, planar, mode,
    stages, scratch, y_new)`` writes the state at t + h into ``y_new``, the stages and the rates there
    (``stages[STAGES]``) into ``stages``."""

    @kernel
    def step(y, f, h, p, n0, planar, mode, stages, scratch, y_new):
        # the tableau's nonzero entries written out (no loop over the stages): a third of the time of loops
        size = y.size
        for i in range(size):
            stages[0, i] = f[i]
        for i in range(size):
            scratch[i] = y[i] + h * (_A[1, 0] * stages[0, i])
        rates(scratch, p, n0, planar, mode, stages[1])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[2, 0] * stages[0, i] + _A[2, 1] * stages[1, i])
        rates(scratch, p, n0, planar, mode, stages[2])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[3, 0] * stages[0, i] + _A[3, 2] * stages[2, i])
        rates(scratch, p, n0, planar, mode, stages[3])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[4, 0] * stages[0, i] + _A[4, 2] * stages[2, i] + _A[4, 3] * stages[3, i])
        rates(scratch, p, n0, planar, mode, stages[4])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[5, 0] * stages[0, i] + _A[5, 3] * stages[3, i] + _A[5, 4] * stages[4, i])
        rates(scratch, p, n0, planar, mode, stages[5])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[6, 0] * stages[0, i] + _A[6, 3] * stages[3, i] + _A[6, 4] * stages[4, i]
                                     + _A[6, 5] * stages[5, i])
        rates(scratch, p, n0, planar, mode, stages[6])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[7, 0] * stages[0, i] + _A[7, 3] * stages[3, i] + _A[7, 4] * stages[4, i]
                                     + _A[7, 5] * stages[5, i] + _A[7, 6] * stages[6, i])
        rates(scratch, p, n0, planar, mode, stages[7])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[8, 0] * stages[0, i] + _A[8, 3] * stages[3, i] + _A[8, 4] * stages[4, i]
                                     + _A[8, 5] * stages[5, i] + _A[8, 6] * stages[6, i] + _A[8, 7] * stages[7, i])
        rates(scratch, p, n0, planar, mode, stages[8])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[9, 0] * stages[0, i] + _A[9, 3] * stages[3, i] + _A[9, 4] * stages[4, i]
                                     + _A[9, 5] * stages[5, i] + _A[9, 6] * stages[6, i] + _A[9, 7] * stages[7, i]
                                     + _A[9, 8] * stages[8, i])
        rates(scratch, p, n0, planar, mode, stages[9])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[10, 0] * stages[0, i] + _A[10, 3] * stages[3, i] + _A[10, 4] * stages[4, i]
                                     + _A[10, 5] * stages[5, i] + _A[10, 6] * stages[6, i]
                                     + _A[10, 7] * stages[7, i] + _A[10, 8] * stages[8, i]
                                     + _A[10, 9] * stages[9, i])
        rates(scratch, p, n0, planar, mode, stages[10])
        for i in range(size):
            scratch[i] = y[i] + h * (_A[11, 0] * stages[0, i] + _A[11, 3] * stages[3, i] + _A[11, 4] * stages[4, i]
                                     + _A[11, 5] * stages[5, i] + _A[11, 6] * stages[6, i]
                                     + _A[11, 7] * stages[7, i] + _A[11, 8] * stages[8, i]
                                     + _A[11, 9] * stages[9, i] + _A[11, 10] * stages[10, i])
        rates(scratch, p, n0, planar, mode, stages[11])
        for i in range(size):
            y_new[i] = y[i] + h * (_B[0] * stages[0, i] + _B[5] * stages[5, i] + _B[6] * stages[6, i]
                                   + _B[7] * stages[7, i] + _B[8] * stages[8, i] + _B[9] * stages[9, i]
                                   + _B[10] * stages[10, i] + _B[11] * stages[11, i])
        rates(y_new, p, n0, planar, mode, stages[12])

    return step


def make_dense(rates):
    """The compiled dense output of a step of ``rates``: ``dense(y0, y1, h, p, n0, planar, mode, stages,
    scratch, F)`` adds the three extra stages to a step's ``stages`` and writes the interpolant's
    coefficients (INTERPOLATOR_POWER rows) into ``F`` for :func:`interpolate`."""

    @kernel
    def dense(y0, y1, h, p, n0, planar, mode, stages, scratch, F):
        size = y0.size
        for e in range(EXTENDED - STAGES - 1):
            s = STAGES + 1 + e
            for i in range(size):
                scratch[i] = y0[i]
            for j in range(s):
                c = h * _A_EXTRA[e, j]
                if c != 0.0:
                    for i in range(size):
                        scratch[i] += c * stages[j, i]
            rates(scratch, p, n0, planar, mode, stages[s])
        for i in range(size):
            dy = y1[i] - y0[i]
            F[0, i] = dy
            F[1, i] = h * stages[0, i] - dy
            F[2, i] = 2.0 * dy - h * (stages[STAGES, i] + stages[0, i])
        for r in range(_D.shape[0]):
            for i in range(size):
                F[3 + r, i] = 0.0
            for j in range(EXTENDED):
                c = h * _D[r, j]
                if c != 0.0:
                    for i in range(size):
                        F[3 + r, i] += c * stages[j, i]

    return dense


@kernel
def accept(y, f, y_new, stages):
    """An accepted step's end made the next one's start: ``y`` = ``y_new``, ``f`` = the rates there."""
    for i in range(y.size):
        y[i] = y_new[i]
        f[i] = stages[STAGES, i]


@kernel
def interpolate(F, y0, x, out):
    """The state a fraction ``x`` into a step from ``y0``, from its dense output ``F`` (scipy's
    Dop853DenseOutput)."""
    last, size = F.shape[0] - 1, y0.size
    for i in range(size):
        out[i] = 0.0
    for k in range(last, -1, -1):  # each component's Horner sum in scipy's order, all components at once
        factor = x if (last - k) % 2 == 0 else 1.0 - x
        for i in range(size):
            out[i] = (out[i] + F[k, i]) * factor
    for i in range(size):
        out[i] += y0[i]


@kernel
def error_norm(stages, h, y, y_new, atol, rtol):
    """scipy DOP853's error norm of one step (its stages, the states at both ends)."""
    size = y.size
    e5, e3 = 0.0, 0.0
    for i in range(size):
        inverse = 1.0 / (atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol)
        a5 = (_E5[0] * stages[0, i] + _E5[5] * stages[5, i] + _E5[6] * stages[6, i] + _E5[7] * stages[7, i]
              + _E5[8] * stages[8, i] + _E5[9] * stages[9, i] + _E5[10] * stages[10, i]
              + _E5[11] * stages[11, i])
        a3 = (_E3[0] * stages[0, i] + _E3[5] * stages[5, i] + _E3[6] * stages[6, i] + _E3[7] * stages[7, i]
              + _E3[8] * stages[8, i] + _E3[9] * stages[9, i] + _E3[10] * stages[10, i]
              + _E3[11] * stages[11, i])
        e5 += (a5 * inverse) ** 2
        e3 += (a3 * inverse) ** 2
    denom = (e5 + 0.01 * e3) * size
    return abs(h) * e5 / np.sqrt(denom) if denom > 0.0 else 0.0


@kernel
def step_factor(err, rejected):
    """scipy's factor for the next step after a step of error norm ``err`` (accepted if below 1; NaN is
    not, and shrinks the step as far as a rejection may), ``rejected``: the step before was."""
    if err < 1.0:
        factor = _MAX_FACTOR if err == 0.0 else min(_MAX_FACTOR, _SAFETY * err**_EXPONENT)
        return min(1.0, factor) if rejected else factor
    grow = _SAFETY * err**_EXPONENT
    return grow if grow > _MIN_FACTOR else _MIN_FACTOR
