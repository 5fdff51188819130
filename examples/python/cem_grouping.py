"""Learn a grouping policy with the cross-entropy method in usar.gym.GroupingEnv, then compare
it with RNE and HP_DIS in one sweep on trials it never saw, and draw both (matplotlib).

The policy scores each robot for each task linearly, score = w_t . (energy, HP, distance to
the task's goal) / 100, and fills the tasks hardest first, each kind's places with its
highest-scoring robots: every answer keeps the quotas. The cross-entropy method (Rubinstein
1999) draws weight vectors from a Gaussian, keeps the best (the elite, by mean rescuees over
training trials), refits the Gaussian to them and repeats. No other dependency than numpy.

    pip install "./python[gym,examples]"
    python examples/python/cem_grouping.py                        # the full form (minutes)
    python examples/python/cem_grouping.py --iterations 2 --population 4 --episodes 1 \
        --duration 60 --trials 2                                   # seconds (CI)
"""

import argparse
import pathlib
import time

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import usar  # noqa: E402
import usar.gym  # noqa: E402

# paper-v1.ron, the paper's mission before the authors' clock: its rounds start with every
# robot back (`round_start: AllBack`), as GroupingEnv needs; paper.ron's rounds group the robots
# available (`Available`), which the environment refuses.
PAPER = pathlib.Path(__file__).resolve().parents[2] / "scenarios" / "paper-v1.ron"
#: Training trials start here; the comparison's are 0, 1, ... (never seen in training).
TRAIN_TRIAL0 = 1000


def groups_of(theta, energy, hp, dist, kinds, quotas, order):
    """The policy's groups: robot ids per task (task order), quotas kept."""
    n_tasks = dist.shape[1]
    w = theta.reshape(n_tasks, 3)
    groups = [[] for _ in range(n_tasks)]
    for k in range(quotas.shape[0]):
        ids = list(np.flatnonzero(kinds == k))
        for t in order:
            feats = np.stack([energy[ids], hp[ids], dist[ids, t]], axis=1) / 100.0
            score = feats @ w[t]
            ranked = [ids[i] for i in np.lexsort((ids, -score))]
            n = int(quotas[k][t])
            groups[t] += [int(i) for i in ranked[:n]]
            ids = [i for i in ids if i not in ranked[:n]]
    return groups


def action_of(theta, obs, env):
    """The environment's action (the task of each robot) for the policy's groups."""
    groups = groups_of(theta, obs["energy_pct"], obs["hp_pct"], obs["distance_to_goal_m"],
                       obs["kind"], obs["quotas"], env.task_order)
    action = np.zeros(len(obs["kind"]), dtype=np.int64)
    for t, ids in enumerate(groups):
        action[ids] = t
    return action


def episode_return(env, theta, trial):
    obs, _ = env.reset(options={"trial": trial})
    total = 0.0
    while True:
        obs, reward, terminated, _, _ = env.step(action_of(theta, obs, env))
        total += reward
        if terminated:
            return total


def cem(env, iterations, population, elite, episodes, seed):
    """The cross-entropy method: returns the final mean and, per iteration, the best and the
    elite's mean return. Every candidate of every iteration is scored on the same training
    trials (common random numbers), so the curve shows the policy, not the trials."""
    rng = np.random.default_rng(seed)
    dim = 3 * len(env.task_names)
    mean, std = np.zeros(dim), np.ones(dim)
    curve = []
    for it in range(iterations):
        thetas = mean + std * rng.standard_normal((population, dim))
        trials = [TRAIN_TRIAL0 + e for e in range(episodes)]
        scores = np.array([np.mean([episode_return(env, th, k) for k in trials]) for th in thetas])
        best = thetas[np.argsort(-scores)[:elite]]
        mean, std = best.mean(axis=0), best.std(axis=0) + 0.05
        curve.append((float(scores.max()), float(np.sort(scores)[-elite:].mean())))
        print(f"iteration {it}: best mean rescuees {scores.max():.1f}, elite mean "
              f"{np.sort(scores)[-elite:].mean():.1f}")
    return mean, curve


class Learned(usar.GroupingMethod):
    """The learned policy as a grouping method, for usar.sweep."""

    name = "cem"

    def __init__(self, theta, order):
        self.theta, self.order = theta, order

    def group(self, request):
        arr = lambda f: np.array([f(r) for r in request.robots], dtype=float)  # noqa: E731
        dist = np.array([[r.distance_to_goal_m[t.name] for t in request.tasks] for r in request.robots])
        return groups_of(self.theta, arr(lambda r: r.energy_pct), arr(lambda r: r.hp_pct), dist,
                         np.array([r.kind_index for r in request.robots]),
                         np.array(request.quotas), self.order)


def main():
    p = argparse.ArgumentParser(description="CEM-trained grouping against RNE and HP_DIS")
    p.add_argument("--iterations", type=int, default=12)
    p.add_argument("--population", type=int, default=16)
    p.add_argument("--elite", type=int, default=4)
    p.add_argument("--episodes", type=int, default=3, help="training trials per candidate")
    p.add_argument("--duration", type=float, default=None, help="simulated seconds (600)")
    p.add_argument("--trials", type=int, default=10, help="comparison trials per method")
    p.add_argument("--seed", type=int, default=2021)
    p.add_argument("--figure", default="cem_grouping.png")
    a = p.parse_args()

    start = time.perf_counter()
    env = usar.gym.GroupingEnv(str(PAPER), duration_s=a.duration)
    theta, curve = cem(env, a.iterations, a.population, min(a.elite, a.population), a.episodes, a.seed)
    env.close()
    print("learned weights (energy, HP, distance per task):", np.round(theta, 3).tolist())

    df = usar.sweep(str(PAPER), methods=["rne", "hp_dis", Learned(theta, env.task_order)],
                    trials=a.trials, duration_s=a.duration)
    total = df[(df.metric == "rescued") & (df.task == "total")]
    stats = total.groupby("method", sort=False)["value"].agg(["mean", "std"])
    print(stats.round(2).to_string())
    print(f"took {time.perf_counter() - start:.0f} s")

    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.plot(range(len(curve)), [c[0] for c in curve], marker="o", label="best candidate")
    left.plot(range(len(curve)), [c[1] for c in curve], marker="s", label="elite mean")
    left.set_xlabel("CEM iteration")
    left.set_ylabel(f"mean rescuees ({a.episodes} training trials)")
    left.legend()
    right.bar(stats.index, stats["mean"], yerr=stats["std"].fillna(0), capsize=4)
    right.set_ylabel(f"rescuees per trial ({a.trials} unseen trials, mean ± sd)")
    fig.tight_layout()
    fig.savefig(a.figure, dpi=120)
    print("wrote", a.figure)


if __name__ == "__main__":
    main()
