"""Batch results on disk, written as they arrive: ``OUT.jsonl`` (one JSON object per case,
appended and flushed per row), ``OUT.csv`` (the same rows as a table, units in the header),
and ``OUT.meta.json`` (the batch definition and the units of every column).

An interrupted batch resumes from the JSON lines: the rows already there are kept and their
cases skipped; a last line cut short by the interruption is dropped. At the end the CSV is
rewritten in case order from the JSON lines, so it holds exactly one row per case.
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.atomic import write_text_atomically

FIXED = ["case", "status", "message"]
TAIL = ["wall_time [s]", "case_id"]


def paths(out: str | Path) -> tuple[Path, Path, Path]:
    """(CSV, JSON lines, meta) for ``out`` (a ``.csv`` suffix is optional)."""
    out = Path(out)
    base = out.with_suffix("") if out.suffix.lower() in (".csv", ".jsonl") else out
    return (base.with_name(base.name + ".csv"), base.with_name(base.name + ".jsonl"),
            base.with_name(base.name + ".meta.json"))


def _clean(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


class Store:
    """Append-as-you-go storage of one batch (see the module docstring).

    Parameters
    ----------
    out : str or Path
        Base path of the results: ``OUT.csv``, ``OUT.jsonl`` and ``OUT.meta.json`` are
        written next to it (a ``.csv`` or ``.jsonl`` suffix is dropped first).
    meta : dict
        The batch definition, written to ``OUT.meta.json``: ``columns`` (the CSV header, in
        order) is required; with ``resume``, its ``problem``, ``kind`` and ``cases`` must
        equal those of the stored batch.
    resume : bool
        Continue the batch already at ``out``: keep its complete JSON lines (dropping a
        last line cut short) and their cases (:attr:`done`). Default False.
    overwrite : bool
        Replace results already at ``out``; without it or ``resume`` (default False), such
        results are an error.
    """

    def __init__(self, out: str | Path, meta: dict[str, Any], resume: bool = False,
                 overwrite: bool = False) -> None:
        self.csv_path, self.jsonl_path, self.meta_path = paths(out)
        self.meta = meta
        self.done: dict[str, dict[str, Any]] = {}
        exists = self.jsonl_path.exists() or self.csv_path.exists()
        if resume and self.jsonl_path.exists():
            self._load(meta)
        elif exists and not (resume or overwrite):
            raise CableOCPError(
                f"--out {self.csv_path}: results of a batch are already there; give --resume "
                "to continue that batch, --overwrite to replace it, or another --out")
        if not (resume and self.jsonl_path.exists()):
            self.jsonl_path.write_text("", encoding="utf-8")
        write_text_atomically(self.meta_path, json.dumps(meta, indent=2, default=str) + "\n")
        self._jsonl = self.jsonl_path.open("a", encoding="utf-8")
        self.columns = meta["columns"]
        new_csv = not (resume and self.csv_path.exists())
        self._csv_fh = self.csv_path.open("w" if new_csv else "a", newline="",
                                          encoding="utf-8")
        self._csv = csv.writer(self._csv_fh)
        if new_csv:
            self._csv.writerow(self.columns)
            for row in sorted(self.done.values(), key=lambda r: r["case"]):
                self._csv.writerow(self._cells(row))
            self._csv_fh.flush()

    def _load(self, meta: dict[str, Any]) -> None:
        old = json.loads(self.meta_path.read_text()) if self.meta_path.exists() else {}
        for key in ("problem", "kind", "cases"):
            if old.get(key) != json.loads(json.dumps(meta.get(key), default=str)):
                raise CableOCPError(
                    f"--resume: {self.jsonl_path} holds another batch (its {key} differs); "
                    "give the same file, grids and seed, or another --out")
        good = []
        with self.jsonl_path.open(encoding="utf-8") as fh:
            for line in fh:
                try:
                    row = json.loads(line)
                except json.JSONDecodeError:
                    break  # a line cut short by the interruption: drop it and what follows
                good.append(line if line.endswith("\n") else line + "\n")
                self.done[row["case_id"]] = row
        write_text_atomically(self.jsonl_path, "".join(good))

    def _cells(self, row: dict[str, Any]) -> list[Any]:
        return ["" if row.get(self._key(c)) is None else row.get(self._key(c))
                for c in self.columns]

    @staticmethod
    def _key(column: str) -> str:
        return "wall_time_s" if column == "wall_time [s]" else column

    def add(self, row: dict[str, Any]) -> None:
        """Append one row to both files and flush them."""
        row = {k: _clean(v) for k, v in row.items()}
        self._jsonl.write(json.dumps(row, default=str) + "\n")
        self._jsonl.flush()
        self._csv.writerow(self._cells(row))
        self._csv_fh.flush()
        self.done[row["case_id"]] = row

    def finish(self) -> list[dict[str, Any]]:
        """Close the files and rewrite the CSV in case order; returns the rows."""
        self.close()
        rows = sorted(self.done.values(), key=lambda r: r["case"])
        buf = io.StringIO()
        w = csv.writer(buf)
        w.writerow(self.columns)
        for row in rows:
            w.writerow(self._cells(row))
        # whole or not at all: a full disk keeps the CSV the rows were appended to
        write_text_atomically(self.csv_path, buf.getvalue())
        return rows

    def close(self) -> None:
        """Close the files (rows already written stay)."""
        for fh in (self._jsonl, self._csv_fh):
            if not fh.closed:
                fh.close()
