"""A Gymnasium environment for learned grouping: :class:`GroupingEnv`, one step per grouping
decision (a round) of one USAR trial; :func:`observation`, the observation builder it shares
with :func:`policy_method` (a policy as a grouping method for :func:`usar.sweep`); and
:func:`evaluate` (a policy against the built-ins on the sweep's held-out trials, with
verdicts).

Needs the optional ``gymnasium`` dependency (``pip install "./python[gym]"``). See
docs/python.md, "A Gymnasium environment".
"""

from __future__ import annotations

import copy
import os
import tempfile
import weakref
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

try:
    import gymnasium
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError(
        "usar.gym needs gymnasium: pip install gymnasium (or the usar[gym] extra)"
    ) from e

from . import _api, _data, _studies, _usar
from ._grouping import GroupingMethod, GroupingRequest
from ._observation import (
    action_mask,
    check_action,
    groups_of_action,
    layout,
    observation,
    observation_space,
    repair_assignment,
)
from ._episode import Replayer, Runner
from ._usar import Scenario

__all__ = [
    "ENV_ID",
    "HELD_OUT_TRIALS",
    "GroupingEnv",
    "action_mask",
    "evaluate",
    "groups_of_action",
    "observation",
    "observation_space",
    "policy_method",
    "repair_assignment",
    "trial_seed",
]

#: The id :func:`gymnasium.make` knows the environment by (``gymnasium.make(ENV_ID)`` runs the
#: paper scenario, ``usar.scenario_path("paper.ron")``), registered when ``usar.gym`` is
#: imported.
ENV_ID = "usar/Grouping-v0"

#: Trials drawn for training (unseeded resets, ``reset(seed=...)``) never have the seed of
#: one of the sweep's trials 0 to ``HELD_OUT_TRIALS - 1`` (``trial_seed(sim.seed, k)``).
HELD_OUT_TRIALS = 10_000


def trial_seed(base_seed: int, trial: int) -> int:
    """The seed of the sweep's trial ``trial`` (0 <= trial < 2**32) under ``sim.seed``
    ``base_seed`` (0 <= base_seed < 2**64): the splitmix64 mix of
    crates/usar-sim/src/mission/initial.rs, computed there (``usar_sim::mission::trial_seed``
    through the native module), an int in 0..2**64-1. ``usar.run(trial=k)`` runs the trial
    whose seed this is. TypeError for a non-integer argument, ValueError for one out of its
    range, each naming the argument."""
    base = _api._count("base_seed", base_seed, 0, 2**64)
    return int(_usar.trial_seed(base, _api._count("trial", trial, 0, 2**32)))


class GroupingEnv(gymnasium.Env):
    """One USAR trial of ``scenario`` as an episode, one step per grouping round.

    ``scenario``: a :class:`usar.Scenario` or a path (default the paper's mission,
    ``usar.scenario_path("paper.ron")``). Its rounds may start with every robot back
    (``mission.round_start: AllBack``) or group the robots available (``Available``, as
    paper.ron): spaces keep their sizes either way. ``duration_s``: simulated seconds per
    trial (default ``mission.duration_s``). ``reward``: ``"rescued"`` or ``"hard"``.
    ``trial``: given, every reset without a seed or options runs the sweep's trial
    ``trial`` (a fixed-trial environment for evaluation). ``render_mode``: ``None`` or
    ``"rgb_array"``.

    **Observation** (:func:`observation`, a ``spaces.Dict``, robots by id, float32 boxes
    with finite bounds): ``kind``, ``available`` (1 for the robots this round groups),
    ``energy_pct``, ``hp_pct``, ``position_m``, ``needs``, ``distance_to_goal_m``,
    ``quotas`` (this round's, per kind and task), ``time_s``, ``rescued_so_far``.

    **Action**: the task of each robot (``MultiDiscrete([tasks] * robots)``, int). It is
    checked (:func:`check_action`): a wrong shape, a non-integer dtype or a task out of range
    raises ValueError naming ``action`` and leaves the episode as it was. The choices of
    robots not available this round are ignored. An action that breaks a quota is repaired
    to the closest one that keeps them (:func:`repair_assignment`).

    **Reward**: the rescuees of the round the action groups (summed over tasks; with
    ``reward="hard"`` only those of the hardest task). The episode ends (``terminated``) when
    the trial's time is up.

    **info** (every value merges in Gymnasium's vector envs): ``seed`` (the trial's seed as
    a decimal string: ``usar.run(seed=int(info["seed"]))`` runs the same trial), ``trial``
    (the sweep's trial index, -1 for a drawn trial), ``round``, ``action_mask`` ((robots,
    tasks) bool, :func:`action_mask`), ``task_order`` (task ids, hardest first, int64); after
    a step also ``moved`` (robots the repair moved from the task they asked for), ``groups``
    (robot ids per task, as run), ``dt_s`` (simulated seconds of the macro step: from this
    round's start to the next one's or the trial's end) and, at the end, ``result`` (the
    :class:`usar.TrialResult`, method ``gym``).

    **Seeding**: ``reset(seed=S)`` seeds ``env.np_random`` and runs a trial whose seed is
    drawn from it; later unseeded resets draw further trials from the same generator (an
    unseeded first reset from fresh entropy). A drawn seed is never one of the sweep's
    trials 0 to ``HELD_OUT_TRIALS - 1`` (``trial_seed(sim.seed, k)``, redrawn if it is):
    those stay held out for :func:`evaluate`. ``options={"trial": k}`` runs the sweep's
    trial ``k`` (as ``usar.run(trial=k)``), refused with a seed; other option keys are
    refused (ValueError naming the option).

    ``copy.deepcopy(env)``, :meth:`clone` and pickling give an environment at the same point
    of the same episode (the recorded groups replayed) with the same generator state.
    :meth:`replay` writes the episode's replay page. ``close()`` ends a running trial; an
    environment dropped or left open at exit ends its trial too.
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 1}

    def __init__(
        self,
        scenario: Union[Scenario, str, os.PathLike, None] = None,
        duration_s: Optional[float] = None,
        reward: str = "rescued",
        trial: Optional[int] = None,
        render_mode: Optional[str] = None,
    ) -> None:
        super().__init__()
        if reward not in ("rescued", "hard"):
            raise ValueError(f"reward: expected 'rescued' or 'hard', found {reward!r}")
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode: expected None or 'rgb_array', found {render_mode!r}")
        if trial is not None:
            trial = _api._count("trial", trial, 0, 2**32)
        if scenario is None:
            scenario = _data.scenario_path("paper.ron")
        self.scenario = _api._scenario(scenario)
        self.duration_s = None if duration_s is None else _api._seconds(duration_s)
        self.reward_kind = reward
        self.trial = trial
        self.render_mode = render_mode
        self._layout = layout(self.scenario, self.duration_s)
        lay = self._layout
        self._base_seed = int(self.scenario.check()["seed"])
        self._held_out = frozenset(
            _usar.trial_seed(self._base_seed, k) for k in range(HELD_OUT_TRIALS)
        )
        #: Task ids from the hardest to the easiest (the scenario's difficulty order).
        self.task_order = list(lay.task_order)
        #: Task names, by task id.
        self.task_names = list(lay.task_names)
        self._robot_kinds = list(lay.robot_kinds)
        self.observation_space = observation_space(self.scenario, self.duration_s)
        self.action_space = gymnasium.spaces.MultiDiscrete([lay.n_tasks] * lay.n_robots)
        self._runner = Runner()
        # One finalizer per environment: it ends the trial when the environment is collected
        # or, still open, at interpreter exit (weakref.finalize runs at exit by default).
        self._finalizer = weakref.finalize(self, self._runner.stop)
        self._request: Optional[GroupingRequest] = None
        self._obs: Optional[Dict[str, np.ndarray]] = None
        self._seed: Optional[int] = None
        self._trial_index = -1
        self._groups: List[List[List[int]]] = []
        self._frame: Optional[Tuple[int, np.ndarray]] = None
        # Whether the runner's path log is this episode's trial's (not for a copy of an
        # episode that had ended, which ran no trial).
        self._logged = False
        # The start of the round a closed episode stopped at, seconds (None: not closed
        # mid-episode): a copy replays its trial to there for its picture, as the log ends.
        self._stopped_s: Optional[float] = None

    # -- the episode ---------------------------------------------------------------------

    def _score(self, rescued: Sequence[int]) -> int:
        if self.reward_kind == "hard":
            return int(rescued[self.task_order[0]])
        return int(sum(rescued))

    def _info(self) -> Dict[str, Any]:
        return {
            "seed": str(self._seed),
            "trial": self._trial_index,
            "task_order": np.array(self.task_order, dtype=np.int64),
        }

    def _draw_seed(self) -> int:
        while True:
            s = int(self.np_random.integers(0, 2**63, dtype=np.int64))
            if s not in self._held_out:
                return s

    def _start(self, seed: int, trial: int, groups: Sequence[List[List[int]]] = ()) -> None:
        """Starts the trial of ``seed`` and plays ``groups`` (recorded) to the round after."""
        self._request = None
        self._frame = None
        self._runner.start(self.scenario, self.duration_s, trial, seed)
        self._logged = True
        self._stopped_s = None
        self._seed, self._trial_index, self._groups = seed, trial, []
        for g in list(groups) + [None]:
            kind, value = self._runner.next()
            if kind != "request":
                raise RuntimeError("the trial ended before its first grouping round")
            self._request = value
            if g is None:
                break
            self._runner.to_trial.put(g)
            self._groups.append(g)
        self._score_before = self._score(self._request.rescued_so_far)
        self._obs = observation(self._request, self.duration_s)

    def reset(
        self, *, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None
    ) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]:
        """Starts an episode (ending one in progress); see the class's **Seeding**. Returns
        (observation, info). Raises ValueError for an unknown option, ``trial`` with a seed,
        or a bad trial index."""
        options = dict(options or {})
        unknown = sorted(str(k) for k in options if k != "trial")
        if unknown:
            raise ValueError(f"options: unknown option {unknown[0]!r} (known: 'trial')")
        if "trial" in options and seed is not None:
            raise ValueError(
                "options: 'trial' picks one of the sweep's trials and seed draws one: give one"
            )
        super().reset(seed=seed)
        if not self._finalizer.alive:
            self._finalizer = weakref.finalize(self, self._runner.stop)
        if "trial" in options:
            trial = _api._count("options['trial']", options["trial"], 0, 2**32)
        elif seed is None and self.trial is not None:
            trial = self.trial
        else:
            trial = -1
        s = trial_seed(self._base_seed, trial) if trial >= 0 else self._draw_seed()
        self._start(s, trial)
        assert self._request is not None and self._obs is not None
        info = self._info()
        info["round"] = self._request.round
        info["action_mask"] = action_mask(self._request)
        return self._obs, info

    def step(self, action: Any) -> Tuple[Dict[str, np.ndarray], float, bool, bool, Dict[str, Any]]:
        """Groups the round with ``action``; see the class's **Action**, **Reward** and
        **info**. Raises RuntimeError before reset() or after the episode's end, ValueError
        naming ``action`` for a bad action (the episode stays as it was)."""
        if self._request is None or self._runner.thread is None:
            raise RuntimeError("call reset() before step() (no episode in progress)")
        r = self._request
        groups, moved = groups_of_action(r, action)
        self._runner.to_trial.put(groups)
        self._groups.append(groups)
        self._frame = None
        try:
            kind, value = self._runner.next()
        except BaseException:
            self._request = None
            raise
        info = self._info()
        info.update(moved=moved, groups=groups)
        if kind == "request":
            self._request = value
            score = self._score(value.rescued_so_far)
            self._obs = observation(value, self.duration_s)
            info["round"] = value.round
            info["action_mask"] = action_mask(value)
            info["dt_s"] = float(value.time_s - r.time_s)
            terminated = False
        else:
            self._request = None
            # A new object: the caller may keep the last observation.
            assert self._obs is not None
            self._obs = {key: v.copy() for key, v in self._obs.items()}
            score = self._score(value.rescued)
            info["round"] = len(self._groups)
            mask = np.zeros((self._layout.n_robots, self._layout.n_tasks), dtype=bool)
            mask[:, 0] = True
            info["action_mask"] = mask
            info["dt_s"] = float(max(self._layout.end_s - r.time_s, 0.0))
            info["result"] = value
            terminated = True
        reward = float(score - self._score_before)
        self._score_before = score
        return self._obs, reward, terminated, False, info

    def close(self) -> None:
        """Ends a trial in progress (the environment can be reset again)."""
        if self._request is not None:
            self._stopped_s = float(self._request.time_s)
        self._request = None
        self._finalizer()
        super().close()

    # -- copies ----------------------------------------------------------------------------

    def _state(self) -> Dict[str, Any]:
        return {
            "kwargs": dict(
                scenario=self.scenario, duration_s=self.duration_s, reward=self.reward_kind,
                trial=self.trial, render_mode=self.render_mode,
            ),
            "np_random": copy.deepcopy(self._np_random),
            "episode": (self._seed, self._trial_index, [copy.deepcopy(g) for g in self._groups]),
            "running": self._request is not None,
            "stopped_s": self._stopped_s,
        }

    @classmethod
    def _from_state(cls, state: Dict[str, Any]) -> "GroupingEnv":
        env = cls(**state["kwargs"])
        env._np_random = state["np_random"]
        seed, trial, groups = state["episode"]
        if state["running"]:
            env._start(seed, trial, groups)
        else:
            env._seed, env._trial_index, env._groups = seed, trial, groups
            env._stopped_s = state.get("stopped_s")
        return env

    def clone(self) -> "GroupingEnv":
        """A new environment at the same point: the same arguments and generator state and,
        in an episode, the same trial at the same round (its recorded groups replayed, as
        fast as the simulation runs them). ``copy.deepcopy(env)`` and pickling make the
        same."""
        return self._from_state(self._state())

    def __deepcopy__(self, memo: Dict[int, Any]) -> "GroupingEnv":
        return self.clone()

    def __reduce__(self) -> Tuple[Callable[..., Any], Tuple[Any, ...]]:
        return (_restore, (self._state(),))

    # -- pictures --------------------------------------------------------------------------

    def _svg(self) -> str:
        """The arena picture (``usar.render``'s) with every robot's path so far, as SVG: drawn
        from the paths the episode's trial recorded as it ran (no trial runs) or, for a copy
        of an episode that had ended (no trial of this environment ran it), replayed."""
        if self._seed is None or not self._groups:
            return _usar.episode_svg(self.scenario)
        if self._logged:
            return _usar.episode_svg(self.scenario, self._runner.log)
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "frame.svg")
            if self._request is not None:
                now = self._request.time_s
            elif self._stopped_s is not None:
                now = self._stopped_s
            else:
                now = self._layout.end_s
            _studies.render(
                self.scenario, out, method=Replayer(self._groups), seed=self._seed,
                duration_s=now,
            )
            with open(out, encoding="utf-8") as f:
                return f.read()

    def render(self) -> Optional[np.ndarray]:  # type: ignore[override]
        """With ``render_mode="rgb_array"``: the arena picture of ``usar.render`` with every
        robot's path from the trial's start to the current round's start (the episode's end
        once it is over; after ``close()`` mid-episode, the round it stopped at), rasterised
        with resvg: an (H, W, 3) uint8 array (the picture's size, about 1160 x 780 for
        paper.ron; its text labels are not drawn), a new array each call. ``None`` without a
        render mode. The paths come from the episode's own trial, recorded as it runs: a
        frame costs one picture and no trial (the frame is cached until the next step; a
        copy of an episode that had ended replays its trial once)."""
        if self.render_mode is None:
            return None
        key = len(self._groups)
        if self._frame is None or self._frame[0] != key:
            h, w, rgb = _usar.rasterize_svg(self._svg())
            self._frame = (key, np.frombuffer(rgb, dtype=np.uint8).reshape(h, w, 3).copy())
        return self._frame[1].copy()

    def replay(self, out: Union[str, os.PathLike], hz: Optional[float] = None) -> Any:
        """Writes the replay page (``usar.replay``, docs/replay.md) of the current or last
        episode to ``out``: its trial with the groups the actions made, to the current round's
        start (the trial's end once it is over; after ``close()`` mid-episode, the round it
        stopped at, as ``render()``). ``hz``: samples per simulated second. Returns the
        :class:`usar.TrialResult` of what the page shows. RuntimeError before any reset."""
        if self._seed is None:
            raise RuntimeError("call reset() first: there is no episode to replay")
        now = self._request.time_s if self._request is not None else self._stopped_s
        duration = self.duration_s if now is None else max(now, 1e-9)
        return _studies.replay(
            self.scenario, out, method=Replayer(self._groups), seed=self._seed,
            duration_s=duration, hz=hz,
        )


def _restore(state: Dict[str, Any]) -> GroupingEnv:
    """Unpickles a :class:`GroupingEnv` (its ``__reduce__``)."""
    return GroupingEnv._from_state(state)


# -- a policy as a grouping method, and its evaluation --------------------------------------


class _PolicyMethod(GroupingMethod):
    """See :func:`policy_method`."""

    def __init__(self, policy: Any, name: str, duration_s: Optional[float]) -> None:
        self.policy, self.name, self._duration_s = policy, name, duration_s
        self._predict = getattr(policy, "predict", None)
        if not callable(self._predict) and not callable(policy):
            raise TypeError(
                "policy: expected a callable obs -> action or an object with "
                f".predict(obs), found {type(policy).__name__}"
            )

    def group(self, request: GroupingRequest) -> List[List[int]]:
        obs = observation(request, self._duration_s)
        if callable(self._predict):
            action = self._predict(obs, deterministic=True)
            if isinstance(action, tuple):
                action = action[0]
        else:
            action = self.policy(obs)
        return groups_of_action(request, action)[0]


def policy_method(policy: Any, name: str = "policy", duration_s: Optional[float] = None) -> GroupingMethod:
    """A grouping method for :func:`usar.run`, :func:`usar.sweep` and the studies that asks
    ``policy`` each round: ``policy(obs) -> action`` (a callable) or ``policy.predict(obs,
    deterministic=True) -> (action, state)`` (a stable-baselines3 model or the like), with
    ``obs`` built by :func:`observation` exactly as :class:`GroupingEnv` builds it
    (``duration_s``: the environment's, for the ``time_s`` bound only) and ``action`` taken
    as the environment takes it (:func:`groups_of_action`: checked, ValueError naming
    ``action``; repaired to the quotas). Results name it ``name``. TypeError for a policy
    that is neither."""
    if not isinstance(name, str) or not name:
        raise TypeError(f"name: expected a non-empty str, found {name!r}")
    return _PolicyMethod(policy, name, duration_s)


def evaluate(
    policy: Any,
    scenario: Union[Scenario, str, os.PathLike, None] = None,
    trials: int = 30,
    methods: Sequence[str] = ("rne", "hp_dis"),
    name: str = "policy",
    duration_s: Optional[float] = None,
    metric: str = "rescued_total",
    test: str = "paired",
    threads: Optional[int] = None,
) -> Tuple[Any, Any]:
    """Runs ``policy`` (as :func:`policy_method`, named ``name``) and the grouping
    ``methods`` (built-in names or Python methods) on the sweep's trials 0 to ``trials - 1``
    of ``scenario`` (default paper.ron), the trials the environment never draws for training
    (see :class:`GroupingEnv`, **Seeding**), over ``duration_s`` (default
    ``mission.duration_s``) on ``threads`` threads (default all cores).

    Returns ``(trials_df, verdicts_df)``: the sweep's long table (:func:`usar.sweep`) and
    ``usar.compare(trials_df, name, methods, metric=metric, test=test)``, one row per rival
    (columns include method, rival, test, statistic, p_value, effect_size, verdict).
    Raises as :func:`usar.sweep` and :func:`usar.compare`."""
    import usar

    s = _api._scenario(_data.scenario_path("paper.ron") if scenario is None else scenario)
    method = policy_method(policy, name=name, duration_s=duration_s)
    rivals = list(methods)
    trials_df = _api.sweep(s, methods=[method, *rivals], trials=trials, duration_s=duration_s,
                           threads=threads)
    compare = getattr(usar, "compare", None)
    if compare is None:
        raise RuntimeError("evaluate: usar.compare is missing from this build of usar")
    rival_names = [r if isinstance(r, str) else _grouping_name(r) for r in rivals]
    verdicts = compare(trials_df, name, rival_names, metric=metric, test=test)
    return trials_df, verdicts


def _grouping_name(method: Any) -> str:
    from ._grouping import method_name

    return method_name(method)


if ENV_ID not in gymnasium.registry:
    gymnasium.register(id=ENV_ID, entry_point="usar.gym:GroupingEnv")
