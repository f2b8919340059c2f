"""The repository's figures/ holds what the code makes, record by record.

The repository's figures/ holds what the code makes: every JSON record `spinbounce reproduce`
writes (catalogue.PRODUCTS) is made afresh once per session and compared with its stored copy.
"""

import json
from pathlib import Path

import pytest

from spinbounce.catalogue import IGNORED_KEYS, PRODUCTS, compare_records, record_names

STORED = Path(__file__).resolve().parents[1] / "figures"
#: LAMMPS is deterministic for one build; on another machine the last bits of a step may differ
#: and grow over a run's 10^3-10^5 steps to far below 1e-9 of the speed. 1e-6 leaves room for
#: that and is a hundred times below the 1e-4 accuracy every record is held to: a change of the
#: physics, the step or the theory shows, platform noise does not.
TOLERANCE = 1e-6


def test_comparison_sees_a_change_and_skips_provenance():
    stored = {"a": [1.0, 2.0], "b": "x", "created": "today", "nested": {"runtime_seconds": 3.0, "v": 0.5}}
    assert compare_records(stored, json.loads(json.dumps(stored)), TOLERANCE) == []
    moved = {**stored, "a": [1.0, 2.0 + 1e-5], "created": "tomorrow", "nested": {"runtime_seconds": 9.0, "v": 0.5}}
    assert compare_records(stored, moved, TOLERANCE) == ["/a[1]: 2.00001, stored 2.0"]
    assert compare_records(stored, {**stored, "b": "y"}, TOLERANCE) == ["/b: 'y', stored 'x'"]
    assert compare_records(stored, {**stored, "a": [1.0]}, TOLERANCE) == ["/a: 1 items, stored 2"]
    assert compare_records({"k": float("nan")}, {"k": float("nan")}, TOLERANCE) == []
    assert compare_records({"run": {"lammps_wall_seconds": 1.0}}, {"run": {"lammps_wall_seconds": 2.0}}, TOLERANCE) == []
    assert "created" in IGNORED_KEYS and "max_deviation_exact" not in IGNORED_KEYS


def test_every_stored_record_belongs_to_a_product_or_a_listed_command():
    made_elsewhere = {"accuracy"}  # spinbounce accuracy (catalogue.LISTED)
    stored = {path.stem for path in STORED.glob("[!.]*.json")}  # not the folder's record of outputs
    assert stored - made_elsewhere == set(record_names())
    assert len(record_names()) == len(set(record_names()))
    assert all(p.records for p in PRODUCTS)


@pytest.mark.lammps
@pytest.mark.parametrize("name", record_names())
def test_fresh_record_equals_the_stored_one(reproduction, name):
    made, _ = reproduction
    stored = json.loads((STORED / f"{name}.json").read_text())
    fresh = json.loads((made.out / f"{name}.json").read_text())
    differences = compare_records(stored, fresh, TOLERANCE)
    assert not differences, (f"figures/{name}.json is not what the code makes ({len(differences)} differences, "
                             f"first: {differences[:5]}); regenerate with `spinbounce reproduce --out figures`")
