"""Bench: the Python sweep against the CLI sweep on scenarios/paper.ron, in the same run.

Times `usar sweep` (the binary) and `usar.sweep(..., out=...)` (the same trials and files)
alternately, `--repeats` times each, and reports the best wall time of each and their ratio;
with `--check` it fails (exit 1) when the Python sweep is more than 10 % slower. It also
measures what a grouping method written in Python costs: a sweep of the built-in ENG against
a Python method that returns ENG's answer (`usar.eng(request)`): the same trials, so the
difference divided by the grouping rounds is the cost of one Python call under the GIL.

    python python/bench/sweep_vs_cli.py --trials 4 --duration 120 --check

The CLI is $USAR_BIN, else target/release/usar (under $CARGO_TARGET_DIR if set).
"""

import argparse
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import usar

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAPER = ROOT / "scenarios" / "paper.ron"


def cli_binary():
    given = os.environ.get("USAR_BIN")
    if given:
        return given
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return str(target / "release" / "usar")


class SameAsEng(usar.GroupingMethod):
    """ENG's answer, through Python: the cost of the call alone."""

    name = "py_eng"
    calls = 0

    def group(self, request):
        SameAsEng.calls += 1
        return usar.eng(request)


def time_requests():
    """Counts the seconds spent building requests (usar._grouping._request)."""
    import usar._grouping as g

    spent = [0.0]
    inner = g._request

    def timed_request(*args):
        t0 = time.perf_counter()
        try:
            return inner(*args)
        finally:
            spent[0] += time.perf_counter() - t0

    g._request = timed_request
    return spent


def timed(f):
    t0 = time.perf_counter()
    value = f()
    return time.perf_counter() - t0, value


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--trials", type=int, default=4)
    p.add_argument("--duration", type=float, default=120.0, help="simulated seconds per trial")
    p.add_argument("--threads", type=int, default=None)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--check", action="store_true", help="exit 1 if Python is > 10 %% slower")
    a = p.parse_args()
    threads = a.threads or os.cpu_count() or 1
    paper = usar.Scenario.load(str(PAPER))
    common = ["--trials", str(a.trials), "--duration", str(a.duration), "--threads", str(threads)]
    cli_s, py_s = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(a.repeats):
            out = pathlib.Path(tmp)
            t, _ = timed(lambda: subprocess.run(
                [cli_binary(), "sweep", str(PAPER), *common, "--quiet", "--out",
                 str(out / f"cli{i}")], check=True, capture_output=True))
            cli_s.append(t)
            t, _ = timed(lambda: usar.sweep(paper, trials=a.trials, duration_s=a.duration,
                                           threads=threads, out=out / f"py{i}", progress=False))
            py_s.append(t)
    ratio = min(py_s) / min(cli_s)
    print(f"paper.ron, 4 methods x {a.trials} trials x {a.duration:g} s, {threads} threads")
    print(f"CLI sweep   : best {min(cli_s):.2f} s of {', '.join(f'{x:.2f}' for x in cli_s)}")
    print(f"Python sweep: best {min(py_s):.2f} s of {', '.join(f'{x:.2f}' for x in py_s)}")
    print(f"Python / CLI: {ratio:.3f} ({(ratio - 1) * 100:+.1f} %)")

    eng_s, df_eng = timed(lambda: usar.sweep(paper, methods=["eng"], trials=a.trials,
                                             duration_s=a.duration, threads=threads,
                                             progress=False))
    py_eng_s, df_py = timed(lambda: usar.sweep(paper, methods=[SameAsEng()], trials=a.trials,
                                               duration_s=a.duration, threads=threads,
                                               progress=False))
    same = (df_eng["value"].fillna(-1).values == df_py["value"].fillna(-1).values).all()
    # The Python side of each call, under the GIL: the request built, then the method.
    spent = time_requests()
    SameAsEng.calls = 0
    t0 = time.perf_counter()
    usar.sweep(paper, methods=[SameAsEng()], trials=a.trials, duration_s=a.duration,
               threads=1, progress=False)
    one_thread_s = time.perf_counter() - t0
    calls = max(SameAsEng.calls, 1)
    print(f"Python method: ENG {eng_s:.2f} s, the same answer from Python {py_eng_s:.2f} s "
          f"(same numbers: {bool(same)}); {calls} calls on 1 thread, "
          f"{spent[0] / calls * 1e3:.3f} ms per call building the request, "
          f"{one_thread_s:.2f} s for that sweep")
    if a.check and ratio > 1.10:
        print("error: the Python sweep is more than 10 % slower than the CLI", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
