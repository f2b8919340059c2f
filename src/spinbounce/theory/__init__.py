"""Every reference the LAMMPS runs are checked against, and the one place that chooses.

* :mod:`.linear`: the paper's exact results (Eqs. 8-23) and their exact damped forms;
* :mod:`.hertz`: the Hertzian normal contact, whose Omega depends on v_n;
* :mod:`.oracle`: the Coulomb-capped contact, integrated with stick-slip events.

Importing ``spinbounce.theory`` gives :mod:`.linear`'s functions at the top, as the paper's
equations are the ones most code asks for.
"""

from .linear import *  # noqa: F401,F403  (the paper's equations, at the top)
from .linear import __all__  # noqa: F401
