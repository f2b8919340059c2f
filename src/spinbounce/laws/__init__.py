"""Contact laws assembled from sub-models, as LAMMPS's GRANULAR package assembles them.

LAMMPS builds one granular model, for a wall and for a pair alike, from sub-models chosen by
keyword (``hooke``, ``hertz``, ``hertz/material``, ...), each declaring its coefficients and
capability flags (its ``contact_radius_flag``, for one). spinbounce does the same
(docs/explanation/contact-laws.md): each sub-model is registered under its LAMMPS keyword in
its kind's registry (:data:`.normal.NORMAL`: one module each), and declares

* its coefficients, once (:class:`~spinbounce.declaration.Parameter`: name, unit, default,
  range and why): they become the flags, scene-file keys, sweep columns and API keywords;
* its capability flags, which the rest of spinbounce asks instead of its name;
* its part of the deck (the words after ``granular``), of the exact reference (contact
  time, largest overlap) and of the step rule (its normal mode).

The damping (:data:`.damping.DAMPING`) and tangential (:data:`.tangential.TANGENTIAL`)
sub-models declare their coefficients and words the same way. The wall command's style
(:data:`.styles.STYLES`) is the assembly: ``granular`` takes the sub-models by keyword,
``classic`` (``hooke/history``) is a fixed assembly with flags of its own. No code outside
this package branches on a sub-model's or a style's keyword.
"""

from .damping import DAMPING, DampingLaw, damping_coefficients, damping_law, damping_parameter
from .damping import KIND as DAMPING_KIND
from .normal import KIND as NORMAL_KIND
from .normal import NORMAL, NormalLaw, normal_coefficients, normal_law, normal_parameter
from .styles import STYLES, Style, style, style_parameter
from .tangential import KIND as TANGENTIAL_KIND
from .tangential import TANGENTIAL, TangentialLaw, tangential_coefficients, tangential_law, tangential_parameter

__all__ = ["NORMAL", "NormalLaw", "normal_law", "normal_parameter", "normal_coefficients", "DAMPING", "DampingLaw",
           "damping_law", "damping_parameter", "damping_coefficients", "TANGENTIAL", "TangentialLaw",
           "tangential_law", "tangential_parameter", "tangential_coefficients", "STYLES", "Style", "style",
           "style_parameter", "settled", "own"]


#: The kinds of sub-model, in the order a model settles them: the normal first (the damping may
#: need its stiffness), the tangential last (it may need both).
KINDS = (NORMAL_KIND, DAMPING_KIND, TANGENTIAL_KIND)


def _chosen(values: dict):
    """The model's normal, damping and tangential sub-models, each with every coefficient of its kind."""
    return tuple((kind.law(values.get(kind.name, kind.default)), kind.coefficients()) for kind in KINDS)


def own(values: dict) -> dict:
    """``values`` without the coefficients of sub-models other than the chosen ones, and without
    a damping or tangential choice that is the default: what a model means (a sweep's digest, a
    fit's group, a run folder's name) does not change when a sub-model is added."""
    foreign = {p.name for law, every in _chosen(values) for p in every if p not in law.coefficients}
    default = {kind.name for kind in (DAMPING_KIND, TANGENTIAL_KIND) if values.get(kind.name) == kind.default}
    return {k: v for k, v in values.items() if k not in foreign and k not in default}


def settled(values: dict) -> dict:
    """A model's values with what its sub-models derive from their own coefficients (a stiffness
    made from a material, dashpots made from a restitution), after refusing another sub-model's
    coefficients: the normal sub-model first, since the damping may need its stiffness, and the
    tangential one last, since it may need both."""
    for law, every in _chosen(values):
        values = {**values, **law.settle(values, every)}
    return values
