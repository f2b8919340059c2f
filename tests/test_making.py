"""reproduce's products made side by side on worker processes: the same records and log as made in turn."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from spinbounce.catalogue import PRODUCTS, Product, compare_records
from spinbounce.making import _remove_half_written, make_products

ROOT = Path(__file__).resolve().parents[1]
#: Two of the quickest products (a few seconds each), listed in the catalogue's order.
QUICK = [p for p in PRODUCTS if p.name in ("tangential", "pair_validity")]


@pytest.mark.lammps
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


def _product(name: str) -> Product:
    return Product(name, f"spinbounce {name}", f"what {name} is", lambda out, runs, log: {}, (name,))


def test_a_failure_is_told_at_once_with_its_lines_after_those_before_it(tmp_path):
    """Products a, b, c: a has ended, c has failed, b still runs. a is told whole, then c's opening and the lines
    it logged before it failed, and its error raised, without waiting for b."""
    from concurrent.futures import Future

    from spinbounce.making import _told_in_order

    chosen = [_product(n) for n in "abc"]
    pending = {n: Future() for n in "abc"}
    pending["a"].set_result((["a's line"], {"a": {}}, 1.0, None))
    pending["c"].set_result((["c's line"], None, 2.0, ValueError("c broke")))
    told: list[str] = []
    with pytest.raises(ValueError, match="c broke"):
        _told_in_order(chosen, pending, tmp_path, told.append)
    assert told == [f"a: what a is -> {tmp_path}/", "a's line", "a: a (1 s)", f"c: what c is -> {tmp_path}/", "c's line"]
    assert not pending["b"].done()


def test_products_ended_out_of_order_are_told_in_the_catalogue_s(tmp_path):
    import threading
    from concurrent.futures import Future

    from spinbounce.making import _told_in_order

    chosen = [_product(n) for n in "ab"]
    pending = {n: Future() for n in "ab"}
    pending["b"].set_result((["b's line"], {"b": {}}, 1.0, None))
    threading.Timer(0.2, pending["a"].set_result, [(["a's line"], {"a": {}}, 3.0, None)]).start()
    told: list[str] = []
    assert set(_told_in_order(chosen, pending, tmp_path, told.append)) == {"a", "b"}
    assert [line for line in told if "line" in line] == ["a's line", "b's line"]


def test_a_worker_killed_ends_the_command_in_one_line():
    """A worker that dies (SIGKILL, the kernel's out-of-memory killer) breaks its pool: the command says so in one
    line and exits 1, as `kill -9` of a worker mid-reproduce did by hand (rc 1, nothing half-written left)."""
    from concurrent.futures.process import BrokenProcessPool

    from spinbounce.cli import _failure

    status, line = _failure(BrokenProcessPool("A process in the process pool was terminated abruptly"), "reproduce")
    assert status == 1 and line.count("\n") == 1 and line.startswith("spinbounce reproduce: error: a worker process")
