"""usar.scenario_path and usar.scenario_names: the shipped scenarios are the checkout's
scenarios/ (the same files, byte for byte, whether from the wheel's usar/scenarios/ or, in a
dev install, through the python/usar/scenarios link), side files beside them."""

import pytest

import usar
from conftest import ROOT


def test_the_shipped_scenarios_are_the_checkouts():
    shipped = usar.scenario_path().parent
    ours = sorted(p.name for p in (ROOT / "scenarios").glob("*.ron"))
    assert sorted(p.name for p in shipped.glob("*.ron")) == ours
    for name in ours:
        assert (shipped / name).read_bytes() == (ROOT / "scenarios" / name).read_bytes(), name


def test_names_list_scenarios_and_paths_reach_side_files():
    names = usar.scenario_names()
    assert "paper.ron" in names and "paper-v1.ron" in names
    assert not [n for n in names if n.endswith(("-claims.ron", "-targets.ron", "-axes.ron"))]
    assert usar.scenario_path("paper") == usar.scenario_path("paper.ron")
    claims = usar.scenario_path("paper-claims.ron")
    assert claims.parent == usar.scenario_path().parent
    # paper.ron names its side files relative to its folder: they are there.
    assert usar.Scenario.load(str(usar.scenario_path())).get("report.claims") == claims.name


def test_unknown_and_bad_names_are_refused():
    with pytest.raises(ValueError, match=r"name: no shipped scenario 'nope'; shipped: .*paper\.ron"):
        usar.scenario_path("nope")
    with pytest.raises(ValueError, match="name: no shipped scenario"):
        usar.scenario_path("../scenarios/paper.ron")
    with pytest.raises(TypeError, match="name: expected a scenario file name"):
        usar.scenario_path(3)
