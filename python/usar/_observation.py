"""The one observation builder of learned grouping: what :class:`usar.gym.GroupingEnv` shows a
policy each round and what :func:`usar.gym.policy_method` shows it inside :func:`usar.sweep`,
so that a policy trained in the environment sees the same numbers when it is evaluated.

:func:`observation` turns a :class:`usar.GroupingRequest` into the dict of arrays,
:func:`observation_space` gives its Gymnasium space, :func:`action_mask` the quota-feasible
choices and :func:`groups_of_action` the groups an action stands for (quotas kept).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from ._grouping import GroupingRequest
from ._usar import Scenario

__all__ = [
    "Layout",
    "action_mask",
    "check_action",
    "groups_of_action",
    "layout",
    "observation",
    "observation_space",
    "repair_assignment",
]


@dataclass(frozen=True)
class Layout:
    """What a scenario fixes of every observation: ``n_robots``, ``n_tasks``, ``n_kinds``,
    ``needs_len``; ``task_names`` (task id order), ``task_order`` (task ids, hardest
    first), ``robot_kinds`` (kind index per robot id), ``distance_to_goal_m`` ((robots,
    tasks) straight-line metres from each robot's start to each task's goal, as the
    requests give them), ``round_start`` (``"AllBack"`` or ``"Available"``) and the
    observation's finite bounds (``width_m``, ``height_m``, ``needs_max``,
    ``distance_max_m``, ``rescuees_max`` per task, ``end_s``)."""

    n_robots: int
    n_tasks: int
    n_kinds: int
    needs_len: int
    task_names: Tuple[str, ...]
    task_order: Tuple[int, ...]
    robot_kinds: Tuple[int, ...]
    distance_to_goal_m: np.ndarray
    round_start: str
    width_m: float
    height_m: float
    needs_max: float
    distance_max_m: float
    rescuees_max: Tuple[int, ...]
    end_s: float


@functools.lru_cache(maxsize=16)
def _layout(scenario: Scenario, duration_s: Optional[float]) -> Layout:
    info = scenario.check()
    data = scenario.to_dict()
    tasks = info["tasks"]
    names = tuple(t["name"] for t in tasks)
    robots = info["robots"]
    # Every needs entry is one of a kind's full-level fields times a factor in [0, 1]
    # (needs.rs, Eqs. 19-21): the largest such field bounds them all.
    fields = (
        "hp_needs_full", "energy_needs_full", "max_speed_m_per_s", "sensing_range_m",
        "observing_range_m", "rescuing_resources", "carrying_capacity",
    )
    needs_max = max(
        float(k.get(f) or 0.0) for k in data["kinds"] for f in fields
    )
    width, height = float(info["arena"]["width_m"]), float(info["arena"]["height_m"])
    return Layout(
        n_robots=len(robots),
        n_tasks=len(tasks),
        n_kinds=len(info["kinds"]),
        needs_len=int(info["needs_len"]),
        task_names=names,
        task_order=tuple(t for _, t in sorted((x["rank"], t) for t, x in enumerate(tasks))),
        robot_kinds=tuple(int(r["kind_index"]) for r in robots),
        distance_to_goal_m=np.array(
            [[r["distance_to_goal_m"][n] for n in names] for r in robots], dtype=np.float32
        ).reshape(len(robots), len(tasks)),
        round_start=str(info["mission"].get("round_start", "AllBack")),
        width_m=width,
        height_m=height,
        needs_max=max(needs_max, 1.0) * (1.0 + 1e-6),
        distance_max_m=3.0 * math.hypot(width, height),
        rescuees_max=tuple(int(t["rescuees"]) for t in tasks),
        end_s=float(duration_s if duration_s is not None else info["duration_s"]),
    )


def layout(scenario: Scenario, duration_s: Optional[float] = None) -> Layout:
    """The :class:`Layout` of ``scenario`` (a :class:`usar.Scenario`) over trials of
    ``duration_s`` simulated seconds (default ``mission.duration_s``); cached per scenario."""
    if not isinstance(scenario, Scenario):
        raise TypeError(f"scenario: expected a usar.Scenario, found {type(scenario).__name__}")
    return _layout(scenario, None if duration_s is None else float(duration_s))


def observation_space(scenario: Scenario, duration_s: Optional[float] = None) -> Any:
    """The Gymnasium ``spaces.Dict`` of :func:`observation` for ``scenario`` (robots by id,
    tasks in scenario order; every bound finite). Needs ``gymnasium``."""
    from gymnasium import spaces

    lay = layout(scenario, duration_s)
    n, k, m, kinds = lay.n_robots, lay.n_tasks, lay.needs_len, lay.n_kinds
    w, h = lay.width_m, lay.height_m
    f32 = np.float32
    return spaces.Dict(
        {
            "kind": spaces.MultiDiscrete([kinds] * n),
            "available": spaces.MultiBinary(n),
            "energy_pct": spaces.Box(0.0, 100.0, (n,), f32),
            "hp_pct": spaces.Box(0.0, 100.0, (n,), f32),
            "position_m": spaces.Box(
                np.tile(np.array([-w, -h], f32), (n, 1)),
                np.tile(np.array([2 * w, 2 * h], f32), (n, 1)),
                (n, 2),
                f32,
            ),
            "needs": spaces.Box(0.0, lay.needs_max, (n, m), f32),
            "distance_to_goal_m": spaces.Box(0.0, lay.distance_max_m, (n, k), f32),
            "quotas": spaces.Box(0.0, float(n), (kinds, k), f32),
            "time_s": spaces.Box(0.0, lay.end_s + 1.0, (1,), f32),
            "rescued_so_far": spaces.Box(
                np.zeros(k, f32), np.array(lay.rescuees_max, f32), (k,), f32
            ),
        }
    )


def observation(request: GroupingRequest, duration_s: Optional[float] = None) -> Dict[str, np.ndarray]:
    """What a learned grouping method sees of ``request`` (a :class:`usar.GroupingRequest`
    whose ``scenario`` is set, as every request of a trial has): a dict of arrays over the
    scenario's whole team by robot id, a point of :func:`observation_space`.

    - ``kind`` (n,) int64: kind index per robot;
    - ``available`` (n,) int8: 1 for the robots this round groups (under ``round_start:
      Available`` the robots back at their start and not resting; every robot under
      ``AllBack``), 0 for the others, whose ``energy_pct``, ``hp_pct``, ``position_m`` and
      ``needs`` are 0 (the request does not hold them);
    - ``energy_pct``, ``hp_pct`` (n,) float32, 0-100;
    - ``position_m`` (n, 2) float32: (x, y) metres, world frame;
    - ``needs`` (n, needs categories) float32: the needs vector per robot (paper Def. 1);
    - ``distance_to_goal_m`` (n, tasks) float32: straight-line metres from each robot's
      start to each task's goal (fixed by the scenario);
    - ``quotas`` (kinds, tasks) float32: robots each kind gives each task this round (under
      ``Available`` the scenario's quotas shrunk to the robots available,
      ``mission.away_quotas``);
    - ``time_s`` (1,) float32: simulated seconds at the round's start;
    - ``rescued_so_far`` (tasks,) float32: rescuees per task over the rounds before.

    ``duration_s`` only sets the bound of ``time_s`` in the cached layout. Raises TypeError
    for a request that is not a GroupingRequest or has no scenario.
    """
    if not isinstance(request, GroupingRequest):
        raise TypeError(f"request: expected a usar.GroupingRequest, found {type(request).__name__}")
    if request.scenario is None:
        raise TypeError("request: its scenario is None (requests of a trial carry theirs)")
    lay = layout(request.scenario, duration_s)
    n, k = lay.n_robots, lay.n_tasks
    available = np.zeros(n, dtype=np.int8)
    energy = np.zeros(n, dtype=np.float32)
    hp = np.zeros(n, dtype=np.float32)
    position = np.zeros((n, 2), dtype=np.float32)
    needs = np.zeros((n, lay.needs_len), dtype=np.float32)
    for r in request.robots:
        available[r.id] = 1
        energy[r.id] = r.energy_pct
        hp[r.id] = r.hp_pct
        if r.position is not None:
            position[r.id] = r.position
        needs[r.id] = r.needs
    rescued = list(request.rescued_so_far) or [0] * k
    return {
        "kind": np.array(lay.robot_kinds, dtype=np.int64),
        "available": available,
        "energy_pct": energy,
        "hp_pct": hp,
        "position_m": position,
        "needs": needs,
        "distance_to_goal_m": lay.distance_to_goal_m.copy(),
        "quotas": np.array(request.quotas, dtype=np.float32).reshape(lay.n_kinds, k),
        "time_s": np.array([request.time_s], dtype=np.float32),
        "rescued_so_far": np.array(rescued, dtype=np.float32),
    }


def action_mask(request: GroupingRequest) -> np.ndarray:
    """Which choices of an action :func:`groups_of_action` keeps for ``request``: a bool
    array (robots, tasks), ``[i, t]`` True when robot ``i`` is available and its kind's quota
    for task ``t`` this round is above 0. An action whose choices are all True still has to
    meet each quota's count, else it is repaired (:func:`repair_assignment`). A robot that is
    not available this round has only task 0 True: its choice is ignored (any task in range
    is accepted), and a masked sampler or policy sees one choice for it."""
    lay = layout(request.scenario)
    mask = np.zeros((lay.n_robots, lay.n_tasks), dtype=bool)
    mask[:, 0] = True
    for r in request.robots:
        mask[r.id] = np.asarray(request.quotas[r.kind_index]) > 0
    return mask


def check_action(action: Any, n_robots: int, n_tasks: int) -> np.ndarray:
    """``action`` (the task id of every robot, by robot id) as an int64 array of shape
    (n_robots,), or ValueError naming ``action``: a wrong shape, a non-integer dtype (floats
    such as 0.7, strings, bools) or a task id outside 0..n_tasks-1."""
    if isinstance(action, (str, bytes)):
        raise ValueError(f"action: expected {n_robots} task ids (integers), found a string")
    try:
        a = np.asarray(action)
    except Exception as e:  # noqa: BLE001 - ragged lists and the like
        raise ValueError(f"action: expected {n_robots} task ids (integers): {e}") from None
    if a.shape != (n_robots,):
        raise ValueError(
            f"action: expected shape ({n_robots},), one task id per robot, found {a.shape}"
        )
    if a.dtype == bool or not np.issubdtype(a.dtype, np.integer):
        raise ValueError(f"action: expected integer task ids, found dtype {a.dtype}")
    a = a.astype(np.int64)
    bad = np.flatnonzero((a < 0) | (a >= n_tasks))
    if bad.size:
        i = int(bad[0])
        raise ValueError(
            f"action: robot {i} asks for task {int(a[i])}; tasks are 0 to {n_tasks - 1}"
        )
    return a


def repair_assignment(
    action: Sequence[int],
    kinds: Sequence[int],
    quotas: Sequence[Sequence[int]],
    order: Sequence[int],
    available: Optional[Sequence[bool]] = None,
) -> Tuple[List[List[int]], int]:
    """The quota-respecting groups closest to ``action`` (the task of each robot, by id):
    the available robots (``available``, default all) are taken by id, each into the task it
    asks for while that task still has room for its kind (``quotas[kind][task]``), otherwise
    into the first task in ``order`` (the hardest first) that has. Returns the groups (robot
    ids per task, task order) and how many available robots were moved from the task they
    asked for. An action that meets every quota is kept as it is. The quotas of each kind
    must add up to its available robots (as every request's do)."""
    n_tasks = len(quotas[0]) if quotas else 0
    room = [list(q) for q in quotas]
    groups: List[List[int]] = [[] for _ in range(n_tasks)]
    moved = 0
    for robot, (want, kind) in enumerate(zip(action, kinds)):
        if available is not None and not available[robot]:
            continue
        want = int(want)
        if 0 <= want < n_tasks and room[kind][want] > 0:
            task = want
        else:
            task = next(t for t in order if room[kind][t] > 0)
            moved += 1
        room[kind][task] -= 1
        groups[task].append(robot)
    return groups, moved


def groups_of_action(request: GroupingRequest, action: Any) -> Tuple[List[List[int]], int]:
    """The groups ``action`` stands for in ``request``'s round: the action checked
    (:func:`check_action`, ValueError naming ``action``), the choices of robots not available
    ignored, the rest repaired to the quotas (:func:`repair_assignment`). Returns (groups,
    robots moved)."""
    lay = layout(request.scenario)
    a = check_action(action, lay.n_robots, lay.n_tasks)
    available = [False] * lay.n_robots
    for r in request.robots:
        available[r.id] = True
    return repair_assignment(a, lay.robot_kinds, request.quotas, request.hardest_first, available)
