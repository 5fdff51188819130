"""Every documented bad input raises the documented exception, with a one-line message."""

import pathlib
import warnings

import pytest

import usar
from conftest import PAPER


def one_line(e):
    text = str(e.value)
    assert "\n" not in text, text
    return text


def test_a_broken_file_is_a_value_error_at_its_line_and_field(tmp_path):
    bad = tmp_path / "bad.ron"
    bad.write_text(PAPER.read_text().replace("max_speed_m_per_s", "max_sped_m_per_s", 1))
    with pytest.raises(ValueError) as e:
        usar.Scenario.load(str(bad))
    text = one_line(e)
    assert text.startswith(f"{bad}:"), text
    assert "did you mean `max_speed_m_per_s`?" in text


def test_from_ron_names_its_origin_line_and_column():
    text = PAPER.read_text().replace("count: 6", "count: 5", 1)
    with pytest.raises(ValueError) as e:
        usar.Scenario.from_ron(text, "team.ron")
    msg = one_line(e)
    assert msg.startswith("team.ron:") and "kinds[0].quota" in msg
    line, col = msg.split(":")[1:3]
    assert line.isdigit() and col.isdigit()


def test_a_missing_file_is_a_value_error(tmp_path):
    with pytest.raises(ValueError) as e:
        usar.Scenario.load(str(tmp_path / "nowhere.ron"))
    assert "nowhere.ron" in one_line(e)


@pytest.mark.parametrize(
    "path,value,expected",
    [
        ("kinds[0].max_speed_m_per_s", -1.0, "set kinds[0].max_speed_m_per_s=-1.0: kinds[0].max_speed_m_per_s:"),
        ("kinds[9].count", 1, "set kinds[9].count=1:"),
        ("mission.no_such_field", 1, "set mission.no_such_field=1:"),
        ("mission.duration_s", float("nan"), "set mission.duration_s: expected a finite number"),
        ("mission.duration_s", {"a": 1}, "set mission.duration_s: no RON form"),
    ],
)
def test_a_bad_set_is_a_one_line_value_error(paper, path, value, expected):
    with pytest.raises(ValueError) as e:
        paper.set(path, value)
    assert one_line(e).startswith(expected), str(e.value)


def test_a_set_that_breaks_a_file_rule_points_into_the_file(paper):
    # As `usar check --set`: the rule's place in the file, and the override it holds with.
    with pytest.raises(ValueError) as e:
        paper.set("kinds[0].count", 7)
    # The quota's line in paper.ron, 1-based.
    with open(PAPER, encoding="utf-8") as f:
        line = 1 + next(i for i, text in enumerate(f) if "quota:" in text)
    assert one_line(e) == (
        f"{PAPER}:{line}:13: kinds[0].quota: hard 3 + easy 3 = 6 but count is 7 "
        "(with set kinds[0].count=7)"
    )


def test_bad_run_arguments(paper):
    with pytest.raises(ValueError, match="unknown grouping method|rne, dis, eng, hp_dis"):
        usar.run(paper, "nope", duration_s=5)
    with pytest.raises(ValueError, match="^duration_s: trial length: expected a number of sec"):
        usar.run(paper, duration_s=-1)
    with pytest.raises(ValueError, match="trial must be"):
        usar.run(paper, trial=-1)
    with pytest.raises(ValueError, match="give trial or seed"):
        usar.run(paper, trial=2, seed=5)
    with pytest.raises(TypeError, match="scenario"):
        usar.run(42)
    with pytest.raises(TypeError, match="method"):
        usar.run(paper, 3.5)


def test_bad_sweep_arguments(paper):
    # The library's checks, named by the keyword arguments (usar sweep names its flags).
    with pytest.raises(ValueError, match="^trials must be at least 1$"):
        usar.sweep(paper, trials=0)
    with pytest.raises(ValueError, match="^threads must be at least 1$"):
        usar.sweep(paper, threads=0, trials=1)
    with pytest.raises(ValueError, match="^methods needs at least one method$"):
        usar.sweep(paper, methods=[], trials=1)
    with pytest.raises(ValueError, match="^duration_s: trial length: expected a number of sec"):
        usar.sweep(paper, trials=1, duration_s=float("nan"))
    with pytest.raises(ValueError, match="^methods lists a method twice: RNE,DIS,RNE$"):
        usar.sweep(paper, methods=["rne", "dis", "RNE"], trials=1, duration_s=5)
    with pytest.raises(ValueError, match="unknown grouping method|rne, dis, eng, hp_dis"):
        usar.sweep(paper, methods=["rne", "bogus"], trials=1, duration_s=5)
    with pytest.raises(ValueError, match="built-in"):
        usar.sweep(paper, methods=[lambda r: r, _named("rne")], trials=1, duration_s=5)


def _named(name):
    def f(request):
        return usar.dis(request)

    f.__name__ = name
    return f


@pytest.mark.parametrize(
    "answer,rule",
    [
        (lambda r: [[x.id for x in r.robots]], "1 groups for 2 tasks"),
        (lambda r: [[0, 0], list(range(1, 12))], "assigned more than once"),
        (lambda r: [[99], list(range(12))], "not in the team"),
        (lambda r: [[], list(range(11))], "is not assigned"),
        # Issue 58: the kind is named, not only numbered.
        (lambda r: [list(range(6)), list(range(6, 12))], r"kind 0 \(carrier\) got .* quotas are"),
        (lambda r: "hard", "one list of robot ids per task"),
        (lambda r: [["a"], []], "robot ids must be integers"),
        (lambda r: {"medium": []}, "unknown task 'medium'"),
    ],
)
def test_a_bad_answer_is_a_grouping_error_naming_the_rule(paper, answer, rule):
    with pytest.raises(usar.GroupingError, match=rule):
        usar.run(paper, answer, duration_s=5)
    with pytest.raises(usar.GroupingError, match=rule):
        usar.sweep(paper, methods=[answer], trials=2, duration_s=5)


def test_a_methods_own_exception_reaches_the_caller(paper):
    def broken(request):
        raise KeyError("no such robot")

    with pytest.raises(KeyError, match="no such robot"):
        usar.run(paper, broken, duration_s=5)
    with pytest.raises(KeyError, match="no such robot"):
        usar.sweep(paper, methods=["dis", broken], trials=2, duration_s=5)


def test_trust_and_grouping_functions_check_their_input():
    # Paper Example 1 (weights [6, 4, 2]): 0.00373 nats.
    t = usar.trust([6, 4, 2], [86, 120, 30], [20, 30, 10])
    assert t == pytest.approx(0.003725, abs=1e-6)
    with pytest.raises(ValueError):
        usar.trust([6, 4], [86, 120, 30], [20, 30, 10])
    with pytest.raises(ValueError):
        usar.trust([6, 4, 2], [-1, 120, 30], [20, 30, 10])
    with pytest.raises(ValueError, match="1-D"):
        usar.trust([[6, 4, 2]], [86, 120, 30], [20, 30, 10])
    with pytest.raises(TypeError, match="GroupingRequest"):
        usar.dis({"robots": []})


DATA = PAPER.parents[1] / "crates" / "experiments" / "tests" / "data"
TARGETS = DATA / "multiverse-targets.ron"
TINY = dict(trials=2, duration_s=5.0, progress=False)


def test_an_empty_out_is_refused_naming_out_and_writes_nothing(paper, tmp_path, monkeypatch):
    # Issue 70: usar.calibrate(out='') wrote into the working folder (pathlib reads '' as
    # '.'), while usar.sweep and usar.multiverse refused it without naming `out`.
    monkeypatch.chdir(tmp_path)
    refused = r'^out: the output folder is an empty path; name a folder \("\." is the working folder\)$'
    with pytest.raises(ValueError, match=refused):
        usar.calibrate(paper, "mission.pickup_s=0.5..2", targets=TARGETS, out="",
                       methods="dis", max_evals=1, check_trials=0, **TINY)
    with pytest.raises(ValueError, match=refused):
        usar.sweep(paper, methods=["dis"], out="", **TINY)
    with pytest.raises(ValueError, match=refused):
        usar.grid(paper, ["mission.pickup_s=1,2"], methods=["dis"], out="", **TINY)
    with pytest.raises(ValueError, match=refused):
        usar.multiverse(paper, DATA / "multiverse-axes.ron", TARGETS, "mission.pickup_s=0.5..2",
                        "", methods=["dis"], progress=False)
    assert list(tmp_path.iterdir()) == []


def _named_request_method(name):
    def f(request):
        return usar.dis(request)

    f.__name__ = name
    return f


@pytest.mark.parametrize("name", ["rne", "HP-dis"])
def test_a_python_method_named_as_a_built_in_is_refused_by_run_and_sweep_alike(paper, tmp_path,
                                                                            name):
    # Issue 70: usar.run took a Python function named `rne` (its results then named like the
    # built-in's), usar.sweep refused it. Both refuse it now, with the same words.
    method = _named_request_method(name)
    expected = (f'a Python method may not be named "{name}", a built-in\'s name: rename it, '
                f'or give "{name}" for the built-in')
    with pytest.raises(ValueError) as run:
        usar.run(paper, method, duration_s=5)
    with pytest.raises(ValueError) as sweep:
        usar.sweep(paper, methods=[method], trials=1, duration_s=5)
    with pytest.raises(ValueError) as render:
        usar.render(paper, tmp_path / "x.svg", method=method, duration_s=5)
    assert one_line(run) == f"method: {expected}"
    assert one_line(sweep) == f"methods: {expected}"
    assert one_line(render) == f"method: {expected}"


def test_the_packages_own_built_in_functions_are_the_built_ins(paper):
    # usar.rne and the others, passed as methods, are the built-ins (not Python methods that
    # happen to bear their names, which are refused above).
    assert usar.run(paper, usar.rne, duration_s=20) == usar.run(paper, "rne", duration_s=20)
    got = usar.sweep(paper, methods=[usar.dis, "eng"], trials=1, duration_s=20)
    assert list(got["method"].unique()) == ["DIS", "ENG"]


@pytest.mark.parametrize("alpha", [float("nan"), float("inf")])
def test_a_claims_non_finite_alpha_names_the_claim_and_field(paper, tmp_path, alpha):
    # Issue 70: alpha=NaN gave "Out of range float values are not JSON compliant", no field.
    claim = {"id": "a", "sentence": "RNE rescues more", "subject": "rne", "metric":
             "rescued_total", "direction": "More", "alpha": alpha}
    with pytest.raises(ValueError) as e:
        usar.sweep(paper, methods=["rne", "dis"], out=tmp_path / "s", claims=[claim], **TINY)
    shown = "NaN" if alpha != alpha else "inf"
    assert one_line(e) == f"claims[0].alpha: expected a finite number, found {shown}"
    # The same in a claims file: the file, the claim and the field.
    (tmp_path / "claims.ron").write_text(
        'Claims(claims: [(id: "a", sentence: "RNE rescues more", subject: "rne", '
        'metric: "rescued_total", direction: More, alpha: NaN)])')
    with pytest.raises(ValueError) as e:
        usar.sweep(paper, methods=["rne", "dis"], out=tmp_path / "s", claims=tmp_path /
                   "claims.ron", **TINY)
    assert str(tmp_path / "claims.ron") in one_line(e) and "claims[0].alpha" in one_line(e)
    # And a scenario given as data names its field.
    data = paper.to_dict()
    data["mission"]["duration_s"] = alpha
    with pytest.raises(ValueError) as e:
        usar.Scenario.from_dict(data, "mine")
    assert one_line(e) == f"mine: mission.duration_s: expected a finite number, found {shown}"


@pytest.mark.parametrize("out,wrong", [("", "has no file name"), ("a/..", "has no file name"),
                                       (".", "is a folder, not a file"),
                                       ("/", "is a folder, not a file")])
def test_render_and_replay_name_out_when_it_names_no_file(paper, tmp_path, monkeypatch, out,
                                                          wrong):
    # Issue 70: render(out='') said " has no file name" (and replay ran its trial first).
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError) as e:
        usar.render(paper, out)
    assert one_line(e) == f"out: {out!r} {wrong}"
    with pytest.raises(ValueError) as e:
        usar.replay(paper, out, duration_s=5)
    assert one_line(e) == f"out: {out!r} {wrong}"


@pytest.mark.parametrize("seconds", [1e300, 1.8e19])
def test_calibrate_with_an_endless_max_time_runs_or_names_max_time(paper, tmp_path, seconds):
    # Issue 70: max_time_s=1e300 raised PanicException (a Duration out of range, and an
    # Instant overflowing at 1.8e19 s). It runs (no time limit) or names max_time_s.
    try:
        c = usar.calibrate(paper, "mission.pickup_s=0.5..2", targets=TARGETS, methods="dis",
                           max_evals=1, check_trials=0, max_time_s=seconds, **TINY)
    except ValueError as e:
        assert str(e).startswith("max_time_s"), str(e)
    else:
        assert c.evaluations == 1


def test_a_copy_of_paper_ron_elsewhere_warns_that_its_report_leaves_out_claims_and_targets(
    tmp_path,
):
    # The Rust library's notice (a tracing event on a worker thread) as a Python warning.
    copy = tmp_path / "paper.ron"
    copy.write_text(PAPER.read_text())
    out = tmp_path / "out"
    with pytest.warns(usar.UsarWarning) as caught:
        usar.sweep(str(copy), methods=["rne"], trials=1, duration_s=5.0, out=str(out))
    messages = [str(w.message) for w in caught if issubclass(w.category, usar.UsarWarning)]
    for field in ["targets", "claims"]:
        assert any(
            f"report.{field}: " in m and "not found (relative to the scenario's folder)" in m
            for m in messages
        ), messages
    assert not any(m.startswith("warning:") for m in messages), messages
    # The warning points at the caller's line (this file), not at the package's own code.
    files = {pathlib.Path(w.filename).name for w in caught if issubclass(w.category, usar.UsarWarning)}
    assert files == {pathlib.Path(__file__).name}, files
    report = (out / "report.md").read_text()
    assert "## Claims" not in report and "### Pooled statistics" not in report, report
    # The warnings were given once: a second call with nothing to warn about gives none.
    with warnings.catch_warnings():
        warnings.simplefilter("error", usar.UsarWarning)
        usar.sweep(PAPER, methods=["rne"], trials=1, duration_s=5.0)


def test_usar_warning_is_a_user_warning_and_scenario_warning_is_one():
    assert issubclass(usar.UsarWarning, UserWarning)
    assert issubclass(usar.ScenarioWarning, usar.UsarWarning)
