"""usar.calibrate, usar.multiverse, usar.render and usar.replay: the studies and pictures of
the ``usar`` command line, with Python grouping methods beside the built-in ones."""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from html import escape
from pathlib import Path, PurePath
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

import pandas as pd

from . import _usar
from ._api import _EXACT, _count, _folder, _progress, _scenario, _seconds, _U64
from ._grouping import MethodLike, method_arg
from ._results import TrialResult
from ._usar import METHOD_NAMES, Scenario

FreeLike = Union[str, Sequence[str], Mapping[str, Sequence[Any]]]


def _free(free: FreeLike) -> List[str]:
    """``free`` as ``--free`` takes it: ``"FIELD=LO..HI[:log][,factor]"`` strings, or a dict
    ``{field: (lo, hi)}`` / ``{field: (lo, hi, "log")}`` (the third item what follows ``:``)."""
    if isinstance(free, str):
        items = [free]
    elif isinstance(free, Mapping):
        items = []
        for field, bounds in free.items():
            b = list(bounds)
            if len(b) not in (2, 3):
                raise ValueError(
                    f"free[{field!r}]: expected (lo, hi) or (lo, hi, 'log'), found {bounds!r}"
                )
            text = f"{field}={float(b[0])!r}..{float(b[1])!r}"
            items.append(text + (f":{b[2]}" if len(b) == 3 else ""))
    else:
        items = [str(f) for f in free]
    return items  # none is the library's error (free: give at least one FIELD=LO..HI)


def _methods(methods: Any, s: Scenario) -> list:
    if methods is None:
        methods = list(METHOD_NAMES)
    if isinstance(methods, (str, bytes)) or callable(methods):
        methods = [methods]
    return [method_arg(m, s) for m in methods]


def _names(values: Any) -> List[str]:
    """Target names: one, or a list of them."""
    return [values] if isinstance(values, str) else [str(v) for v in values]


def _path(value: Any) -> Optional[str]:
    return None if value is None else os.fspath(value)


def _out_file(out: Any) -> Any:
    """``out`` as the path of a file to write. Raises ValueError, before anything runs, for
    a folder (``out: '.' is a folder, not a file``) or a path that names no file (``''``,
    ``'a/..'``: ``out: '' has no file name``)."""
    text = os.fspath(out)
    if os.path.isdir(text):
        raise ValueError(f"out: {text!r} is a folder, not a file")
    if PurePath(os.fsdecode(text)).name in ("", ".."):
        raise ValueError(f"out: {text!r} has no file name")
    return text


def _command(function: str, origin: str, free: List[str], options: Dict[str, Any]) -> str:
    """How a study was asked for, quoted in its files:
    ``usar.calibrate('scenarios/paper.ron', free=[...], trials=4)``."""
    args = [repr(origin), f"free={free!r}"]
    args += [f"{k}={v!r}" for k, v in options.items() if v is not None]
    return f"usar.{function}({', '.join(args)})"


def _frame_of(rows: Optional[list]) -> Optional[pd.DataFrame]:
    if rows is None:
        return None
    columns = ["target", "value", "goal", "band", "holds", "report_only"]
    return pd.DataFrame(rows, columns=columns)


class Calibration:
    """What :func:`usar.calibrate` found.

    Attributes: ``best`` (dict: each free field's label, e.g. ``mission.pickup_s``, to its
    best value), ``loss`` (the best loss; 0 when every statistic lies in its band; ``inf``
    when no evaluation ran its trials), ``admissible`` (loss 0), ``stop`` (why the search
    stopped), ``scenario`` (the calibrated :class:`usar.Scenario`, ``calibrated.ron``),
    ``trace`` (DataFrame of ``trace.csv``: one row per evaluation, the values, statistics
    and loss), ``statistics`` (DataFrame: each target's ``value`` at the best values, its
    ``goal``, ``band``, whether it ``holds``, and ``report_only``), ``unseen`` (the same on
    the unseen trials, or None when ``check_trials=0``), ``evaluations``, ``ran`` and
    ``reused`` (evaluations in all, run now and taken from the trace), ``summary`` (what
    ``usar calibrate`` prints), ``out`` (the folder, or None) and ``files``.
    """

    def __init__(self, data: Dict[str, Any], out: Path, keep: bool) -> None:
        self.best: Dict[str, float] = {label: float(x) for label, x in data["best"]}
        self.loss: float = float("inf") if data["loss"] is None else float(data["loss"])
        self.admissible: bool = bool(data["admissible"])
        self.stop: str = data["stop"]
        self.evaluations: int = int(data["evaluations"])
        self.ran: int = int(data["ran"])
        self.reused: int = int(data["reused"])
        self.summary: str = data["summary"]
        self.statistics: pd.DataFrame = _frame_of(data["statistics"])
        self.unseen: Optional[pd.DataFrame] = _frame_of(data["unseen"])
        self.trace: pd.DataFrame = pd.read_csv(out / "trace.csv", **_EXACT)
        text = (out / "calibrated.ron").read_text(encoding="utf-8")
        origin = os.fspath(out / "calibrated.ron") if keep else "calibrated.ron"
        self.scenario: Scenario = Scenario.from_ron(text, origin)
        self.out: Optional[Path] = out if keep else None
        self.files: List[str] = list(data["files"]) if keep else []

    def __repr__(self) -> str:
        values = ", ".join(f"{k}={v!r}" for k, v in self.best.items())
        return (
            f"Calibration({values}; loss {self.loss:g}, admissible {self.admissible}, "
            f"{self.evaluations} evaluations)"
        )

    def _repr_html_(self) -> str:
        values = "".join(
            f"<tr><td>{escape(k)}</td><td>{v!r}</td></tr>" for k, v in self.best.items()
        )
        return (
            f"<div><b>usar.Calibration</b>: loss {self.loss:g}, admissible "
            f"{self.admissible}, {self.evaluations} evaluations ({escape(self.stop)})"
            f"<table><tr><th>free field</th><th>best value</th></tr>{values}</table>"
            f"{self.statistics.to_html(index=False)}</div>"
        )


def calibrate(
    scenario: Union[Scenario, str, os.PathLike],
    free: FreeLike,
    targets: Optional[Union[str, os.PathLike]] = None,
    out: Optional[Union[str, os.PathLike]] = None,
    methods: Optional[Sequence[MethodLike]] = None,
    trials: int = 10,
    seed: Optional[int] = None,
    duration_s: Optional[float] = None,
    digits: int = 4,
    max_evals: int = 60,
    max_time_s: Optional[float] = None,
    threads: Optional[int] = None,
    check_seed: Optional[int] = None,
    check_trials: int = 30,
    optimizer: str = "nelder-mead",
    start_mid: bool = False,
    overwrite: bool = False,
    report_only: Sequence[str] = (),
    require: Sequence[str] = (),
    progress: Optional[bool] = None,
) -> Calibration:
    """Fits free scenario fields to a targets file, as ``usar calibrate`` (docs/calibration.md).

    ``free``: the fields and ranges, as ``--free`` takes them (``"mission.pickup_s=0.5..2"``,
    ``"mission.hp_pct_per_step_in_radiation=0.003..0.03:log"``), a list of them, or a dict
    ``{"mission.pickup_s": (0.5, 2)}``. ``targets``: a targets file (default the paper's
    eighteen, ``scenarios/paper-targets.ron``); ``report_only`` and ``require`` name targets
    to leave out of the loss or fit after all. ``methods``: names and/or Python grouping
    methods (default the four built-ins); every evaluation runs ``trials`` trials of each
    (common random numbers from ``seed``, default ``sim.seed``), ``duration_s`` simulated
    seconds each (default ``mission.duration_s``). ``digits``: significant digits of the free
    values; ``max_evals``: the evaluation budget; ``max_time_s``: a wall-clock budget of this
    call (no new evaluation starts after it). ``check_trials`` unseen trials per method from
    ``check_seed`` check the best values (0 skips). ``optimizer``: ``"nelder-mead"`` or
    ``"cma-es"``; ``start_mid`` starts at the ranges' middles. ``threads``: worker threads
    (default all cores; results do not depend on it).

    ``out``: the folder of ``usar calibrate --out`` (``trace.jsonl``, ``calibrated.ron``,
    ``trace.csv``, ``calibration.md``, the figures; the same bytes as the CLI's for the same
    arguments, but the command quoted in ``calibrated.ron`` and ``calibration.md`` and the
    timings). Calling again on it continues the same calibration (a larger ``max_evals``
    extends it); ``overwrite=True`` discards another one there. Default: a temporary folder,
    removed before returning. The date in the files is ``SOURCE_DATE_EPOCH``'s when set.

    Returns a :class:`usar.Calibration`. Raises ValueError (bad arguments or files, a folder
    holding something else), TypeError, a Python method's own exception or
    :class:`usar.GroupingError` (the first met: the calibration stops at once and keeps
    nothing of the evaluation it was in, so the same call continues once the method is
    fixed) and KeyboardInterrupt (Ctrl-C: the trials not started are skipped and the
    evaluation running is dropped; with ``out``, the trace keeps every finished evaluation
    and the same call continues).
    """
    s = _scenario(scenario)
    args = _methods(methods, s)
    values = dict(
        trials=_count("trials", trials, 0, 2**32),
        seed=None if seed is None else _count("seed", seed, 0, _U64),
        duration_s=_seconds(duration_s),
        digits=_count("digits", digits, 0, 2**32),
        max_evals=_count("max_evals", max_evals, 0, 2**63),
        threads=None if threads is None else _count("threads", threads, 1, 2**16),
        check_seed=None if check_seed is None else _count("check_seed", check_seed, 0, _U64),
        check_trials=_count("check_trials", check_trials, 0, 2**32),
    )
    if max_time_s is not None:
        max_time_s = float(max_time_s)
    names = [a if isinstance(a, str) else a[0] for a in args]
    call = _command("calibrate", s.origin, _free(free), {
        "targets": _path(targets), "out": _path(out), "methods": names, "trials": trials,
        "seed": seed, "duration_s": duration_s, "digits": digits, "max_evals": max_evals,
        "max_time_s": max_time_s, "check_seed": check_seed, "check_trials": check_trials,
        "optimizer": optimizer, "start_mid": start_mid or None,
        "report_only": list(_names(report_only)) or None,
        "require": list(_names(require)) or None,
    })
    keep = out is not None
    folder = Path(_folder(out)) if keep else Path(tempfile.mkdtemp(prefix="usar-calibrate-"))
    callback, close = _progress(progress, values["max_evals"], "evaluation", "calibrate")
    try:
        text = _usar.run_calibration(
            s, _free(free), os.fspath(folder), _path(targets), args, values["trials"],
            values["seed"], values["duration_s"], values["digits"], values["max_evals"],
            max_time_s, values["threads"], values["check_seed"], values["check_trials"],
            str(optimizer), bool(start_mid), bool(overwrite), _names(report_only),
            _names(require), call, callback,
        )
        return Calibration(json.loads(text), folder, keep)
    finally:
        close()
        if not keep:
            shutil.rmtree(folder, ignore_errors=True)


class Multiverse:
    """What :func:`usar.multiverse` found (docs/multiverse.md).

    Attributes: ``table`` (DataFrame of ``multiverse.csv``, every row), ``universes`` (its
    ``row == "universe"`` rows: one per universe with its choice on each axis, whether it is
    ``admissible``, its calibration ``loss`` and calibrated values, its ``status``),
    ``claims`` (the ``row == "claim"`` rows: each claim's ``verdict``, ``effect`` with its
    95 % interval, ``p`` and strongest ``rival`` in each admissible universe), ``metrics``
    (the ``row == "metric"`` rows: each method's mean and sd of each metric), ``admissible``
    and ``count`` (admissible universes and universes run), ``failed`` (``[id, message]``
    of each failed universe), ``ran`` and ``reused``, ``summary`` (what ``usar multiverse``
    prints), ``out`` and ``files``.
    """

    def __init__(self, data: Dict[str, Any], out: Path) -> None:
        self.table: pd.DataFrame = pd.read_csv(out / "multiverse.csv", **_EXACT)
        rows = self.table["row"]
        self.universes = self.table[rows == "universe"].dropna(axis=1, how="all")
        self.claims = self.table[rows == "claim"].dropna(axis=1, how="all")
        self.metrics = self.table[rows == "metric"].dropna(axis=1, how="all")
        self.count: int = int(data["universes"])
        self.admissible: int = int(data["admissible"])
        self.failed: List[list] = list(data["failed"])
        self.ran: int = int(data["ran"])
        self.reused: int = int(data["reused"])
        self.summary: str = data["summary"]
        self.out: Path = out
        self.files: List[str] = list(data["files"])

    def __repr__(self) -> str:
        return (
            f"Multiverse({self.count} universes, {self.admissible} admissible, "
            f"{len(self.failed)} failed; {os.fspath(self.out)})"
        )

    def _repr_html_(self) -> str:
        return (
            f"<div><b>usar.Multiverse</b>: {self.count} universes, {self.admissible} "
            f"admissible, {len(self.failed)} failed<pre>{escape(self.summary)}</pre></div>"
        )


def multiverse(
    scenario: Union[Scenario, str, os.PathLike],
    axes: Union[str, os.PathLike],
    targets: Union[str, os.PathLike],
    free: FreeLike,
    out: Union[str, os.PathLike],
    methods: Optional[Sequence[MethodLike]] = None,
    claims: Optional[Union[str, os.PathLike, Sequence[dict]]] = None,
    near_loss: Optional[float] = None,
    report_only: Sequence[str] = (),
    trials: int = 10,
    seed: Optional[int] = None,
    duration_s: Optional[float] = None,
    calibration_trials: int = 5,
    calibration_seed: Optional[int] = None,
    max_evals: int = 30,
    sample: Optional[int] = None,
    sample_seed: int = 0,
    threads: Optional[int] = None,
    overwrite: bool = False,
    progress: Optional[bool] = None,
) -> Multiverse:
    """The method comparison in every universe of an axes file, as ``usar multiverse``
    (docs/multiverse.md): each universe (one alternative per axis) is calibrated to
    ``targets`` over the ``free`` fields (as :func:`usar.calibrate` takes them;
    ``calibration_trials`` per method, at most ``max_evals`` evaluations), and, when it
    reaches every band, its methods are compared (``trials`` per method, common random
    numbers from ``seed``) and each claim checked.

    ``methods``: names and/or Python grouping methods (default the four built-ins).
    ``claims``: a claims file, or a list of claims as dicts with a claims file's fields
    (see :func:`usar.sweep`); default the file the scenario's ``report: (claims: ...)``
    names, else none. ``near_loss``: also give the shares among universes whose loss is at
    most this. ``sample``: run that many universes drawn from the factorial (``sample_seed``).
    ``out``: the folder (required: the universes' records live there); the same bytes as
    ``usar multiverse --out`` writes for the same arguments, and calling again continues
    (``overwrite=True`` discards another multiverse there).

    Returns a :class:`usar.Multiverse`. Raises as :func:`usar.calibrate` (a Python
    method's exception or Ctrl-C stops it with no record of the universe running: its
    calibration trace and comparison journal keep what finished, and the same call
    continues); a universe that fails otherwise is no error (``failed`` lists it; calling
    again retries it). A ``report`` claims file the scenario names but that is missing is a
    UserWarning (no claims are checked).
    """
    s = _scenario(scenario)
    args = _methods(methods, s)
    callback, close = _progress(progress, 1, "universe", "multiverse")
    try:
        text = _usar.run_multiverse_py(
            s, os.fspath(axes), os.fspath(targets), _free(free), _folder(out), args,
            os.fspath(claims) if isinstance(claims, (str, os.PathLike)) else claims,
            None if near_loss is None else float(near_loss), _names(report_only),
            _count("trials", trials, 0, 2**32),
            None if seed is None else _count("seed", seed, 0, _U64), _seconds(duration_s),
            _count("calibration_trials", calibration_trials, 0, 2**32),
            None if calibration_seed is None else _count("calibration_seed", calibration_seed,
                                                         0, _U64),
            _count("max_evals", max_evals, 0, 2**63),
            None if sample is None else _count("sample", sample, 1, 2**63),
            _count("sample_seed", sample_seed, 0, _U64),
            None if threads is None else _count("threads", threads, 1, 2**16),
            bool(overwrite), callback,
        )
    finally:
        close()
    return Multiverse(json.loads(text), Path(os.fspath(out)))


def render(
    scenario: Union[Scenario, str, os.PathLike],
    out: Union[str, os.PathLike],
    method: Optional[MethodLike] = None,
    trial: Optional[int] = None,
    duration_s: Optional[float] = None,
    seed: Optional[int] = None,
) -> Path:
    """Writes the top-down SVG picture of ``usar render`` to ``out``: the arena (walls,
    debris, radiation zones, tasks, rest station) with the robots at their starts, or, given
    a ``method`` (a built-in name or a Python grouping method), with the path every robot
    took in one trial (``trial``, default 0, or the trial of ``seed`` used as is; over
    ``duration_s``, default ``mission.duration_s``), sampled every 0.5 s. The same bytes as
    ``usar render SCENARIO --out OUT [--trace --method M --trial K --duration D]``.

    Returns ``out`` as a Path. Raises ValueError (bad arguments, an output path that cannot
    be written), the errors of :func:`usar.run` for the trial, and KeyboardInterrupt.
    """
    s = _scenario(scenario)
    if method is None and (trial is not None or seed is not None or duration_s is not None):
        raise ValueError("trial, seed and duration_s describe a trial: give method too")
    if trial is not None and seed is not None:
        raise ValueError("trial and seed: give trial or seed, not both")
    path = _out_file(out)
    arg = None if method is None else method_arg(method, s)
    _usar.render(
        s, path, arg, _count("trial", 0 if trial is None else trial, 0, 2**32),
        _seconds(duration_s), None if seed is None else _count("seed", seed, 0, _U64),
    )
    return Path(os.fspath(out))


def replay(
    scenario: Union[Scenario, str, os.PathLike],
    out: Union[str, os.PathLike],
    method: MethodLike = "rne",
    trial: Optional[int] = None,
    duration_s: Optional[float] = None,
    seed: Optional[int] = None,
    hz: Optional[float] = None,
) -> TrialResult:
    """Writes the self-contained HTML replay of ``usar replay`` (docs/replay.md) of one trial
    to ``out``: ``method`` (a built-in name or a Python grouping method), ``trial`` (default
    0) or the trial of ``seed`` used as is, over ``duration_s`` (default
    ``mission.duration_s``), sampled at ``hz`` samples per simulated second (default 10,
    lowered for large teams). The same bytes as ``usar replay SCENARIO --method M --trial K
    --out OUT`` for a built-in method.

    Returns the trial's :class:`usar.TrialResult` (equal to :func:`usar.run`'s). Raises as
    :func:`usar.render`.
    """
    s = _scenario(scenario)
    if trial is not None and seed is not None:
        raise ValueError("trial and seed: give trial or seed, not both")
    text, _size = _usar.replay(
        s, _out_file(out), method_arg(method, s),
        _count("trial", 0 if trial is None else trial, 0, 2**32), _seconds(duration_s),
        None if seed is None else _count("seed", seed, 0, _U64),
        None if hz is None else float(hz),
    )
    return TrialResult(json.loads(text))
