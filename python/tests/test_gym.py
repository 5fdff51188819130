"""usar.gym.GroupingEnv on the paper scenario (paper.ron, rounds of the robots available):
Gymnasium's checks, seeding apart from the sweep's trials, vector envs, checked actions,
seeded episodes equal to usar.run under the same groups, copies, pictures, a clean exit, and
a policy as a grouping method evaluated against the built-ins."""

import copy
import gc
import pickle
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

import usar  # noqa: E402
import usar.gym  # noqa: E402
from gymnasium.utils.env_checker import check_env  # noqa: E402

PAPER = usar.scenario_path("paper.ron")
PAPER_V1 = usar.scenario_path("paper-v1.ron")
DURATION = 120.0
BASE_SEED = usar.Scenario.load(PAPER).check()["seed"]


def env(**kw):
    return usar.gym.GroupingEnv(PAPER, duration_s=kw.pop("duration_s", DURATION), **kw)


def most_energy_hardest(obs, e):
    """A deterministic policy: per kind, the available robots with the most energy take the
    hardest task's places, the rest the next task's (every quota met)."""
    action = np.zeros(len(obs["kind"]), dtype=np.int64)
    for k in range(obs["quotas"].shape[0]):
        ids = [int(i) for i in np.flatnonzero((obs["kind"] == k) & (obs["available"] == 1))]
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
    rewards, groups, infos = [], [], [info]
    while True:
        obs, reward, terminated, truncated, info = e.step(policy(obs, e))
        assert not truncated
        rewards.append(reward)
        groups.append(info["groups"])
        infos.append(info)
        assert info["moved"] == 0
        if terminated:
            return rewards, groups, info["result"], infos


def test_make_with_no_argument_runs_the_paper_scenario_and_checker_passes():
    e = gymnasium.make(usar.gym.ENV_ID)
    assert e.unwrapped.scenario == usar.Scenario.load(PAPER)
    assert e.unwrapped.scenario.check()["mission"]["round_start"] == "Available"
    e.close()
    e = gymnasium.make(usar.gym.ENV_ID, duration_s=60.0, render_mode="rgb_array")
    check_env(e.unwrapped)
    e.close()


def test_observations_are_float32_within_finite_bounds_and_keep_their_keys():
    e = env()
    space = e.observation_space
    assert set(space.spaces) >= {
        "kind", "available", "energy_pct", "hp_pct", "position_m", "needs",
        "distance_to_goal_m", "quotas", "time_s", "rescued_so_far",
    }
    for key, sub in space.spaces.items():
        if isinstance(sub, gymnasium.spaces.Box):
            assert sub.dtype == np.float32, key
            assert np.all(np.isfinite(sub.low)) and np.all(np.isfinite(sub.high)), key
    obs, info = e.reset(seed=5)
    partial = False
    for _ in range(20):
        assert space.contains(obs)
        assert list(info["task_order"]) == e.task_order
        mask = info["action_mask"]
        assert mask.shape == (12, 2) and mask.dtype == bool
        # A robot not available this round: only task 0 offered, its values zero.
        off = np.flatnonzero(obs["available"] == 0)
        partial |= off.size > 0
        assert np.all(mask[off] == [True, False])
        assert np.all(obs["energy_pct"][off] == 0)
        # Quotas are this round's: they add up, per kind, to the robots available.
        for k in range(3):
            assert obs["quotas"][k].sum() == np.sum((obs["kind"] == k) & (obs["available"] == 1))
        obs, _, terminated, _, info = e.step(most_energy_hardest(obs, e))
        assert info["dt_s"] > 0
        if terminated:
            obs, info = e.reset()
    # paper.ron's rounds do group part of the team at times.
    assert partial
    e.close()


def test_seeding_draws_new_trials_apart_from_the_sweeps_held_out_ones():
    held_out = {usar.gym.trial_seed(BASE_SEED, k) for k in range(10)}
    # The documented mix is the library's: usar.run(trial=k) runs its seed.
    for k in (0, 3, 5):
        assert usar.run(PAPER, "rne", trial=k, duration_s=10.0).seed == usar.gym.trial_seed(BASE_SEED, k)
    e = env(duration_s=10.0)
    _, info = e.reset(seed=1)
    seeds = [int(info["seed"])]
    for _ in range(20):
        _, info = e.reset()
        assert info["trial"] == -1
        seeds.append(int(info["seed"]))
    assert len(set(seeds[1:])) >= 18
    assert not held_out & set(seeds)
    # The same seed gives the same draws; an unseeded fresh env is not trial 0.
    _, again = e.reset(seed=1)
    assert int(again["seed"]) == seeds[0]
    fresh = env(duration_s=10.0)
    _, info = fresh.reset()
    assert int(info["seed"]) not in held_out
    # The sweep's trials by option, refused with a seed; unknown options refused.
    _, info = e.reset(options={"trial": 3})
    assert (info["trial"], int(info["seed"])) == (3, usar.gym.trial_seed(BASE_SEED, 3))
    with pytest.raises(ValueError, match="options: 'trial'"):
        e.reset(seed=1, options={"trial": 3})
    with pytest.raises(ValueError, match="unknown option 'trail'"):
        e.reset(options={"trail": 3})
    e.close()
    fresh.close()


def test_trial_seed_is_the_librarys_and_checks_its_arguments():
    # splitmix64's first output from the state 0.
    assert usar.gym.trial_seed(0, 0) == 0xE220A8397B1DCDAF
    # Another base seed, near 2**64 so that base + trial wraps: usar.run reports the same.
    base = 2**64 - 2
    other = usar.Scenario.load(PAPER).set("sim.seed", base)
    for k in (0, 1, 2, 9):
        assert usar.run(other, "rne", trial=k, duration_s=5.0).seed == usar.gym.trial_seed(base, k)
    assert usar.gym.trial_seed(np.uint64(base), np.int32(2)) == usar.gym.trial_seed(base, 2)
    for args, error, name in [
        ((-1, 0), ValueError, "base_seed"),
        ((2**64, 0), ValueError, "base_seed"),
        ((0, -1), ValueError, "trial"),
        ((0, 2**32), ValueError, "trial"),
        ((1.0, 0), TypeError, "base_seed"),
        ((True, 0), TypeError, "base_seed"),
        ((0, "3"), TypeError, "trial"),
        ((0, None), TypeError, "trial"),
    ]:
        with pytest.raises(error, match=f"^{name}"):
            usar.gym.trial_seed(*args)


def test_a_drawn_seed_is_redrawn_when_it_is_a_held_out_trials(monkeypatch):
    e = env(duration_s=10.0)
    e.reset(seed=4)
    first = int(e.np_random.integers(0, 2**63, dtype=np.int64))
    e.reset(seed=4)
    monkeypatch.setattr(e, "_held_out", frozenset({first}))
    e.reset(seed=4)
    _, info = e.reset(seed=4)
    assert int(info["seed"]) != first
    e.close()


@pytest.mark.parametrize("kind", ["sync", "async"])
def test_vector_envs_run_trials_0_to_9_by_option_and_by_auto_reset_and_close(kind):
    make = lambda: usar.gym.GroupingEnv(PAPER, duration_s=60.0)  # noqa: E731
    cls = gymnasium.vector.SyncVectorEnv if kind == "sync" else gymnasium.vector.AsyncVectorEnv
    v = cls([make, make])
    try:
        for k in range(10):
            _, info = v.reset(options={"trial": k})
            assert list(info["seed"]) == [str(usar.gym.trial_seed(BASE_SEED, k))] * 2
            v.step(v.action_space.sample())
        v.reset(seed=0)
        seen = set()
        for _ in range(40):
            _, _, terminated, _, info = v.step(v.action_space.sample())
            seen.update(int(s) for s in info["seed"])
        # Auto-reset drew trials of its own: more than the two first, none held out.
        assert len(seen) > 2
        assert not seen & {usar.gym.trial_seed(BASE_SEED, k) for k in range(10)}
    finally:
        v.close()


def test_actions_are_checked_and_the_episode_stays_intact():
    e = env()
    obs, _ = e.reset(seed=11)
    good = most_energy_hardest(obs, e)
    bad = [
        (np.full(12, 2), "task 2"),
        (np.full(12, -1), "task -1"),
        (np.zeros((12, 2), dtype=np.int64), r"shape \(12,\)"),
        (np.zeros(17, dtype=np.int64), r"shape \(12,\)"),
        (np.zeros(5, dtype=np.int64), r"shape \(12,\)"),
        (np.full(12, 0.7), "integer"),
        (np.zeros(12), "integer"),
        (["0"] * 12, "integer"),
        ("0" * 12, "string"),
        ([5] * 12, "task 5"),
        (np.zeros(12, dtype=bool), "integer"),
    ]
    for action, words in bad:
        with pytest.raises(ValueError, match="action: .*" + words):
            e.step(action)
    obs2, reward, terminated, _, info = e.step(good)
    assert info["round"] == 1 and info["moved"] == 0 and not terminated
    e.close()


def test_an_action_that_breaks_a_quota_is_repaired_and_unavailable_robots_ignored():
    kinds = [0, 0, 0, 1, 1]
    quotas = [[2, 1], [1, 1]]
    groups, moved = usar.gym.repair_assignment([0, 1, 0, 1, 0], kinds, quotas, [0, 1])
    assert (groups, moved) == ([[0, 2, 4], [1, 3]], 0)
    # Robot 2 asks for task 0, whose room for kind 0 is gone: it goes to task 1.
    groups, moved = usar.gym.repair_assignment([0, 0, 0, 1, 1], kinds, quotas, [0, 1])
    assert (groups, moved) == ([[0, 1, 4], [2, 3]], 2)
    # Robots not available are left out, whatever they ask for.
    groups, moved = usar.gym.repair_assignment(
        [0, 1, 1, 1, 0], kinds, [[1, 1], [1, 0]], [0, 1], available=[1, 1, 0, 0, 1]
    )
    assert (groups, moved) == ([[0, 4], [1]], 0)
    e = env()
    e.reset(seed=1)
    _, _, _, _, info = e.step(np.zeros(12, dtype=np.int64))
    assert info["moved"] > 0
    e.close()


def test_a_seeded_episode_equals_usar_run_under_the_same_groups():
    e = env()
    rewards, groups, result, infos = episode(e, seed=12345)
    seed = int(infos[0]["seed"])
    assert result.seed == seed and len(groups) >= 2
    again = usar.run(PAPER, method=gym(iter(groups)), seed=seed, duration_s=DURATION)
    assert again.to_dict() == result.to_dict()
    # The rewards are the rounds' rescuees; the steps' seconds add up to the trial's.
    assert sum(rewards) == sum(result.rescued)
    assert rewards == [sum(r.rescued) for r in result.rounds]
    assert sum(i["dt_s"] for i in infos[1:]) == pytest.approx(DURATION)
    # A trial by index, as usar.run(trial=...).
    _, groups3, result3, _ = episode(e, options={"trial": 3})
    again = usar.run(PAPER, method=gym(iter(groups3)), trial=3, duration_s=DURATION)
    assert again.to_dict() == result3.to_dict()
    e.close()


def test_a_scenario_whose_rounds_start_with_every_robot_back_still_runs():
    e = usar.gym.GroupingEnv(PAPER_V1, duration_s=DURATION)
    rewards, groups, result, infos = episode(e, seed=2)
    assert all(np.all(i["action_mask"]) for i in infos[:-1])
    again = usar.run(PAPER_V1, method=gym(iter(groups)), seed=int(infos[0]["seed"]),
                     duration_s=DURATION)
    assert again.to_dict() == result.to_dict()
    e.close()


def test_the_same_seed_and_actions_give_the_same_episode_and_other_seeds_another():
    a, b = env(), env()
    ra, ga, res_a, _ = episode(a, seed=7)
    rb, gb, res_b, _ = episode(b, seed=7)
    assert (ra, ga, res_a.to_dict()) == (rb, gb, res_b.to_dict())
    _, _, res_c, _ = episode(a, seed=8)
    assert res_c.to_dict() != res_a.to_dict()
    a.close()
    b.close()


def test_copies_and_pickles_continue_the_same_episode():
    e = env()
    obs, _ = e.reset(seed=21)
    obs, *_ = e.step(most_energy_hardest(obs, e))
    for twin in (copy.deepcopy(e), e.clone(), pickle.loads(pickle.dumps(e))):
        for key in obs:
            np.testing.assert_array_equal(twin._obs[key], obs[key])
        a = e.clone()
        ra = episode_rest(a, obs)
        rb = episode_rest(twin, obs)
        assert ra == rb
        # The generators are copies: the same next draw.
        assert twin.np_random.integers(1 << 30) == a.np_random.integers(1 << 30)
        twin.close()
        a.close()
    e.close()


def episode_rest(e, obs):
    total = []
    while True:
        obs, reward, terminated, _, info = e.step(most_energy_hardest(obs, e))
        total.append(reward)
        if terminated:
            return total, info["result"].to_dict()


def test_render_gives_the_arena_picture_and_replay_writes_the_episode(tmp_path):
    e = env(duration_s=60.0, render_mode="rgb_array")
    obs, _ = e.reset(seed=3)
    start = e.render()
    assert start.dtype == np.uint8 and start.ndim == 3 and start.shape[2] == 3
    assert start.shape[0] > 100 and start.shape[1] > 100
    # Not blank: walls are dark grey on white.
    assert start.min() < 100 and start.max() == 255
    groups = []
    while True:
        obs, _, terminated, _, info = e.step(most_energy_hardest(obs, e))
        groups.append(info["groups"])
        if terminated:
            break
    end = e.render()
    assert end.shape == start.shape and not np.array_equal(end, start)
    result = e.replay(tmp_path / "episode.html")
    assert (tmp_path / "episode.html").stat().st_size > 1000
    assert result.to_dict() == info["result"].to_dict()
    assert env().render() is None
    with pytest.raises(ValueError, match="render_mode"):
        env(render_mode="human")
    e.close()


def counting(monkeypatch, names, calls):
    """Replaces the native functions `names` with ones that append their name to `calls`."""
    for name in names:
        def call(*args, _real=getattr(usar._usar, name), _name=name, **kwargs):
            calls.append(_name)
            return _real(*args, **kwargs)

        monkeypatch.setattr(usar._usar, name, call)


def frame_of(svg_path):
    h, w, rgb = usar._usar.rasterize_svg(svg_path.read_text(encoding="utf-8"))
    return np.frombuffer(rgb, dtype=np.uint8).reshape(h, w, 3)


def test_render_draws_the_running_trials_paths_once_per_round_and_runs_no_trial(
    monkeypatch, tmp_path
):
    from usar._episode import Replayer

    # Rounds start at 0, 125 and 237 s: the frames of the second and third.
    e = env(duration_s=300.0, render_mode="rgb_array")
    obs, info = e.reset(seed=4)
    obs, _, terminated, _, step_info = e.step(most_energy_hardest(obs, e))
    groups = [step_info["groups"]]
    assert not terminated
    calls = []
    points = [(list(groups), e._request.time_s)]
    with monkeypatch.context() as m:
        counting(m, ["run_trial", "run_trial_logged", "render", "replay", "episode_svg"], calls)
        first = e.render()
        again = e.render()
        np.testing.assert_array_equal(first, again)
        # One picture drawn, from the running trial's paths: no trial ran.
        assert calls == ["episode_svg"]
        again[:] = 0  # each call gives a new array
        np.testing.assert_array_equal(e.render(), first)
        obs, _, terminated, _, step_info = e.step(most_energy_hardest(obs, e))
        assert not terminated
        after = e.render()
        assert calls == ["episode_svg"] * 2
    groups.append(step_info["groups"])
    points.append((list(groups), e._request.time_s))
    assert after.shape == first.shape and not np.array_equal(after, first)
    # Each is the picture of the trial run to that round's start with the same groups.
    for frame, (played, now) in zip((first, after), points):
        usar.render(PAPER, tmp_path / "ref.svg", method=Replayer(played),
                    seed=int(info["seed"]), duration_s=now)
        np.testing.assert_array_equal(frame, frame_of(tmp_path / "ref.svg"))
    # A copy draws the same picture: mid-episode (its trial replayed) and at the end (a copy
    # of an ended episode replays it for its picture).
    np.testing.assert_array_equal(copy.deepcopy(e).render(), after)
    # Closed mid-episode, before any frame: the paths to the round it stopped at.
    twin = e.clone()
    twin.close()
    np.testing.assert_array_equal(twin.render(), after)
    # Its replay page shows the same stretch: the trial to the round it stopped at.
    stopped = twin.replay(tmp_path / "stopped.html").to_dict()
    assert stopped["duration_s"] == pytest.approx(points[-1][1])
    # And a copy of it (no trial of its own: it replays to that round, not to the end).
    np.testing.assert_array_equal(copy.deepcopy(twin).render(), after)
    np.testing.assert_array_equal(pickle.loads(pickle.dumps(twin)).render(), after)
    while not terminated:
        obs, _, terminated, _, _ = e.step(most_energy_hardest(obs, e))
    end = e.render()
    np.testing.assert_array_equal(pickle.loads(pickle.dumps(e)).render(), end)
    e.close()


def test_close_and_reset_add_no_finalizer_and_no_thread():
    import weakref

    before = threading.active_count()
    e = env(duration_s=30.0)
    count = len(weakref.finalize._registry)
    for _ in range(30):
        e.reset()
    assert len(weakref.finalize._registry) == count
    assert threading.active_count() == before + 1
    e.close()
    assert threading.active_count() == before
    with pytest.raises(RuntimeError, match="reset"):
        e.step(e.action_space.sample())
    # Reset after close works.
    e.reset(seed=1)
    e.close()


def test_an_environment_dropped_mid_episode_ends_its_trial():
    before = threading.active_count()
    # A fixed action on the whole mission: the first round ends well before the trial does, so
    # the trial is still running after the step (a random action could make the first round
    # outlast a short trial, ending the episode and its thread).
    e = env(duration_s=None)
    obs, _ = e.reset(seed=2)
    _, _, terminated, _, _ = e.step(most_energy_hardest(obs, e))
    assert not terminated
    assert threading.active_count() == before + 1
    del e
    gc.collect()
    for _ in range(100):
        if threading.active_count() == before:
            break
        threading.Event().wait(0.02)
    assert threading.active_count() == before


@pytest.mark.parametrize("how", ["open", "mid-episode", "vector"])
def test_an_environment_left_open_exits_cleanly(how):
    body = {
        "open": "e = gymnasium.make('usar/Grouping-v0', duration_s=60.0); e.reset(seed=1)",
        "mid-episode": (
            "e = gymnasium.make('usar/Grouping-v0', duration_s=60.0); e.reset()\n"
            "e.step(e.action_space.sample())"
        ),
        "vector": (
            "v = gymnasium.vector.SyncVectorEnv([lambda: usar.gym.GroupingEnv(duration_s=60.0)]"
            " * 2); v.reset(seed=1)"
        ),
    }[how]
    code = "import gymnasium, usar, usar.gym\n" + body + "\nprint('ok')\n"
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, timeout=120)
    assert (done.returncode, done.stdout.strip()) == (0, "ok"), done.stderr
    assert "Fatal" not in done.stderr


def test_a_policy_as_a_method_sees_the_environments_observation():
    e = env()
    seen = []

    def policy(obs):
        seen.append(obs)
        return most_energy_hardest(obs, e)

    method = usar.gym.policy_method(policy, name="energy")
    result = usar.run(PAPER, method=method, trial=4, duration_s=DURATION)
    assert result.method == "energy"
    obs, _ = e.reset(options={"trial": 4})
    for key in obs:
        np.testing.assert_array_equal(seen[0][key], obs[key])
    _, groups, result_env, _ = episode(e, options={"trial": 4})
    assert [r.groups for r in result.rounds] == [r.groups for r in result_env.rounds]
    one = usar.sweep(PAPER, methods=[method], trials=3, threads=1, duration_s=60.0)
    two = usar.sweep(PAPER, methods=[method], trials=3, threads=2, duration_s=60.0)
    assert one.equals(two)

    class Model:  # stable-baselines3's face: predict(obs, deterministic) -> (action, state)
        def predict(self, obs, deterministic=False):
            return np.zeros(12, dtype=np.int64), None

    assert usar.run(PAPER, method=usar.gym.policy_method(Model()), trial=0,
                    duration_s=30.0).method == "policy"
    with pytest.raises(TypeError, match="policy"):
        usar.gym.policy_method(3)
    with pytest.raises(ValueError, match="action"):
        usar.run(PAPER, method=usar.gym.policy_method(lambda obs: [0.5] * 12), duration_s=30.0)
    e.close()


def test_evaluate_compares_the_policy_with_the_built_ins_on_held_out_trials():
    if not hasattr(usar, "compare"):
        pytest.skip("usar.compare is not in this build yet")
    e = env()
    trials_df, verdicts = usar.gym.evaluate(
        lambda obs: most_energy_hardest(obs, e), PAPER, trials=4, duration_s=60.0,
        name="energy",
    )
    assert sorted(trials_df.trial.unique()) == [0, 1, 2, 3]
    # Built-ins are named as the sweep's tables name them (RNE, HP_DIS).
    assert {m.lower() for m in trials_df.method.unique()} == {"energy", "rne", "hp_dis"}
    assert [r.lower() for r in verdicts.rival] == ["rne", "hp_dis"]
    assert set(verdicts.method) == {"energy"}
    assert {"p_value", "effect_size", "verdict", "test"} <= set(verdicts.columns)
    e.close()
