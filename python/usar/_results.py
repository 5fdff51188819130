"""The result of one trial (:func:`usar.run`), read from the JSON of ``usar run --json``."""

from __future__ import annotations

import copy
import re
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

    def rounds_frame(self) -> "pandas.DataFrame":  # noqa: F821
        """The per-round yields as a tidy DataFrame, one row per round and task: the columns
        of ``usar run --rounds-csv`` but ``cell`` (``method, trial, seed, round, task,
        start_s, end_s, completed, group_size, rescued, left_area_s, left_because,
        deliveries, empty_deliveries, left_for_rest, back_s, wait_s``), the same values
        (``left_because`` as ``search_budget``, ``capacity_full``, ...; ``wait_s`` is
        ``end_s - back_s``; a figure the round does not have is missing, NaN or None)."""
        import pandas as pd

        rows = []
        for i, r in enumerate(self._data.get("rounds", [])):
            for t, task in enumerate(self._data["tasks"]):
                def at(key: str) -> Any:
                    values = r.get(key) or []
                    return values[t] if t < len(values) else None

                back = at("back_s")
                cause = at("left_because")
                groups = r.get("groups") or []
                rows.append({
                    "method": self._data["method"],
                    "trial": self._data["trial"],
                    "seed": self._data["seed"],
                    "round": i,
                    "task": task,
                    "start_s": r["start_s"],
                    "end_s": r["end_s"],
                    "completed": r["completed"],
                    "group_size": len(groups[t]) if t < len(groups) else 0,
                    "rescued": at("rescued") or 0,
                    "left_area_s": at("left_area_s"),
                    "left_because": None if cause is None else _snake(cause),
                    "deliveries": at("deliveries"),
                    "empty_deliveries": at("empty_deliveries"),
                    "left_for_rest": at("left_for_rest"),
                    "back_s": back,
                    "wait_s": None if back is None else r["end_s"] - back,
                })
        frame = pd.DataFrame(rows, columns=_ROUND_COLUMNS)
        return frame.astype({"trial": "int64", "seed": "uint64"})

    def _repr_html_(self) -> str:
        """A table for notebooks: rescuees, energy and HP spent per task and in total."""
        from html import escape

        rows = "".join(
            f"<tr><td>{escape(str(t))}</td><td>{r}</td><td>{e:.1f}</td><td>{h:.1f}</td></tr>"
            for t, r, e, h in zip(
                self._data["tasks"], self._data["rescued"],
                self._data["energy_spent_pct"], self._data["hp_lost_pct"],
            )
        )
        return (
            f"<div><b>usar.TrialResult</b> {escape(str(self._data['scenario']))}, "
            f"{escape(str(self._data['method']))}, trial {self._data['trial']}, "
            f"{self._data['duration_s']} s, {len(self.rounds)} rounds"
            "<table><tr><th>task</th><th>rescued</th><th>energy spent, % points</th>"
            f"<th>HP lost, % points</th></tr>{rows}"
            f"<tr><td><i>total</i></td><td>{self.rescued_total}</td><td></td><td></td></tr>"
            "</table></div>"
        )

    @property
    def rescued_total(self) -> int:
        """Rescuees delivered over all tasks."""
        return int(sum(self._data["rescued"]))


_ROUND_COLUMNS = [
    "method", "trial", "seed", "round", "task", "start_s", "end_s", "completed", "group_size",
    "rescued", "left_area_s", "left_because", "deliveries", "empty_deliveries", "left_for_rest",
    "back_s", "wait_s",
]


def _snake(name: str) -> str:
    """``SearchBudget`` -> ``search_budget``, as the rounds CSV writes a leave cause."""
    return re.sub(r"(?<!^)(?=[A-Z])", "_", name).lower()
