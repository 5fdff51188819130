"""A PettingZoo environment for learned grouping: :func:`parallel_env`, one agent per robot,
each choosing its task every grouping round of one USAR trial.

Built on the Gymnasium environment :class:`usar.gym.GroupingEnv` by composition: the agents'
actions make its joint action (the task of each robot, by id), its observation and request
make each agent's observation, its reward is every agent's reward. Needs the optional
``pettingzoo`` dependency (``pip install "./python[pettingzoo]"``). See docs/python.md,
"A PettingZoo environment".
"""

from __future__ import annotations

import inspect
import math
import os
import warnings
from typing import Any, Dict, List, Mapping, Optional, Tuple, Union

import numpy as np

try:
    from gymnasium import spaces
    from pettingzoo import ParallelEnv
    from pettingzoo.utils import parallel_to_aec
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError(
        "usar.pettingzoo needs pettingzoo and gymnasium: pip install pettingzoo gymnasium "
        "(or the usar[pettingzoo] extra)"
    ) from e

from . import _api
from ._data import scenario_path
from ._usar import Scenario
from .gym import GroupingEnv

__all__ = ["GroupingParallelEnv", "parallel_env", "env", "TRUST_HIGH_NATS"]

#: The upper bound of the trust entries of an observation, nats. With the package's
#: smoothing of needs distributions (relative, 1e-9) RNE trust is at most about 20.7 nats
#: (``usar.trust`` of two robots with no need in common); larger values would be clipped.
TRUST_HIGH_NATS = 32.0

#: The options :meth:`GroupingParallelEnv.reset` hands to the Gymnasium environment.
_GYM_OPTIONS = ("trial",)

#: The kind fields that bound each entry of a needs vector (hp, v, sen, eng, res, cap, obs:
#: usar-sim's ``needs_vector``, paper Eqs. 19-21): no entry exceeds its kind's field.
_NEEDS_BOUNDS = (
    "hp_needs_full",
    "max_speed_m_per_s",
    "sensing_range_m",
    "energy_needs_full",
    "rescuing_resources",
    "carrying_capacity",
    "observing_range_m",
)


def _default_scenario() -> Optional[str]:
    """The scenario of ``scenario=None``: the paper's mission, :class:`usar.gym.GroupingEnv`'s
    own default (``None``, ``paper.ron``) when it has one, else ``paper-v1.ron`` (rounds that
    start with every robot back, which an older GroupingEnv needs)."""
    parameter = inspect.signature(GroupingEnv.__init__).parameters.get("scenario")
    if parameter is not None and parameter.default is None:
        return None
    return str(scenario_path("paper-v1.ron"))


class GroupingParallelEnv(ParallelEnv):
    """One USAR trial of ``scenario`` as a PettingZoo parallel episode: one agent per robot,
    one step per grouping round, a team reward.

    **Agents**: one per robot of the scenario, named by its kind and its index within the
    kind (``"carrier_0"`` ... ``"carrier_5"``, ``"supplier_0"`` ... ``"supplier_3"``,
    ``"observer_0"``, ``"observer_1"`` in the paper's team); ``possible_agents`` lists them by
    robot id and :attr:`robot_of` maps a name to its robot id. Every agent acts every round
    until the trial's time is up; then all are terminated together (``agents`` empties). A
    robot away this round (resting, under ``mission.round_start: Available``) still acts; its
    choice is ignored.

    **Action** of an agent: its task (``Discrete(n_tasks)``, task ids in the scenario's
    order, :attr:`task_names`). The agents' actions make the joint action of
    :class:`usar.gym.GroupingEnv`, which repairs a joint action that breaks a kind's quota
    (:func:`usar.gym.repair_assignment`): ``infos[agent]["task"]`` is the task the agent got
    (-1 when it was away) and ``infos[agent]["moved"]`` whether it was moved from the one it
    chose. An action that is not an integer in ``0 .. n_tasks - 1``, a missing agent or an
    unknown one raises ``ValueError`` naming the agent; the episode goes on.

    **Observation** of an agent: a float32 vector (``Box`` with finite bounds), the agent's
    own view of the round, in this order (:attr:`observation_fields` gives each part's slice):

    - ``kind``: one-hot of its kind (``n_kinds`` entries);
    - ``energy_pct``, ``hp_pct``: its levels, 0-100 (0 while away, as the Gymnasium
      environment gives them);
    - ``needs``: its needs vector (7 entries: hp, v, sen, eng, res, cap, obs; paper Eqs.
      19-21), each between 0 and the largest value of that entry among the kinds (0 while
      away);
    - ``distance_to_goal_m``: straight-line distance to each task's goal point, metres
      (``n_tasks`` entries, task order);
    - ``available``: 1 if the robot is grouped this round, 0 if it is away (resting);
    - ``time_s``: simulated seconds when the round starts (0 to the trial's length + 1);
    - ``trust``: its RNE trust towards each robot, by robot id (``n_robots`` entries):
      ``usar.trust(weights, own needs, other's needs)``, paper Eq. 7 with the scenario's
      ``needs_weights``, in nats, lower = more trust; 0 towards itself;
      :data:`TRUST_HIGH_NATS` (above any computed value) towards a robot away this round and,
      while the agent is away, towards every other (the round's request holds no needs of a
      robot away).

    Values are clipped to the bounds; the scenario's fields bound them, so a valid scenario
    needs no clipping.

    **Reward**: the Gymnasium environment's reward, the same for every agent: the rescuees of
    the round the joint action groups (``reward="hard"``: only the hardest task's).

    **Infos** per agent: ``action_mask`` (int8 0/1, ``n_tasks``, the form
    ``action_space(agent).sample(mask)`` takes: 1 for the tasks its kind's quotas leave room
    for this round, or the Gymnasium environment's own mask row when it gives one),
    ``robot_id``, ``available``, ``round``, ``seed`` (the trial's seed, as the Gymnasium
    environment gives it), ``trial`` and ``dt_s`` (the round's simulated seconds) when it
    gives them and, after a step, ``task`` and ``moved``; at the end ``result`` (the
    :class:`usar.TrialResult`, also :attr:`result`).

    ``reset(seed=S)`` is the Gymnasium environment's ``reset(seed=S)`` (which trial it runs
    is that environment's rule); the same seed and actions give the same episode.
    ``options={"trial": k}`` is handed to the Gymnasium environment; other option keys are
    ignored with a warning (PettingZoo's API test resets with ``options={"options": 1}``).
    ``state()`` is every agent's observation, concatenated by robot id.

    ``scenario``: a :class:`usar.Scenario` or a path (default: the paper's mission, the
    Gymnasium environment's default ``paper.ron`` when it has one, else
    ``usar.scenario_path("paper-v1.ron")``); ``duration_s``: the trial's length (default the
    scenario's); ``reward``: ``"rescued"`` or ``"hard"``; ``render_mode``: one of
    :attr:`metadata` ``["render_modes"]`` (those of :class:`usar.gym.GroupingEnv`) or
    ``None``; further keyword arguments (``trial``) go to :class:`usar.gym.GroupingEnv`.
    Errors: ``ValueError`` naming the argument.
    """

    metadata = {
        "name": "usar_grouping_v0",
        "render_modes": list(GroupingEnv.metadata.get("render_modes", [])),
        "is_parallelizable": True,
    }

    def __init__(
        self,
        scenario: Union[Scenario, str, os.PathLike, None] = None,
        duration_s: Optional[float] = None,
        reward: str = "rescued",
        render_mode: Optional[str] = None,
        **kwargs: Any,
    ) -> None:
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            known = ", ".join(repr(m) for m in self.metadata["render_modes"]) or "none"
            raise ValueError(f"render_mode: expected None or one of {known}, found {render_mode!r}")
        if scenario is None:
            scenario = _default_scenario()
        if scenario is not None:
            scenario = _api._scenario(scenario)
        if render_mode is not None:
            kwargs["render_mode"] = render_mode
        #: The Gymnasium environment this one is built on.
        self.gym_env = GroupingEnv(scenario, duration_s=duration_s, reward=reward, **kwargs)
        self.render_mode = render_mode
        self.scenario = self.gym_env.scenario
        info = self.scenario.check()
        kinds = [k["name"] for k in info["kinds"]]
        robots = info["robots"]
        #: Task names, by task id.
        self.task_names: List[str] = list(self.gym_env.task_names)
        #: Task ids from the hardest to the easiest.
        self.task_order: List[int] = list(self.gym_env.task_order)
        n, k, m = len(robots), len(self.task_names), int(info["needs_len"])
        self._n, self._k, self._kinds = n, k, len(kinds)
        self._robot_kinds = [int(r["kind_index"]) for r in robots]
        seen = {name: 0 for name in kinds}
        names = []
        for r in robots:
            names.append(f"{r['kind']}_{seen[r['kind']]}")
            seen[r["kind"]] += 1
        self.possible_agents: List[str] = names
        self.agents: List[str] = []
        #: Robot id of each agent name.
        self.robot_of: Dict[str, int] = {a: i for i, a in enumerate(names)}
        weights = self.scenario.get("needs_weights")
        if isinstance(weights, dict):
            weights = list(weights.values())
        self._weights = [float(w) for w in weights]

        # Bounds of each part of the observation, in order.
        kind_fields = self.scenario.to_dict()["kinds"]
        if m == len(_NEEDS_BOUNDS) and all(f in kf for kf in kind_fields for f in _NEEDS_BOUNDS):
            needs_high = [max(float(kf[f]) for kf in kind_fields) for f in _NEEDS_BOUNDS]
        else:  # pragma: no cover - every scenario has 7 needs today
            needs_high = [1e6] * m
        width, height = info["arena"]["width_m"], info["arena"]["height_m"]
        far = max(
            [math.hypot(width, height)]
            + [float(d) for r in robots for d in r["distance_to_goal_m"].values()]
        )
        end = float(duration_s if duration_s is not None else info["duration_s"])
        parts = [
            ("kind", [0.0] * self._kinds, [1.0] * self._kinds),
            ("energy_pct", [0.0], [100.0]),
            ("hp_pct", [0.0], [100.0]),
            ("needs", [0.0] * m, needs_high),
            ("distance_to_goal_m", [0.0] * k, [far] * k),
            ("available", [0.0], [1.0]),
            ("time_s", [0.0], [end + 1.0]),
            ("trust", [0.0] * n, [TRUST_HIGH_NATS] * n),
        ]
        #: The slice of each part of an agent's observation vector, by name.
        self.observation_fields: Dict[str, slice] = {}
        start = 0
        for name, low, _ in parts:
            self.observation_fields[name] = slice(start, start + len(low))
            start += len(low)
        self._low = np.array([x for _, low, _ in parts for x in low], dtype=np.float32)
        self._high = np.array([x for _, _, high in parts for x in high], dtype=np.float32)
        space = spaces.Box(self._low, self._high, dtype=np.float32)
        self.observation_spaces = {a: space for a in names}
        self.action_spaces = {a: spaces.Discrete(k) for a in names}
        self.state_space = spaces.Box(
            np.tile(self._low, n), np.tile(self._high, n), dtype=np.float32
        )
        #: The :class:`usar.TrialResult` of the last episode that ended, else ``None``.
        self.result = None
        self._obs: Optional[Dict[str, np.ndarray]] = None
        self._info: Dict[str, Any] = {}

    # PettingZoo's API test wants the same space object each call.
    def observation_space(self, agent: str) -> spaces.Box:
        """The observation space of ``agent`` (the same for every agent)."""
        return self.observation_spaces[agent]

    def action_space(self, agent: str) -> spaces.Discrete:
        """The action space of ``agent``: ``Discrete(n_tasks)``."""
        return self.action_spaces[agent]

    def _available(self, obs: Mapping[str, Any], info: Mapping[str, Any]) -> np.ndarray:
        """The availability flag per robot: the Gymnasium environment's (in its observation or
        its info), else every robot grouped."""
        for source in (obs, info):
            for key in ("available", "availability"):
                if key in source:
                    return np.asarray(source[key]).astype(bool).reshape(self._n)
        return np.ones(self._n, dtype=bool)

    def _masks(self, obs: Mapping[str, np.ndarray], info: Mapping[str, Any]) -> np.ndarray:
        """The action mask per robot, (n, k) bool: the Gymnasium environment's, else the tasks
        the kind's quotas leave room for this round."""
        if "action_mask" in info:
            return np.asarray(info["action_mask"], dtype=bool).reshape(self._n, self._k)
        quotas = np.asarray(obs["quotas"])
        return quotas[self._robot_kinds] > 0

    def _trust(self, needs: np.ndarray, available: np.ndarray) -> np.ndarray:
        """The RNE trust matrix, (n, n): row i is robot i's trust towards each robot (Eq. 7),
        0 on the diagonal, :data:`TRUST_HIGH_NATS` where either robot is away (its needs are
        not in the round's request)."""
        rows = [[float(x) for x in row] for row in np.asarray(needs, dtype=float)]
        t = np.full((self._n, self._n), TRUST_HIGH_NATS)
        for i, a in enumerate(rows):
            t[i, i] = 0.0
            if not available[i]:
                continue
            for j, b in enumerate(rows):
                if i != j and available[j]:
                    t[i, j] = _api.trust(self._weights, a, b)
        return t

    def _observe(
        self, obs: Mapping[str, np.ndarray], info: Mapping[str, Any]
    ) -> Tuple[Dict[str, np.ndarray], Dict[str, Dict[str, Any]]]:
        """Each agent's observation and info from the Gymnasium environment's."""
        n = self._n
        available = self._available(obs, info)
        masks = self._masks(obs, info)
        trust = self._trust(obs["needs"], available)
        kinds = np.asarray(obs["kind"], dtype=np.int64)
        full = np.concatenate(
            [
                np.eye(self._kinds)[kinds],
                np.asarray(obs["energy_pct"], dtype=float).reshape(n, 1),
                np.asarray(obs["hp_pct"], dtype=float).reshape(n, 1),
                np.asarray(obs["needs"], dtype=float).reshape(n, -1),
                np.asarray(obs["distance_to_goal_m"], dtype=float).reshape(n, self._k),
                available.astype(float).reshape(n, 1),
                np.full((n, 1), float(np.asarray(obs["time_s"]).reshape(-1)[0])),
                trust,
            ],
            axis=1,
        ).astype(np.float32)
        full = np.clip(full, self._low, self._high)
        self._full = full
        common = {key: info[key] for key in ("round", "seed", "trial", "dt_s") if key in info}
        observations = {}
        infos: Dict[str, Dict[str, Any]] = {}
        for i, agent in enumerate(self.possible_agents):
            observations[agent] = full[i]
            infos[agent] = {
                "action_mask": masks[i].astype(np.int8),
                "robot_id": i,
                "available": bool(available[i]),
                **common,
            }
        return observations, infos

    def reset(
        self, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None
    ) -> Tuple[Dict[str, np.ndarray], Dict[str, Dict[str, Any]]]:
        """Starts an episode: the trial of ``seed`` (see the class). Returns each agent's
        observation and info."""
        gym_options = None
        if options is not None:
            if not isinstance(options, Mapping):
                raise TypeError(f"options: expected a dict, found {type(options).__name__}")
            unknown = [key for key in options if key not in _GYM_OPTIONS]
            if unknown:
                warnings.warn(
                    f"options: unknown keys {unknown} ignored (known: {', '.join(_GYM_OPTIONS)})",
                    UserWarning,
                    stacklevel=2,
                )
            gym_options = {key: options[key] for key in options if key in _GYM_OPTIONS} or None
        obs, info = self.gym_env.reset(seed=seed, options=gym_options)
        self.agents = list(self.possible_agents)
        self.result = None
        self._obs, self._info = obs, info
        return self._observe(obs, info)

    def _joint_action(self, actions: Any) -> np.ndarray:
        """The task of each robot, by id, from the agents' actions; ValueError naming the agent."""
        if not isinstance(actions, Mapping):
            raise TypeError(
                f"actions: expected a dict agent name -> task, found {type(actions).__name__}"
            )
        unknown = [a for a in actions if a not in self.robot_of]
        if unknown:
            raise ValueError(
                f"actions: unknown agent {unknown[0]!r} (agents: {', '.join(self.agents)})"
            )
        missing = [a for a in self.agents if a not in actions]
        if missing:
            raise ValueError(f"actions: no action for agent {missing[0]!r}")
        joint = np.zeros(self._n, dtype=np.int64)
        for agent, a in actions.items():
            value = a.item() if isinstance(a, np.ndarray) and a.shape in ((), (1,)) else a
            if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
                raise ValueError(
                    f"actions[{agent!r}]: expected a task id (int) in 0..{self._k - 1}, "
                    f"found {a!r}"
                )
            if not 0 <= int(value) < self._k:
                raise ValueError(
                    f"actions[{agent!r}]: task {int(value)} out of range 0..{self._k - 1}"
                )
            joint[self.robot_of[agent]] = int(value)
        return joint

    def step(self, actions: Dict[str, Any]) -> Tuple[
        Dict[str, np.ndarray],
        Dict[str, float],
        Dict[str, bool],
        Dict[str, bool],
        Dict[str, Dict[str, Any]],
    ]:
        """One grouping round: ``actions`` maps every live agent to its task. Returns each
        agent's observation, reward (the team's), termination, truncation and info."""
        if not self.agents:
            raise RuntimeError("the episode is over (or not started): call reset() before step()")
        joint = self._joint_action(actions)
        obs, reward, terminated, truncated, info = self.gym_env.step(joint)
        self._obs, self._info = obs, info
        observations, infos = self._observe(obs, info)
        task = np.full(self._n, -1, dtype=np.int64)
        for t, group in enumerate(info.get("groups", [])):
            for robot in group:
                task[int(robot)] = t
        for i, agent in enumerate(self.possible_agents):
            infos[agent]["task"] = int(task[i])
            infos[agent]["moved"] = bool(task[i] >= 0 and task[i] != joint[i])
        if terminated:
            self.result = info.get("result")
            for agent in self.possible_agents:
                infos[agent]["result"] = self.result
        agents = self.agents
        rewards = {a: float(reward) for a in agents}
        terminations = {a: bool(terminated) for a in agents}
        truncations = {a: bool(truncated) for a in agents}
        observations = {a: observations[a] for a in agents}
        infos = {a: infos[a] for a in agents}
        if terminated or truncated:
            self.agents = []
        return observations, rewards, terminations, truncations, infos

    def state(self) -> np.ndarray:
        """Every agent's observation of the current round, concatenated by robot id (float32,
        ``state_space``): a centralised critic's input."""
        if self._obs is None:
            raise RuntimeError("call reset() before state()")
        return self._full.reshape(-1).copy()

    def render(self) -> Any:
        """The Gymnasium environment's picture (``render_mode``), or ``None`` without one."""
        if self.render_mode is None:
            return None
        return self.gym_env.render()

    def close(self) -> None:
        """Ends the episode's trial (the Gymnasium environment's ``close``)."""
        self.gym_env.close()


def parallel_env(
    scenario: Union[Scenario, str, os.PathLike, None] = None,
    duration_s: Optional[float] = None,
    reward: str = "rescued",
    render_mode: Optional[str] = None,
    **kwargs: Any,
) -> GroupingParallelEnv:
    """A :class:`GroupingParallelEnv` (a ``pettingzoo.ParallelEnv``): one agent per robot of
    ``scenario`` (default the paper's mission), each choosing its task each round, with a
    team reward. Arguments as :class:`GroupingParallelEnv`; errors: ``ValueError`` naming
    the argument."""
    return GroupingParallelEnv(
        scenario, duration_s=duration_s, reward=reward, render_mode=render_mode, **kwargs
    )


def env(**kwargs: Any):
    """The same environment as an AEC (agent by agent) ``pettingzoo.AECEnv``:
    ``pettingzoo.utils.parallel_to_aec(parallel_env(**kwargs))``."""
    return parallel_to_aec(parallel_env(**kwargs))

