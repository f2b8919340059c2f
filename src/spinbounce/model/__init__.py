"""What to simulate: the declared parameters, the contact model and the step.

``spinbounce.model`` knows nothing of files or LAMMPS: :mod:`.parameters` declares every
parameter once, :mod:`.contact` builds the contact model from it, :mod:`.timestep` holds the
one rule for the step. Importing the package imports none of them (a command's ``--help`` reads
:mod:`.parameters` only).
"""
