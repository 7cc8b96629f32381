"""Shared fixtures: paths to the shipped problem files."""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"


@pytest.fixture(scope="session")
def problems() -> Path:
    """Folder of the shipped problem files."""
    return PROBLEMS
