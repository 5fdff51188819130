"""usar.verdicts and usar.compare: a sweep's claims, or an ad-hoc comparison of methods, tested
on its trials DataFrame and returned as a DataFrame. The statistics are the library's (the
claims check ``report.md`` runs, ``usar_report::claims::check_claim_on``); this module only
turns the trials into columns and the rows into a table."""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import pandas as pd

from . import _usar
from ._api import _scenario, wide
from ._usar import Scenario

__all__ = ["verdicts", "compare"]

#: The columns of the tables :func:`verdicts` and :func:`compare` return, in order.
COLUMNS = [
    "claim", "sentence", "method", "rival", "metric", "direction", "test", "test_words",
    "paired", "alpha", "correction", "n", "n_method", "n_rival", "unpaired", "mean_method",
    "mean_rival", "difference", "statistic", "dof", "p_raw", "p_value", "p_reverse",
    "effect_size", "significant", "verdict", "reason",
]

#: ``test=`` names and the claims-file test each means.
_TESTS = {
    "paired": "PairedT", "paired_t": "PairedT", "pairedt": "PairedT", "t": "PairedT",
    "wilcoxon": "Wilcoxon",
    "unpaired": "Welch", "welch": "Welch",
    "mann_whitney": "MannWhitney", "mannwhitney": "MannWhitney",
}

_KEYS = ["scenario", "method", "trial", "seed"]


def _test(test: Any) -> str:
    """``test`` as a claims file's test name; ValueError naming ``test`` when unknown."""
    if not isinstance(test, str):
        raise TypeError(f"test: expected a test's name (str), found {type(test).__name__}")
    key = test.strip().lower().replace("-", "_").replace(" ", "_")
    if key not in _TESTS:
        raise ValueError(
            f"test: unknown test {test!r} (paired, wilcoxon, welch or unpaired, mann-whitney)"
        )
    return _TESTS[key]


def _key(name: str) -> str:
    """A method name as claims compare them: case, spaces around and ``-``/``_`` ignored."""
    return name.strip().lower().replace("-", "_")


def _wide(trials: Any) -> pd.DataFrame:
    """The trials as ``trials.csv``'s wide table: a long table (:func:`usar.sweep`) is turned
    wide (:func:`usar.wide`), a wide one is taken as it is. ValueError naming ``trials``."""
    if not isinstance(trials, pd.DataFrame):
        raise TypeError(
            f"trials: expected the DataFrame of usar.sweep, found {type(trials).__name__}"
        )
    for key in _KEYS:
        if key not in trials.columns:
            raise ValueError(
                f"trials: not a table of usar.sweep (no column {key!r}; expected the long "
                "table usar.sweep returns or the wide one of usar.wide)"
            )
    if {"metric", "value", "task"} <= set(trials.columns):
        trials = wide(trials)
    if trials.empty:
        raise ValueError("trials: the table has no trial")
    return trials


def _cells(table: pd.DataFrame) -> List[Tuple[Dict[str, Any], pd.DataFrame]]:
    """The table per grid cell (the cell's key columns and values), or the whole table."""
    if "cell" not in table.columns:
        return [({}, table)]
    keys = list(table.columns[: list(table.columns).index("scenario")])
    return [
        (dict(zip(keys, group[keys].iloc[0])), group)
        for _, group in table.groupby("cell", sort=False)
    ]


def _tasks(table: pd.DataFrame) -> List[str]:
    """The task names, in the scenario's order, from the ``rescued_<task>`` columns."""
    return [c[len("rescued_"):] for c in table.columns
            if c.startswith("rescued_") and c != "rescued_total"]


def _columns(table: pd.DataFrame) -> Tuple[List[str], List[int], List[int]]:
    """The method, trial and seed columns as lists (seeds as Python ints, exact)."""
    return (
        [str(m) for m in table["method"]],
        [int(t) for t in table["trial"]],
        [int(s) for s in table["seed"].astype("uint64")],
    )


def _metric_columns(table: pd.DataFrame) -> Dict[str, List[float]]:
    """Every metric column as floats (NaN where undefined)."""
    return {
        c: table[c].astype("float64").tolist()
        for c in table.columns
        if c not in _KEYS and c != "cell" and pd.api.types.is_numeric_dtype(table[c])
    }


def _enough(table: pd.DataFrame, methods: Sequence[str]) -> None:
    """ValueError naming ``trials`` when one of ``methods`` has fewer than 2 trials."""
    counts = table.groupby("method", sort=False).size()
    for m in methods:
        if counts.get(m, 0) < 2:
            raise ValueError(
                f"trials: {m} has {counts.get(m, 0)} trial(s); the tests need at least 2 per "
                "method (usar.sweep(..., trials=2) or more)"
            )


def _frame(rows: List[Dict[str, Any]], cell: Dict[str, Any]) -> pd.DataFrame:
    out = pd.DataFrame(rows, columns=COLUMNS)
    for c in ("n", "n_method", "n_rival", "unpaired"):
        out[c] = out[c].astype("Int64")
    for k, v in reversed(list(cell.items())):
        out.insert(0, k, v)
    return out


def _claims_scenario(scenario: Any, table: pd.DataFrame) -> Optional[Scenario]:
    """The scenario whose ``report.claims`` to check: ``scenario``, or else the shipped
    scenario the trials name (``paper`` -> ``paper.ron``)."""
    if scenario is not None:
        return _scenario(scenario)
    from ._data import scenario_path

    names = list(pd.unique(table["scenario"]))
    try:
        if len(names) != 1:
            raise ValueError
        return Scenario.load(os.fspath(scenario_path(str(names[0]))))
    except (ValueError, FileNotFoundError):
        raise ValueError(
            f"scenario: the trials' scenario {', '.join(map(str, names))} is not a shipped one; "
            "give scenario= (its report.claims names the claims) or claims="
        ) from None


def verdicts(
    trials: pd.DataFrame,
    scenario: Optional[Union[Scenario, str, os.PathLike]] = None,
    test: Optional[str] = None,
    claims: Optional[Union[str, os.PathLike, Sequence[dict]]] = None,
) -> pd.DataFrame:
    """The claims of a sweep checked on its trials, as ``report.md``'s "Claims" section checks
    them, as a DataFrame; with or without ``out=`` in :func:`usar.sweep`.

    ``trials``: the long table :func:`usar.sweep` returns (or :func:`usar.read_trials_long`
    of a ``trials_long.csv``), or its wide form (:func:`usar.wide`, ``trials.csv``); a
    :func:`usar.grid` table gives each cell's rows, led by its ``cell`` and varied fields.
    ``claims``: a claims file (such as ``scenarios/paper-claims.ron``) or a list of claims
    as dicts (as :func:`usar.sweep` takes them); default the file the scenario's
    ``report.claims`` names, ``scenario`` being a :class:`usar.Scenario` or a path (default:
    the shipped scenario the trials' ``scenario`` column names, ``paper`` -> ``paper.ron``).
    ``test``: ``None`` (default) tests each claim by its own test, as ``report.md`` does (the
    paired t-test unless its file says otherwise); ``"paired"`` (Student's paired t-test),
    ``"wilcoxon"`` (signed-rank, paired), ``"welch"`` or ``"unpaired"`` (Welch's t-test) or
    ``"mann-whitney"`` (U test, unpaired) tests every claim by that one instead.

    Returns one row per claim and rival compared, claims in their file's order and rivals in
    the sweep's (a claim compared with no rival: one row, ``rival`` missing). Columns:
    ``claim`` (id), ``sentence``, ``method`` (the claim's subject), ``rival``, ``metric`` (a
    ``trials.csv`` column), ``direction`` (``higher``/``lower`` is better), ``test`` (its
    name as ``report.md`` words it: ``paired t-test``, ``Wilcoxon signed-rank test``,
    ``Welch``, ``Mann-Whitney U``), ``test_words`` (``report.md``'s table cell, e.g.
    ``one-sided paired t-test over 10 pairs of trials, alpha 0.05``), ``paired``, ``alpha``,
    ``correction`` (``none`` or ``Holm``), ``n`` (pairs for a paired test; the trials of both
    methods for an unpaired one), ``n_method``, ``n_rival`` (trials with a value),
    ``unpaired`` (trials without a partner, left out of the pairs), ``mean_method``,
    ``mean_rival``, ``difference`` (the mean paired difference, or the difference of the
    means; method minus rival, in the metric's unit), ``statistic`` (paired t, Wilcoxon W+,
    Welch t or U, oriented so that positive points the claimed way), ``dof`` (NaN for the
    rank tests), ``p_raw`` (one-sided), ``p_value`` (the p the verdict compares with alpha:
    Holm-adjusted over the claim's rivals when ``correction`` is ``Holm``, else ``p_raw``),
    ``p_reverse`` (the claim's t-test of the opposite direction), ``effect_size`` (Cohen's
    d_z for a paired test, d for an unpaired one, oriented as ``statistic``),
    ``significant`` (``p_value < alpha``), ``verdict`` (the claim's, on each of its rows:
    ``holds``, ``not significant``, ``does not hold``, ``not tested``) and ``reason`` (why
    not tested). ``attrs["claims"]`` names the claims' origin. The numbers are the ones
    ``report.md`` prints for the same trials.

    Raises ValueError naming the argument: ``trials`` (not a sweep's table, a method with
    fewer than 2 trials, a claim's metric column missing), ``test`` (unknown), ``claims`` (a
    file that does not read or check) or ``scenario`` (none given and the trials' one not
    shipped, or naming no claims file); TypeError for wrong types.
    """
    table = _wide(trials)
    native_test = None if test is None else _test(test)
    claims_arg: Any = claims
    if isinstance(claims, (str, os.PathLike)):
        claims_arg = os.fspath(claims)
    s = None if claims is not None else _claims_scenario(scenario, table)
    frames = []
    origin = ""
    for cell, group in _cells(table):
        methods = [str(m) for m in pd.unique(group["method"])]
        _enough(group, methods)
        origin, rows = _usar.claim_verdicts(
            claims_arg, s, methods, _tasks(group), *_columns(group), _metric_columns(group),
            native_test,
        )
        frames.append(_frame(rows, cell))
    out = pd.concat(frames, ignore_index=True) if len(frames) > 1 else frames[0]
    out.attrs["claims"] = origin
    return out


def _direction(direction: Any, metric: str) -> str:
    if direction is None:
        if metric.startswith("rescued_"):
            return "More"
        if metric.startswith(("energy_", "hp_")):
            return "Less"
        raise ValueError(
            f"direction: say whether a higher or a lower {metric} is better "
            "(direction='more' or 'less')"
        )
    if isinstance(direction, str) and direction.strip().lower() in ("more", "less"):
        return direction.strip().capitalize()
    raise ValueError(f"direction: expected 'more' or 'less', not {direction!r}")


def compare(
    trials: pd.DataFrame,
    method: str,
    rivals: Optional[Union[str, Sequence[str]]] = None,
    metric: str = "rescued_total",
    test: str = "paired",
    alpha: float = 0.05,
    direction: Optional[str] = None,
) -> pd.DataFrame:
    """An ad-hoc comparison: ``method`` (e.g. a Python grouping method named ``"policy"``)
    against each of ``rivals`` on ``metric``, tested on a sweep's trials as a claim is (no
    claims file needed); the same table as :func:`usar.verdicts`, one row per rival, each
    rival judged on its own (its ``verdict``: ``holds`` when ``method`` is better at
    ``p_value < alpha``; no correction over rivals; ``claim`` is missing).

    ``trials``: as :func:`usar.verdicts` (one cell of a grid at a time). ``method`` and
    ``rivals`` (a name or a list; default every other method of the trials, in their
    order) are names as the trials' ``method`` column spells them (case and ``-``/``_``
    ignored). ``metric``: a ``trials.csv`` column (``rescued_total``, ``rescued_hard``,
    ``hp_per_hard_rescuee_pct``, ``rounds``, ...). ``test``: ``"paired"`` (default,
    Student's paired t-test: trial k against trial k, the same draws), ``"wilcoxon"``,
    ``"welch"``/``"unpaired"`` or ``"mann-whitney"``, one-sided, at level ``alpha`` in
    (0, 0.5]. ``direction``: ``"more"`` or ``"less"`` is better; default ``more`` for
    ``rescued_*`` and ``less`` for the energy and HP costs (required for ``rounds`` and
    ``mean_round_s``).

    Raises ValueError naming the argument: ``method`` or ``rivals`` (not in the trials, or
    the method among its rivals), ``metric`` (no such column), ``test`` (unknown), ``alpha``,
    ``direction`` or ``trials`` (not a sweep's table, a grid's, or a method compared with
    fewer than 2 trials); TypeError for wrong types.
    """
    table = _wide(trials)
    if "cell" in table.columns and table["cell"].nunique() > 1:
        raise ValueError("trials: a grid's table; compare one cell at a time (select by 'cell')")
    native_test = _test(test)
    if isinstance(alpha, bool) or not isinstance(alpha, (int, float)):
        raise TypeError(f"alpha: expected a number, found {type(alpha).__name__}")
    if not 0.0 < float(alpha) <= 0.5:
        raise ValueError(f"alpha: a one-sided level in (0, 0.5], not {alpha}")
    methods = [str(m) for m in pd.unique(table["method"])]
    by_key = {_key(m): m for m in methods}

    def find(arg: str, name: Any) -> str:
        if not isinstance(name, str):
            raise TypeError(f"{arg}: expected a method's name (str), found {type(name).__name__}")
        if _key(name) not in by_key:
            raise ValueError(
                f"{arg}: {name!r} is not among the trials' methods ({', '.join(methods)})"
            )
        return by_key[_key(name)]

    subject = find("method", method)
    if rivals is None:
        chosen = [m for m in methods if m != subject]
    else:
        chosen = [find("rivals", r) for r in ([rivals] if isinstance(rivals, str) else rivals)]
    if subject in chosen:
        raise ValueError(f"rivals: {subject} is the method compared, not a rival")
    if not chosen:
        raise ValueError(f"rivals: no method to compare {subject} with (the trials have only it)")
    if not isinstance(metric, str):
        raise TypeError(f"metric: expected a column name (str), found {type(metric).__name__}")
    columns = _metric_columns(table)
    if metric not in columns:
        raise ValueError(
            f"metric: no column {metric!r} in the trials (columns: {', '.join(columns)})"
        )
    native_direction = _direction(direction, metric)
    _enough(table, [subject] + chosen)
    rows = _usar.compare_values(
        subject, chosen, metric, native_direction, native_test, float(alpha), methods,
        _tasks(table), *_columns(table), columns[metric],
    )
    return _frame(rows, {})
