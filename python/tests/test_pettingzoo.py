"""usar.pettingzoo: PettingZoo's API and seed tests, seeded episodes, action masks, the team
reward equal to the Gymnasium environment's, RNE trust in the observation, bad actions."""

import warnings

import numpy as np
import pytest

pytest.importorskip("gymnasium")
pettingzoo = pytest.importorskip("pettingzoo")

import usar  # noqa: E402
import usar.gym  # noqa: E402
import usar.pettingzoo as upz  # noqa: E402
from pettingzoo.test import api_test, parallel_api_test, parallel_seed_test  # noqa: E402

# paper-v1.ron: its rounds start with every robot back, as usar.gym.GroupingEnv needs today.
SCENARIO = str(usar.scenario_path("paper-v1.ron"))
DURATION = 120.0


def make(**kwargs):
    kwargs.setdefault("duration_s", DURATION)
    return upz.parallel_env(SCENARIO, **kwargs)


def policy(seed):
    """A deterministic random policy: a generator of joint actions."""
    rng = np.random.default_rng(seed)
    return lambda agents, k: {a: int(rng.integers(k)) for a in agents}


def episode(e, seed, act_seed=0):
    """Observations, rewards and infos of one episode of `e` under a fixed random policy."""
    pick = policy(act_seed)
    obs, infos = e.reset(seed=seed)
    trace = [(obs, None, infos)]
    while e.agents:
        obs, rew, term, trunc, infos = e.step(pick(e.agents, len(e.task_names)))
        kept = {a: {k: v for k, v in i.items() if k != "result"} for a, i in infos.items()}
        trace.append((obs, rew, kept))
    return trace


def same(a, b):
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (tuple, list)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, np.ndarray):
        return a.dtype == b.dtype and np.array_equal(a, b)
    return a == b


def test_parallel_api_test_passes():
    e = make()
    with warnings.catch_warnings():
        # The API test resets with options={"options": 1}: ignored with a warning.
        warnings.simplefilter("ignore", UserWarning)
        parallel_api_test(e, num_cycles=50)
    e.close()


def test_seed_test_and_aec_api_test_pass():
    parallel_seed_test(lambda: make(), num_cycles=20)
    e = upz.env(scenario=SCENARIO, duration_s=DURATION)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        api_test(e, num_cycles=50)
    e.close()


def test_agents_spaces_and_observation_layout():
    e = make()
    assert e.possible_agents == (
        [f"carrier_{i}" for i in range(6)]
        + [f"supplier_{i}" for i in range(4)]
        + [f"observer_{i}" for i in range(2)]
    )
    assert [e.robot_of[a] for a in e.possible_agents] == list(range(12))
    space = e.observation_space("carrier_0")
    assert space.dtype == np.float32
    assert np.all(np.isfinite(space.low)) and np.all(np.isfinite(space.high))
    assert space.shape == (3 + 1 + 1 + 7 + 2 + 1 + 1 + 12,)
    assert e.action_space("observer_1").n == 2
    f = e.observation_fields
    obs, infos = e.reset(seed=7)
    gobs = e.gym_env._obs
    for agent, o in obs.items():
        i = e.robot_of[agent]
        assert o in space
        assert np.argmax(o[f["kind"]]) == gobs["kind"][i]
        np.testing.assert_allclose(o[f["energy_pct"]], gobs["energy_pct"][i], rtol=1e-6)
        np.testing.assert_allclose(o[f["needs"]], gobs["needs"][i], rtol=1e-6)
        np.testing.assert_allclose(
            o[f["distance_to_goal_m"]], gobs["distance_to_goal_m"][i], rtol=1e-6
        )
        assert o[f["available"]][0] == 1.0
        assert o[f["time_s"]][0] == 0.0
        assert infos[agent]["robot_id"] == i and infos[agent]["seed"] == e._info["seed"]
    e.close()


def test_trust_is_the_packages_rne_trust_of_the_needs():
    e = make()
    obs, _ = e.reset(seed=3)
    f = e.observation_fields
    weights = list(e.scenario.get("needs_weights").values())
    for a in ("carrier_0", "supplier_2", "observer_1"):
        trust = obs[a][f["trust"]]
        assert trust[e.robot_of[a]] == 0.0
        for b in e.possible_agents:
            if b != a:
                needs = e.gym_env._obs["needs"]
                want = usar.trust(weights, needs[e.robot_of[a]], needs[e.robot_of[b]])
                assert trust[e.robot_of[b]] == pytest.approx(want, rel=1e-5, abs=1e-7)
    # Trust is not symmetric (relative entropy), and robots of a kind trust each other more
    # (lower RNE) than they trust an observer.
    t = np.stack([obs[a][f["trust"]] for a in e.possible_agents])
    assert not np.allclose(t, t.T)
    assert t[0, 1] < t[0, 10]
    e.close()


def test_observations_stay_in_bounds_without_clipping():
    e = make()
    f = e.observation_fields
    space = e.observation_space("carrier_0")
    pick = policy(1)
    for seed in range(3):
        obs, _ = e.reset(seed=seed)
        while True:
            g = e.gym_env._obs
            for a, o in obs.items():
                i = e.robot_of[a]
                assert o in space
                # The bounds are the scenario's: the clip leaves every value as it was.
                for key in ("energy_pct", "hp_pct", "needs", "distance_to_goal_m"):
                    np.testing.assert_array_equal(o[f[key]], np.float32(g[key][i]))
                assert o[f["time_s"]][0] == np.float32(g["time_s"][0]) < DURATION + 1.0
                assert np.all(o[f["trust"]] < upz.TRUST_HIGH_NATS)
            assert e.state().shape == e.state_space.shape and e.state() in e.state_space
            if not e.agents:
                break
            obs, *_ = e.step(pick(e.agents, 2))
    e.close()


def test_seeded_episodes_repeat_and_differ_by_seed():
    a, b = make(), make()
    ta, tb = episode(a, 11), episode(b, 11)
    assert len(ta) == len(tb) >= 3
    assert all(same(x, y) for x, y in zip(ta, tb))
    tc = episode(b, 12)
    assert not same(ta[0][0], tc[0][0])
    a.close()
    b.close()


def test_team_reward_equals_the_gym_envs_reward():
    e = make(duration_s=300.0)
    g = usar.gym.GroupingEnv(SCENARIO, duration_s=300.0)
    pick = policy(5)
    obs, _ = e.reset(seed=4)
    g.reset(seed=4)
    total, rounds = 0.0, 0
    while e.agents:
        actions = pick(e.agents, 2)
        joint = [actions[a] for a in e.possible_agents]
        _, rew, term, trunc, infos = e.step(actions)
        _, grew, gterm, _, ginfo = g.step(joint)
        assert set(rew.values()) == {grew}
        assert all(v == gterm for v in term.values()) and not any(trunc.values())
        total += grew
        rounds += 1
        for a, info in infos.items():
            assert e.robot_of[a] in ginfo["groups"][info["task"]]
            assert info["moved"] == (info["task"] != actions[a])
    assert rounds > 2 and total > 0
    assert e.agents == []
    assert e.result is not None and all(i["result"] is e.result for i in infos.values())
    assert sum(e.result.rescued) == total
    with pytest.raises(RuntimeError, match="reset"):
        e.step({})
    e.close()
    g.close()


def test_action_mask_follows_the_kinds_quotas():
    s = usar.Scenario.load(SCENARIO).update({"kinds[2].quota.hard": 2, "kinds[2].quota.easy": 0})
    e = upz.parallel_env(s, duration_s=60.0)
    hard = s.task_names.index("hard")
    _, infos = e.reset(seed=1)
    for a, info in infos.items():
        mask = info["action_mask"]
        assert mask.dtype == np.int8 and mask.shape == (2,)
        if a.startswith("observer"):
            assert mask.tolist() == [int(t == hard) for t in range(2)]
        else:
            assert mask.tolist() == [1, 1]
    # An observer that asks for the task its kind has no room in is moved to the other.
    actions = {a: 1 - hard for a in e.agents}
    _, _, _, _, infos = e.step(actions)
    assert infos["observer_0"]["task"] == hard and infos["observer_0"]["moved"]
    # Sampling with the mask only picks the allowed task.
    space = e.action_space("observer_0")
    space.seed(0)
    assert {space.sample(infos["observer_0"]["action_mask"]) for _ in range(20)} == {hard}
    e.close()


@pytest.mark.parametrize(
    "bad, agent, match",
    [
        (2, "supplier_1", "supplier_1.*out of range"),
        (-1, "carrier_0", "carrier_0.*out of range"),
        (0.7, "observer_0", "observer_0.*expected a task id"),
        ("0", "carrier_3", "carrier_3.*expected a task id"),
        (True, "carrier_5", "carrier_5.*expected a task id"),
        (np.array([0, 1]), "supplier_0", "supplier_0.*expected a task id"),
    ],
)
def test_bad_action_names_the_agent_and_keeps_the_episode(bad, agent, match):
    e = make()
    e.reset(seed=2)
    actions = {a: 0 for a in e.agents}
    actions[agent] = bad
    with pytest.raises(ValueError, match=match):
        e.step(actions)
    actions[agent] = np.int64(1)
    _, rew, term, _, infos = e.step(actions)
    assert set(term) == set(e.possible_agents) and infos[agent]["round"] == 1
    e.close()


def test_missing_or_unknown_agent_is_refused():
    e = make()
    e.reset(seed=2)
    actions = {a: 0 for a in e.agents}
    del actions["observer_1"]
    with pytest.raises(ValueError, match="no action for agent 'observer_1'"):
        e.step(actions)
    with pytest.raises(ValueError, match="unknown agent 'robot_99'"):
        e.step({**{a: 0 for a in e.agents}, "robot_99": 0})
    with pytest.raises(TypeError, match="actions"):
        e.step([0] * 12)
    e.step({a: 0 for a in e.agents})
    e.close()


def test_arguments_checked():
    with pytest.raises(ValueError, match="render_mode"):
        make(render_mode="ansi")
    with pytest.raises(ValueError, match="reward"):
        make(reward="all")
    e = make()
    with pytest.warns(UserWarning, match="options: unknown keys \\['speed'\\]"):
        e.reset(seed=1, options={"speed": 2})
    e.close()


def test_default_scenario_runs():
    e = upz.parallel_env(duration_s=30.0)
    obs, _ = e.reset(seed=0)
    assert len(obs) == 12 and e.scenario.name == e.gym_env.scenario.name
    e.close()


def test_robots_away_under_available_rounds():
    """paper.ron's rounds group the robots available: an agent away has available 0, the
    least trust towards the others and from them, and no task. Its robots start near the
    low-energy line (30 %) so that some rest at the start of a round."""
    paper = usar.Scenario.load(str(usar.scenario_path("paper.ron"))).update(
        {"mission.initial_energy.mean_pct": 32.0, "mission.initial_energy.std_dev_pct": 3.0}
    )
    try:
        e = upz.parallel_env(paper, duration_s=600.0)
    except ValueError as err:
        pytest.skip(f"GroupingEnv does not take paper.ron yet: {err}")
    f = e.observation_fields
    obs, infos = e.reset(seed=0)
    away_seen = 0
    while e.agents:
        away = [a for a in e.agents if not infos[a]["available"]]
        for a in e.agents:
            o = obs[a]
            assert o[f["available"]][0] == float(infos[a]["available"])
            trust = o[f["trust"]]
            assert trust[e.robot_of[a]] == 0.0
            for b in away:
                if b != a:
                    assert trust[e.robot_of[b]] == upz.TRUST_HIGH_NATS
        for a in away:
            assert np.all(np.delete(obs[a][f["trust"]], e.robot_of[a]) == upz.TRUST_HIGH_NATS)
        before = away
        obs, _, _, _, infos = e.step({a: 0 for a in e.agents})
        for a in before:
            assert infos[a]["task"] == -1 and not infos[a]["moved"]
        away_seen += len(before)
    assert away_seen > 0
    e.close()


def test_render_is_the_gym_envs_picture():
    if "rgb_array" not in upz.GroupingParallelEnv.metadata["render_modes"]:
        pytest.skip("GroupingEnv has no render modes yet")
    if not hasattr(usar._usar, "rasterize_svg"):
        pytest.skip("the native module predates its rasteriser (rebuild with maturin)")
    e = make(render_mode="rgb_array", duration_s=60.0)
    assert e.render_mode == "rgb_array"
    e.reset(seed=0)
    e.step({a: 0 for a in e.agents})
    picture = e.render()
    assert picture.dtype == np.uint8 and picture.ndim == 3 and picture.shape[2] == 3
    np.testing.assert_array_equal(picture, e.gym_env.render())
    e.close()
    plain = make()
    assert plain.render() is None
    plain.close()
