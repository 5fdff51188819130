"""usar.run, usar.sweep and usar.trust: the Python entry points over the native module."""

from __future__ import annotations

import io
import json
import os
import sys
from typing import Any, List, Optional, Sequence, Union

import numpy as np
import pandas as pd

from . import _usar
from ._grouping import MethodLike, method_arg
from ._results import TrialResult
from ._usar import METHOD_NAMES, Scenario

_U64 = 2**64


def _scenario(scenario: Any) -> Scenario:
    if isinstance(scenario, Scenario):
        return scenario
    if isinstance(scenario, (str, os.PathLike)):
        return Scenario.load(os.fspath(scenario))
    raise TypeError(f"scenario: expected a usar.Scenario or a path, found {type(scenario).__name__}")


def _count(name: str, value: Any, minimum: int, maximum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        hint = ""
        if name == "seed" and isinstance(value, (float, np.floating)):
            hint = (
                " (a float cannot hold every 64-bit integer; a seed column read by"
                " usar.read_trials_long or returned by usar.sweep is uint64)"
            )
        raise TypeError(f"{name}: expected an integer, found {type(value).__name__}{hint}")
    if not minimum <= int(value) < maximum:
        raise ValueError(f"{name} must be in {minimum}..{maximum - 1}, not {value}")
    return int(value)


def _seconds(value: Any) -> Optional[float]:
    # Only the type: the library refuses a length that is not a positive number of seconds.
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
        raise TypeError(f"duration_s: expected seconds as a number, found {type(value).__name__}")
    return float(value)


def _folder(out: Any) -> Any:
    """``out`` as a folder's path (None stays None). Raises ValueError for an empty path,
    which would name the working folder (pathlib reads ``''`` as ``'.'``)."""
    if out is None:
        return None
    text = os.fspath(out)
    if not text:
        raise ValueError(
            "out: the output folder is an empty path; name a folder (\".\" is the working folder)"
        )
    return text


def run(
    scenario: Union[Scenario, str, os.PathLike],
    method: MethodLike = "rne",
    trial: Optional[int] = None,
    duration_s: Optional[float] = None,
    seed: Optional[int] = None,
) -> TrialResult:
    """Runs one trial, as ``usar run SCENARIO --method M --trial K [--duration D] [--seed S]``.

    ``method``: a built-in name (``rne``, ``dis``, ``eng``, ``hp_dis``), a
    :class:`usar.GroupingMethod` (instance or subclass) or any callable ``group(request)``.
    ``trial`` (>= 0, default 0) picks the starting team, seed ``trial_seed(sim.seed, trial)``;
    ``seed`` (0 <= seed < 2**64) is used as is instead (give one of them: both is a
    ValueError, as ``--trial`` with ``--seed`` is). ``duration_s``: simulated
    seconds (> 0), default the scenario's ``mission.duration_s`` (rounded up to whole steps).

    Returns a :class:`usar.TrialResult`, equal to ``usar run --json``'s output. The trial
    runs with the GIL released; a Python method takes it once per grouping round.

    Raises ValueError (unknown method, bad numbers, a scenario file that does not load),
    TypeError (wrong argument types), :class:`usar.GroupingError` (a Python method's bad
    answer), the Python method's own exception, :class:`usar.TrialError` (another failure)
    and KeyboardInterrupt (Ctrl-C).
    """
    if trial is not None and seed is not None:
        raise ValueError(
            "trial and seed: give trial or seed, not both"
            " (a trial's seed is trial_seed(sim.seed, trial))"
        )
    s = _scenario(scenario)
    trial = _count("trial", 0 if trial is None else trial, 0, 2**32)
    seed = None if seed is None else _count("seed", seed, 0, _U64)
    arg = method_arg(method, s)
    return TrialResult(json.loads(_usar.run_trial(s, arg, trial, _seconds(duration_s), seed)))


def _progress(
    progress: Optional[bool], total: int, unit: str = "trial", desc: str = "sweep"
) -> tuple:
    """(callback, closer) of a tqdm bar over ``total`` steps named ``unit``, or (None, no-op)."""
    if progress is None:
        progress = sys.stderr.isatty() or "ipykernel" in sys.modules
    if not progress:
        return None, lambda: None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None, lambda: None
    bar = tqdm(total=total, unit=unit, desc=desc)

    def update(done: int, total: int) -> None:
        if total != bar.total:  # a grid's trials (every cell's), a resumed study
            bar.total = total
            bar.refresh()
        if done > bar.n:
            bar.update(done - bar.n)

    return update, bar.close


# pandas before 3.0 parses floats fast but inexactly unless asked; 3.0 parses them exactly
# by default and deprecates the option.
_EXACT = {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}


# Column types that do not depend on the data: a trial seed is any 64-bit unsigned integer,
# so `seed` is uint64 even when every seed of a sweep is below 2**63 (pandas would guess int64,
# and `pd.concat` of an int64 and a uint64 column makes float64, which loses seeds).
_DTYPES = {"trial": "int64", "seed": "uint64"}


def read_trials_long(path: Any) -> pd.DataFrame:
    """Reads a ``trials_long.csv`` (a path or a binary file) as :func:`usar.sweep` returns
    it: every float exactly the f64 written (shortest round-trip text), ``trial`` int64 and
    ``seed`` uint64 whatever the values (so frames of several sweeps concatenate without
    losing a seed, and ``usar.run(seed=row.seed)`` repeats a trial)."""
    return pd.read_csv(path, dtype=_DTYPES, **_EXACT)


#: How a long row's (metric, task) names its trials.csv column; ``{t}`` is the task's name.
_WIDE_NAMES = {
    "rescued": ("rescued_total", "rescued_{t}"),
    "energy_pct": ("energy_total_pct", "energy_{t}_pct"),
    "hp_pct": ("hp_total_pct", "hp_{t}_pct"),
    "energy_per_rescuee_pct": ("energy_per_rescuee_pct", "energy_per_{t}_rescuee_pct"),
    "hp_per_rescuee_pct": ("hp_per_rescuee_pct", "hp_per_{t}_rescuee_pct"),
}

#: The trials.csv columns of each long metric, per-task ones first (``{t}``), then the total.
_WIDE_ORDER = [
    ("rescued", True),
    ("energy_pct", False),
    ("hp_pct", False),
    ("rounds", None),
    ("energy_per_rescuee_pct", False),
    ("hp_per_rescuee_pct", False),
    ("mean_round_s", None),
]


def wide(frame: pd.DataFrame) -> pd.DataFrame:
    """The long table of :func:`usar.sweep` (or :func:`usar.read_trials_long`, or
    :func:`usar.grid`) as ``trials.csv`` has it: one row per trial (``scenario, method,
    trial, seed``, after a grid's ``cell`` and varied fields; in the long table's order) and one column per metric and task, named as ``trials.csv`` names them
    (``rescued_total``, ``rescued_hard``, ``energy_hard_pct``, ``energy_total_pct``, ...,
    ``rounds``, ``energy_per_hard_rescuee_pct``, ..., ``mean_round_s``), in its column order.
    Counts (``rescued_*``, ``rounds``) are int64; a cost per rescuee without rescuees is NaN.

    Raises ValueError for a frame without the long table's columns.
    """
    needed = ["scenario", "method", "trial", "seed", "task", "metric", "value"]
    missing = [c for c in needed if c not in frame.columns]
    if missing:
        raise ValueError(f"frame: not a long table of usar.sweep (no column {missing[0]!r})")
    # A grid's frame (usar.grid) leads with the cell and its values: they are keys too.
    keys = list(frame.columns[: list(frame.columns).index("task")])
    tasks = [t for t in pd.unique(frame["task"].fillna("")) if t not in ("", "total")]

    def column(metric: str, task: Any) -> str:
        if metric not in _WIDE_NAMES:
            return metric
        total, per_task = _WIDE_NAMES[metric]
        return total if task == "total" else per_task.format(t=task)

    names = [column(m, t) for m, t in zip(frame["metric"], frame["task"].fillna(""))]
    rows = pd.MultiIndex.from_frame(frame[keys].drop_duplicates())
    table = (
        frame.assign(_column=names)
        .set_index(keys + ["_column"])["value"]
        .unstack("_column")
        .reindex(rows)
    )
    order: List[str] = []
    for metric, total_first in _WIDE_ORDER:
        if total_first is None:
            order.append(metric)
            continue
        per_task = [column(metric, t) for t in tasks]
        total = [column(metric, "total")]
        order += total + per_task if total_first else per_task + total
    out = table.reindex(columns=[c for c in order if c in table.columns]).reset_index()
    out.columns.name = None
    for c in out.columns:
        if c == "rounds" or c.startswith("rescued_"):
            out[c] = out[c].astype("int64")
    return out.astype({"trial": "int64", "seed": "uint64"})


def _run_cells(
    scenario: Any, methods: Any, trials: Any, threads: Any, out: Any, resume: bool,
    duration_s: Any, seed: Any, progress: Optional[bool], overwrite: bool, targets: Any,
    claims: Any, vary: List[str],
) -> list:
    """The arguments of :func:`sweep` and :func:`grid` checked, then the native sweep: per
    cell, the varied fields' values and the bytes of its ``trials_long.csv``."""
    s = _scenario(scenario)
    if methods is None:
        methods = list(METHOD_NAMES)
    if isinstance(methods, (str, bytes)) or callable(methods):
        methods = [methods]
    args = [method_arg(m, s) for m in methods]
    # Only what the native call can hold: the library refuses 0 trials or threads itself.
    trials = _count("trials", trials, 0, 2**32)
    threads = None if threads is None else _count("threads", threads, 0, 2**16)
    seed = None if seed is None else _count("seed", seed, 0, _U64)
    folder = _folder(out)
    callback, close = _progress(progress, len(args) * trials)
    try:
        return _usar.run_sweep(
            s, args, trials, threads, folder, bool(resume), _seconds(duration_s), seed, callback,
            bool(overwrite),
            None if targets is None else os.fspath(targets),
            os.fspath(claims) if isinstance(claims, (str, os.PathLike)) else claims,
            vary,
        )
    finally:
        close()


def sweep(
    scenario: Union[Scenario, str, os.PathLike],
    methods: Optional[Sequence[MethodLike]] = None,
    trials: int = 10,
    threads: Optional[int] = None,
    out: Optional[Union[str, os.PathLike]] = None,
    resume: bool = False,
    duration_s: Optional[float] = None,
    seed: Optional[int] = None,
    progress: Optional[bool] = None,
    overwrite: bool = False,
    targets: Optional[Union[str, os.PathLike]] = None,
    claims: Optional[Union[str, os.PathLike, Sequence[dict]]] = None,
) -> pd.DataFrame:
    """Runs every method for ``trials`` trials, as ``usar sweep``, and returns the long table.

    ``methods``: names and/or Python methods (default the four built-ins, in
    ``usar.METHOD_NAMES`` order). ``trials`` >= 1 per method; trial ``k`` of every method
    starts from the same team (seed ``trial_seed(seed or sim.seed, k)``). ``threads`` >= 1
    (default all cores; results do not depend on it). ``duration_s``: simulated seconds per
    trial (> 0), default ``mission.duration_s``. ``out``: a folder to write what
    ``usar sweep --out`` writes (journal.jsonl, trials.csv, trials_long.csv, summary.csv,
    report.md, figures); ``resume=True`` continues its journal; ``overwrite=True`` discards
    a sweep's journal, tables and figures already in ``out`` and starts afresh (other files
    stay; a folder of another kind, such as a calibration's, is refused, and so is a folder of
    your own files that no run wrote). ``progress``: a tqdm
    bar (default: on a terminal or in a notebook, when tqdm is installed). With ``out``,
    ``targets`` (a targets file, as ``--targets``) and ``claims`` (a claims file, as
    ``--claims``, or a list of claims as dicts with a claims file's fields: ``{"id": "1",
    "sentence": ..., "subject": "my_method", "metric": "rescued_hard", "direction": "More",
    "rivals": {"Only": ["DIS"]}}``) are checked in ``out/report.md``; default those the
    scenario's ``report`` section names.

    Returns a DataFrame equal to ``trials_long.csv`` read by :func:`usar.read_trials_long`:
    columns ``scenario, method, trial, seed, task, metric, value``, the same rows in the
    same order. Trials run in parallel with the GIL released; Ctrl-C stops the sweep
    (KeyboardInterrupt; with ``out`` the finished trials stay in the journal).

    Raises ValueError, TypeError, :class:`usar.GroupingError` or a Python method's own
    exception (the first one met), :class:`usar.TrialError` (failed trials, after the others
    ran) and KeyboardInterrupt.
    """
    data = _run_cells(
        scenario, methods, trials, threads, out, resume, duration_s, seed, progress,
        overwrite, targets, claims, [],
    )
    return read_trials_long(io.BytesIO(bytes(data[0][1])))


def grid(
    scenario: Union[Scenario, str, os.PathLike],
    vary: Sequence[str],
    methods: Optional[Sequence[MethodLike]] = None,
    trials: int = 10,
    threads: Optional[int] = None,
    out: Optional[Union[str, os.PathLike]] = None,
    resume: bool = False,
    duration_s: Optional[float] = None,
    seed: Optional[int] = None,
    progress: Optional[bool] = None,
    overwrite: bool = False,
    targets: Optional[Union[str, os.PathLike]] = None,
    claims: Optional[Union[str, os.PathLike, Sequence[dict]]] = None,
) -> pd.DataFrame:
    """A parameter grid, as ``usar sweep SCENARIO --vary FIELD=V1,V2 ...``: the comparison once
    per cell, every combination of the ``vary`` values (``["mission.pickup_s=0,1",
    "kinds[*].max_speed_m_per_s=1,1.5"]``; the first varies slowest), the same trials and
    seeds in every cell. The other arguments are :func:`usar.sweep`'s; with ``out`` it writes
    what ``usar sweep --vary ... --out`` writes (a folder per cell, ``grid.csv``,
    ``grid.md``, the grid figures).

    Returns the long table of every cell, cell after cell, with the cell's index (``cell``)
    and the value of each varied field as written (a column named by its path) before the
    long table's columns.

    Raises ValueError for a bad ``vary`` (naming the argument and what is wrong), else as
    :func:`usar.sweep`.
    """
    if isinstance(vary, (str, bytes)):
        vary = [vary]
    vary = [str(v) for v in vary]
    if not vary:
        raise ValueError("vary: give at least one FIELD=V1,V2,... (usar.sweep runs one cell)")
    fields = [v.split("=", 1)[0].strip() for v in vary]
    data = _run_cells(
        scenario, methods, trials, threads, out, resume, duration_s, seed, progress,
        overwrite, targets, claims, vary,
    )
    frames = []
    for cell, (values, csv) in enumerate(data):
        frame = read_trials_long(io.BytesIO(bytes(csv)))
        for position, (field, value) in enumerate(zip(fields, values)):
            frame.insert(position, field, value)
        frame.insert(0, "cell", cell)
        frames.append(frame)
    return pd.concat(frames, ignore_index=True)


def trust(
    weights: Sequence[float], needs_a: Sequence[float], needs_b: Sequence[float]
) -> float:
    """Trust of robot A in robot B, nats (paper Eq. 7; Example 1 gives 0.00373).

    ``weights``: one per needs category, > 0; ``needs_a``, ``needs_b``: needs vectors
    (paper Def. 1) of the same length, >= 0. Lists or 1-D numpy arrays. Raises ValueError
    for empty, mismatched, negative or non-finite values.
    """
    vectors = []
    for name, v in (("weights", weights), ("needs_a", needs_a), ("needs_b", needs_b)):
        a = np.asarray(v, dtype=float)
        if a.ndim != 1:
            raise ValueError(f"{name}: expected a 1-D vector, found shape {a.shape}")
        vectors.append([float(x) for x in a])
    return _usar.trust(*vectors)


