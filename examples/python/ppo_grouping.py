"""Train stable-baselines3's PPO in usar.gym.GroupingEnv ("usar/Grouping-v0", paper.ron), then
compare the trained policy with RNE and HP_DIS on the sweep's trials it never saw
(usar.gym.evaluate: the policy as a grouping method, the paired verdicts).

Optional: stable-baselines3 and torch are not dependencies of the package, and CI does not run
this example. The observation stays the environment's Dict, each box scaled to [0, 1] by its
bounds (Scaled below), for SB3's MultiInputPolicy; the action is the MultiDiscrete task of each
robot. SB3's plain PPO does not mask actions: it ignores info["action_mask"] and the
environment repairs every action to the round's quotas (info["moved"] counts the robots it
moved; the mean is printed). sb3-contrib's MaskablePPO would read a mask through an
action_masks() method; this example does not use it.

Training trials are drawn by reset(seed=SEED) and the unseeded resets after it (never the
sweep's trials, usar.gym.HELD_OUT_TRIALS); the comparison runs on the sweep's trials 0 to
TRIALS - 1.

    pip install numpy pandas gymnasium stable-baselines3 torch   # and the usar package
    python examples/python/ppo_grouping.py                        # 10,240 steps (minutes)
    python examples/python/ppo_grouping.py --steps 128 --trials 2 --duration 60   # seconds
"""

import argparse
import time

import gymnasium
import numpy as np

try:
    import torch
    from stable_baselines3 import PPO
except ImportError as e:  # the message is the point
    raise SystemExit(f"this example needs stable-baselines3 and torch ({e}): "
                     "pip install stable-baselines3 torch") from e

import usar  # noqa: E402
import usar.gym  # noqa: E402


class Scaled(gymnasium.ObservationWrapper):
    """The environment's Dict observation with every Box scaled to [0, 1] by its finite bounds
    (usar.gym.observation_space); MultiBinary and MultiDiscrete entries stay as they are (SB3
    one-hot encodes them). ``scale`` is also applied to the observations of the evaluation."""

    def __init__(self, env):
        super().__init__(env)
        self.bounds = {
            k: (s.low, s.high) for k, s in env.observation_space.spaces.items()
            if isinstance(s, gymnasium.spaces.Box)
        }
        spaces = dict(env.observation_space.spaces)
        for k, (low, _) in self.bounds.items():
            spaces[k] = gymnasium.spaces.Box(0.0, 1.0, low.shape, np.float32)
        self.observation_space = gymnasium.spaces.Dict(spaces)

    def scale(self, obs):
        """``obs`` with each Box entry mapped to (x - low) / (high - low), clipped to [0, 1]."""
        out = dict(obs)
        for k, (low, high) in self.bounds.items():
            out[k] = np.clip((obs[k] - low) / np.maximum(high - low, 1e-6), 0.0, 1.0)
            out[k] = out[k].astype(np.float32)
        return out

    def observation(self, obs):
        return self.scale(obs)


class Moves(gymnasium.Wrapper):
    """Counts the steps and the robots the environment's repair moved (info["moved"])."""

    def __init__(self, env):
        super().__init__(env)
        self.steps = self.moved = 0

    def step(self, action):
        obs, reward, terminated, truncated, info = self.env.step(action)
        self.steps += 1
        self.moved += int(info.get("moved", 0))
        return obs, reward, terminated, truncated, info


def main():
    p = argparse.ArgumentParser(description="PPO-trained grouping against RNE and HP_DIS")
    p.add_argument("--steps", type=int, default=10_240, help="training steps (grouping rounds)")
    p.add_argument("--n-steps", type=int, default=512, help="PPO rollout length per update")
    p.add_argument("--duration", type=float, default=None, help="simulated seconds (600)")
    p.add_argument("--trials", type=int, default=10, help="comparison trials per method")
    p.add_argument("--seed", type=int, default=2021)
    a = p.parse_args()

    torch.set_num_threads(1)  # one core; the trials run between the network's updates
    start = time.perf_counter()
    moves = Moves(gymnasium.make(usar.gym.ENV_ID, duration_s=a.duration))
    env = Scaled(moves)
    n_steps = max(8, min(a.n_steps, a.steps))
    model = PPO("MultiInputPolicy", env, n_steps=n_steps, batch_size=min(64, n_steps),
                learning_rate=3e-4, gamma=0.99, ent_coef=0.01, seed=a.seed, verbose=0)
    model.learn(total_timesteps=a.steps)
    train_s = time.perf_counter() - start
    episodes = [float(e["r"]) for e in model.ep_info_buffer]  # SB3's Monitor: the last 100
    print(f"trained {model.num_timesteps} steps in {train_s:.0f} s; robots moved by the repair: "
          f"{moves.moved / max(moves.steps, 1):.2f} a step")
    if episodes:
        print(f"mean return of the last {len(episodes)} training episodes: "
              f"{np.mean(episodes):.1f}")
    env.close()

    def policy(obs):
        return model.predict(env.scale(obs), deterministic=True)[0]

    df, verdicts = usar.gym.evaluate(policy, trials=a.trials, methods=("rne", "hp_dis"),
                                     name="ppo", duration_s=a.duration)
    rescued = df[(df.metric == "rescued") & (df.task == "total")]
    for method, values in rescued.groupby("method", sort=False)["value"]:
        print(f"{method}: {values.mean():.1f} ± {values.std():.1f} rescuees a trial "
              f"({len(values)} held-out trials)")
    for v in verdicts.itertuples():
        print(f"{v.method} > {v.rival}: {v.mean_method:.1f} against {v.mean_rival:.1f}, "
              f"{v.test} p = {v.p_value:.4f}, effect size {v.effect_size:.2f}, {v.verdict}")
    print(f"took {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
