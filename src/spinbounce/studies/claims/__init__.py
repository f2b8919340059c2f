"""Every quantitative claim of the paper, measured with LAMMPS and set beside the exact theory.

* :mod:`.ledger`: the claim record, the verdict kinds and what every claim shares;
* :mod:`.collisions`, :mod:`.contact`, :mod:`.frozen`, :mod:`.damping`, :mod:`.energy`: the
  claims by topic, one function each; after the paper's, the LAMMPS implementation it used,
  in this build (:mod:`.collisions`) and :mod:`.pairs` (two spheres of equal alpha have the
  wall's Omega);
* :mod:`.write`: CLAIMS.md and claims.json.
"""

from __future__ import annotations

import warnings
from pathlib import Path

from . import collisions, contact, damping, energy, frozen, pairs
from .ledger import COLLISION_TOL, FROZEN_TOL, VERDICTS, Claim, Runs, verdict
from .write import counts, write_claims

__all__ = ["CLAIMS", "COLLISION_TOL", "FROZEN_TOL", "VERDICTS", "Claim", "counts", "evaluate_claims", "verdict",
           "write_claims"]

#: The claims, in the paper's order.
CLAIMS = (
    collisions.omega_default, collisions.omega_sign, contact.tau_independent, contact.hertz_tau,
    contact.hard_sphere, contact.tau_damped_longer, contact.tau_damped_vn, frozen.frozen_mean_rolling,
    frozen.frozen_slope, collisions.rolling_unchanged, collisions.harmonic_ratios, collisions.magic_ratio,
    collisions.rough_no_spin, collisions.rough_no_slide, collisions.reflection_angle, damping.eq22,
    frozen.decay_rate, damping.rapid_damping_rolls, damping.eq23_matrix, damping.rolling_vs_rough,
    energy.no_slip_no_loss, energy.friction_less_dissipation, collisions.classic_wall_is_eq1,
    pairs.equal_alpha,
)


def evaluate_claims(run_dir: Path, log=print) -> list[Claim]:
    """Run every claim's LAMMPS measurements under ``run_dir``; return the claims in order."""
    runs = Runs(run_dir)
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # e.g. stiff-ratio step warnings: every claim states its dt
        for fn in CLAIMS:
            claim = fn(runs)
            log(f"  {claim.key:<22} {claim.verdict}")
            out.append(claim)
    return out
