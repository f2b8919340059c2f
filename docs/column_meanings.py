"""What each column of a sweep's table means, for the generated outputs page.

The column list itself comes from a real run (docs/gen_reference.py); a column with no
meaning here stops the build, so a new column cannot reach the site undescribed.
"""

from __future__ import annotations

from spinbounce.model import parameters

#: The state's names in the table (the paper's symbols in brackets).
STATES = {
    "v_n": "v_n, normal velocity (> 0: away from the wall)",
    "v_t": "v_t, tangential velocity",
    "r_omega": "r omega, the spin in the paper's plane times r",
    "omega": "omega, the spin in the paper's plane (LAMMPS's -omega_y)",
    "v_s": "v_s, second tangential velocity (3-D)",
    "r_omega_s": "r omega_s (3-D, LAMMPS's r omega_x)",
    "omega_s": "omega_s (3-D, LAMMPS's omega_x)",
    "r_omega_n": "r omega_n, spin about the normal times r (3-D)",
    "omega_n": "omega_n (3-D, LAMMPS's omega_z)",
    "z": "height of the sphere's centre above the wall",
}
#: Suffix -> what the value is.
WHEN = {
    "initial": "requested initial",
    "lammps_initial": "initial, as LAMMPS holds it after setting it up",
    "lammps": "final, as LAMMPS ran it (after the contact)",
    "theory": "final, from the theory that applies",
    "error": "final LAMMPS minus theory",
    "estimate": "estimated error of the extrapolated final (sweeps with a tolerance)",
}
OTHER = {
    "group": "model group: one point of the model grid",
    "chunk": "chunk number within the group (one LAMMPS run)",
    "index": "the collision's index within its group (the same states in every group)",
    "energy_gain": "(E_final - E_initial)/E_initial, from LAMMPS (negative: energy lost)",
    "error": "largest |LAMMPS - theory| over the state columns, over the size of the initial state",
    "energy_excess": "kinetic energy LAMMPS ended with beyond the theory's, over E(0)",
    "status": "ok, inaccurate (error above the target), energy_gained, grazing (overlap too small to resolve) or "
              "no_limit (LAMMPS has no dt -> 0 limit: no reference, error NaN)",
    "dt": "the timestep the group ran at (a pair sweep: the batch's deck step; with a tolerance: the finest "
          "run's); a time-scaled row's own step is dt/time_scale; a pair row its chunk's runs left beyond the "
          "accuracy ran again finer, at the steps per contact or the dt its step_method names",
    "time_scale": "how many times slower the row ran in the deck (a time-scaled Hertzian batch: s_i = T*/T_i, "
                  "its contact stretched to the batch's longest; an aligned pair batch: the pair's own; its "
                  "own step was dt/time_scale (a pair row run again finer: finer, as its step_method says); 1 "
                  "otherwise)",
    "nsteps": "LAMMPS steps (with a tolerance or a pair sweep's two runs: all runs' together, a pair row run "
              "again finer counting its own runs too)",
    "tolerance": "the accuracy asked for (sweeps with a tolerance only)",
    "Omega_theory": "the theory's Omega (Eq. 18) for this sphere's v_n; NaN where none exists",
    "theory": "which theory the rows are compared with (spinbounce.exact.choose)",
    "scene_hash": "digest of the sweep's description: equal for a scene file and the same flags",
    "lammps_version": "the LAMMPS build that ran",
    "spinbounce_version": "the spinbounce version that ran",
}


def meaning(column: str) -> str:
    """The meaning of a sweep table's column, or KeyError if it has none."""
    if column in OTHER:
        return OTHER[column]
    declared = {p.column: p for p in parameters.MODEL}
    if column in declared:
        p = declared[column]
        return f"model parameter: {p.meaning}" + (f" ({p.none_value:g}: none)" if p.optional else "")
    for suffix in sorted(WHEN, key=len, reverse=True):
        state = column.removesuffix(f"_{suffix}")
        if state != column and state in STATES:
            return f"{STATES[state]}: {WHEN[suffix]}"
    raise KeyError(f"column {column!r} has no meaning in docs/column_meanings.py")
