import pytest


@pytest.fixture
def run_dir(tmp_path):
    """A fresh folder for one LAMMPS run."""
    path = tmp_path / "run"
    path.mkdir()
    return path


@pytest.fixture(scope="session")
def reproduction(tmp_path_factory):
    """Everything `spinbounce reproduce` makes (catalogue.PRODUCTS: figures 2-7, the claims and the
    studies beyond the paper, about 4 minutes), made once per session by its own function: the figure,
    claim, stored-record and command tests all read this one result."""
    from spinbounce.cli.reproduce import reproduce

    root = tmp_path_factory.mktemp("reproduce")
    lines = []
    made = reproduce(root / "figures", root / "runs", log=lines.append)
    return made, lines


@pytest.fixture(scope="session")
def figures_made(reproduction):
    """(out folder, figure records by name, the one log line of each figure)."""
    from spinbounce.figures import FIGURES

    made, lines = reproduction
    figure_lines = [line for line in lines if line.split(":")[0] in FIGURES]
    return made.out, {r["figure"]: r for r in made.figures}, figure_lines


@pytest.fixture(scope="session")
def claims_made(reproduction):
    """The judged claims, in order."""
    return reproduction[0].claims
