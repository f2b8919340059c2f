"""What to simulate: the declared parameters, the contact model, the scenes and the step.

``spinbounce.model`` knows nothing of files or LAMMPS. :mod:`.parameters` declares every
parameter once; :mod:`.contact` builds the contact model from it; :mod:`.scenes` holds the
collision and frozen-contact scenes; :mod:`.timestep` the one rule for the step. Importing
the package imports none of them (a command's ``--help`` reads :mod:`.parameters` only).
"""
