"""Type stubs of the native module ``usar._usar`` (Rust, PyO3). Use the ``usar`` package:
``usar.Scenario`` and the exceptions are these; ``usar.run``, ``usar.sweep``, ``usar.calibrate``,
``usar.multiverse``, ``usar.render`` and ``usar.replay`` wrap the functions below."""

from os import PathLike
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

METHOD_NAMES: List[str]
"""The built-in grouping methods, in the default sweep order: rne, dis, eng, hp_dis."""

class GroupingError(ValueError):
    """A grouping method's answer broke a rule (not one group per task, a robot in no group
    or two, an unknown id, a kind's quota not met); the message names the rule."""

class UsarWarning(UserWarning):
    """A notice of the libraries, given when a call returns to Python: a claims or targets
    file the scenario names that is missing (a copy of paper.ron outside the repository), a
    figure not drawn, a journal record or trace line that does not verify and runs again.
    The lines ``usar`` prints as ``warning: ...``."""

class ScenarioWarning(UsarWarning):
    """A valid scenario whose trials will yield less than it suggests (a task no group can
    rescue from, a goal some robots cannot reach): the lines ``usar check`` prints as
    warnings, given by ``Scenario.load``, ``Scenario.from_ron``, ``set`` and ``update``."""

class TrialError(RuntimeError):
    """A trial failed while running; in a sweep the others still ran (message lists them)."""

class Scenario:
    """A validated scenario (RON), immutable: ``set``/``update`` return edited copies.

    Errors are ``ValueError`` with the loader's one-line message
    ``file:line:col: field.path: message`` (as ``usar check``), or for an edit
    ``set FIELD=VALUE: field.path: message`` (as ``usar check --set``).
    """

    @staticmethod
    def load(path: Union[str, PathLike]) -> Scenario:
        """Reads and validates a scenario file. ValueError if missing or invalid; a
        :class:`ScenarioWarning` per line ``usar check`` warns with (a task never worked, an
        unreachable goal)."""
    @staticmethod
    def from_ron(text: str, origin: str = "<string>") -> Scenario:
        """Validates RON text; ``origin`` names it in errors. ValueError if invalid; warns
        as :meth:`load`."""
    def set(self, path: str, value: Any) -> Scenario:
        """A copy with the field at ``path`` (any ``usar sweep --vary`` path:
        ``kinds[0].count``, ``mission.duration_s``, ``tasks.hard.goal_m``,
        ``radiation_zones[*].radius_m``) set to ``value`` and validated at once. Values:
        int, float (finite), bool, None, tuple, list, or a str: the text itself where the
        field holds text (a name, the description, a unit variant such as ``"Aerial"``),
        RON text elsewhere (``"Some(3)"``). ValueError on a bad path or value or a broken
        rule; warns as :meth:`load` about the copy."""
    def update(self, fields: Dict[str, Any]) -> Scenario:
        """A copy with several fields set in order, validated once at the end (e.g. a
        count and its quota together)."""
    def get(self, path: str) -> Any:
        """The value at a field path as Python data; a ``[*]`` path gives every element's,
        as a list. ValueError if the path names nothing."""
    def to_dict(self) -> Dict[str, Any]:
        """Every field as Python data (the scenario's JSON form; an enum variant with data
        is a one-key dict)."""
    @staticmethod
    def from_dict(data: Dict[str, Any], origin: str = "<dict>") -> Scenario:
        """A scenario from ``to_dict()``'s data; ValueError if invalid."""
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    def to_ron(self) -> str:
        """The scenario as RON, every field written out (``usar check --print``); reads
        back as the same scenario."""
    def check(self) -> Dict[str, Any]:
        """What ``usar check`` prints, as data: ``name``, ``description``, ``arena``
        (``width_m``, ``height_m``, ``wall_thickness_m``), ``dt_s``, ``duration_s``,
        ``simulated_s``, ``steps``, ``seed``, ``control_period_s``, ``kinds`` (``name``,
        ``role``, ``locomotion``, ``count``, ``quota`` by task, speeds m/s, ranges and
        radius m, ``carrying_capacity``, ``rescuing_resources``), ``tasks`` (``name``,
        ``difficulty``, ``rank`` 0 = hardest, as in a ``GroupingRequest``, ``rescuees``, ``search_area_m``, ``goal_m``,
        ``drop_off`` ((x, y), r), ``quota`` by kind, ``start_to_goal_m`` (min, max, mean)),
        ``robots`` (``id``, ``kind``, ``kind_index``, ``start_m``, ``distance_to_goal_m`` by
        task), ``rest_stations``, ``debris_rects``, ``debris_circles``, ``radiation_zones``
        ((x, y), r, dose factor), ``hash`` (the scenario hash), ``needs_len`` (the length
        of a needs vector, 7) and ``mission`` (every mission parameter, as the scenario file
        names it: ``duration_s``, ``pickup_s``, ``hp_pct_per_step_in_radiation``, ...)."""
    @property
    def overrides(self) -> List[str]:
        """The edits applied so far, as ``FIELD=VALUE`` texts, in order."""
    @property
    def name(self) -> str:
        """The scenario's name."""
    @property
    def origin(self) -> str:
        """The path or origin that errors name."""
    @property
    def task_names(self) -> List[str]:
        """Task names, scenario order."""

MethodArg = Union[str, Tuple[str, Callable[[Dict[str, Any]], List[List[int]]]]]

def run_trial(
    scenario: Scenario,
    method: MethodArg,
    trial: int = 0,
    duration_s: Optional[float] = None,
    seed: Optional[int] = None,
) -> str:
    """One trial; returns the JSON of ``usar run --json``. Use ``usar.run``."""

def run_sweep(
    scenario: Scenario,
    methods: Sequence[MethodArg],
    trials: int = 10,
    threads: Optional[int] = None,
    out: Optional[str] = None,
    resume: bool = False,
    duration_s: Optional[float] = None,
    seed: Optional[int] = None,
    progress: Optional[Callable[[int, int], None]] = None,
    overwrite: bool = False,
    targets: Optional[str] = None,
    claims: Optional[Union[str, Sequence[Dict[str, Any]]]] = None,
    vary: Sequence[str] = (),
) -> List[Tuple[List[str], bytes]]:
    """A sweep or, with ``vary``, a grid; returns per cell the varied fields' values and the
    bytes of its ``trials_long.csv``. Use ``usar.sweep`` or ``usar.grid``."""

def run_calibration(
    scenario: Scenario, free: List[str], out: str, targets: Optional[str],
    methods: Sequence[MethodArg], trials: int, seed: Optional[int], duration_s: Optional[float],
    digits: int, max_evals: int, max_time_s: Optional[float], threads: Optional[int],
    check_seed: Optional[int], check_trials: int, optimizer: str, start_mid: bool,
    overwrite: bool, report_only: List[str], require: List[str], command: str,
    progress: Optional[Callable[[int, int], None]],
) -> str:
    """A calibration into ``out``; returns a JSON text of its outcome. Use
    ``usar.calibrate``."""

def run_multiverse_py(
    scenario: Scenario, axes: str, targets: str, free: List[str], out: str,
    methods: Sequence[MethodArg], claims: Optional[Union[str, Sequence[Dict[str, Any]]]],
    near_loss: Optional[float], report_only: List[str], trials: int, seed: Optional[int],
    duration_s: Optional[float], calibration_trials: int, calibration_seed: Optional[int],
    max_evals: int, sample: Optional[int], sample_seed: int, threads: Optional[int],
    overwrite: bool, progress: Optional[Callable[[int, int], None]],
) -> str:
    """A multiverse into ``out``; returns a JSON text of its outcome. Use
    ``usar.multiverse``."""

def render(
    scenario: Scenario, out: str, method: Optional[MethodArg] = None, trial: int = 0,
    duration_s: Optional[float] = None, seed: Optional[int] = None,
) -> int:
    """Writes ``usar render``'s SVG; returns samples per robot. Use ``usar.render``."""

def replay(
    scenario: Scenario, out: str, method: MethodArg, trial: int = 0,
    duration_s: Optional[float] = None, seed: Optional[int] = None, hz: Optional[float] = None,
) -> Tuple[str, int]:
    """Writes ``usar replay``'s page; returns the trial's JSON and the page's bytes. Use
    ``usar.replay``."""

class PathLog:
    """Every robot's path so far in one trial, filled by :func:`run_trial_logged` as the trial
    runs (samples as ``usar render --trace``'s, every 0.5 s, plus the positions after the last
    step) and drawn by :func:`episode_svg`. ``len(log)``: samples per robot so far (0 before
    the trial starts). Not picklable. ``usar.gym`` makes one per trial."""

    def __init__(self) -> None: ...
    def __len__(self) -> int: ...

def run_trial_logged(
    scenario: Scenario,
    method: MethodArg,
    log: PathLog,
    trial: int = 0,
    duration_s: Optional[float] = None,
    seed: Optional[int] = None,
) -> str:
    """:func:`run_trial`, ``log`` recording the paths (emptied first). Used by ``usar.gym``."""

def episode_svg(scenario: Scenario, log: Optional[PathLog] = None) -> str:
    """``usar render``'s SVG text: with ``log``, the paths in it so far; without (or with an
    empty log), the arena with the robots at their starts. Used by ``usar.gym``'s frames."""

def trust(weights: List[float], needs_a: List[float], needs_b: List[float]) -> float:
    """Trust of A in B, nats (paper Eq. 7). Use ``usar.trust``."""

def trial_seed(base_seed: int, trial: int) -> int:
    """The seed of trial ``trial`` under ``base_seed`` (``usar_sim::mission::trial_seed``).
    Use ``usar.gym.trial_seed``."""

def builtin_group(
    name: str,
    raw: Dict[str, Any],
    scenario: Optional[Scenario] = None,
    weights: Optional[List[float]] = None,
) -> List[List[int]]:
    """A built-in method's groups for a raw request. Use ``usar.rne`` etc."""

def claim_verdicts(
    claims: Optional[Union[str, Sequence[dict]]],
    scenario: Optional[Scenario],
    methods: List[str],
    tasks: List[str],
    method: List[str],
    trial: List[int],
    seed: List[int],
    columns: Dict[str, List[float]],
    test: Optional[str] = None,
) -> Tuple[str, List[Dict[str, Any]]]:
    """The claims' origin and one row per claim and rival, checked on trials given as columns
    (test: ``PairedT``, ``Wilcoxon``, ``Welch``, ``MannWhitney``). Use ``usar.verdicts``."""

def compare_values(
    subject: str,
    rivals: List[str],
    metric: str,
    direction: str,
    test: str,
    alpha: float,
    methods: List[str],
    tasks: List[str],
    method: List[str],
    trial: List[int],
    seed: List[int],
    values: List[float],
) -> List[Dict[str, Any]]:
    """One row per rival of ``subject`` on one metric column. Use ``usar.compare``."""
