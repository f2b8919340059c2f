"""reproduce's products made side by side on worker processes: the same records and log as made in turn."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from spinbounce.catalogue import PRODUCTS, compare_records
from spinbounce.making import _remove_half_written, make_products

pytestmark = pytest.mark.lammps

ROOT = Path(__file__).resolve().parents[1]
#: Two of the quickest products (a few seconds each), listed in the catalogue's order.
QUICK = [p for p in PRODUCTS if p.name in ("tangential", "pair_validity")]


def test_side_by_side_makes_the_stored_records_and_tells_each_product_whole_in_order(tmp_path):
    """Both records as the repository stores them (figures/: tests/test_stored_records.py's tolerance), and
    the log of each product together, opening to closing, in the catalogue's order whichever ended first."""
    lines: list[str] = []
    made = make_products(QUICK, tmp_path / "out", tmp_path / "runs", log=lines.append, workers=2)
    assert set(made) == {"tangential", "pair_validity"}
    for name in made:
        stored = json.loads((ROOT / "figures" / f"{name}.json").read_text())
        fresh = json.loads((tmp_path / "out" / f"{name}.json").read_text())
        assert compare_records(stored, fresh, 1e-6) == [], name
    told = [line.split(":")[0] for line in lines if re.match(r"^(tangential|pair_validity): ", line)]
    assert told == ["tangential", "tangential", "pair_validity", "pair_validity"], lines
    assert lines[0].startswith("tangential: ") and re.fullmatch(r"pair_validity: pair_validity \(\d+ s\)", lines[-1])


def test_a_stopped_worker_s_half_written_files_go_and_nothing_else(tmp_path):
    """``.NAME.PID.tmp`` of the stopped workers' ids only: another process's, and whole files, stay."""
    (tmp_path / "sub").mkdir()
    theirs = [tmp_path / ".fig2.png.4242.tmp", tmp_path / "sub" / ".claims.json.4243.tmp"]
    kept = [tmp_path / ".fig2.png.999.tmp", tmp_path / "fig2.png", tmp_path / ".spinbounce-outputs.json"]
    for path in theirs + kept:
        path.write_text("x")
    _remove_half_written(tmp_path, {"4242", "4243"})
    assert not any(p.exists() for p in theirs) and all(p.exists() for p in kept)
