"""The code in the README and the docs runs: every ```python block is executed from the
repository root, each in a fresh namespace (a snippet that drifts from the API fails here)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def _snippets() -> list[tuple[str, str]]:
    out = []
    for page in PAGES:
        for k, code in enumerate(BLOCK.findall(page.read_text(encoding="utf-8"))):
            out.append((f"{page.relative_to(ROOT)}#{k + 1}", code))
    return out


SNIPPETS = _snippets()


def test_there_are_snippets() -> None:
    """The extraction is not blind: the README and docs/api.md have snippets."""
    names = {n.split("#")[0] for n, _ in SNIPPETS}
    assert {"README.md", "docs/api.md"} <= names


@pytest.mark.parametrize("name,code", SNIPPETS, ids=[n for n, _ in SNIPPETS])
def test_snippet_runs(name: str, code: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)
    exec(compile(code, name, "exec"), {"__name__": "__snippet__"})  # noqa: S102
