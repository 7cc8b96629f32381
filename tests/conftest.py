"""Shared fixtures: paths to the shipped problem files; the test helpers' folder on sys.path."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
# Test helpers written independently of the package (shooting_reference): importable by name
# from the test modules (pytest runs with --import-mode=importlib, which adds no test folder).
sys.path.insert(0, str(Path(__file__).resolve().parent))
PROBLEMS = ROOT / "problems"


@pytest.fixture(scope="session")
def problems() -> Path:
    """Folder of the shipped problem files."""
    return PROBLEMS
