"""A Gymnasium environment for learned grouping: :class:`GroupingEnv`, one step per grouping
decision (a round) of one USAR trial.

Needs the optional ``gymnasium`` dependency (``pip install "./python[gym]"``). See
docs/python.md, "A Gymnasium environment".
"""

from __future__ import annotations

import os
import queue
import threading
import weakref
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

try:
    import gymnasium
    from gymnasium import spaces
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError(
        "usar.gym needs gymnasium: pip install gymnasium (or the usar[gym] extra)"
    ) from e

from . import _api
from ._grouping import GroupingMethod, GroupingRequest
from ._usar import Scenario

__all__ = ["GroupingEnv", "repair_assignment", "ENV_ID"]

#: The id :func:`gymnasium.make` knows the environment by (``gymnasium.make(ENV_ID,
#: scenario="scenarios/paper-v1.ron")``), registered when ``usar.gym`` is imported.
ENV_ID = "usar/Grouping-v0"


class _Stop(Exception):
    """Raised inside the trial's thread to end an episode that is abandoned."""


class _EnvMethod(GroupingMethod):
    """The grouping method of an episode's trial: each round, it hands the request over and
    answers the groups the environment's action gives (``None``: the episode is abandoned).
    Results name it ``gym``. It holds the queues, not the environment, so that an
    environment dropped without ``close()`` is collected and its trial ended."""

    name = "gym"

    def __init__(self, to_trial: "queue.Queue[Any]", from_trial: "queue.Queue[Any]") -> None:
        self._to_trial, self._from_trial = to_trial, from_trial

    def group(self, request: GroupingRequest) -> List[List[int]]:
        self._from_trial.put(("request", request))
        groups = self._to_trial.get()
        if groups is None:
            raise _Stop()
        return groups


def _run_trial(
    scenario: Scenario,
    duration_s: Optional[float],
    trial: Optional[int],
    seed: Optional[int],
    to_trial: "queue.Queue[Any]",
    from_trial: "queue.Queue[Any]",
) -> None:
    """The episode's trial, in its thread: its result, `stopped` or its error at the end."""
    try:
        result = _api.run(
            scenario,
            method=_EnvMethod(to_trial, from_trial),
            trial=trial,
            seed=seed,
            duration_s=duration_s,
        )
        from_trial.put(("done", result))
    except _Stop:
        from_trial.put(("stopped", None))
    except BaseException as e:  # noqa: BLE001 - handed to the caller of step()
        from_trial.put(("error", e))


def repair_assignment(
    action: Sequence[int], kinds: Sequence[int], quotas: Sequence[Sequence[int]], order: Sequence[int]
) -> Tuple[List[List[int]], int]:
    """The quota-respecting groups closest to ``action`` (the task of each robot, by id):
    robots are taken by id, each into the task it asks for while that task still has room
    for its kind (``quotas[kind][task]``), otherwise into the first task in ``order`` (the
    hardest first) that has. Returns the groups (robot ids per task, task order) and how many
    robots were moved from the task they asked for. An action that meets every quota is kept
    as it is.
    """
    n_tasks = len(quotas[0]) if quotas else 0
    room = [list(q) for q in quotas]
    groups: List[List[int]] = [[] for _ in range(n_tasks)]
    moved = 0
    for robot, (want, kind) in enumerate(zip(action, kinds)):
        want = int(want)
        if 0 <= want < n_tasks and room[kind][want] > 0:
            task = want
        else:
            task = next(t for t in order if room[kind][t] > 0)
            moved += 1
        room[kind][task] -= 1
        groups[task].append(robot)
    return groups, moved


class GroupingEnv(gymnasium.Env):
    """One USAR trial of ``scenario`` as an episode, one step per grouping round.

    **Observation** (a dict, what a grouping method sees, robots by id): ``kind`` (kind index
    per robot), ``energy_pct`` and ``hp_pct`` (0-100), ``position_m`` (x, y metres),
    ``needs`` (the needs vector per robot), ``distance_to_goal_m`` (per robot and task),
    ``quotas`` (robots each kind gives each task), ``time_s`` (simulated seconds) and
    ``rescued_so_far`` (per task).

    **Action**: the task of each robot (``MultiDiscrete([tasks] * robots)``). An action that
    breaks a kind's quota is repaired to the closest one that keeps them
    (:func:`repair_assignment`); ``info["moved"]`` counts the robots moved.

    **Reward**: the rescuees of the round the action groups (per task summed; with
    ``reward="hard"`` only those of the hardest task). The episode ends (``terminated``) when
    the trial's time is up; ``info["result"]`` then holds the :class:`usar.TrialResult`
    (its method named ``gym``).

    The scenario must start its rounds with every robot back (``mission.round_start:
    AllBack``, as ``scenarios/paper-v1.ron`` does): each round then groups the whole team,
    and the observation and action keep their sizes (a ValueError otherwise).
    ``scenarios/paper.ron`` starts its rounds with the robots available (the authors' clock,
    docs/calibration.md), which this environment does not take yet.

    ``reset(seed=S)`` starts the trial whose seed is ``S`` (as ``usar.run(seed=S)``); without
    one, ``trial`` (default 0) picks it as ``usar.run(trial=...)`` does, and a reset with
    ``options={"trial": k}`` picks another. The same seed and the same actions give the same
    episode, and the same numbers as ``usar.run`` with a method that answers those groups.
    """

    metadata = {"render_modes": []}

    def __init__(
        self,
        scenario: Union[Scenario, str, os.PathLike],
        duration_s: Optional[float] = None,
        trial: int = 0,
        reward: str = "rescued",
    ) -> None:
        super().__init__()
        if reward not in ("rescued", "hard"):
            raise ValueError(f"reward: expected 'rescued' or 'hard', found {reward!r}")
        self.scenario = _api._scenario(scenario)
        info = self.scenario.check()
        if info["mission"].get("round_start", "AllBack") != "AllBack":
            raise ValueError(
                f"scenario: mission.round_start is {info['mission']['round_start']}; "
                "GroupingEnv needs AllBack (every robot grouped every round, a fixed-size "
                "observation and action), as scenarios/paper-v1.ron has"
            )
        self.duration_s = duration_s
        self.trial = int(trial)
        self.reward_kind = reward
        self._kinds = [k["name"] for k in info["kinds"]]
        self._tasks = [t["name"] for t in info["tasks"]]
        #: Task ids from the hardest to the easiest (the scenario's difficulty order).
        self.task_order = [t for _, t in sorted((x["rank"], t) for t, x in enumerate(info["tasks"]))]
        #: Task names, by task id.
        self.task_names = list(self._tasks)
        robots = info["robots"]
        n, k, m = len(robots), len(self._tasks), int(info["needs_len"])
        self._robot_kinds = [r["kind_index"] for r in robots]
        width, height = info["arena"]["width_m"], info["arena"]["height_m"]
        end = float(duration_s if duration_s is not None else info["duration_s"])
        big = np.float64(np.finfo(np.float64).max)
        self.observation_space = spaces.Dict(
            {
                "kind": spaces.MultiDiscrete([len(self._kinds)] * n),
                "energy_pct": spaces.Box(0.0, 100.0, (n,), np.float64),
                "hp_pct": spaces.Box(0.0, 100.0, (n,), np.float64),
                "position_m": spaces.Box(
                    np.tile([-width, -height], (n, 1)),
                    np.tile([2 * width, 2 * height], (n, 1)),
                    (n, 2),
                    np.float64,
                ),
                "needs": spaces.Box(0.0, big, (n, m), np.float64),
                "distance_to_goal_m": spaces.Box(0.0, big, (n, k), np.float64),
                "quotas": spaces.Box(0, n, (len(self._kinds), k), np.int64),
                "time_s": spaces.Box(0.0, end + 1.0, (1,), np.float64),
                "rescued_so_far": spaces.Box(0, np.iinfo(np.int64).max, (k,), np.int64),
            }
        )
        self.action_space = spaces.MultiDiscrete([k] * n)
        self._thread: Optional[threading.Thread] = None
        self._to_trial: "queue.Queue[Any]" = queue.Queue()
        self._from_trial: "queue.Queue[Tuple[str, Any]]" = queue.Queue()
        self._request: Optional[GroupingRequest] = None
        self._obs: Optional[Dict[str, np.ndarray]] = None

    # The trial runs in a thread (`_run_trial`): its grouping method hands each request over
    # and waits for the groups; usar.run releases the GIL between rounds.
    def _stop(self) -> None:
        if self._thread is not None and self._thread.is_alive():
            self._to_trial.put(None)
            while True:
                kind, _ = self._from_trial.get()
                if kind in ("stopped", "done", "error"):
                    break
                self._to_trial.put(None)
            self._thread.join()
        self._thread = None
        self._request = None
        self._to_trial = queue.Queue()
        self._from_trial = queue.Queue()

    def _observation(self, r: GroupingRequest) -> Dict[str, np.ndarray]:
        positions = [p if p is not None else (0.0, 0.0) for p in (x.position for x in r.robots)]
        return {
            "kind": np.array([x.kind_index for x in r.robots], dtype=np.int64),
            "energy_pct": np.array([x.energy_pct for x in r.robots], dtype=np.float64),
            "hp_pct": np.array([x.hp_pct for x in r.robots], dtype=np.float64),
            "position_m": np.array(positions, dtype=np.float64).reshape(len(r.robots), 2),
            "needs": r.needs_matrix().astype(np.float64),
            "distance_to_goal_m": np.array(
                [[x.distance_to_goal_m[t] for t in self._tasks] for x in r.robots],
                dtype=np.float64,
            ),
            "quotas": np.array(r.quotas, dtype=np.int64),
            "time_s": np.array([r.time_s], dtype=np.float64),
            "rescued_so_far": np.array(r.rescued_so_far, dtype=np.int64),
        }

    def _score(self, rescued: Sequence[int]) -> int:
        if self.reward_kind == "hard":
            return int(rescued[self._hardest])
        return int(sum(rescued))

    def _next(self) -> Tuple[str, Any]:
        kind, value = self._from_trial.get()
        if kind == "error":
            if self._thread is not None:
                self._thread.join()
            self._thread = None
            self._request = None
            raise value
        return kind, value

    def reset(
        self, *, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None
    ) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]:
        super().reset(seed=seed)
        self._stop()
        trial = None if seed is not None else int((options or {}).get("trial", self.trial))
        self._thread = threading.Thread(
            target=_run_trial,
            args=(self.scenario, self.duration_s, trial, seed, self._to_trial, self._from_trial),
            daemon=True,
        )
        self._thread.start()
        # Dropped without close(): the trial is told to stop.
        weakref.finalize(self, self._to_trial.put, None)
        kind, value = self._next()
        if kind != "request":
            self._thread.join()
            self._thread = None
            raise RuntimeError("the trial ended before its first grouping round")
        self._seed = trial_seed = value.seed
        self._request = value
        self._hardest = value.hardest_first[0]
        self._score_before = self._score(value.rescued_so_far)
        self._obs = self._observation(value)
        return self._obs, {"seed": trial_seed, "round": value.round}

    def step(self, action: Any) -> Tuple[Dict[str, np.ndarray], float, bool, bool, Dict[str, Any]]:
        if self._request is None or self._thread is None:
            raise RuntimeError("call reset() before step()")
        r = self._request
        groups, moved = repair_assignment(
            np.asarray(action).reshape(-1), self._robot_kinds, r.quotas, r.hardest_first
        )
        self._to_trial.put(groups)
        kind, value = self._next()
        info: Dict[str, Any] = {"moved": moved, "groups": groups, "seed": self._seed}
        if kind == "request":
            self._request = value
            score = self._score(value.rescued_so_far)
            self._obs = self._observation(value)
            info["round"] = value.round
            terminated = False
        else:
            self._thread.join()
            self._thread = None
            self._request = None
            # A new object: the caller may keep the last observation.
            self._obs = {key: v.copy() for key, v in self._obs.items()}
            score = self._score(value.rescued)
            info["result"] = value
            terminated = True
        reward = float(score - self._score_before)
        self._score_before = score
        return self._obs, reward, terminated, False, info

    def close(self) -> None:
        self._stop()
        super().close()


if ENV_ID not in gymnasium.registry:
    gymnasium.register(id=ENV_ID, entry_point="usar.gym:GroupingEnv")
