"""Shared fixtures: the repository's fixtures and the `tribo` binary whose
Parquet output the package must reproduce."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def cli():
    """Runs the tribo binary (TRIBO_BIN, or `tribo` on PATH) in the
    repository root; skips when there is none."""
    binary = os.environ.get("TRIBO_BIN") or shutil.which("tribo")
    if not binary or not Path(binary).exists():
        pytest.skip("no tribo binary: set TRIBO_BIN to compare with the CLI")

    def call(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run(
            [binary, *map(str, args)], cwd=ROOT, capture_output=True, text=True
        )

    return call
