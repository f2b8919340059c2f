"""``--contact``: a contact law as a LAMMPS user writes it after ``fix wall/gran granular`` or in
``pair_coeff``, read into the model's own parameters.

For example ``hertz/material 1e4 0.3 0.3 damping tsuji tangential mindlin NULL 1.0 0.5`` is
normal = hertz/material with E = 1e4, ETA_N = 0.3 and nu = 0.3, damping = tsuji (ETA_N is its
restitution e_n), tangential = mindlin with LAMMPS's NULL stiffness, X_T = 1 and mu = 0.5 (mu =
1e12, what spinbounce writes for none, is read as none). A line that names no damping has LAMMPS's
default, viscoelastic (ETA_N then scales the dashpot with the contact radius), not the paper's velocity. Each
sub-model declares its coefficients in LAMMPS's order (``lammps_coefficients``) and the damping
says what ETA_N and X_T mean to it (``from_lammps``), so the words are read by the registries that
write decks. The text never reaches LAMMPS: it becomes validated numbers and registered keywords,
and anything else (rolling, twisting, heat, an unknown word) is refused by name.
"""

from __future__ import annotations

import math

from ..errors import SceneError
from .base import NO_CAP_MU, DampingLaw, lookup
from .damping import DAMPING
from .normal import NORMAL
from .tangential import TANGENTIAL

__all__ = ["parse_contact", "expand_contact"]

#: Blocks a LAMMPS granular line may hold that no sub-model here models.
UNMODELLED = {"rolling": "rolling resistance", "twisting": "twisting resistance", "heat": "heat conduction",
              "synchronized_verlet": "the synchronized Verlet option"}


def _fail(word, why: str):
    raise SceneError("contact", word, why)


def _number(word: str, name: str, optional: bool) -> float | None:
    """A coefficient's word as a finite number (NULL, for an optional one, as none)."""
    if word == "NULL" and optional:
        return None
    try:
        value = float(word)
    except ValueError:
        _fail(word, f"must be a number for {name}" + (" (or NULL)" if optional else ""))
    if not math.isfinite(value):
        _fail(word, f"must be finite for {name}")
    return value


def _coefficients(law, words: list[str], at: int, optional: tuple[str, ...] = ()) -> tuple[dict, int]:
    """The law's coefficients from ``words[at:]``, in its declared order; and where it ended."""
    names = law.lammps_coefficients
    given = words[at:at + len(names)]
    if len(given) < len(names):
        _fail(law.keyword, f"takes {len(names)} coefficients ({', '.join(names)}), given {len(given)}")
    return {name: _number(word, name, name in optional) for name, word in zip(names, given)}, at + len(names)


def parse_contact(text: str) -> dict:
    """The model's parameters of a LAMMPS granular contact line (``hooke 10 0 tangential ...``)."""
    if not isinstance(text, str) or not text.split():
        _fail(text, "must be the words after 'granular', e.g. 'hooke 10 0.5 tangential linear_history 1 0 0.3'")
    words = text.split()
    words = words[1:] if words[0] == "granular" else words
    normal = lookup(NORMAL, "normal", words[0]) if words else None
    if normal is None:
        _fail(text, "names no normal sub-model")
    found, at = _coefficients(normal, words, 1)
    values, damping, tangential = {"normal": normal.keyword}, None, None
    while at < len(words):
        word = words[at]
        if word == "damping" and damping is None and at + 1 < len(words):
            damping, at = lookup(DAMPING, "damping", words[at + 1]), at + 2
        elif word == "tangential" and tangential is None and at + 1 < len(words):
            tangential = lookup(TANGENTIAL, "tangential", words[at + 1])
            more, at = _coefficients(tangential, words, at + 2, optional=("mindlin_kt",))
            found.update(more)
        elif word == "limit_damping":
            values["limit_damping"], at = True, at + 1
        elif word in UNMODELLED:
            _fail(word, f"is not modelled here ({UNMODELLED[word]}): leave it out")
        else:
            _fail(word, "is not a keyword of a granular contact here (damping, tangential, limit_damping)")
    if tangential is None:
        _fail(text, "needs a tangential sub-model (LAMMPS refuses a granular model without one)")
    eta_n, x_t, mu = found.pop("eta_n"), found.pop("x_t"), found.pop("mu")
    if damping is None:  # LAMMPS's default, as it reads the line; with ETA_N = 0 it damps nothing: the paper's
        damping = DAMPING[DampingLaw.lammps_default_keyword if eta_n > 0.0 else DampingLaw.default_keyword]
    for name, value in (("ETA_N", eta_n), ("X_T", x_t)):
        if value < 0.0:
            _fail(value, f"{name} must be >= 0 (negative damping would create energy)")
    values.update(found, damping=damping.keyword, tangential=tangential.keyword,
                  mu=None if mu >= NO_CAP_MU else mu, **damping.from_lammps(eta_n, x_t))
    return values


def expand_contact(values: dict) -> dict:
    """``values`` with a ``contact`` line read into parameters; one given both ways is refused."""
    if values.get("contact") is None:
        return {k: v for k, v in values.items() if k != "contact"}
    if values.get("wall") not in (None, "granular"):
        raise SceneError("wall", values["wall"], "must be granular with contact: the line is granular's words")
    read = parse_contact(values["contact"])
    for name, value in values.items():
        if name in read and value is not None:
            raise SceneError(name, value, "is given by contact too: give it once")
    return {**{k: v for k, v in values.items() if k != "contact"}, **read}
