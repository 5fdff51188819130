"""Grouping methods in Python: the request a method sees each round, the base class, the
adapter that runs a Python method inside a trial, and rne-core's methods as functions."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _usar
from ._usar import GroupingError, Scenario


@dataclass(frozen=True)
class Robot:
    """One robot at grouping time (paper Sec. VI.B-C).

    ``id`` (index in the scenario's team), ``kind`` (kind name) and ``kind_index``, ``role``
    (``Carrier``, ``Supplier`` or ``Observer``), ``needs`` (needs vector, numpy float array
    of the scenario's needs categories, paper Def. 1), ``position`` ((x, y) metres, world
    frame, as of the last step), ``energy_pct`` and ``hp_pct`` (percent, 0-100) and
    ``distance_to_goal_m`` (task name -> straight-line metres to its goal).
    """

    id: int
    kind: str
    kind_index: int
    role: str
    needs: np.ndarray
    position: Optional[Tuple[float, float]]
    energy_pct: float
    hp_pct: float
    distance_to_goal_m: Dict[str, float]


@dataclass(frozen=True)
class Task:
    """One task: ``id`` (index, scenario order), ``name``, ``difficulty`` (higher is harder),
    ``rank`` (0 = the hardest) and ``quotas`` (kind name -> robots of that kind it takes)."""

    id: int
    name: str
    difficulty: int
    rank: int
    quotas: Dict[str, int]


@dataclass(frozen=True)
class GroupingRequest:
    """What a grouping method sees each round: the ``robots`` (sorted by id) and the
    ``tasks`` (scenario order), the ``trial`` index, the trial's ``seed``, the ``round``
    (0, 1, ... within the trial), the ``scenario``, ``time_s`` (simulated seconds when the
    round starts) and ``rescued_so_far`` (rescuees per task, scenario order, over the rounds
    before this one).

    A method answers one group of robot ids per task, in task order (a list of lists), or a
    dict task name -> ids; ids may be ints, numpy integers or :class:`Robot` objects. The
    answer must be a partition of the team with every kind's quota met, else
    :class:`usar.GroupingError` names the rule broken.
    """

    robots: Tuple[Robot, ...]
    tasks: Tuple[Task, ...]
    trial: int
    seed: int
    round: int
    scenario: Optional[Scenario]
    hardest_first: Tuple[int, ...]
    quotas: Tuple[Tuple[int, ...], ...]
    time_s: float = 0.0
    rescued_so_far: Tuple[int, ...] = ()

    def needs_matrix(self) -> np.ndarray:
        """The robots' needs vectors as rows: shape (robots, needs categories), float."""
        return np.stack([r.needs for r in self.robots])

    def robots_of_kind(self, kind: str) -> List[Robot]:
        """The robots of the kind named ``kind``, by id."""
        return [r for r in self.robots if r.kind == kind]

    def rng(self) -> np.random.Generator:
        """A numpy generator seeded by (trial seed, round): the same draws for the same
        trial on any number of threads."""
        return np.random.default_rng([self.seed, self.round])

    def _raw(self) -> Dict[str, Any]:
        """The raw form the native functions read."""
        names = [t.name for t in self.tasks]
        return {
            "ids": [r.id for r in self.robots],
            "kinds": [r.kind_index for r in self.robots],
            "needs": [[float(x) for x in r.needs] for r in self.robots],
            "energy_pct": [r.energy_pct for r in self.robots],
            "hp_pct": [r.hp_pct for r in self.robots],
            "distance_to_goal_m": [[r.distance_to_goal_m[n] for n in names] for r in self.robots],
            "quotas": [list(q) for q in self.quotas],
            "hardest_first": list(self.hardest_first),
        }


def _request(raw: Dict[str, Any], info: Dict[str, Any], scenario: Scenario) -> GroupingRequest:
    """A request from the raw dict of the native side and the scenario's ``check()``."""
    kinds, tasks = info["kinds"], info["tasks"]
    names = [t["name"] for t in tasks]
    robots = tuple(
        Robot(
            id=raw["ids"][i],
            kind=kinds[k]["name"],
            kind_index=k,
            role=kinds[k]["role"],
            needs=np.asarray(raw["needs"][i], dtype=float),
            position=raw["positions"][i],
            energy_pct=raw["energy_pct"][i],
            hp_pct=raw["hp_pct"][i],
            distance_to_goal_m=dict(zip(names, raw["distance_to_goal_m"][i])),
        )
        for i, k in enumerate(raw["kinds"])
    )
    quotas = raw["quotas"]
    order = raw["hardest_first"]
    task_list = tuple(
        Task(
            id=t,
            name=spec["name"],
            difficulty=spec["difficulty"],
            rank=order.index(t),
            quotas={kinds[k]["name"]: quotas[k][t] for k in range(len(kinds))},
        )
        for t, spec in enumerate(tasks)
    )
    return GroupingRequest(
        robots=robots,
        tasks=task_list,
        trial=raw["trial"],
        seed=raw["seed"],
        round=raw["round"],
        scenario=scenario,
        hardest_first=tuple(order),
        quotas=tuple(tuple(q) for q in quotas),
        time_s=float(raw.get("time_s", 0.0)),
        rescued_so_far=tuple(int(n) for n in raw.get("rescued_so_far", [0] * len(task_list))),
    )


class GroupingMethod:
    """Base class of a grouping method written in Python.

    Override :meth:`group`; set the class attribute ``name`` (default: the class name in
    lower case), which results, ``trials.csv`` and the figures show. Any callable
    ``group(request) -> groups`` works as well; this class only names it.
    """

    name: str = ""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if not cls.__dict__.get("name"):
            cls.name = cls.__name__.lower()

    def group(self, request: GroupingRequest) -> Union[Sequence[Sequence[Any]], Dict[str, Any]]:
        """One group of robot ids per task (task order), or a dict task name -> ids."""
        raise NotImplementedError(f"{type(self).__name__}.group")

    def __call__(self, request: GroupingRequest) -> Any:
        return self.group(request)


MethodLike = Union[str, GroupingMethod, Callable[[GroupingRequest], Any], type]


def _id_of(x: Any, method: str, ids: frozenset) -> int:
    if isinstance(x, Robot):
        return x.id
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, np.integer)):
        raise GroupingError(f"method {method}: robot ids must be integers, found {x!r}")
    if int(x) not in ids:
        shown = ", ".join(str(i) for i in sorted(ids))
        raise GroupingError(
            f"method {method}: robot id {int(x)} is not in the team of this round (ids: {shown})"
        )
    return int(x)


def _groups(answer: Any, request: GroupingRequest, method: str) -> List[List[int]]:
    """The answer as one list of ids per task, in task order."""
    names = [t.name for t in request.tasks]
    if isinstance(answer, dict):
        unknown = [k for k in answer if k not in names]
        if unknown:
            raise GroupingError(
                f"method {method}: unknown task {unknown[0]!r} (tasks: {', '.join(names)})"
            )
        answer = [answer.get(n, []) for n in names]
    if isinstance(answer, (str, bytes)) or not isinstance(answer, (list, tuple, np.ndarray)):
        raise GroupingError(
            f"method {method}: the answer must be one list of robot ids per task, "
            f"found {type(answer).__name__}"
        )
    ids = frozenset(r.id for r in request.robots)
    out = []
    for g in answer:
        if isinstance(g, (str, bytes)) or not hasattr(g, "__iter__"):
            raise GroupingError(
                f"method {method}: each group must be a list of robot ids, found {g!r}"
            )
        out.append([_id_of(x, method, ids) for x in g])
    return out


def method_name(method: Any) -> str:
    """The name results show for a Python method."""
    name = getattr(method, "name", None)
    if isinstance(name, str) and name:
        return name
    name = getattr(method, "__name__", None)
    if isinstance(name, str) and name and name != "<lambda>":
        return name
    return type(method).__name__.lower()


def method_arg(method: MethodLike, scenario: Scenario) -> Union[str, Tuple[str, Callable]]:
    """What the native side takes: a built-in's name, or (name, adapter). The package's own
    functions of the built-ins (:func:`rne`, :func:`dis`, ...) are the built-ins by name; any
    other Python method named as a built-in is refused by the native side (ValueError)."""
    if isinstance(method, str):
        return method
    builtin = _BUILTIN_FUNCTIONS.get(id(method))
    if builtin is not None and builtin[0] is method:
        return builtin[1]
    if isinstance(method, type):
        if not issubclass(method, GroupingMethod):
            raise TypeError(f"method: {method.__name__} is not a usar.GroupingMethod subclass")
        method = method()
    if not callable(method):
        raise TypeError(
            f"method: expected a name, a usar.GroupingMethod or a callable, "
            f"found {type(method).__name__}"
        )
    name = method_name(method)
    info = scenario.check()

    def adapter(raw: Dict[str, Any]) -> List[List[int]]:
        request = _request(raw, info, scenario)
        return _groups(method(request), request, name)

    return (name, adapter)


def _builtin(name: str, request: GroupingRequest, weights: Optional[Sequence[float]]) -> List[List[int]]:
    if not isinstance(request, GroupingRequest):
        raise TypeError(f"request: expected a usar.GroupingRequest, found {type(request).__name__}")
    w = None if weights is None else [float(x) for x in np.asarray(weights, dtype=float).ravel()]
    return _usar.builtin_group(name, request._raw(), request.scenario, w)


def rne(request: GroupingRequest, weights: Optional[Sequence[float]] = None) -> List[List[int]]:
    """Hierarchical RNE grouping (paper Algorithm 1): one sorted list of ids per task.

    The trust model is the request's scenario's (its ``needs_weights``), or ``weights`` (one
    per needs category, > 0). Raises ValueError for a bad request or weights.
    """
    return _builtin("rne", request, weights)


def dis(request: GroupingRequest) -> List[List[int]]:
    """DIS baseline (paper Sec. VI.C): robots choose nearest-first, each the nearest task
    whose quota for its kind has room."""
    return _builtin("dis", request, None)


def eng(request: GroupingRequest) -> List[List[int]]:
    """ENG baseline (paper Sec. VI.C): the robots with the most energy take the hardest task."""
    return _builtin("eng", request, None)


def hp_dis(request: GroupingRequest) -> List[List[int]]:
    """HP_DIS baseline (paper Sec. VI.C): by HP, then distance, hardest task first."""
    return _builtin("hp_dis", request, None)


#: The functions above by id: passed as a method, each is its built-in, run natively.
_BUILTIN_FUNCTIONS = {id(f): (f, f.__name__) for f in (rne, dis, eng, hp_dis)}
