"""A gas of frictional spheres from Python: ``gas`` (:func:`spinbounce.scenes.gas.run.run_gas` on a model
made from the declared parameters) and its report."""

from __future__ import annotations

from pathlib import Path

from ..scenes.gas.parameters import DEFAULT
from .collisions import model as make_model

__all__ = ["gas"]


def gas(*, spheres: int = DEFAULT["spheres"], packing: float = DEFAULT["packing"], t_tr: float = DEFAULT["t_tr"],
        t_rot: float = DEFAULT["t_rot"], collisions: float = DEFAULT["collisions"], samples: int = DEFAULT["samples"],
        seed: int = DEFAULT["seed"], draws: int = DEFAULT["draws"], dt: float | None = None, ranks: int = 1,
        out: str | Path | None = None, force: bool = False, log=None, **model_parameters):
    """Run a gas of ``spheres`` spheres of the model (the declared parameters, any law of the registry, a cap
    included) at ``packing`` from T_tr(0) = ``t_tr`` and T_rot(0) = ``t_rot`` for ``collisions`` collisions
    per sphere (at the starting rate), in this process or (``ranks`` > 1) under ``mpiexec -np ranks``, beside
    the theories (:mod:`spinbounce.scenes.gas.predict`, from ``draws`` collisions at each temperature): a
    :class:`~spinbounce.scenes.gas.run.GasReport`. A run estimated beyond an hour needs ``force``; a named
    ``out`` holding an earlier run is refused unless ``force``."""
    from ..scenes.gas.run import run_gas

    return run_gas(make_model(**model_parameters), spheres=spheres, packing=packing, t_tr=t_tr, t_rot=t_rot,
                   collisions=collisions, samples=samples, seed=seed, draws=draws, dt=dt, ranks=ranks, out=out,
                   force=force, log=log)
