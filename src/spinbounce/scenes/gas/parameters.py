"""The gas's own parameters, declared once (the contact law and the spheres' m, r and alpha are the
model's): light, so that the command line lists them without loading the scene."""

from __future__ import annotations

from ...declaration import Parameter

__all__ = ["GAS", "MIN_SPHERES", "DEFAULT", "SHOWN_GAS"]

#: Below this many spheres a temperature's own noise, sqrt(2/(3N)), passes 2.6%.
MIN_SPHERES = 1000
#: Above this the starting lattice and the data file outgrow one machine's memory.
MAX_SPHERES = 100_000_000

#: The gas's own parameters (the contact law and the spheres' m, r, alpha are the model's).
GAS: tuple[Parameter, ...] = (
    Parameter("spheres", "gas: number of spheres", "1", 20000, low=MIN_SPHERES, high=MAX_SPHERES,
              why_low=f"below {MIN_SPHERES} a temperature's noise sqrt(2/(3N)) passes 2.6%",
              why="the starting lattice and data file are built in this process's memory (5 GB at 1e8)",
              sweepable=False),
    Parameter("packing", "gas: packing fraction (sphere volume over box volume)", "1", 0.05, low=0.0, low_open=True,
              high=0.45, why="the starting lattice holds no denser gas without overlaps",
              why_low="a packing fraction is positive", sweepable=False),
    Parameter("t_tr", "gas: translational temperature at the start, m <v_x^2>", "energy", 1.0, low=0.0,
              low_open=True, why="a gas at rest has no collisions", sweepable=False),
    Parameter("t_rot", "gas: rotational temperature at the start, I <omega_x^2>", "energy", 0.0, low=0.0,
              why="a temperature is not negative", sweepable=False),
    Parameter("collisions", "gas: duration, in collisions per sphere at the starting Enskog rate", "1", 20.0,
              low=0.0, low_open=True, high=1e4, why="a run of more than 1e4 collisions per sphere is not a gas "
              "study this tool sizes", why_low="a run has a length", sweepable=False),
    Parameter("samples", "gas: times reported", "1", 100, low=2, high=100000,
              why="a series needs two times, and more than 1e5 rows is a dump", sweepable=False),
    Parameter("seed", "gas: random seed (placement, velocities, spins, the theory's collisions)", "1", 1, low=1,
              high=900000000, why="LAMMPS's seeds are positive 31-bit numbers", sweepable=False),
    Parameter("draws", "gas: collisions drawn at each temperature for the pair-level theories, and half as many "
              "three-sphere encounters (what a collision loses, and moves between translation and rotation, is then "
              "known to about 0.04 T_tr/sqrt(draws); the move to 0.3 T_tr/sqrt(draws) for a law without the planar "
              "rule, a cap)", "1", 40000, low=1000,
              high=1_000_000, why_low="fewer leave the theory's noise above 1e-3 a collision",
              why="each draw is a Python object in three LAMMPS pair runs: 1e6 takes about 10 minutes", sweepable=False),
)

#: Each gas parameter's declared default, by name (the scene, the run and the API take these).
DEFAULT = {p.name: p.default for p in GAS}


#: The gas the products show (the gas figure's cases; the claims' soft gas is its kt/kn = 0.1 one): 5,000 Hookean
#: spheres, 60 collisions per sphere at the starting rate: a cooling gas (kt/kn = 0.1 loses most of its energy)
#: meets about 22, its last quarter within about 1% of its steady ratio (it reaches 90% of it after about 10).
SHOWN_GAS = {"spheres": 5000, "packing": 0.05, "kn": 1e4, "collisions": 60.0, "samples": 80, "draws": 10000}
