"""The scenarios shipped with the package: :func:`scenario_path`.

A wheel carries the repository's ``scenarios/`` folder as package data (``usar/scenarios/``,
with paper.ron's targets and claims files beside it, so its ``report`` section resolves in
the installed package). In a checkout ``python/usar/scenarios`` is a symbolic link to the
checkout's ``scenarios/`` (maturin copies the files through it into the wheel), so an editable
install (``maturin develop``) reads the checkout's own files and an edited scenario is seen at
once; the paths given are the link's target (``scenarios/paper.ron`` of the checkout).
"""

from __future__ import annotations

import pathlib
from typing import List

__all__ = ["scenario_path", "scenario_names"]

_HERE = pathlib.Path(__file__).resolve().parent


def _folder() -> pathlib.Path:
    """The folder of the shipped scenarios: the package's own (a wheel, or the checkout's
    through the link), else the checkout's."""
    shipped = _HERE / "scenarios"
    if shipped.is_dir():
        return shipped.resolve()
    checkout = _HERE.parent.parent / "scenarios"
    if checkout.is_dir():
        return checkout
    raise FileNotFoundError(
        f"no scenarios shipped with usar: neither {shipped} nor {checkout} is a folder "
        "(reinstall the package from its wheel)"
    )


def _is_scenario(path: pathlib.Path) -> bool:
    """Whether the RON file's first value is a ``Scenario(...)`` (not ``Claims(``,
    ``Targets(`` or ``Axes(``), after its ``//`` comments and blank lines."""
    for line in path.read_text(encoding="utf-8").splitlines():
        text = line.strip()
        if text and not text.startswith("//"):
            return text.startswith("Scenario(")
    return False


def scenario_names() -> List[str]:
    """The file names of the shipped scenarios (``"paper.ron"``, ``"paper-v1.ron"``, ...),
    sorted; the side files shipped beside them (``paper-targets.ron``, ``paper-claims.ron``,
    ``paper-axes.ron``) are not listed, though :func:`scenario_path` gives their paths too.
    Raises ``FileNotFoundError`` when the package ships none."""
    return sorted(p.name for p in _folder().glob("*.ron") if _is_scenario(p))


def scenario_path(name: str = "paper.ron") -> pathlib.Path:
    """The path of the shipped scenario ``name`` (a file name such as ``"paper.ron"``, with or
    without ``.ron``; default the paper's mission, ``paper.ron``), for :meth:`usar.Scenario.load`
    or any function that takes a scenario path; a side file's name (``"paper-claims.ron"``)
    gives its path.

    Raises ``ValueError`` naming ``name`` and the shipped names when there is no such scenario.
    """
    if not isinstance(name, str):
        raise TypeError(f"name: expected a scenario file name (str), found {type(name).__name__}")
    file = name if name.endswith(".ron") else f"{name}.ron"
    path = _folder() / file
    if pathlib.Path(file).name != file or not path.is_file():
        raise ValueError(
            f"name: no shipped scenario {name!r}; shipped: {', '.join(scenario_names())}"
        )
    return path
