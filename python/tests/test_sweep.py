"""usar.sweep equals `usar sweep`'s trials_long.csv (same rows, values and order), in memory
and with `out` (the same files), and a Python method runs through a sweep."""

import subprocess

import numpy as np
import pandas as pd
import pytest

import usar
from conftest import PAPER, SHORT_S


def cli_sweep(usar_cli, out, methods, trials, threads):
    subprocess.run(
        [usar_cli, "sweep", str(PAPER), "--methods", ",".join(methods), "--trials", str(trials),
         "--duration", str(SHORT_S), "--threads", str(threads), "--quiet", "--out", str(out)],
        check=True,
        capture_output=True,
    )
    return usar.read_trials_long(out / "trials_long.csv")


def test_sweep_frame_equals_the_cli_trials_long_csv(paper, usar_cli, tmp_path):
    methods = ["rne", "dis", "eng", "hp_dis"]
    want = cli_sweep(usar_cli, tmp_path / "cli", methods, 2, 2)
    got = usar.sweep(paper, methods=methods, trials=2, threads=2, duration_s=SHORT_S)
    pd.testing.assert_frame_equal(got, want, check_exact=True)
    assert list(got.columns) == ["scenario", "method", "trial", "seed", "task", "metric", "value"]
    # Also as plain pandas reads the file (default float parser): same text, same frame.
    plain = pd.read_csv(tmp_path / "cli" / "trials_long.csv")
    assert plain.shape == got.shape
    assert (plain["method"] == got["method"]).all()


def test_sweep_with_out_writes_the_cli_files(paper, usar_cli, tmp_path):
    cli = tmp_path / "cli"
    cli_sweep(usar_cli, cli, ["rne", "eng"], 2, 1)
    got = usar.sweep(paper, methods=["rne", "eng"], trials=2, threads=2,
                     duration_s=SHORT_S, out=tmp_path / "py")
    for name in ["trials.csv", "trials_long.csv", "summary.csv"]:
        assert (tmp_path / "py" / name).read_bytes() == (cli / name).read_bytes(), name
    for name in ["report.md", "fig3a_rescuees.svg", "journal.jsonl"]:
        assert (tmp_path / "py" / name).exists(), name
    pd.testing.assert_frame_equal(got, usar.read_trials_long(cli / "trials_long.csv"),
                                  check_exact=True)
    # The wide table is trials.csv's: the same columns in its order, the same values.
    want = pd.read_csv(cli / "trials.csv", dtype={"trial": "int64", "seed": "uint64"},
                       **usar._api._EXACT)
    pd.testing.assert_frame_equal(usar.wide(got), want, check_exact=True)
    with pytest.raises(ValueError, match="no column 'task'"):
        usar.wide(want)
    # The same call again reads every trial back from the journal.
    again = usar.sweep(paper, methods=["rne", "eng"], trials=2, duration_s=SHORT_S,
                       out=tmp_path / "py", resume=True)
    pd.testing.assert_frame_equal(again, got, check_exact=True)


class KMeansNeeds(usar.GroupingMethod):
    """Per kind, sort robots by the first principal direction of their needs vectors (a
    one-dimensional k-means split) and deal them to the tasks hardest first."""

    name = "kmeans_needs"

    def group(self, request):
        groups = {t.name: [] for t in request.tasks}
        hardest_first = sorted(request.tasks, key=lambda t: t.rank)
        for kind in {r.kind for r in request.robots}:
            robots = request.robots_of_kind(kind)
            needs = np.stack([r.needs for r in robots])
            centred = needs - needs.mean(axis=0)
            axis = np.linalg.svd(centred, full_matrices=False)[2][0] if len(robots) > 1 else None
            score = centred @ axis if axis is not None else np.zeros(len(robots))
            order = [robots[i] for i in np.argsort(-score, kind="stable")]
            for task in hardest_first:
                n = task.quotas[kind]
                groups[task.name].extend(order[:n])
                order = order[n:]
        return groups


def random_groups(request):
    """Each kind's robots shuffled by the trial's generator, then dealt by quota."""
    rng = request.rng()
    out = [[] for _ in request.tasks]
    for k, quota in enumerate(request.quotas):
        ids = [r.id for r in request.robots if r.kind_index == k]
        rng.shuffle(ids)
        for t, n in enumerate(quota):
            out[t].extend(ids[:n])
            ids = ids[n:]
    return out


def test_python_methods_run_through_a_sweep_deterministically(paper):
    methods = ["eng", KMeansNeeds(), random_groups]
    one = usar.sweep(paper, methods=methods, trials=2, threads=1, duration_s=SHORT_S)
    two = usar.sweep(paper, methods=methods, trials=2, threads=2, duration_s=SHORT_S)
    pd.testing.assert_frame_equal(one, two, check_exact=True)
    assert list(dict.fromkeys(one["method"])) == ["ENG", "kmeans_needs", "random_groups"]
    rescued = one[(one.metric == "rescued") & (one.task == "total")]
    assert len(rescued) == 6
    assert (rescued["value"] >= 0).all()


class SameAsEng(usar.GroupingMethod):
    name = "same_as_eng"

    def group(self, request):
        return usar.eng(request)


def test_a_python_method_giving_engs_answer_gives_engs_numbers(paper):
    df = usar.sweep(paper, methods=["eng", SameAsEng], trials=2, duration_s=SHORT_S)
    eng = df[df.method == "ENG"].drop(columns="method").reset_index(drop=True)
    mine = df[df.method == "same_as_eng"].drop(columns="method").reset_index(drop=True)
    pd.testing.assert_frame_equal(eng, mine, check_exact=True)


def test_requests_carry_the_team(paper):
    seen = []

    def spy(request):
        seen.append(request)
        return usar.dis(request)

    usar.run(paper, spy, duration_s=10)
    first = seen[0]
    assert first.round == 0 and first.trial == 0
    assert len(first.robots) == 12
    assert first.robots[0].needs.dtype == np.float64
    assert first.robots[0].role == "Carrier" and first.robots[0].kind == "carrier"
    assert first.robots[0].position is not None and len(first.robots[0].position) == 2
    assert 0.0 <= first.robots[0].energy_pct <= 100.0
    assert [t.name for t in first.tasks] == ["hard", "easy"]
    assert first.tasks[0].quotas == {"carrier": 3, "supplier": 2, "observer": 1}
    assert first.needs_matrix().shape[0] == 12
    assert usar.rne(first) == usar.rne(first)
    assert sorted(i for g in usar.hp_dis(first) for i in g) == list(range(12))


def test_the_seed_column_is_uint64_whatever_the_seeds(paper, tmp_path):
    """Issue 58: `seed` was int64 when every seed was below 2**63 and uint64 otherwise, so
    `pd.concat` of two sweeps made it float64 and lost seeds."""
    small = tmp_path / "small.csv"
    small.write_text(
        "scenario,method,trial,seed,task,metric,value\n"
        "paper,RNE,0,5,,rescued_total,3\n"
    )
    big = tmp_path / "big.csv"
    big.write_text(
        "scenario,method,trial,seed,task,metric,value\n"
        "paper,RNE,0,11487996472437173461,,rescued_total,3\n"
    )
    a, b = usar.read_trials_long(small), usar.read_trials_long(big)
    assert a["seed"].dtype == np.uint64 and b["seed"].dtype == np.uint64
    both = pd.concat([a, b], ignore_index=True)
    assert both["seed"].dtype == np.uint64
    assert int(both["seed"].iloc[1]) == 11487996472437173461
    frame = usar.sweep(paper, methods=["dis"], trials=2, duration_s=SHORT_S)
    assert frame["seed"].dtype == np.uint64 and frame["trial"].dtype == np.int64
    # A trial repeats from its row of the frame.
    row = frame.iloc[0]
    again = usar.run(paper, "dis", seed=row["seed"], duration_s=SHORT_S)
    assert again.seed == int(row["seed"])
    with pytest.raises(TypeError, match="a float cannot hold every 64-bit integer"):
        usar.run(paper, "dis", seed=float(row["seed"]), duration_s=SHORT_S)


def test_a_refused_out_speaks_python_and_overwrite_starts_afresh(paper, tmp_path):
    """Issue 58: a sweep with other parameters into an existing `out` advised `--overwrite`
    and `--resume` (no such arguments in Python) and called a `set()` an edited file."""
    out = tmp_path / "out"
    usar.sweep(paper, methods=["dis"], trials=1, duration_s=SHORT_S, out=out)
    with pytest.raises(ValueError) as refused:
        usar.sweep(paper, methods=["dis"], trials=2, duration_s=SHORT_S, out=out)
    message = str(refused.value)
    assert "overwrite=True" in message and "resume=True" in message, message
    assert "--" not in message, message
    edited = paper.set("mission.pickup_s", 2.0)
    with pytest.raises(ValueError, match="the scenario changed") as refused:
        usar.sweep(edited, methods=["dis"], trials=1, duration_s=SHORT_S, out=out)
    assert "scenario file was edited" not in str(refused.value)
    again = usar.sweep(paper, methods=["dis"], trials=2, duration_s=SHORT_S, out=out,
                       overwrite=True)
    assert sorted(again["trial"].unique()) == [0, 1]
    assert len(pd.read_csv(out / "trials.csv")) == 2
    with pytest.raises(ValueError, match="give one"):
        usar.sweep(paper, methods=["dis"], trials=2, out=out, resume=True, overwrite=True)


def test_claims_of_ones_own_from_python_reach_report_md(paper, tmp_path):
    mine = [{"id": "hard-rne", "sentence": "RNE rescues more in the hard task than DIS",
             "subject": "rne", "rivals": {"Only": ["dis"]}, "metric": "rescued_hard",
             "direction": "More", "test": "MannWhitney"}]
    usar.sweep(paper, methods=["rne", "dis"], trials=2, duration_s=SHORT_S,
               out=tmp_path / "a", claims=mine)
    report = (tmp_path / "a" / "report.md").read_text()
    assert "(hard-rne) RNE rescues more in the hard task than DIS" in report
    assert "(4b)" not in report and "one-sided Mann-Whitney U, alpha 0.05" in report
    # A claims file, as --claims FILE.
    path = tmp_path / "mine.ron"
    path.write_text('Claims(claims: [(id: "x", sentence: "DIS rescues the most", '
                    'subject: "DIS", metric: "rescued_total", direction: More)])')
    usar.sweep(paper, methods=["rne", "dis"], trials=2, duration_s=SHORT_S,
               out=tmp_path / "b", claims=path)
    assert "(x) DIS rescues the most" in (tmp_path / "b" / "report.md").read_text()
    with pytest.raises(ValueError, match="give out= too"):
        usar.sweep(paper, methods=["rne"], trials=1, duration_s=SHORT_S, claims=mine)
    bad = [dict(mine[0], metric="rescued_north")]
    with pytest.raises(ValueError, match=r"claims\[0\]\.metric: .*rescued_north"):
        usar.sweep(paper, methods=["rne", "dis"], trials=1, duration_s=SHORT_S,
                   out=tmp_path / "c", claims=bad)
    with pytest.raises(ValueError, match=r"claims\[0\]: unknown variant `Most`"):
        usar.sweep(paper, methods=["rne", "dis"], trials=1, duration_s=SHORT_S,
                   out=tmp_path / "d", claims=[dict(mine[0], direction="Most")])


def test_claims_from_python_take_the_paired_tests(paper, tmp_path):
    """Issue 71: `test` names the paired tests too; the report says they are paired."""
    mine = [{"id": "w", "sentence": "RNE rescues more in total than DIS", "subject": "rne",
             "rivals": {"Only": ["dis"]}, "metric": "rescued_total", "direction": "More",
             "test": "Wilcoxon"},
            {"id": "t", "sentence": "DIS rescues more in total than RNE", "subject": "dis",
             "rivals": {"Only": ["rne"]}, "metric": "rescued_total", "direction": "More"}]
    usar.sweep(paper, methods=["rne", "dis"], trials=3, duration_s=SHORT_S,
               out=tmp_path / "a", claims=mine)
    report = (tmp_path / "a" / "report.md").read_text()
    assert "one-sided Wilcoxon signed-rank test over 3 pairs of trials, alpha 0.05" in report
    assert "one-sided paired t-test over 3 pairs of trials, alpha 0.05" in report
    with pytest.raises(ValueError, match=r"claims\[0\]: unknown variant `Paired`"):
        usar.sweep(paper, methods=["rne", "dis"], trials=2, duration_s=SHORT_S,
                   out=tmp_path / "b", claims=[dict(mine[0], test="Paired")])


def test_a_grid_is_the_sweep_once_per_cell_with_the_cells_values(paper, usar_cli, tmp_path):
    vary = ["mission.pickup_s=0,2"]
    got = usar.grid(paper, vary, methods=["rne", "dis"], trials=2, threads=2,
                    duration_s=SHORT_S, out=tmp_path / "py")
    assert list(got.columns[:2]) == ["cell", "mission.pickup_s"]
    assert sorted(set(zip(got["cell"], got["mission.pickup_s"]))) == [(0, "0"), (1, "2")]
    # Each cell's rows are the sweep of that cell's scenario, as the CLI's cell folders hold.
    for cell, value in [(0, "0"), (1, "2")]:
        one = usar.sweep(paper.set("mission.pickup_s", float(value)), methods=["rne", "dis"],
                         trials=2, duration_s=SHORT_S)
        rows = got[got["cell"] == cell].drop(columns=["cell", "mission.pickup_s"])
        pd.testing.assert_frame_equal(rows.reset_index(drop=True), one, check_exact=True)
    cli = tmp_path / "cli"
    subprocess.run([usar_cli, "sweep", str(PAPER), "--vary", vary[0], "--methods", "rne,dis",
                    "--trials", "2", "--duration", str(SHORT_S), "--quiet", "--out", str(cli)],
                   check=True)
    assert (tmp_path / "py" / "grid.csv").read_bytes() == (cli / "grid.csv").read_bytes()
    # The wide table of a grid keeps the cell and its values as keys.
    wide = usar.wide(got)
    assert list(wide.columns[:6]) == ["cell", "mission.pickup_s", "scenario", "method", "trial",
                                      "seed"]
    assert len(wide) == 2 * 2 * 2
    with pytest.raises(ValueError, match="vary: give at least one"):
        usar.grid(paper, [], trials=1)
    # Named by the keyword argument, not `usar sweep`'s flag.
    with pytest.raises(ValueError, match=r"^vary mission\.pikup_s=0,1: no field \"pikup_s\""):
        usar.grid(paper, ["mission.pikup_s=0,1"], trials=1)
