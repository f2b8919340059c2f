"""Files written into a folder the user names are replaced only if spinbounce wrote them, unchanged since."""

import json

import pytest

from spinbounce.errors import SceneError
from spinbounce.outputs import MANIFEST, replacing, write_output


def test_a_users_file_is_refused_and_kept(tmp_path):
    mine = tmp_path / "CLAIMS.md"
    mine.write_text("my own notes\n")
    with pytest.raises(SceneError, match=r"CLAIMS.md.*not written by spinbounce.*--force"):
        write_output(mine, "# claims\n")
    assert mine.read_text() == "my own notes\n"
    assert not (tmp_path / MANIFEST).exists()


def test_its_own_earlier_output_is_refreshed_and_an_edited_one_refused(tmp_path):
    path = tmp_path / "fig2.json"
    write_output(path, '{"run": 1}\n')
    write_output(path, '{"run": 2}\n')  # a rerun into its own folder
    assert path.read_text() == '{"run": 2}\n'
    path.write_text('{"run": 2, "edited by hand": true}\n')
    with pytest.raises(SceneError, match="changed since"):
        write_output(path, '{"run": 3}\n')
    assert "edited by hand" in path.read_text()


def test_force_replaces_any_file_and_records_it(tmp_path):
    path = tmp_path / "fig2.png"
    path.write_bytes(b"a user's image")
    with replacing():
        write_output(path, b"new image")
    assert path.read_bytes() == b"new image"
    assert set(json.loads((tmp_path / MANIFEST).read_text())["files"]) == {"fig2.png"}
    write_output(path, b"newer image")  # now spinbounce's own: no --force needed


def test_an_unreadable_record_protects_every_file(tmp_path):
    path = tmp_path / "fig2.json"
    write_output(path, "{}\n")
    (tmp_path / MANIFEST).write_text("{not json")
    with pytest.raises(SceneError):
        write_output(path, "[]\n")
    assert path.read_text() == "{}\n"


def test_a_folder_in_the_way_is_refused(tmp_path):
    (tmp_path / "fig2.pdf").mkdir()
    with replacing(False), pytest.raises(SceneError, match="is a folder"):
        write_output(tmp_path / "fig2.pdf", b"%PDF")


def test_reproduce_refuses_a_users_file_before_any_product_runs(tmp_path):
    from spinbounce.cli import main

    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "HERTZ.md").write_text("my Hertz notes\n")
    with pytest.raises(SystemExit) as exited:
        main(["reproduce", "--out", str(tmp_path / "out"), "--runs", str(tmp_path / "runs")])
    assert exited.value.code == 2
    assert [p.name for p in (tmp_path / "out").iterdir()] == ["HERTZ.md"] and not (tmp_path / "runs").exists()


def test_the_products_list_every_file_the_stored_folder_holds():
    """catalogue.Product.files is what reproduce checks before it runs: the stored figures/ is made by
    reproduce and accuracy, so the two lists must be the same files."""
    from pathlib import Path

    from spinbounce.catalogue import PRODUCTS
    from spinbounce.figures.core import figure_files

    stored = {p.name for p in (Path(__file__).parents[1] / "figures").iterdir() if not p.name.startswith(".")}
    made = {f for p in PRODUCTS for f in p.files} | {*figure_files("accuracy"), "ACCURACY.md"}
    assert made == stored


def test_figures_refuse_a_later_figures_file_before_the_first_runs(tmp_path):
    from spinbounce.cli import main

    out = tmp_path / "out"
    out.mkdir()
    (out / "fig7.png").write_text("my own picture\n")
    with pytest.raises(SystemExit) as exited:
        main(["figures", "--out", str(out)])
    assert exited.value.code == 2
    assert [p.name for p in out.iterdir()] == ["fig7.png"]  # fig2 to fig6 never ran: no runs/, no files
