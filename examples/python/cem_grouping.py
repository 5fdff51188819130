"""Learn a grouping policy with the cross-entropy method in usar.gym.GroupingEnv, then compare
it with RNE and HP_DIS on the sweep's trials it never saw (usar.gym.evaluate: the policy as a
grouping method, the paired verdicts), and draw both (matplotlib).

The policy scores each robot for each task linearly, score = w_t . (energy, HP, distance to
the task's goal) / 100, and fills the tasks hardest first, each kind's places with its
highest-scoring available robots: every answer keeps the quotas. It reads the environment's
observation (usar.gym.observation), so usar.gym.policy_method runs it unchanged in a sweep. The cross-entropy method (Rubinstein
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

# The paper's mission (its rounds group the robots available: `round_start: Available`).
PAPER = usar.scenario_path("paper.ron")


def action_of(theta, obs, order):
    """The policy's action (the task of each robot, by id) for the observation ``obs``: per
    kind, the available robots ranked by each task's score fill the tasks hardest first
    (``order``), as many as this round's quota; robots not available keep task 0 (ignored)."""
    energy, hp, dist = obs["energy_pct"], obs["hp_pct"], obs["distance_to_goal_m"]
    kinds, quotas = obs["kind"], obs["quotas"]
    w = theta.reshape(dist.shape[1], 3)
    action = np.zeros(len(kinds), dtype=np.int64)
    for k in range(quotas.shape[0]):
        ids = list(np.flatnonzero((kinds == k) & (obs["available"] == 1)))
        for t in order:
            feats = np.stack([energy[ids], hp[ids], dist[ids, t]], axis=1) / 100.0
            score = feats @ w[t]
            ranked = [ids[i] for i in np.lexsort((ids, -score))]
            n = int(quotas[k][t])
            action[ranked[:n]] = t
            ids = [i for i in ids if i not in ranked[:n]]
    return action


def episode_return(env, theta, seed):
    """The return of one training episode: the trial drawn by ``reset(seed=seed)``, never one
    of the sweep's trials (usar.gym.HELD_OUT_TRIALS)."""
    obs, _ = env.reset(seed=seed)
    total = 0.0
    while True:
        obs, reward, terminated, _, _ = env.step(action_of(theta, obs, env.task_order))
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
        seeds = [seed + e for e in range(episodes)]
        scores = np.array([np.mean([episode_return(env, th, s) for s in seeds]) for th in thetas])
        best = thetas[np.argsort(-scores)[:elite]]
        mean, std = best.mean(axis=0), best.std(axis=0) + 0.05
        curve.append((float(scores.max()), float(np.sort(scores)[-elite:].mean())))
        print(f"iteration {it}: best mean rescuees {scores.max():.1f}, elite mean "
              f"{np.sort(scores)[-elite:].mean():.1f}")
    return mean, curve


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

    order = env.task_order
    df, verdicts = usar.gym.evaluate(lambda obs: action_of(theta, obs, order), PAPER,
                                     trials=a.trials, name="cem", duration_s=a.duration)
    total = df[(df.metric == "rescued") & (df.task == "total")]
    stats = total.groupby("method", sort=False)["value"].agg(["mean", "std"])
    print(stats.round(2).to_string())
    shown = ["method", "rival", "mean_method", "mean_rival", "p_value", "effect_size", "verdict"]
    print(verdicts[shown].round(4).to_string(index=False))
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
