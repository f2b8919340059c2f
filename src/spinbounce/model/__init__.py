"""What to simulate: the declared parameters, the contact model, the scenes and the step.

``spinbounce.model`` knows nothing of files or LAMMPS. :mod:`.parameters` declares every
parameter once; :mod:`.contact` builds the contact model from it; :mod:`.scenes` holds the
collision and frozen-contact scenes; :mod:`.timestep` the one rule for the step.
"""

from .contact import ContactModel, PhysicsWarning
from .parameters import MODEL, RUN, STATE, Parameter, SceneError
from .scenes import STATE_3D, Collision, Frozen

__all__ = ["ContactModel", "PhysicsWarning", "SceneError", "Parameter", "MODEL", "STATE", "RUN", "STATE_3D",
           "Collision", "Frozen"]
