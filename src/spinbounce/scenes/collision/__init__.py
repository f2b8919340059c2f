"""The wall collision (theory.md): spheres that start touching the wall and bounce off it."""

from .scene import HERTZ_STEPS_PER_HALF_PERIOD, STATE, STATE_3D, STATE_ARGS, Collision
from .time_scale import scaled_contact_time

__all__ = ["Collision", "STATE", "STATE_3D", "STATE_ARGS", "HERTZ_STEPS_PER_HALF_PERIOD",
           "scaled_contact_time"]
