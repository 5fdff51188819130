"""usar.gym.GroupingEnv: Gymnasium's checks, seeded episodes equal to usar.run under the same
groups, determinism, repairs of actions that break a quota, abandoned episodes."""

import pathlib

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

import usar  # noqa: E402
import usar.gym  # noqa: E402
from gymnasium.utils.env_checker import check_env  # noqa: E402

# paper-v1.ron: its rounds start with every robot back (`round_start: AllBack`), as the
# environment needs; paper.ron's rounds group the robots available (`Available`) and are refused.
PAPER = str(pathlib.Path(__file__).resolve().parents[2] / "scenarios" / "paper-v1.ron")
DURATION = 120.0


def env():
    return usar.gym.GroupingEnv(PAPER, duration_s=DURATION)


def most_energy_hardest(obs, e):
    """A deterministic policy: per kind, the robots with the most energy take the hardest
    task's places, the rest the next task's."""
    action = np.zeros(len(obs["kind"]), dtype=np.int64)
    for k in range(obs["quotas"].shape[0]):
        ids = [int(i) for i in np.flatnonzero(obs["kind"] == k)]
        ids.sort(key=lambda i: (-obs["energy_pct"][i], i))
        for t in e.task_order:
            n = int(obs["quotas"][k][t])
            for i in ids[:n]:
                action[i] = t
            ids = ids[n:]
    return action


def gym(answers):
    """A method answering `answers` in turn, named as the environment's (`gym`)."""

    def gym(request):
        return next(answers)

    return gym


def episode(e, seed=None, options=None, policy=most_energy_hardest):
    obs, info = e.reset(seed=seed, options=options)
    rewards, groups = [], []
    while True:
        obs, reward, terminated, truncated, info = e.step(policy(obs, e))
        assert not truncated
        rewards.append(reward)
        groups.append(info["groups"])
        assert info["moved"] == 0
        if terminated:
            return rewards, groups, info["result"]


def test_gymnasiums_checker_passes_on_the_registered_environment():
    e = gymnasium.make(usar.gym.ENV_ID, scenario=PAPER, duration_s=60.0)
    check_env(e.unwrapped, skip_render_check=True)
    e.close()


def test_a_seeded_episode_equals_usar_run_under_the_same_groups():
    e = env()
    rewards, groups, result = episode(e, seed=12345)
    assert len(groups) >= 2
    again = usar.run(PAPER, method=gym(iter(groups)), seed=12345, duration_s=DURATION)
    assert again.to_dict() == result.to_dict()
    # The rewards are the rounds' rescuees: they add up to the trial's.
    assert sum(rewards) == sum(result.rescued)
    per_round = [sum(r.rescued) for r in result.rounds]
    assert rewards == per_round
    # A trial by index, as usar.run(trial=...).
    rewards3, groups3, result3 = episode(e, options={"trial": 3})
    again = usar.run(PAPER, method=gym(iter(groups3)), trial=3, duration_s=DURATION)
    assert again.to_dict() == result3.to_dict()
    e.close()


def test_the_same_seed_and_actions_give_the_same_episode_and_other_seeds_another():
    a, b = env(), env()
    ra, ga, res_a = episode(a, seed=7)
    rb, gb, res_b = episode(b, seed=7)
    assert (ra, ga, res_a.to_dict()) == (rb, gb, res_b.to_dict())
    _, _, res_c = episode(a, seed=8)
    assert res_c.to_dict() != res_a.to_dict()
    a.close()
    b.close()


def test_a_policy_as_a_method_sweeps_the_same_on_one_and_two_threads():
    e = env()

    def method(request):
        obs = e._observation(request)
        groups, _ = usar.gym.repair_assignment(
            most_energy_hardest(obs, e), e._robot_kinds, request.quotas, request.hardest_first
        )
        return groups

    one = usar.sweep(PAPER, methods=[method], trials=3, threads=1, duration_s=60.0)
    two = usar.sweep(PAPER, methods=[method], trials=3, threads=2, duration_s=60.0)
    assert one.equals(two)
    e.close()


def test_an_action_that_breaks_a_quota_is_repaired_to_the_closest_that_keeps_them():
    kinds = [0, 0, 0, 1, 1]
    quotas = [[2, 1], [1, 1]]
    groups, moved = usar.gym.repair_assignment([0, 1, 0, 1, 0], kinds, quotas, [0, 1])
    assert (groups, moved) == ([[0, 2, 4], [1, 3]], 0)
    # Robot 2 asks for task 0, whose room for kind 0 is gone: it goes to task 1.
    groups, moved = usar.gym.repair_assignment([0, 0, 0, 1, 1], kinds, quotas, [0, 1])
    assert (groups, moved) == ([[0, 1, 4], [2, 3]], 2)
    # Out-of-range tasks are moved too.
    groups, moved = usar.gym.repair_assignment([9, 9, 9, 9, 9], kinds, quotas, [1, 0])
    assert moved == 5 and sorted(sum(groups, [])) == [0, 1, 2, 3, 4]
    e = env()
    e.reset(seed=1)
    _, _, _, _, info = e.step(np.zeros(12, dtype=np.int64))
    assert info["moved"] > 0
    e.close()


def test_an_abandoned_episode_ends_with_a_reset_or_close():
    e = env()
    e.reset(seed=3)
    e.step(e.action_space.sample())
    obs, info = e.reset(seed=3)
    assert info["round"] == 0 and info["seed"] == 3
    e.close()
    with pytest.raises(RuntimeError, match="reset"):
        e.step(e.action_space.sample())
    with pytest.raises(ValueError, match="reward"):
        usar.gym.GroupingEnv(PAPER, reward="fun")


def test_a_scenario_whose_rounds_group_part_of_the_team_is_refused():
    corridor = pathlib.Path(PAPER).parent / "corridor.ron"
    s = usar.Scenario.load(corridor).set("mission.round_start", "Available")
    with pytest.raises(ValueError, match="round_start is Available; GroupingEnv needs AllBack"):
        usar.gym.GroupingEnv(s)


def test_an_environment_dropped_mid_episode_ends_its_trial():
    import gc
    import threading

    before = threading.active_count()
    e = env()
    e.reset(seed=2)
    e.step(e.action_space.sample())
    assert threading.active_count() == before + 1
    del e
    gc.collect()
    for _ in range(100):
        if threading.active_count() == before:
            break
        threading.Event().wait(0.02)
    assert threading.active_count() == before
