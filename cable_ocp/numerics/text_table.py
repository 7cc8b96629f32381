"""The one formatter of plain-text tables (every table the CLI and the benchmarks print).

:func:`table` right-aligns every column to its widest cell, puts an optional units line
under the headings, and keeps a table within ``width`` columns (default :data:`WIDTH`, 100):
a wider table is printed as several blocks of columns, each repeating the first (the row's
name), one under the other, so that no line wraps in a terminal or a log. A row always has
one cell per heading (a missing value is a cell too, ``-``), so a failed row keeps the
columns of the others.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

__all__ = ["MISSING", "WIDTH", "table"]

#: the widest line of a table, characters
WIDTH = 100
#: the cell of a value that does not exist (None, NaN, infinity)
MISSING = "-"
_GAP = "  "


def _cell(v: Any) -> str:
    if v is None:
        return MISSING
    if isinstance(v, float):
        return f"{v:.4g}" if v == v and abs(v) != float("inf") else MISSING
    return str(v)


def _block(cols: list[int], heads: list[list[str]], cells: list[list[str]],
           widths: list[int], left: int) -> list[str]:
    def line(r: list[str]) -> str:
        return _GAP.join(r[i].ljust(widths[i]) if i < left else r[i].rjust(widths[i])
                         for i in cols)

    lines = [line(h).rstrip() for h in heads]
    lines.append(_GAP.join("-" * widths[i] for i in cols))
    lines += [line(r) for r in cells]
    return lines


def table(headers: Sequence[str], rows: Sequence[Sequence[Any]],
          units: Sequence[str] | None = None, width: int = WIDTH, left: int = 0) -> str:
    """Fixed-width text table; floats are printed with 4 significant digits.

    Parameters
    ----------
    headers : sequence of str
        Column headings, printed above a line of dashes.
    rows : sequence of sequence
        The rows, each with exactly one value per heading (``ValueError`` otherwise): a
        float is printed as ``{:.4g}``, None, NaN and infinity as ``-``, anything else
        (e.g. text formatted by the caller) with ``str``; every column is right-aligned
        to its widest cell.
    units : sequence of str, optional
        A second heading line (e.g. ``"[m]"``), one per heading; None (default): none.
        A block of columns (below) none of which has a unit has no such line.
    width : int
        The widest line (default :data:`WIDTH`): the columns that do not fit go into
        further blocks below, each starting with the first column again. A single column
        wider than that is printed whole.
    left : int
        How many leading columns are left-aligned (default 0: every column right-aligned;
        1: the row's name on the left).
    """
    n = len(headers)
    heads = [list(headers)] + ([list(units)] if units is not None else [])
    cells = [[_cell(v) for v in r] for r in rows]
    for r in heads + cells:
        if len(r) != n:
            raise ValueError(f"a table row has {len(r)} cells for {n} headings: {r}")
    widths = [max(len(r[i]) for r in heads + cells) for i in range(n)]
    blocks: list[list[int]] = [[0]]
    used = widths[0]
    for i in range(1, n):
        if len(blocks[-1]) > 1 and used + len(_GAP) + widths[i] > width:
            blocks.append([0])
            used = widths[0]
        blocks[-1].append(i)
        used += len(_GAP) + widths[i]
    out: list[str] = []
    for k, cols in enumerate(blocks):
        if k:
            out.append("")
        # a block whose columns have no units has no units line
        hk = [h for j, h in enumerate(heads) if j == 0 or any(h[i] for i in cols)]
        out += _block(cols, hk, cells, widths, left)
    return "\n".join(out)
