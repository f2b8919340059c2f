"""The dump parser, on a dump captured from a real run (three spheres, alpha = 0.1, rigid route).

Values are compared with what the file says to the last printed digit (%.17g round-trips
a double exactly, so the tolerance is 0).
"""

from pathlib import Path

import numpy as np
import pytest

from spinbounce.scenes.frozen.table import paper_variables
from spinbounce.lammps.dumps import DumpError, read_dump

DATA = Path(__file__).parent / "data"
REAL = DATA / "collision_alpha0.1_three.dump"


def test_real_dump_frames_rows_and_values():
    table = read_dump(REAL)
    assert list(table.columns) == ["step", "id", "x", "y", "z", "vx", "vy", "vz", "omegax", "omegay", "omegaz"]
    assert sorted(table["step"].unique()) == [0, 1051]
    assert len(table) == 6
    first = table.iloc[0]
    np.testing.assert_array_equal(first[["id", "z", "vx", "vz"]].to_numpy(dtype=float), [1, 0.5, 1.0, -1.0])
    last = table.iloc[-1]
    assert last["id"] == 3
    np.testing.assert_allclose(
        last[["x", "z", "vx", "vz", "omegay"]].to_numpy(dtype=float),
        [1.8476209478392862, 0.50170433065329145, 1.7288725686030402, 1.2000013440845232, 6.4225486279393147],
        rtol=0, atol=0,
    )


def test_paper_variables_flip_omega_y():
    table = paper_variables(read_dump(REAL), r=0.5)
    start = table[table["step"] == 0].set_index("id")
    # sphere 2 was given omega = +3 (anticlockwise): LAMMPS stores omega_y = -3
    assert start.loc[2, "omega"] == pytest.approx(3.0, abs=1e-15)
    assert start.loc[2, "slip"] == pytest.approx(-0.5 + 1.5, abs=1e-15)


def test_rows_sorted_by_id_whatever_the_file_order(tmp_path):
    lines = REAL.read_text().splitlines()
    atoms = lines[9:12]
    shuffled = lines[:9] + [atoms[2], atoms[0], atoms[1]] + lines[12:]
    path = tmp_path / "shuffled.dump"
    path.write_text("\n".join(shuffled) + "\n")
    np.testing.assert_array_equal(read_dump(path).to_numpy(), read_dump(REAL).to_numpy())


@pytest.mark.parametrize(
    "mangle, message",
    [
        (lambda ls: ls[:-1], "missing atoms"),  # truncated last frame
        (lambda ls: ["garbage"] + ls, "expected 'ITEM: TIMESTEP'"),
        (lambda ls: ls[:8] + ["ITEM: ATOMS id x"] + ls[9:], "columns|do not have"),
        (lambda ls: [], "no frames"),
    ],
    ids=["truncated", "garbage", "columns", "empty"],
)
def test_malformed_dumps_raise(tmp_path, mangle, message):
    path = tmp_path / "bad.dump"
    path.write_text("\n".join(mangle(REAL.read_text().splitlines())) + "\n")
    with pytest.raises(DumpError, match=message):
        read_dump(path)


def test_nan_written_by_lammps_is_kept_for_the_checks(tmp_path):
    lines = REAL.read_text().splitlines()
    lines[-1] = "3 nan 0 nan nan 0 nan 0 nan 0"
    path = tmp_path / "nan.dump"
    path.write_text("\n".join(lines) + "\n")
    table = read_dump(path)
    assert np.isnan(table["vx"].iloc[-1])
