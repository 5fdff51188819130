"""usar.calibrate, usar.multiverse, usar.render and usar.replay: the CLI's files from Python,
with Python grouping methods and claims given as Python objects."""

import os
import pathlib
import subprocess

import pandas as pd
import pytest

import usar
from conftest import PAPER, ROOT

CORRIDOR = ROOT / "scenarios" / "corridor.ron"
DATA = ROOT / "crates" / "experiments" / "tests" / "data"
AXES = DATA / "multiverse-axes.ron"
TARGETS = DATA / "multiverse-targets.ron"
EPOCH = {"SOURCE_DATE_EPOCH": "946684800"}


def hp_first(request):
    """HP_DIS written in Python: the built-in's own grouping, so its trials are HP_DIS's."""
    return usar.hp_dis(request)


def cli(usar_cli, *args, cwd=None):
    env = dict(os.environ, **EPOCH)
    done = subprocess.run([usar_cli, *map(str, args)], cwd=cwd, env=env, capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def body(path):
    """A file's lines but its comments (which quote the command that made it)."""
    return [l for l in pathlib.Path(path).read_text().splitlines() if not l.startswith("//")]


CALIBRATION = dict(trials=2, duration_s=60.0, max_evals=4, check_trials=1)


def test_calibrate_with_a_python_method_writes_the_cli_files(usar_cli, tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", EPOCH["SOURCE_DATE_EPOCH"])
    free = ["mission.pickup_s=0.5..2", "mission.search_time_budget_s=8..30"]
    cli(usar_cli, "calibrate", PAPER, "--methods", "rne,hp_dis",
        "--trials", 2, "--duration", 60, "--max-evals", 4, "--check-trials", 1,
        *sum((["--free", f] for f in free), []), "--out", tmp_path / "cli", "--quiet")
    c = usar.calibrate(PAPER, free, methods=["rne", hp_first],
                       out=tmp_path / "py", threads=1, progress=False, **CALIBRATION)
    written = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert sorted(p.name for p in (tmp_path / "py").iterdir()) == written
    for name in [n for n in written if n.endswith((".csv", ".svg"))]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert body(tmp_path / "py" / "calibrated.ron") == body(tmp_path / "cli" / "calibrated.ron")
    assert c.trace.equals(pd.read_csv(tmp_path / "cli" / "trace.csv", **usar._api._EXACT))
    assert list(c.best) == ["mission.pickup_s", "mission.search_time_budget_s"]
    assert c.scenario.get("mission.pickup_s") == c.best["mission.pickup_s"]
    assert c.evaluations == len(c.trace) == 4 and (c.ran, c.reused) == (4, 0)
    assert list(c.statistics.columns) == ["target", "value", "goal", "band", "holds",
                                          "report_only"]
    assert c.unseen is not None and len(c.unseen) == len(c.statistics)
    assert "usar.calibrate(" in (tmp_path / "py" / "calibrated.ron").read_text()
    # Called again with a larger budget, it continues the same calibration.
    more = usar.calibrate(PAPER, free, methods=["rne", hp_first],
                          out=tmp_path / "py", progress=False, **dict(CALIBRATION, max_evals=5))
    assert (more.ran, more.reused) == (1, 4)


def test_calibrate_without_out_leaves_no_folder_and_speaks_python(tmp_path, monkeypatch):
    import tempfile
    (tmp_path / "tmp").mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path / "tmp"))
    c = usar.calibrate(PAPER, {"mission.pickup_s": (0.5, 2)}, targets=TARGETS, methods="rne",
                       trials=1, duration_s=30, max_evals=1, check_trials=0, progress=False)
    assert c.out is None and c.files == [] and c.evaluations == 1
    assert list((tmp_path / "tmp").iterdir()) == []
    assert "--" not in c.stop
    assert "<b>usar.Calibration</b>" in c._repr_html_()
    with pytest.raises(ValueError, match=r"^max_evals must be at least 1"):
        usar.calibrate(PAPER, "mission.pickup_s=0.5..2", targets=TARGETS, max_evals=0,
                       progress=False)
    with pytest.raises(ValueError, match=r"^free mission\.nope=0\.5\.\.2: no field \"nope\" in mission"):
        usar.calibrate(PAPER, "mission.nope=0.5..2", targets=TARGETS, progress=False)
    with pytest.raises(ValueError, match="optimizer"):
        usar.calibrate(PAPER, "mission.pickup_s=0.5..2", targets=TARGETS, optimizer="adam",
                       progress=False)


def claims(subject):
    """A user's claims: the subject rescues more in task easy than RNE (Mann-Whitney), and
    costs less energy in all than every other method."""
    return [
        {"id": "north", "sentence": f"{subject} rescues more in easy than RNE",
         "subject": subject, "rivals": {"Only": ["RNE"]}, "metric": "rescued_easy",
         "direction": "More", "test": "MannWhitney"},
        {"id": "cheap", "sentence": f"{subject} spends less energy", "subject": subject,
         "metric": "energy_total_pct", "direction": "Less", "correction": "Holm"},
    ]


def claims_ron(subject):
    rows = []
    for c in claims(subject):
        rivals = "Only([\"RNE\"])" if "rivals" in c else "Every"
        extra = "".join(f", {k}: {c[k]}" for k in ("test", "correction") if k in c)
        rows.append(f"(id: \"{c['id']}\", sentence: \"{c['sentence']}\", subject: "
                    f"\"{c['subject']}\", rivals: {rivals}, metric: \"{c['metric']}\", "
                    f"direction: {c['direction']}{extra})")
    return "Claims(claims: [" + ", ".join(rows) + "])"


MULTIVERSE = ["--free", "mission.pickup_s=0.5..2", "--trials", "2", "--duration", "60",
              "--calibration-trials", "1", "--max-evals", "3", "--quiet"]


def test_multiverse_with_a_python_method_and_claims_is_the_cli_multiverse(usar_cli, tmp_path,
                                                                          monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", EPOCH["SOURCE_DATE_EPOCH"])
    (tmp_path / "cli").mkdir()
    (tmp_path / "py").mkdir()
    (tmp_path / "claims.ron").write_text(claims_ron("HP_DIS"))
    cli(usar_cli, "multiverse", CORRIDOR, "--axes", AXES, "--targets", TARGETS, "--claims",
        tmp_path / "claims.ron", "--methods", "rne,hp_dis", *MULTIVERSE, "--out", "mv",
        cwd=tmp_path / "cli")
    monkeypatch.chdir(tmp_path / "py")
    m = usar.multiverse(CORRIDOR, AXES, TARGETS, "mission.pickup_s=0.5..2", "mv",
                        methods=["rne", hp_first], claims=claims("hp_first"), trials=2,
                        duration_s=60, calibration_trials=1, max_evals=3, threads=1,
                        progress=False)
    want = (tmp_path / "cli" / "mv" / "multiverse.csv").read_text()
    got = (tmp_path / "py" / "mv" / "multiverse.csv").read_text()
    assert got.replace("hp_first", "HP_DIS") == want
    assert (m.count, m.admissible, m.failed) == (4, 2, [])
    assert set(m.claims["claim"]) == {"north", "cheap"}
    assert len(m.universes) == 4 and "admissible" in m.universes.columns
    assert set(m.metrics["method"]) == {"RNE", "hp_first"}
    files = sorted(p.name for p in (tmp_path / "py" / "mv").iterdir() if p.suffix == ".svg")
    assert files == ["sensitivity_cheap.svg", "sensitivity_north.svg", "spec_curve_cheap.svg",
                     "spec_curve_north.svg", "targets.svg"]
    md = (tmp_path / "py" / "mv" / "multiverse.md").read_text()
    assert "north" in md and "RNE rescues more" not in md
    # Called again, everything is reused.
    again = usar.multiverse(CORRIDOR, AXES, TARGETS, "mission.pickup_s=0.5..2", "mv",
                            methods=["rne", hp_first], claims=claims("hp_first"), trials=2,
                            duration_s=60, calibration_trials=1, max_evals=3, progress=False)
    assert (again.ran, again.reused) == (0, 4)
    assert (tmp_path / "py" / "mv" / "multiverse.csv").read_text() == got
    # The same claims as a file give the same multiverse.
    (tmp_path / "mine.ron").write_text(claims_ron("hp_first"))
    usar.multiverse(CORRIDOR, AXES, TARGETS, "mission.pickup_s=0.5..2", "mv2",
                    methods=["rne", hp_first], claims=tmp_path / "mine.ron", trials=2,
                    duration_s=60, calibration_trials=1, max_evals=3, progress=False)
    assert (tmp_path / "py" / "mv2" / "multiverse.csv").read_text() == got


def test_multiverse_refuses_bad_claims_in_python_words(tmp_path):
    bad = claims("hp_first")
    bad[0]["rivals"] = {"Only": ["XYZ"]}
    with pytest.raises(ValueError, match="XYZ"):
        usar.multiverse(CORRIDOR, AXES, TARGETS, "mission.pickup_s=0.5..2", tmp_path / "mv",
                        methods=["rne", hp_first], claims=bad, progress=False)
    with pytest.raises(ValueError, match=r"^calibration_trials must be at least 1"):
        usar.multiverse(CORRIDOR, AXES, TARGETS, "mission.pickup_s=0.5..2", tmp_path / "mv",
                        calibration_trials=0, progress=False)


def test_render_and_replay_write_the_cli_files(usar_cli, tmp_path):
    cli(usar_cli, "render", PAPER, "--out", tmp_path / "arena-cli.svg")
    usar.render(PAPER, tmp_path / "arena.svg")
    assert (tmp_path / "arena.svg").read_bytes() == (tmp_path / "arena-cli.svg").read_bytes()
    cli(usar_cli, "render", PAPER, "--out", tmp_path / "trace-cli.svg", "--trace", "--method",
        "hp_dis", "--trial", 2, "--duration", 40)
    usar.render(PAPER, tmp_path / "trace.svg", method=hp_first, trial=2, duration_s=40)
    assert (tmp_path / "trace.svg").read_bytes() == (tmp_path / "trace-cli.svg").read_bytes()
    cli(usar_cli, "replay", PAPER, "--method", "dis", "--trial", 1, "--duration", 40, "--out",
        tmp_path / "cli.html")
    r = usar.replay(PAPER, tmp_path / "py.html", method="dis", trial=1, duration_s=40)
    assert (tmp_path / "py.html").read_bytes() == (tmp_path / "cli.html").read_bytes()
    assert r == usar.run(PAPER, "dis", trial=1, duration_s=40)
    py = usar.replay(PAPER, tmp_path / "hp.html", method=hp_first, duration_s=40, hz=2)
    assert py.rescued == usar.run(PAPER, hp_first, duration_s=40).rescued
    with pytest.raises(ValueError, match="give method too"):
        usar.render(PAPER, tmp_path / "x.svg", trial=3)
    with pytest.raises(ValueError, match="hz"):
        usar.replay(PAPER, tmp_path / "x.html", hz=-1)


BROKEN = {"on": True}


def flaky(request):
    """HP_DIS, or an exception while BROKEN is on."""
    if BROKEN["on"]:
        raise RuntimeError("broken on purpose")
    return usar.hp_dis(request)


def test_a_python_method_that_raises_stops_a_calibration_and_keeps_nothing_of_it(tmp_path):
    free = ["mission.pickup_s=0.5..2", "mission.search_time_budget_s=8..30"]
    args = dict(methods=["rne", flaky], out=tmp_path / "cal", progress=False, **CALIBRATION)
    BROKEN["on"] = True
    with pytest.raises(RuntimeError, match="broken on purpose"):
        usar.calibrate(PAPER, free, **args)
    # Nothing of the evaluation it was in: the trace holds its header only.
    assert len((tmp_path / "cal" / "trace.jsonl").read_text().splitlines()) == 1
    assert not (tmp_path / "cal" / "calibrated.ron").exists()
    BROKEN["on"] = False
    fixed = usar.calibrate(PAPER, free, **args)
    fresh = usar.calibrate(PAPER, free, **dict(args, out=tmp_path / "fresh"))
    assert (fixed.ran, fixed.reused) == (4, 0)
    assert fixed.trace.equals(fresh.trace)


def test_a_missing_claims_file_of_the_scenario_is_a_warning(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    s = usar.Scenario.load(CORRIDOR).set("report.claims", "missing-claims.ron")
    with pytest.warns(UserWarning, match="report.claims: .*missing-claims.ron not found"):
        m = usar.multiverse(s, AXES, TARGETS, "mission.pickup_s=0.5..2", "mv",
                            methods=["rne", "dis"], trials=1, duration_s=30,
                            calibration_trials=1, max_evals=1, progress=False)
    assert len(m.claims) == 0
