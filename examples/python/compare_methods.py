"""Compare the paper's four grouping methods (RNE, DIS, ENG, HP_DIS) and one written in Python
on scenarios/paper.ron, and draw the rescuees per method (a matplotlib figure).

    pip install ./python matplotlib
    python examples/python/compare_methods.py                  # 10 trials x 600 s (minutes)
    python examples/python/compare_methods.py --duration 60 --trials 2   # seconds (CI)

USAR_EXAMPLE_DURATION=60 sets the default duration too (CI runs it so).
"""

import argparse
import os
import pathlib

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402

import usar  # noqa: E402

PAPER = pathlib.Path(__file__).resolve().parents[2] / "scenarios" / "paper.ron"


def most_hp_first(request):
    """A grouping method in Python: per kind, the robots with the most HP take the hardest
    task first (ties by energy)."""
    groups = {t.name: [] for t in request.tasks}
    for kind in {r.kind for r in request.robots}:
        robots = sorted(request.robots_of_kind(kind), key=lambda r: (-r.hp_pct, -r.energy_pct))
        for task in sorted(request.tasks, key=lambda t: t.rank):
            n = task.quotas[kind]
            groups[task.name] += [r.id for r in robots[:n]]
            robots = robots[n:]
    return groups


def main():
    env = os.environ.get("USAR_EXAMPLE_DURATION")
    p = argparse.ArgumentParser(description="RNE, DIS, ENG, HP_DIS and a Python method")
    p.add_argument("--duration", type=float, default=float(env) if env else None,
                   help="simulated seconds per trial (default: the scenario's 600 s)")
    p.add_argument("--trials", type=int, default=10)
    p.add_argument("--figure", default="rescuees.png")
    a = p.parse_args()

    df = usar.sweep(str(PAPER), methods=[*usar.METHOD_NAMES, most_hp_first],
                    trials=a.trials, duration_s=a.duration)
    total = df[(df.metric == "rescued") & (df.task == "total")]
    stats = total.groupby("method", sort=False)["value"].agg(["mean", "std"])
    print(stats.round(2).to_string())

    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.bar(stats.index, stats["mean"], yerr=stats["std"].fillna(0), capsize=4)
    ax.set_ylabel("rescuees per trial (mean, sd)")
    ax.set_title(f"paper.ron, {a.trials} trials" + (f" x {a.duration:g} s" if a.duration else ""))
    fig.tight_layout()
    fig.savefig(a.figure, dpi=120)
    print(f"wrote {a.figure}")


if __name__ == "__main__":
    main()
