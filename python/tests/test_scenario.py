"""Scenarios: load, text round trip, edits by field path and the check summary."""

import warnings

import pytest

import usar
from conftest import PAPER, ROOT, SHORT_S


def test_round_trip_through_ron_keeps_the_scenario(paper):
    text = paper.to_ron()
    again = usar.Scenario.from_ron(text, "copy.ron")
    assert again.check() == paper.check()
    # The text differs only in its first comment (the origin).
    assert again.to_ron().splitlines()[1:] == text.splitlines()[1:]
    assert paper.check()["hash"] == again.check()["hash"]


def test_from_ron_of_the_file_is_load(paper):
    same = usar.Scenario.from_ron(PAPER.read_text(), "paper.ron")
    assert same.check() == paper.check()


def test_check_is_the_summary_as_data(paper):
    c = paper.check()
    assert c["name"] == "paper"
    assert [k["name"] for k in c["kinds"]] == ["carrier", "supplier", "observer"]
    assert [k["count"] for k in c["kinds"]] == [6, 4, 2]
    assert c["kinds"][0]["quota"] == {"hard": 3, "easy": 3}
    assert [t["name"] for t in c["tasks"]] == ["hard", "easy"]
    # Ranks count from 0 (the hardest), as a GroupingRequest's tasks do.
    assert c["tasks"][0]["rank"] == 0
    # The mission's parameters, every one, as the scenario file names them.
    assert c["mission"]["duration_s"] == 600.0
    assert c["mission"]["pickup_s"] == paper.get("mission.pickup_s")
    assert len(c["robots"]) == 12
    assert c["steps"] > 0 and c["dt_s"] > 0
    assert len(c["hash"]) > 8


def test_set_returns_a_validated_copy(paper):
    short = paper.set("mission.duration_s", 30.0)
    assert short.check()["duration_s"] == pytest.approx(30.0, abs=1e-12)
    assert paper.check()["duration_s"] != short.check()["duration_s"]
    assert short.overrides == ["mission.duration_s=30.0"]
    eight = paper.update({"kinds[0].count": 8, "kinds[0].quota.hard": 5})
    assert eight.check()["kinds"][0]["count"] == 8
    assert len(eight.check()["robots"]) == 14
    # Variants and tuples as RON.
    moved = paper.set("tasks.hard.goal_m", (10.0, 50.0)).set("kinds[2].locomotion", "Ground")
    assert moved.check()["tasks"][0]["goal_m"] == (10.0, 50.0)
    assert moved.check()["kinds"][2]["locomotion"] == "ground"
    assert "tasks.hard.goal_m=(10.0, 50.0)" in moved.to_ron().splitlines()[0]


def test_set_and_run_agree_with_a_set_scenario(paper):
    via_set = usar.run(paper.set("mission.duration_s", 10.0), "dis")
    via_arg = usar.run(paper, "dis", duration_s=10.0)
    assert via_set.to_dict() == via_arg.to_dict()


def test_what_usar_check_warns_about_reaches_python(paper):
    """Issue 58: `usar check` warned "no kind has a quota for it; the task is never worked";
    Scenario.load, set and usar.run said nothing."""
    three = ROOT / "scenarios" / "three-tasks.ron"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s = usar.Scenario.load(str(three))
        paper.set("mission.duration_s", 30.0)
    idle = {
        "kinds[0].quota.hard": 4, "kinds[0].quota.easy": 0,
        "kinds[1].quota.hard": 2, "kinds[1].quota.easy": 0,
        "kinds[2].quota.hard": 2, "kinds[2].quota.easy": 0,
    }
    with pytest.warns(usar.ScenarioWarning, match=r"three-tasks.ron: tasks.easy: no kind has a "
                      r"quota for it; the task is never worked") as caught:
        edited = s.update(idle)
    assert len(caught) == 1 and caught[0].filename == __file__
    with pytest.warns(usar.ScenarioWarning, match="tasks.easy"):
        usar.Scenario.from_ron(edited.to_ron(), "mine.ron")
    assert issubclass(usar.ScenarioWarning, UserWarning)


def test_a_scenario_is_data_pickles_and_compares_by_value(paper, tmp_path):
    """Issue 58: Scenario could not be pickled or deep-copied, `==` was identity, there was no
    get(path), to_dict() or building from a dict, and a string value needed RON quotes while
    a number was accepted for a text field."""
    import copy
    import pickle

    again = usar.Scenario.load(str(PAPER))
    assert again == paper and hash(again) == hash(paper)
    edited = paper.set("mission.pickup_s", 2.0)
    assert edited != paper
    for twin in (pickle.loads(pickle.dumps(edited)), copy.deepcopy(edited), copy.copy(edited)):
        assert twin == edited and twin.overrides == edited.overrides
        assert twin.to_ron() == edited.to_ron()
    assert paper.get("mission.pickup_s") == paper.to_dict()["mission"]["pickup_s"]
    assert edited.get("mission.pickup_s") == 2.0
    assert paper.get("kinds[*].count") == [k["count"] for k in paper.to_dict()["kinds"]]
    with pytest.raises(ValueError, match=r"get mission.pickup_sec: .*pickup_s"):
        paper.get("mission.pickup_sec")
    built = usar.Scenario.from_dict(paper.to_dict())
    assert built == paper and built.origin == "<dict>"
    named = paper.set("name", "my paper")
    assert named.name == "my paper" and named.get("name") == "my paper"
    assert paper.set("description", 'with "quotes"').get("description") == 'with "quotes"'
    with pytest.raises(ValueError, match="expected a str"):
        paper.set("description", 5)
    # A unit variant is a str too; RON text still goes where the field is not text.
    aerial = paper.set("kinds[0].locomotion", "Aerial")
    assert aerial.get("kinds[0].locomotion") == "Aerial"
    assert paper.set("mission.search_time_budget_s", "Some(20.0)").get(
        "mission.search_time_budget_s") == 20.0
    # Results are the same for an equal scenario, whichever way it was built.
    a = usar.run(built, "dis", duration_s=SHORT_S)
    b = usar.run(pickle.loads(pickle.dumps(paper)), "dis", duration_s=SHORT_S)
    assert a == b


def test_notebooks_get_html_tables(paper):
    """Issue 58: no `_repr_html_` for a Scenario or a TrialResult."""
    edited = paper.set("name", "<mine>")
    html = edited._repr_html_()
    assert "&lt;mine&gt;" in html and "<mine>" not in html
    assert "<td>carrier</td>" in html and "set name=" in html
    result = usar.run(paper, "dis", duration_s=SHORT_S)
    table = result._repr_html_()
    assert "<td>hard</td>" in table and "usar.TrialResult" in table
    assert f"<td>{result.rescued_total}</td>" in table


def test_a_str_is_ron_where_the_field_takes_it_and_text_elsewhere(paper):
    """Review of issue 58's fix: an enum field holding a unit variant still takes a variant
    with data; an optional text field takes None and a plain path."""
    threshold = paper.set("mission.hp_effect", "Threshold(below_pct: 50.0, factor: 0.6)")
    assert threshold.get("mission.hp_effect") == {"Threshold": {"below_pct": 50.0, "factor": 0.6}}
    assert paper.get("report.targets") == "paper-targets.ron"
    assert paper.set("report.targets", None).get("report.targets") is None
    assert paper.set("report.targets", "other.ron").get("report.targets") == "other.ron"
    assert paper.set("name", "5").get("name") == "5"


def test_from_dict_takes_numpy_values_and_a_path(paper):
    import numpy as np

    data = paper.to_dict()
    data["mission"]["duration_s"] = np.float64(300.0)
    data["kinds"][0]["count"] = np.int64(data["kinds"][0]["count"])
    built = usar.Scenario.from_dict(data, path=str(PAPER))
    assert built.get("mission.duration_s") == 300.0
    with pytest.raises(TypeError, match="has no JSON form"):
        data["name"] = object()
        usar.Scenario.from_dict(data)
