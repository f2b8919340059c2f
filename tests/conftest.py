import pytest


@pytest.fixture
def run_dir(tmp_path):
    """A fresh folder for one LAMMPS run."""
    path = tmp_path / "run"
    path.mkdir()
    return path
