"""The frozen contact's deck (``frozen.lmp.j2`` beside this module): one sphere held at z.

``scene`` is this folder's :class:`.scene.Frozen`, which calls this module
(never the other way round).
"""

from __future__ import annotations

from pathlib import Path

from ...lammps.decks import Deck, common_context, render_template


__all__ = ["render_frozen"]


def render_frozen(scene) -> Deck:
    model = scene.model
    ctx = common_context(model, zhi=4.0 * model.r, reach=abs(scene.v_t) * scene.dt)
    ctx.update(
        z=scene.z, vx=scene.v_t, wy=-scene.omega, dt=scene.dt, nsteps=scene.nsteps, every=scene.every
    )
    text = render_template(Path(__file__).parent, "frozen.lmp.j2", **ctx)
    return Deck(text=text, rigid=ctx["rigid"])
