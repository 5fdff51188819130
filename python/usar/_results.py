"""The result of one trial (:func:`usar.run`), read from the JSON of ``usar run --json``."""

from __future__ import annotations

import copy
from typing import Any, Dict, List


class Record:
    """A JSON object with its keys as attributes (a round, a robot's metrics, task figures).

    ``to_dict()`` gives the JSON object back, as ``usar run --json`` writes it.
    """

    def __init__(self, data: Dict[str, Any]) -> None:
        self._data = data
        for key, value in data.items():
            setattr(self, key, value)

    def to_dict(self) -> Dict[str, Any]:
        """The record as a dict (a deep copy): the JSON object of ``usar run --json``."""
        return copy.deepcopy(self._data)

    def __repr__(self) -> str:
        fields = ", ".join(f"{k}={v!r}" for k, v in list(self._data.items())[:6])
        return f"{type(self).__name__}({fields}{', ...' if len(self._data) > 6 else ''})"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Record) and self._data == other._data


class TrialResult(Record):
    """One trial's result: the fields of ``usar run --json`` as attributes.

    Attributes (units in the names): ``scenario``, ``method`` (display name, e.g. ``RNE``),
    ``trial``, ``seed``, ``duration_s`` (simulated seconds), ``tasks`` (names, scenario order),
    ``rescued`` (rescuees delivered per task, list in task order), ``energy_spent_pct`` and
    ``hp_lost_pct`` (per task, percent points summed over robots), ``by_task`` (task name ->
    :class:`Record` with ``rescued``, ``energy_spent_pct``, ``hp_lost_pct``), ``total`` (the
    same over all tasks), ``rounds`` (list of :class:`Record`: ``start_s``, ``end_s``,
    ``completed``, ``groups``, ``rescued``, and per task ``left_area_s``, ``left_because``,
    ``deliveries``, ``empty_deliveries``, ``left_for_rest``, ``back_s``: the per-round yields of
    docs/calibration.md) and ``robots`` (list of :class:`Record` per robot:
    ``id``, ``kind``, ``distance_m``, ``final_energy_pct``, ``final_hp_pct``,
    ``energy_spent_pct``, ``hp_lost_pct``, ``recharges``, ``time_in_radiation_s``,
    ``time_held_s``, ``collision_lists``, ``deadlocks_resolved``, ``picked_up``,
    ``delivered``, ``unreachable_goals``). ``to_dict()`` is the JSON object itself.
    """

    rounds: List[Record]
    robots: List[Record]
    by_task: Dict[str, Record]
    total: Record

    def __init__(self, data: Dict[str, Any]) -> None:
        super().__init__(data)
        self.rounds = [Record(r) for r in data.get("rounds", [])]
        self.robots = [Record(r) for r in data.get("robots", [])]
        self.by_task = {k: Record(v) for k, v in data.get("by_task", {}).items()}
        self.total = Record(data.get("total", {}))

    @property
    def rescued_total(self) -> int:
        """Rescuees delivered over all tasks."""
        return int(sum(self._data["rescued"]))
