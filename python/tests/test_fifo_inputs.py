"""Issue 70: a FIFO with no writer given as a scenario, claims, targets or axes file is
refused at once (it is not a regular file) instead of waiting for a writer for ever.

Each call runs in a child interpreter with a timeout, so that a regression fails the test
(the child is killed) instead of hanging the suite."""

import os
import subprocess
import sys

import pytest

from conftest import PAPER, ROOT

DATA = ROOT / "crates" / "experiments" / "tests" / "data"
CORRIDOR = ROOT / "scenarios" / "corridor.ron"
SHORT = "trials=1, duration_s=5.0, progress=False"

CALLS = {
    "scenario": "usar.Scenario.load(FIFO)",
    "scenario of run": "usar.run(FIFO, 'dis', duration_s=5.0)",
    "claims": f"usar.sweep(PAPER, methods=['rne', 'dis'], out=OUT, claims=FIFO, {SHORT})",
    "targets of sweep": f"usar.sweep(PAPER, methods=['dis'], out=OUT, targets=FIFO, {SHORT})",
    "targets": "usar.calibrate(PAPER, 'mission.pickup_s=0.5..2', targets=FIFO, out=OUT, "
    f"methods='dis', max_evals=1, check_trials=0, {SHORT})",
    "axes": f"usar.multiverse(CORRIDOR, FIFO, DATA / 'multiverse-targets.ron', "
    f"'mission.pickup_s=0.5..2', OUT, methods=['dis'], progress=False)",
}

CHILD = """
import pathlib, sys
import usar
FIFO, OUT = sys.argv[1], sys.argv[2]
PAPER, CORRIDOR, DATA = (pathlib.Path(p) for p in sys.argv[3:6])
try:
    {call}
except ValueError as e:
    print(e)
    sys.exit(0)
sys.exit("no error")
"""


@pytest.mark.parametrize("what", list(CALLS))
def test_a_fifo_without_a_writer_is_refused_at_once(tmp_path, what):
    fifo = tmp_path / "input.ron"
    os.mkfifo(fifo)
    args = [fifo, tmp_path / "out", PAPER, CORRIDOR, DATA]
    try:
        done = subprocess.run(
            [sys.executable, "-c", CHILD.format(call=CALLS[what]), *map(str, args)],
            capture_output=True, text=True, timeout=60,
        )
    except subprocess.TimeoutExpired:
        pytest.fail(f"{what}: still waiting for the FIFO's writer after 60 s")
    assert done.returncode == 0, done.stderr
    message = done.stdout.strip()
    assert "\n" not in message, message
    assert str(fifo) in message and "not a regular file" in message, message
