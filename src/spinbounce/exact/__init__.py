"""Every reference the LAMMPS runs are checked against, and the one place that chooses.

* :mod:`.linear`: the paper's exact results (Eqs. 8-23) and their exact damped forms;
* :mod:`.hertz`: the Hertzian normal contact, whose Omega depends on v_n;
* :mod:`.coulomb`: the Coulomb-capped contact, exact in each stick or slip phase and batched;
* :mod:`.oracle`: the same contact integrated with scipy and stick-slip events, its
  independent check;
* :mod:`.classic`: LAMMPS's classic wall as this build implements it;
* :mod:`.pair`, :mod:`.pair_exact`: two spheres, planar and as LAMMPS integrates them;
  :mod:`.pair_capped` with a Coulomb cap (3-D, any law, both dashpots); for Hooke's law
  :mod:`.pair_batch` (uncapped) and :mod:`.pair_capped_batch` (capped) solve a whole batch
  in compiled code, on scipy's DOP853 compiled (:mod:`.dop853`, :mod:`.vec3`);
* :mod:`.rigid_body`: the rigid-body sliding impulse and Walton's law.

The exact references know nothing of LAMMPS, files or the API: they import numpy, scipy and
(the compiled batches) numba only. Importing ``spinbounce.exact`` gives :mod:`.linear`'s functions at the top, as the
paper's equations are the ones most code asks for; :mod:`.choose` decides which theory
applies. The Python API's call for them is the function ``spinbounce.theory(...)``.
"""

from .linear import *  # noqa: F401,F403  (the paper's equations, at the top)
from .linear import __all__  # noqa: F401
