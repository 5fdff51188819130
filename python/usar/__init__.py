"""usar: relative-needs-entropy (RNE) robot-robot trust and USAR multi-robot trials.

The Python face of the rne-usar Rust crates (Yang & Parasuraman, "How Can Robots Trust Each
Other For Better Cooperation? A Relative Needs Entropy Based Robot-Robot Trust Assessment
Model", IEEE SMC 2021). Every number comes from the same library code as the ``usar``
command line: the same scenario and seed give the same results, bit for bit.

- :class:`Scenario`: load (``Scenario.load(path)``, ``Scenario.from_ron(text)``), edit by
  field path (``scenario.set("kinds[0].count", 8)``), write (``to_ron()``), summarise
  (``check()``).
- :func:`run`: one trial -> :class:`TrialResult` (as ``usar run --json``).
- :func:`sweep`: methods x trials in parallel -> pandas DataFrame (as ``trials_long.csv``);
  :func:`wide` turns it into ``trials.csv``'s wide table; :func:`grid` runs it once per
  cell of a parameter grid (``--vary``).
- :func:`calibrate`: fit free fields to a targets file -> :class:`Calibration`;
  :func:`multiverse`: the comparison in every universe of an axes file -> :class:`Multiverse`.
- :func:`verdicts`: a sweep's claims tested on its trials -> DataFrame (``report.md``'s verdicts,
  with or without ``out``); :func:`compare`: one method against its rivals, no claims file.
- :func:`scenario_path` (``"paper.ron"`` and the other shipped scenarios), :func:`scenario_names`.
- :func:`render` (an SVG picture, with a trial's paths) and :func:`replay` (an HTML page
  that plays a trial).
- :func:`trust`, :func:`rne`, :func:`dis`, :func:`eng`, :func:`hp_dis`: rne-core as functions.
- :class:`GroupingMethod` or any callable ``group(request) -> list of groups``: a grouping
  method written in Python, run by :func:`run`, :func:`sweep` and the studies once per grouping round.
- :class:`UsarWarning`: the library's notices as Python warnings (a claims or targets file the
  scenario names that is missing, a figure not drawn); :class:`ScenarioWarning` is one.

Units follow the field names: ``_s`` seconds, ``_m`` metres, ``_pct`` percent points.
Documentation: docs/python.md in the repository.
"""

from ._usar import (
    METHOD_NAMES,
    GroupingError,
    Scenario,
    ScenarioWarning,
    TrialError,
    UsarWarning,
)
from ._grouping import (
    GroupingMethod,
    GroupingRequest,
    Robot,
    Task,
    dis,
    eng,
    hp_dis,
    rne,
)
from ._results import Record, TrialResult
from ._api import grid, read_trials_long, run, sweep, trust, wide
from ._studies import Calibration, Multiverse, calibrate, multiverse, render, replay
from ._data import scenario_names, scenario_path
from ._verdicts import compare, verdicts

__all__ = [
    "METHOD_NAMES",
    "Calibration",
    "Multiverse",
    "GroupingError",
    "GroupingMethod",
    "GroupingRequest",
    "Record",
    "Robot",
    "Scenario",
    "ScenarioWarning",
    "Task",
    "TrialError",
    "TrialResult",
    "UsarWarning",
    "calibrate",
    "compare",
    "dis",
    "grid",
    "eng",
    "hp_dis",
    "multiverse",
    "read_trials_long",
    "render",
    "replay",
    "rne",
    "run",
    "scenario_names",
    "scenario_path",
    "sweep",
    "trust",
    "verdicts",
    "wide",
]
__version__ = "0.1.0"
