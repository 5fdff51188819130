"""The thread machinery of a :class:`usar.gym.GroupingEnv` episode: its trial runs as
``usar.run`` in a thread of its own (:class:`Runner`), with a grouping method
(:class:`EnvMethod`) that hands each round's request to the environment and waits for the
groups its action makes, and records every robot's path as it goes (its ``PathLog``, which
the environment's pictures are drawn from); :class:`Replayer` answers an episode's recorded
groups again (its replay page, the picture of a copied episode that had ended). Private: use
:mod:`usar.gym`.
"""

from __future__ import annotations

import json
import queue
import threading
from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

from . import _usar
from ._grouping import GroupingMethod, GroupingRequest, method_arg
from ._observation import groups_of_action, layout
from ._results import TrialResult
from ._usar import Scenario


class Stop(Exception):
    """Raised inside the trial's thread to end an episode that is abandoned."""


class EnvMethod(GroupingMethod):
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
            raise Stop()
        return groups


class Replayer(GroupingMethod):
    """Answers an episode's recorded groups in turn (named ``gym``, as the episode's method);
    past them, the action of all zeros repaired to the quotas."""

    name = "gym"

    def __init__(self, groups: Sequence[List[List[int]]]) -> None:
        self._groups = list(groups)
        self._lock = threading.Lock()

    def group(self, request: GroupingRequest) -> List[List[int]]:
        with self._lock:
            if request.round < len(self._groups):
                return self._groups[request.round]
        lay = layout(request.scenario)
        return groups_of_action(request, np.zeros(lay.n_robots, dtype=np.int64))[0]


def run_trial(
    scenario: Scenario,
    duration_s: Optional[float],
    trial: int,
    seed: int,
    to_trial: "queue.Queue[Any]",
    from_trial: "queue.Queue[Any]",
    log: _usar.PathLog,
) -> None:
    """The episode's trial (the sweep's trial ``trial``, or the seed ``seed`` as is when
    ``trial`` is -1), in its thread, run as :func:`usar.run` runs it, ``log`` recording every
    robot's path as it goes: its result, `stopped` or its error at the end."""
    method = method_arg(EnvMethod(to_trial, from_trial), scenario)
    try:
        if trial >= 0:
            text = _usar.run_trial_logged(scenario, method, log, trial, duration_s, None)
        else:
            text = _usar.run_trial_logged(scenario, method, log, 0, duration_s, seed)
        from_trial.put(("done", TrialResult(json.loads(text))))
    except Stop:
        from_trial.put(("stopped", None))
    except BaseException as e:  # noqa: BLE001 - handed to the caller of step()
        from_trial.put(("error", e))


class Runner:
    """The thread of an environment's current trial, its two queues and the log of its paths
    (``log``, a new :class:`usar._usar.PathLog` per trial). It holds no reference
    to the environment: the environment's one finalizer (``weakref.finalize``, also run at
    interpreter exit) calls :meth:`stop`, so that no trial thread is still inside the native
    module when Python finalizes (a daemon thread that takes the GIL then is ended with
    ``pthread_exit``, whose unwinding through the native frames aborts the process)."""

    def __init__(self) -> None:
        self.thread: Optional[threading.Thread] = None
        self.to_trial: "queue.Queue[Any]" = queue.Queue()
        self.from_trial: "queue.Queue[Tuple[str, Any]]" = queue.Queue()
        self.log = _usar.PathLog()

    def start(
        self, scenario: Scenario, duration_s: Optional[float], trial: int, seed: int
    ) -> None:
        self.stop()
        self.to_trial, self.from_trial = queue.Queue(), queue.Queue()
        self.log = _usar.PathLog()
        self.thread = threading.Thread(
            target=run_trial,
            args=(scenario, duration_s, trial, seed, self.to_trial, self.from_trial, self.log),
            name="usar.gym trial",
            daemon=True,
        )
        self.thread.start()

    def next(self) -> Tuple[str, Any]:
        """The trial's next message: ``("request", GroupingRequest)`` or ``("done",
        TrialResult)``; its error is raised."""
        kind, value = self.from_trial.get()
        if kind != "request":
            self.join()
        if kind == "error":
            raise value
        return kind, value

    def join(self) -> None:
        if self.thread is not None:
            self.thread.join()
        self.thread = None

    def stop(self) -> None:
        """Ends the trial (if running) and waits for its thread."""
        if self.thread is not None and self.thread.is_alive():
            self.to_trial.put(None)
            while True:
                kind, _ = self.from_trial.get()
                if kind in ("stopped", "done", "error"):
                    break
                self.to_trial.put(None)
        self.join()
