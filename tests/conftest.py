"""Shared fixtures: paths to the shipped problem files; the test helpers' folder on sys.path;
a private statics function cache."""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
# Test helpers written independently of the package (shooting_reference, closed_forms): by name
# from the test modules (pytest runs with --import-mode=importlib, which adds no test folder).
sys.path.insert(0, str(Path(__file__).resolve().parent))
PROBLEMS = ROOT / "problems"


@pytest.fixture(scope="session")
def problems() -> Path:
    """Folder of the shipped problem files."""
    return PROBLEMS


@pytest.fixture(scope="session", autouse=True)
def _private_function_cache(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """The statics solvers' on-disk function cache (cable_ocp.statics.cache) goes to a
    temporary folder for the whole session (subprocesses inherit it): the tests never
    read or write the user's cache."""
    old = {k: os.environ.get(k) for k in ("CABLE_OCP_CACHE_DIR", "CABLE_OCP_CACHE")}
    folder = tmp_path_factory.mktemp("function_cache")
    os.environ["CABLE_OCP_CACHE_DIR"] = str(folder)
    os.environ.pop("CABLE_OCP_CACHE", None)
    yield folder
    for k, v in old.items():
        if v is None:
            os.environ.pop(k, None)
        else:
            os.environ[k] = v

@pytest.fixture
def cache_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """An empty cache folder of the test's own (function cache and compiled libraries)."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("CABLE_OCP_CACHE_DIR", str(folder))
    monkeypatch.delenv("CABLE_OCP_CACHE", raising=False)
    return folder
