"""Shared fixtures: the repository's scenarios and the `usar` command line to compare with.

The CLI is `$USAR_BIN` when set, else `target/release/usar` under `$CARGO_TARGET_DIR` or the
repository, built with `cargo build --release -p experiments --bin usar` when missing.
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
