"""Shared fixtures: the repository's scenarios and the `usar` command line to compare with.

The CLI is `$USAR_BIN` when set, else `target/release/usar` under `$CARGO_TARGET_DIR` or the
repository, built with `cargo build --release -p experiments --bin usar` when missing.

With `USAR_TEST_INSTALLED=1` (CI runs the tests against the wheel installed in a venv), the
session stops at once when `usar` is imported from this checkout's `python/usar` instead.
"""

import os
import pathlib
import subprocess

import pytest

import usar

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAPER = ROOT / "scenarios" / "paper.ron"
# Short trials keep the suite quick; the numbers are still compared exactly.
SHORT_S = 20.0

if os.environ.get("USAR_TEST_INSTALLED") == "1":
    _imported = pathlib.Path(usar.__file__).resolve()
    if ROOT in _imported.parents:
        raise pytest.UsageError(
            f"USAR_TEST_INSTALLED=1 but usar is imported from the checkout ({_imported}), "
            "not from the installed wheel: run pytest from a folder outside the checkout"
        )


@pytest.fixture(scope="session")
def paper():
    """scenarios/paper.ron, loaded."""
    return usar.Scenario.load(str(PAPER))


@pytest.fixture(scope="session")
def usar_cli():
    """The path of the `usar` binary."""
    given = os.environ.get("USAR_BIN")
    if given:
        return given
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    binary = target / "release" / "usar"
    if not binary.exists():
        subprocess.run(
            ["cargo", "build", "--release", "-p", "experiments", "--bin", "usar"],
            cwd=ROOT,
            check=True,
        )
    return str(binary)
