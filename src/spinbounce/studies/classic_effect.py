"""What this build's classic wall does to a user's collisions, against the physics they meant.

The classic ``fix wall/gran hooke/history`` scales its tangential spring by the contact radius
sqrt(r delta) in this LAMMPS build (:mod:`spinbounce.exact.classic`); the granular form's
``linear_history`` is the paper's model. Over a ladder of impact speeds, both from
:func:`spinbounce.exact.choose.predict`: Omega = u'(out)/u'(in) - 1 of the sticking contact (no
cap, Eq. 18's definition), the rebound v_t and r omega, and the kinetic energy gained (Eq. 21;
> 0: the wall gave the sphere energy). Speeds are fractions of the tunnelling speed r sqrt(kn/m),
above which the Hookean overlap would exceed the radius (LAMMPS_FACTS section 6).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..model.contact import ContactModel
from ..exact import choose, linear

__all__ = ["TABLE_FRACTIONS", "CURVE_FRACTIONS", "FIGURE_KT_OVER_KN", "LAMMPS_FRACTIONS", "tunnelling_speed",
           "table_speeds", "compare", "omega_curves", "lammps_omegas", "fix_lines"]

#: The table's speeds, as fractions of the tunnelling speed (the user's own |v_n| is added).
TABLE_FRACTIONS = (0.01, 0.1, 0.3, 0.6, 0.9)
#: The figure's curves: from slow to just below tunnelling.
CURVE_FRACTIONS = np.linspace(0.03, 0.95, 59)
#: The figure's stiffness ratios beside the user's: soft, the paper's magic 2/7, stiff.
FIGURE_KT_OVER_KN = (0.1, 2.0 / 7.0, 0.5)
#: Where LAMMPS's classic wall is run for the figure's points.
LAMMPS_FRACTIONS = (0.15, 0.45, 0.9)


def tunnelling_speed(model: ContactModel) -> float:
    """r sqrt(kn/m): the undamped Hookean overlap |v_n| sqrt(m/kn) reaches r at this speed."""
    return model.r * math.sqrt(model.kn / model.m)


def table_speeds(model: ContactModel, v_n: float) -> np.ndarray:
    """The ladder of |v_n| for the table, with the user's own."""
    return np.unique(np.append(np.asarray(TABLE_FRACTIONS) * tunnelling_speed(model), abs(v_n)))


def _omega(model: ContactModel, speeds) -> np.ndarray:
    """Omega of the sticking contact (no cap) at each |v_n|: one unit of slip in, u'(out) - 1."""
    states = np.column_stack([-np.asarray(speeds, dtype=float), np.ones(len(speeds)), np.zeros(len(speeds))])
    final = choose.predict(model.replace(mu=None), states)
    return final[:, 1] + final[:, 2] - 1.0


def compare(model: ContactModel, speeds, v_t: float, omega: float) -> list[dict]:
    """Per |v_n|: Omega of each form, the rebound of the state (v_n, v_t, omega) through each
    form (with the model's own cap and damping), their difference and the energy gained."""
    speeds = np.asarray(speeds, dtype=float)
    initial = np.column_stack([-speeds, np.full(len(speeds), v_t), np.full(len(speeds), model.r * omega)])
    classic, meant = (model.replace(wall=wall) for wall in ("classic", "granular"))
    final_c, final_m = choose.predict(classic, initial), choose.predict(meant, initial)
    omega_c, omega_m = _omega(classic, speeds), _omega(meant, speeds)
    energy_in = np.array([linear.energy(s, model.m, model.alpha) for s in initial])
    gain_c, gain_m = ([linear.energy(s, model.m, model.alpha) for s in final] / energy_in - 1.0
                      for final in (final_c, final_m))
    return [{"v_n": float(speed), "omega_classic": float(omega_c[k]), "omega_meant": float(omega_m[k]),
             "final_classic": final_c[k].tolist(), "final_meant": final_m[k].tolist(),
             "d_vt": float(final_c[k, 1] - final_m[k, 1]), "d_r_omega": float(final_c[k, 2] - final_m[k, 2]),
             "energy_gain_classic": float(gain_c[k]), "energy_gain_meant": float(gain_m[k])}
            for k, speed in enumerate(speeds)]


def omega_curves(model: ContactModel) -> list[dict]:
    """Omega of the classic wall against |v_n| for the user's kt/kn and the figure's three, in
    order, with the paper's."""
    speeds = CURVE_FRACTIONS * tunnelling_speed(model)
    curves = []
    for ratio in sorted({*FIGURE_KT_OVER_KN, model.kt / model.kn}):
        at_ratio = model.replace(kt=ratio * model.kn)
        curves.append({"kt_over_kn": ratio, "v_n": speeds.tolist(),
                       "omega_classic": _omega(at_ratio.replace(wall="classic"), speeds).tolist(),
                       "omega_meant": float(_omega(at_ratio.replace(wall="granular"), speeds[:1])[0])})
    return curves


def lammps_omegas(model: ContactModel, ratio: float, folder: Path) -> dict:
    """LAMMPS's classic wall at :data:`LAMMPS_FRACTIONS` of the tunnelling speed, at its default
    step (probed to the default accuracy): Omega and each row's error against the classic theory."""
    from ..scenes.collision import Collision
    from ..pipeline import run_scene

    classic = model.replace(kt=ratio * model.kn, mu=None, wall="classic")
    speeds = np.asarray(LAMMPS_FRACTIONS) * tunnelling_speed(model)
    result = run_scene(Collision(classic, v_n=-speeds, v_t=1.0, omega=0.0), Path(folder), record=False)
    table = result.table
    return {"v_n": speeds.tolist(), "omega": (table["v_t_lammps"] + table["r_omega_lammps"] - 1.0).tolist(),
            "error": table["error"].tolist(), "dt": result.scene.dt}


def fix_lines(model: ContactModel) -> dict:
    """The ``fix wall/gran`` line of these numbers in each form: what the classic wall runs, and
    the granular line that gives the paper's model with the same numbers."""
    from ..lammps.decks import fix_line

    return {wall: fix_line(model.replace(wall=wall)) for wall in ("classic", "granular")}
