"""Time-scaled batches: a wall batch of Hertzian speeds runs each sphere in its own time units.

A contact run in time units s times longer, its mass (and so its moment of inertia) times
s^2, its velocities and spins over s, the same radius and the same wall, follows the same
overlaps and forces at the same fraction of the contact, which lasts s times longer; its final
velocities and spins are the original's over s. This holds for the Hookean and Hertzian forces
(the same overlap at the same fraction), the tangential springs on the slip history (kt u, or
the Mindlin k_t a u, a = sqrt(r delta)) and the Coulomb cap mu F_n (forces are unchanged at the
same overlap); not for a dashpot, -gamma v, whose gamma would have to be s times larger, sphere
by sphere, which one ``fix wall/gran`` cannot give. So a batch whose contacts last T_i runs
sphere i at s_i = T*/T_i, T* the longest: every contact lasts T* in the deck, one step ends
them all mid-step (:mod:`spinbounce.model.timestep`), and the error is second order again
(:class:`.scene.Collision`: ``deck_contact_time``, ``time_scales``). The pair batches do the
same per pair (:func:`spinbounce.scenes.pair.scene.time_scaled`).
"""

from __future__ import annotations

import numpy as np

from ...model.contact import ContactModel

__all__ = ["scaled_contact_time", "dashpot"]


def scaled_contact_time(model: ContactModel, v_n) -> float | None:
    """T*: how long every contact of a batch of spheres at these v_n lasts in its deck, the longest
    contact time, sphere i at the time scale s_i = T*/T_i >= 1. None where the batch runs as it
    is: its contacts all last as long (one dt ends them all mid-step), or it has a dashpot (the
    scale would not be exact)."""
    if dashpot(model):
        return None
    times = model.contact_times(v_n)
    return float(np.max(times)) if np.ptp(times) > 0.0 else None


def dashpot(model: ContactModel) -> bool:
    """Whether the contact has a dashpot (the damping sub-model's gamma_n or gamma_t against the wall)."""
    return model.gamma_n > 0.0 or model.gamma_t > 0.0
