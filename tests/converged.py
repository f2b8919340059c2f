"""LAMMPS run to convergence for one wall collision, shared by the tests against converged LAMMPS."""

from __future__ import annotations

import numpy as np

from spinbounce.model.contact import ContactModel
from spinbounce.pipeline import run_scene
from spinbounce.scenes.collision import Collision


def converged(model: ContactModel, state, out, steps: int = 1000, halvings: int = 16) -> np.ndarray:
    """LAMMPS's final (v_n, v_t, r omega) with dt halved until two runs differ by less than 1e-7,
    the contact's end kept mid-step (dt = tau/(N + 1/2)): otherwise the end's place in its step
    jumps from run to run and two runs can agree by chance."""
    tau = float(model.contact_times(state[0])[0])
    previous = None
    for k in range(halvings):
        scene = Collision(model, v_n=state[0], v_t=state[1], omega=state[2] / model.r, dt=tau / (steps * 2**k + 0.5))
        final = run_scene(scene, out / f"run-{k}", record=False).table[
            ["v_n_lammps", "v_t_lammps", "r_omega_lammps"]].to_numpy()[0]
        if previous is not None and np.abs(final - previous).max() < 1e-7:
            return final
        previous = final
    raise AssertionError("LAMMPS did not converge to 1e-7")
