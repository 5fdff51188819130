"""Paths and values as safe as the CLI's: an output folder that is empty, a file or a device
is refused before anything is written (a FIFO given as an input: test_fifo_inputs.py); robot
ids out of range and numpy scalars get clear answers."""

import os

import numpy as np
import pytest

import usar
from conftest import PAPER


def _listing(folder):
    return sorted((p, os.path.getsize(os.path.join(folder, p))) for p in os.listdir(folder))


@pytest.mark.parametrize("out", ["", "file", "/dev/null"])
def test_an_output_folder_that_is_no_folder_is_refused_and_nothing_changes(paper, tmp_path, monkeypatch, out):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "report.md").write_text("mine")
    (tmp_path / "summary.csv").write_text("mine")
    (tmp_path / "file").write_text("mine")
    before = _listing(tmp_path)
    with pytest.raises(ValueError) as e:
        usar.sweep(paper, methods=["rne"], trials=1, duration_s=5, out=out, progress=False)
    text = str(e.value)
    assert "\n" not in text
    assert ("empty path" in text) if out == "" else ("not a folder" in text), text
    assert _listing(tmp_path) == before
    assert (tmp_path / "report.md").read_text() == "mine"


def test_a_folder_of_another_kind_is_refused(paper, tmp_path):
    folder = tmp_path / "mine"
    folder.mkdir()
    (folder / "usar-owner.json").write_text('{"tool":"usar","kind":"multiverse","format":1}\n')
    with pytest.raises(ValueError, match="holds a multiverse .* a sweep never writes"):
        usar.sweep(paper, methods=["rne"], trials=1, duration_s=5, out=str(folder), progress=False)
    assert sorted(os.listdir(folder)) == ["usar-owner.json"]


@pytest.mark.parametrize("bad", [-1, 2**70, 12])
def test_a_robot_id_out_of_range_is_named(paper, bad):
    def method(request):
        groups = usar.dis(request)
        groups[0] = [bad] + list(groups[0][1:])
        return groups

    with pytest.raises(usar.GroupingError, match=f"robot id {bad} is not in the team of this round"):
        usar.run(paper, method, duration_s=5)


@pytest.mark.parametrize(
    "value,expected",
    [(np.float32(1.5), 1.5), (np.float64(1.25), 1.25), (np.int64(2), 2.0)],
)
def test_numpy_scalars_set_fields(paper, value, expected):
    s = paper.set("mission.pickup_s", value)
    assert f"pickup_s: {expected}" in s.to_ron()
