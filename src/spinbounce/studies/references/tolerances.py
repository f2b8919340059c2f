"""How close a fresh run must come to a stored reference, column by column, and why."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["COLLISION_MU_TOLERANCES", "COLLISION_TOLERANCES", "FROZEN_TOLERANCES", "MEASUREMENTS", "Tolerance",
           "tolerance_record"]


@dataclass(frozen=True)
class Tolerance:
    """Largest allowed |fresh - stored| for every row of one column, and why that much.

    ``name`` labels the reason, shared by the columns it covers (manifest key).
    """

    name: str
    atol: float
    why: str


# LAMMPS runs serially here and is deterministic: two runs on one build agree bit for bit
# (measured: 0.0 in every column of every case; so do the data-file and library atom
# routes and the lmp executable). What can differ on another machine is the last bit of
# a libm call; velocity Verlet is neutrally stable for these linear springs, so such a
# difference is carried along, not amplified. As a stand-in, moving every initial
# velocity by 1 ulp moved no collision output by more than 7.1e-15 and no frozen output
# (6000 steps) by more than 1.1e-15. The LAMMPS tolerance, 1e-10, is four orders above
# that and still catches the smallest real changes tried: dt*(1 + 1e-9) moved every
# case by 9.6e-10 to 5.9e-8, kt*(1 + 1e-8) by 4.9e-10 to 2.8e-5 (the integration error
# itself is ~1e-5). The measurements are recorded in the manifest (MEASUREMENTS).
_EXACT = Tolerance(
    "case_input", 0.0,
    "an input of the case definition, written and read back exactly (repr): any difference means the "
    "case itself was changed")
_THEORY = Tolerance(
    "theory", 1e-12,
    "pure Python/numpy theory (sqrt, exp, sin, cos of O(10) arguments): another libm may differ in the "
    "last bit, ~1e-15; 1e-12 allows that, and any change of a formula or a parameter moves it by far more")
_ORACLE = Tolerance(
    "oracle", 1e-9,
    "the Coulomb oracle (finite mu): adaptive DOP853 at rtol 1e-12 with located events, whose steps "
    "depend on scipy's version and on rounding (two revisions of its event handling differed by 3.7e-12); "
    "1e-9 allows that, while mu*(1 + 1e-7) moves the outputs by 5e-8")
_LAMMPS_FINAL = Tolerance(
    "lammps_final_state", 1e-10,
    "LAMMPS final state after <= ~1050 steps: bit-identical on this build; a 1-ulp change of the inputs "
    "moves it by <= 7.1e-15, so rounding on another CPU stays far below 1e-10, while dt*(1 + 1e-9) moves "
    "it by >= 1.2e-9 and kt*(1 + 1e-8) by >= 4.9e-10")
_LAMMPS_SERIES = Tolerance(
    "lammps_series", 1e-10,
    "LAMMPS frozen series over ~6000 steps: bit-identical on this build; a rounding difference would "
    "drift in phase, linearly in time: a 1-ulp change of the inputs moves it by <= 1.1e-15 at the end, so "
    "1e-10 has a 10^5 margin, while dt*(1 + 1e-9) moves it by >= 9.6e-10 and kt*(1 + 1e-8) by >= 4.6e-9")
_HELD = Tolerance(
    "held", 1e-12,
    "held height and normal velocity of the frozen sphere: exactly constant in LAMMPS (normal force "
    "cancelled, v_n = 0); the pipeline itself allows 1e-12 in z")
_TIME = Tolerance(
    "time", 1e-12,
    "step * dt, with dt from arithmetic and sqrt only (correctly rounded): reproduced exactly; 1e-12 is "
    "far below one step")

#: Collision reference columns -> tolerance. ``omega_lammps`` carries the spin in the
#: paper's units; r*omega is r times it and adds nothing.
COLLISION_TOLERANCES: dict[str, Tolerance] = {
    "id": _EXACT,
    "v_n_initial": _EXACT,
    "v_t_initial": _EXACT,
    "omega_initial": _EXACT,
    "v_n_lammps": _LAMMPS_FINAL,
    "v_t_lammps": _LAMMPS_FINAL,
    "omega_lammps": _LAMMPS_FINAL,
    "z_lammps": _LAMMPS_FINAL,
    "v_n_theory": _THEORY,
    "v_t_theory": _THEORY,
    "omega_theory": _THEORY,
}

#: A collision with a finite mu: the same, with the oracle's tolerance on its theory columns.
COLLISION_MU_TOLERANCES = {k: (_ORACLE if v is _THEORY else v) for k, v in COLLISION_TOLERANCES.items()}

#: Frozen-contact reference columns -> tolerance.
FROZEN_TOLERANCES: dict[str, Tolerance] = {
    "t": _TIME,
    "v_t": _LAMMPS_SERIES,
    "omega": _LAMMPS_SERIES,
    "z": _HELD,
    "v_n": _HELD,
    "v_t_theory": _THEORY,
    "r_omega_theory": _THEORY,
}

#: The measurements behind the tolerances, recorded in the manifest next to them.
MEASUREMENTS = {
    "rerun": "two fresh runs of every case: largest difference 0.0 in every column; the data-file and "
             "library atom routes and the lmp executable reproduce the inline route exactly",
    "rounding_stand_in": "every initial velocity moved by 1 ulp: collision outputs move by <= 7.1e-15, "
                         "frozen outputs by <= 1.1e-15",
    "real_changes": "dt*(1 + 1e-9): collisions move by 1.2e-9 to 5.9e-8, frozen series by 9.6e-10 and "
                    "2.5e-8; dt*(1 + 1e-6): 9.6e-7 to 5.9e-5; kt*(1 + 1e-8): collisions by 4.9e-10 to "
                    "2.8e-5, frozen series by 4.6e-9 and 1.2e-7",
}


def tolerance_record() -> dict:
    """Per scene kind, column -> atol and the name of its reason; then the reasons (manifest entry)."""
    tables = {"collision": COLLISION_TOLERANCES, "collision_finite_mu": COLLISION_MU_TOLERANCES,
              "frozen": FROZEN_TOLERANCES}
    record = {kind: {column: {"atol": tol.atol, "reason": tol.name} for column, tol in table.items()}
              for kind, table in tables.items()}
    record["reasons"] = {tol.name: tol.why for table in tables.values() for tol in table.values()}
    return record
