"""usar.run equals `usar run --json`, field for field and bit for bit."""

import json
import subprocess

import pytest

import usar
from conftest import PAPER, SHORT_S


def cli_run(usar_cli, tmp_path, *args):
    out = tmp_path / "trial.json"
    subprocess.run(
        [usar_cli, "run", str(PAPER), *args, "--json", str(out)],
        check=True,
        capture_output=True,
    )
    return json.loads(out.read_text())


@pytest.mark.parametrize("method,trial", [("rne", 0), ("hp_dis", 3)])
def test_run_equals_the_cli_json(paper, usar_cli, tmp_path, method, trial):
    want = cli_run(
        usar_cli, tmp_path, "--method", method, "--trial", str(trial), "--duration", str(SHORT_S)
    )
    got = usar.run(paper, method=method, trial=trial, duration_s=SHORT_S)
    assert got.to_dict() == want
    assert got.method == want["method"]
    assert got.by_task["hard"].rescued == want["by_task"]["hard"]["rescued"]
    assert [r.to_dict() for r in got.robots] == want["robots"]
    assert got.robots[0].final_energy_pct == want["robots"][0]["final_energy_pct"]
    assert len(got.rounds) == len(want["rounds"])


def test_a_seed_is_used_as_is(paper, usar_cli, tmp_path):
    want = cli_run(usar_cli, tmp_path, "--method", "eng", "--seed", "7", "--duration", "10")
    got = usar.run(paper, "eng", seed=7, duration_s=10)
    assert got.to_dict() == want
    assert got.seed == 7


def test_result_attributes_add_up(paper):
    r = usar.run(paper, "dis", duration_s=SHORT_S)
    assert r.tasks == ["hard", "easy"]
    assert r.total.rescued == sum(r.rescued) == r.rescued_total
    assert r.total.energy_spent_pct == pytest.approx(sum(r.energy_spent_pct), abs=1e-9)
    assert all(0.0 <= robot.final_energy_pct <= 100.0 for robot in r.robots)
    assert all(w.end_s >= w.start_s for w in r.rounds)


def test_trial_with_seed_is_refused_as_on_the_command_line(paper):
    """Issue 58: `trial=0, seed=3` was accepted though the docs call it an error."""
    with pytest.raises(ValueError, match="give trial or seed, not both"):
        usar.run(paper, "dis", trial=0, seed=3, duration_s=1.0)
    assert usar.run(paper, "dis", seed=3, duration_s=1.0).seed == 3
    assert usar.run(paper, "dis", duration_s=1.0) == usar.run(paper, "dis", trial=0, duration_s=1.0)


def test_rounds_frame_is_the_rounds_csv_of_the_cli(paper, usar_cli, tmp_path):
    """Issue 58: `pd.DataFrame(r.rounds)` gave one column of objects; the tidy frame equals
    `usar run --rounds-csv` (without its `cell` column)."""
    import numpy as np
    import pandas as pd

    csv = tmp_path / "rounds.csv"
    subprocess.run(
        [usar_cli, "run", str(PAPER), "--method", "rne", "--duration", "200",
         "--rounds-csv", str(csv)],
        check=True, capture_output=True,
    )
    want = pd.read_csv(csv, dtype={"seed": "uint64"}, keep_default_na=False, na_values=[""])
    want = want.drop(columns=["cell"])
    got = usar.run(paper, "rne", duration_s=200).rounds_frame()
    assert list(got.columns) == list(want.columns)
    assert len(got) == len(want) > 2
    for column in want.columns:
        for a, b in zip(got[column], want[column]):
            missing_a = a is None or (isinstance(a, float) and np.isnan(a))
            missing_b = b is None or (isinstance(b, float) and np.isnan(b))
            assert missing_a == missing_b and (missing_a or a == b), (column, a, b)
