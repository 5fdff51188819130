"""usar.verdicts and usar.compare: report.md's claim verdicts as a DataFrame, the same numbers
as report.md and the `usar sweep` command line print for the same trials."""

import math
import re
import subprocess

import pandas as pd
import pytest

import usar
from conftest import PAPER

# Trials long enough for every method to rescue in both tasks (costs per rescuee defined).
TRIALS, DURATION_S = 5, 300.0


@pytest.fixture(scope="module")
def swept(paper, tmp_path_factory):
    """The paper sweep with out=: (trials frame, report.md's text)."""
    out = tmp_path_factory.mktemp("verdicts") / "sweep"
    frame = usar.sweep(paper, trials=TRIALS, duration_s=DURATION_S, out=out, progress=False)
    return frame, (out / "report.md").read_text()


def num(x):
    """usar_report::table::num: report.md's numbers."""
    if not math.isfinite(x):
        return "n/a"
    a = abs(x)
    if a >= 100:
        return f"{x:.1f}"
    if a >= 1:
        return f"{x:.2f}"
    if a >= 0.01 or a == 0:
        return f"{x:.3f}"
    mantissa, exponent = f"{x:.2e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def pval(p):
    """usar_report::table::pval: report.md's p-values."""
    if not math.isfinite(p):
        return "n/a"
    return "< 0.001" if p < 0.001 else f"{p:.3f}"


def report_rows(report):
    """report.md's comparison rows: {(claim id, rival): [cells after the rival's mean]}."""
    rows, claim = {}, None
    for line in report.splitlines():
        heading = re.match(r"### \((\w+)\) ", line)
        if heading:
            claim = heading.group(1)
        elif claim and line.startswith("| ") and not line.startswith("| vs "):
            cells = [c.strip() for c in line.strip("|").split("|")]
            rows[(claim, cells[0])] = cells[2:]
        if line.startswith("## ") and line != "## Claims":
            claim = None
    return rows


def test_verdicts_equal_report_md(swept):
    frame, report = swept
    v = usar.verdicts(frame)
    wilcoxon = usar.verdicts(frame, test="wilcoxon").set_index(["claim", "rival"])
    welch = usar.verdicts(frame, test="welch").set_index(["claim", "rival"])
    assert v.attrs["claims"].endswith("paper-claims.ron")
    assert list(pd.unique(v["claim"])) == ["1", "2", "3", "4a", "4b"]
    assert set(v["rival"]) == {"RNE", "DIS", "ENG", "HP_DIS"}
    assert (v["test"] == "paired t-test").all() and v["paired"].all()
    # The verdict table: the test's words and the verdict of each claim.
    for claim, rows in v.groupby("claim", sort=False):
        line = f"| {rows['test_words'].iloc[0]} | **{rows['verdict'].iloc[0]}** |"
        assert any(l.startswith(f"| ({claim}) ") and l.endswith(line) for l in report.splitlines()), (
            claim, line)
    # Every comparison row: pairs, mean paired difference, paired t (dof), p, Wilcoxon W+, p,
    # p(reverse), Welch p.
    rows = report_rows(report)
    assert len(rows) == len(v) == 15
    for _, r in v.iterrows():
        k = (r["claim"], r["rival"])
        want = [
            str(r["n"]), num(r["difference"]), f"{num(r['statistic'])} ({num(r['dof'])})",
            pval(r["p_value"]), num(wilcoxon.loc[k, "statistic"]), pval(wilcoxon.loc[k, "p_value"]),
            pval(r["p_reverse"]), pval(welch.loc[k, "p_value"]),
        ]
        assert rows[k] == want, k
        assert r["p_value"] == r["p_raw"]  # no correction in the paper's claims
        assert r["effect_size"] == pytest.approx(r["statistic"] / math.sqrt(r["n"]))
        assert r["significant"] == (r["p_value"] < 0.05)


def test_verdicts_without_out_and_from_the_wide_table_are_the_same(swept, paper):
    frame, _ = swept
    again = usar.sweep(paper, trials=TRIALS, duration_s=DURATION_S, progress=False)
    pd.testing.assert_frame_equal(usar.verdicts(again, scenario=PAPER), usar.verdicts(frame))
    pd.testing.assert_frame_equal(usar.verdicts(usar.wide(frame)), usar.verdicts(frame))


def test_verdicts_equal_the_command_lines(usar_cli, tmp_path):
    out = tmp_path / "cli"
    printed = subprocess.run(
        [usar_cli, "sweep", str(PAPER), "--trials", str(TRIALS), "--duration", str(DURATION_S),
         "--out", str(out)],
        check=True, capture_output=True, text=True,
    ).stdout
    v = usar.verdicts(usar.read_trials_long(out / "trials_long.csv"))
    for claim, rows in v.groupby("claim", sort=False):
        words = rows["test_words"].iloc[0].split(", ")[0].removeprefix("one-sided ")
        line = (f"{rows['verdict'].iloc[0]} ({words}, max p = "
                f"{pval(rows['p_value'].max())})")
        assert f"  ({claim}) " in printed and line in printed, (line, printed)


def test_paired_and_unpaired_differ(swept):
    frame, _ = swept
    paired = usar.compare(frame, "rne")
    unpaired = usar.compare(frame, "rne", test="unpaired")
    assert list(paired["rival"]) == ["DIS", "ENG", "HP_DIS"]
    assert (paired["test"] == "paired t-test").all() and (unpaired["test"] == "Welch").all()
    assert list(paired["n"]) == [TRIALS] * 3 and list(unpaired["n"]) == [2 * TRIALS] * 3
    assert paired["claim"].isna().all()
    # The same differences of means, other statistics and p-values.
    assert paired["difference"].tolist() == pytest.approx(unpaired["difference"].tolist())
    assert (paired["p_value"] != unpaired["p_value"]).all()
    assert (paired["dof"] == TRIALS - 1).all() and (unpaired["dof"] != TRIALS - 1).all()
    # compare's paired rows are claim 1's (RNE's total against every rival).
    claim1 = usar.verdicts(frame).query("claim == '1'").reset_index(drop=True)
    for c in ["rival", "n", "statistic", "dof", "p_value", "effect_size"]:
        assert paired[c].tolist() == claim1[c].tolist(), c
    # Rank tests, a rival list, a cost metric (lower is better).
    w = usar.compare(frame, "HP-DIS", rivals="dis", metric="hp_per_hard_rescuee_pct",
                     test="wilcoxon")
    assert list(w["rival"]) == ["DIS"] and w["direction"].iloc[0] == "lower"
    assert w["test"].iloc[0] == "Wilcoxon signed-rank test" and math.isnan(w["dof"].iloc[0])
    mw = usar.compare(frame, "eng", rivals=["rne", "dis"], test="mann-whitney", alpha=0.1)
    assert list(mw["test"]) == ["Mann-Whitney U"] * 2 and (mw["alpha"] == 0.1).all()


def test_holm_adjusts_over_a_claims_rivals(swept):
    frame, _ = swept
    claim = {"id": "h", "sentence": "RNE rescues the most", "subject": "RNE",
             "metric": "rescued_total", "direction": "More", "correction": "Holm"}
    v = usar.verdicts(frame, claims=[claim])
    assert (v["correction"] == "Holm").all()
    raw = v["p_raw"].tolist()
    order = sorted(range(3), key=lambda i: raw[i])
    running, want = 0.0, [0.0] * 3
    for rank, i in enumerate(order):
        running = max(running, min(1.0, (3 - rank) * raw[i]))
        want[i] = running
    assert v["p_value"].tolist() == pytest.approx(want, rel=1e-12)
    assert (v["p_value"] >= v["p_raw"]).all() and (v["p_value"] > v["p_raw"]).any()


def test_a_python_method_is_compared_by_name(paper):
    class Policy(usar.GroupingMethod):
        name = "policy"

        def group(self, request):
            return usar.eng(request)

    frame = usar.sweep(paper, methods=["rne", Policy], trials=3, duration_s=120, progress=False)
    got = usar.compare(frame, "policy")
    assert list(got["method"]) == ["policy"] and list(got["rival"]) == ["RNE"]
    assert got["n"].iloc[0] == 3


def test_bad_input_names_the_argument(swept, paper):
    frame, _ = swept
    cases = [
        (dict(method="nobody"), r"^method: 'nobody' is not among the trials' methods"),
        (dict(method="rne", rivals=["ghost"]), r"^rivals: 'ghost'"),
        (dict(method="rne", rivals=["rne"]), r"^rivals: RNE is the method compared"),
        (dict(method="rne", test="anova"), r"^test: unknown test 'anova'"),
        (dict(method="rne", metric="rescued_lunar"), r"^metric: no column 'rescued_lunar'"),
        (dict(method="rne", metric="rounds"), r"^direction: "),
        (dict(method="rne", alpha=0.9), r"^alpha: "),
    ]
    for kwargs, message in cases:
        with pytest.raises(ValueError, match=message):
            usar.compare(frame, **kwargs)
    with pytest.raises(ValueError, match=r"^test: unknown test 'ttest'"):
        usar.verdicts(frame, test="ttest")
    with pytest.raises(ValueError, match=r"^trials: not a table of usar.sweep"):
        usar.verdicts(frame.drop(columns=["seed"]))
    with pytest.raises(TypeError, match=r"^trials: "):
        usar.compare([1, 2], "rne")
    one = usar.sweep(paper, methods=["rne", "dis"], trials=1, duration_s=60, progress=False)
    with pytest.raises(ValueError, match=r"^trials: RNE has 1 trial\(s\); the tests need at least 2"):
        usar.compare(one, "rne")
    with pytest.raises(ValueError, match=r"^trials: RNE has 1 trial"):
        usar.verdicts(one)
    renamed = frame.assign(scenario="not-shipped")
    with pytest.raises(ValueError, match=r"^scenario: the trials' scenario not-shipped"):
        usar.verdicts(renamed)


def test_a_grid_gives_each_cells_verdicts(paper):
    g = usar.grid(paper, ["mission.pickup_s=2,4"], methods=["rne", "dis"], trials=3,
                  duration_s=120, progress=False)
    v = usar.verdicts(g)
    assert list(v.columns[:2]) == ["cell", "mission.pickup_s"]
    assert list(v["cell"]) == [0] * 5 + [1] * 5
    for cell in (0, 1):
        alone = usar.verdicts(g[g["cell"] == cell].drop(columns=["cell", "mission.pickup_s"]))
        mine = v[v["cell"] == cell].drop(columns=["cell", "mission.pickup_s"])
        pd.testing.assert_frame_equal(mine.reset_index(drop=True), alone)
    with pytest.raises(ValueError, match=r"^trials: a grid's table"):
        usar.compare(g, "rne")
