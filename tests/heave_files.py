"""A heave problem run on a modified copy of its cable scene (tests of the cable plants).

The shipped heave files name their cable scene by a path relative to themselves
(``[unit] cable_scene``); :func:`heave_with_line` writes a copy of one with that path
pointing at a copy of the line (``line.toml``, e.g. with fewer segments), both in a test's
folder.
"""

from __future__ import annotations

import re
from pathlib import Path

HEAVE = Path(__file__).resolve().parents[1] / "problems" / "heave"


def heave_with_line(folder: Path, heave_name: str, line_text: str) -> Path:
    """Write ``line.toml`` (``line_text``) and ``heave.toml`` (problems/heave/``heave_name``
    with its cable scene replaced by ``line.toml``) into ``folder``; return the heave file."""
    (folder / "line.toml").write_text(line_text)
    heave, count = re.subn(r'(?m)^cable_scene = "[^"]*"', 'cable_scene = "line.toml"',
                           (HEAVE / heave_name).read_text())
    assert count == 1, f"{heave_name}: no single cable_scene line"
    out = folder / "heave.toml"
    out.write_text(heave)
    return out
