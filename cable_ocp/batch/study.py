"""A load-case study: :func:`run_batch` cuts the cases into chunks (warm starts along the
grid, guided self-scheduling), runs them on the chosen executor, stores the rows as they
arrive and returns a :class:`BatchResult` (the package's docstring has the example).
"""

from __future__ import annotations

import contextlib
import math
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.batch.arrays import ARRAYS, DIMS
from cable_ocp.batch.cases import Case, build_cases
from cable_ocp.batch.executors import RunnerSpec, run_dask, run_local, run_serial
from cable_ocp.batch.kinds import SUCCESS, runner_kind
from cable_ocp.batch.store import FIXED, FORMAT, TAIL, Store, sha256_data, sha256_file
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt
from cable_ocp.numerics.export import optional_module, summary_repr
from cable_ocp.scene.files import apply_overrides, read_problem
from cable_ocp.version import __version__

__all__ = ["BatchResult", "run_batch"]


@dataclass
class BatchResult:
    """The rows of a batch, one per case, in case order.

    Attributes
    ----------
    kind : str
        ``"statics"``, ``"footprint"``, ``"heave"``.
    inputs : list of str
        The swept dotted keys (problem-file units).
    outputs : list of str
        Output columns, ``name [unit]``.
    rows : list of dict
        One dict per case: ``case``, ``case_id``, ``status``, ``message``, ``wall_time_s``,
        the inputs, the outputs and ``duplicate_of`` (the first case with the same
        parameters, or None).
    paths : tuple of Path, optional
        (CSV, JSON lines, meta) when written to disk.
    wall_time_s : float
        Wall time of this run, s.
    skipped : int
        Cases already done in the stored batch this run resumed.
    notes : list of str
        What a resume dropped from the stored rows (lines that are not rows, a line cut
        short, ``worker_lost`` rows run again), one remark each.
    random_inputs : list of str
        The inputs among :attr:`inputs` drawn at random (``randoms``): a figure draws their
        cases as points, not joined by lines.
    arrays : dict, optional
        Case index -> {name: 1-D array} (:mod:`cable_ocp.batch.arrays`) when the batch kept
        them (``keep_arrays`` or ``arrays``); None otherwise.
    """

    kind: str
    inputs: list[str]
    outputs: list[str]
    rows: list[dict[str, Any]]
    paths: tuple[Path, Path, Path] | None = None
    wall_time_s: float = 0.0
    skipped: int = field(default=0)
    notes: list[str] = field(default_factory=list)
    random_inputs: list[str] = field(default_factory=list)
    arrays: dict[int, dict[str, np.ndarray]] | None = None

    def swept(self) -> list[str]:
        """The inputs that take more than one value over the rows (all inputs if none
        does)."""
        return [k for k in self.inputs if len({str(r.get(k)) for r in self.rows}) > 1] or list(
            self.inputs)

    def duplicates(self) -> list[list[int]]:
        """Groups of cases with identical parameters (each group's case indices, in
        order; a group has two or more): separate cases and rows, each with its own seed."""
        groups: dict[str, list[int]] = {}
        for r in self.rows:
            groups.setdefault(str(r.get("case_id")), []).append(r["case"])
        return [g for g in groups.values() if len(g) > 1]

    def column(self, name: str) -> np.ndarray:
        """One input or output column as a float array (NaN where missing)."""
        return np.array([np.nan if r.get(name) is None else float(r[name]) for r in self.rows])

    def statuses(self) -> dict[str, int]:
        """Number of cases per status."""
        out: dict[str, int] = {}
        for r in self.rows:
            out[r["status"]] = out.get(r["status"], 0) + 1
        return out

    @property
    def failures(self) -> int:
        """Cases that are not a success."""
        ok = SUCCESS.get(self.kind, ("solved",))
        return sum(r["status"] not in ok for r in self.rows)

    def __repr__(self) -> str:
        """A few lines: kind, cases per status, the swept keys and columns."""
        counts = self.statuses()
        status = ", ".join(f"{n} {st}" for st, n in sorted(counts.items())) or "no cases"
        return summary_repr(
            "BatchResult", self.kind, status,
            [("cases", len(self.rows), ""), ("failures", self.failures, ""),
             ("skipped", self.skipped, ""), ("wall_time_s", self.wall_time_s, "s"),
             ("inputs", " ".join(self.inputs) or "-", ""),
             ("outputs", len(self.outputs), ""),
             ("store", str(self.paths[0].with_suffix("")) if self.paths else "-", "")])

    def to_pandas(self) -> Any:
        """The rows as a ``pandas.DataFrame``, one per case (index ``case``): ``case_id``,
        ``status``, ``message``, ``wall_time_s``, the swept inputs and the outputs (units
        in the column names). Needs pandas (the extra ``[io]``)."""
        pd = optional_module("pandas", "BatchResult.to_pandas()")
        frame = pd.DataFrame(self.rows)
        return frame.set_index("case") if "case" in frame else frame

    def to_xarray(self) -> Any:
        """The rows as an ``xarray.Dataset`` over the dimension ``case``: one variable per
        input (named by its key) and output (its name without the unit, the unit in
        ``units``), ``status`` and ``message``. Needs xarray (the extra ``[io]``)."""
        xr = optional_module("xarray", "BatchResult.to_xarray()")
        data: dict[str, Any] = {}
        for col in [*self.inputs, *self.outputs, "wall_time_s"]:
            name, _, unit = col.partition(" [")
            values = [r.get(col) for r in self.rows]
            numeric = all(v is None or isinstance(v, (int, float)) for v in values)
            arr = self.column(col) if numeric else np.array(
                ["" if v is None else str(v) for v in values])
            attrs = {"units": unit.rstrip("]")} if unit else {}
            if col == "wall_time_s":
                attrs = {"units": "s"}
            data[name] = ("case", arr, attrs)
        for col in ("case_id", "status", "message"):
            data[col] = ("case", np.array([str(r.get(col, "")) for r in self.rows]))
        cases = np.array([int(r.get("case", i)) for i, r in enumerate(self.rows)])
        return xr.Dataset(data, coords={"case": cases},
                          attrs={"kind": self.kind, "inputs": ", ".join(self.inputs),
                                 "inputs_units": "as in the problem file (SI)"})

    def plot(self, ax: Any = None, column: str | None = None, **kwargs: Any
             ) -> tuple[Any, Any]:
        """Draw one output against the swept keys (matplotlib), MoorPy's habit:
        ``fig, ax = res.plot()``.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Draw on it; None (default): a new figure as ``cable-ocp batch --plot``
            (:func:`cable_ocp.plots.batch.batch_figure`).
        column : str, optional
            The output, e.g. ``"max_tension [N]"`` (default: the first output column).
        **kwargs
            ``title``.

        Returns
        -------
        (fig, ax)
            The figure and the Axes drawn on (with ``ax=None``: an array of its panels).
        """
        from cable_ocp.plots.accessors import plot_batch_result

        return plot_batch_result(self, ax, column=column, **kwargs)


def _blocks(cases: Sequence[Case]) -> list[int]:
    """Indices where a new block of cases starts: a block is a run of consecutive cases
    along the key that changes most often in this order (on a grid, its fastest axis),
    the other keys held. Along a block each case warm-starts from the one before, and
    the keys held are usually what a solver is built for (the current speed of a statics
    scene, a cable property), so a block is best run by one worker."""
    if len(cases) < 2:
        return [0]
    keys = list(cases[0].overrides)
    changes = {k: sum(a.overrides.get(k) != b.overrides.get(k)
                      for a, b in zip(cases, cases[1:], strict=False)) for k in keys}
    fast = max(keys, key=lambda k: changes[k]) if keys else None
    held = [k for k in keys if k != fast]
    starts = [0]
    for i in range(1, len(cases)):
        if any(cases[i].overrides.get(k) != cases[i - 1].overrides.get(k) for k in held):
            starts.append(i)
    return starts


def _chunks(cases: Sequence[Case], workers: int, chunk_size: int | None) -> list[list[Case]]:
    """Runs of consecutive cases, ``chunk_size`` each if given; else of decreasing size
    (guided self-scheduling, Polychronopoulos & Kuck (1987)): each chunk takes about 1/(2 w)
    of the cases still unassigned, at least 2, so that the first chunks are long (warm
    starts along the grid) and the last ones short: the workers finish within a case or
    two of each other instead of up to a whole chunk apart. A chunk ends at the start of
    a block (:func:`_blocks`) when one lies within half its size of the target end, so
    that two workers rarely build a solver for the same block."""
    n = len(cases)
    if chunk_size:
        return [list(cases[i:i + chunk_size]) for i in range(0, n, chunk_size)]
    w = max(1, workers)
    starts = _blocks(cases)[1:]
    out, i = [], 0
    while i < n:
        size = max(2, math.ceil((n - i) / (2 * w)))
        target = i + size
        near = [b for b in starts if i + size / 2 <= b <= i + 1.5 * size]
        end = min(near, key=lambda b: (abs(b - target), b)) if near else target
        end = min(max(end, i + 1), n)
        out.append(list(cases[i:end]))
        i = end
    return out


def run_batch(problem: str | Path | dict[str, Any], grids: Sequence[tuple[str, list]] = (),
              ranges: Sequence[tuple[str, list]] = (), samples: int = 0,
              randoms: Sequence[tuple[str, str, tuple[float, float]]] = (), seed: int = 0,
              *, command: str | None = None, options: dict[str, Any] | None = None,
              out: str | Path | None = None, resume: bool = False, overwrite: bool = False,
              workers: int | None = None, scheduler: Any = None, chunk_size: int | None = None,
              max_attempts: int = 2, spec: RunnerSpec | None = None,
              progress: Callable[[int, int, dict[str, Any]], None] | None = None,
              overrides: dict[str, Any] | None = None,
              keep_arrays: bool = False, arrays: str | Path | None = None,
              ) -> BatchResult:
    """Run a load-case study.

    Parameters
    ----------
    problem : path or dict
        The base problem file (any scene kind with a runner) or its dictionary.
    grids, ranges : list of (key, values)
        Swept keys (:func:`parse_grid`, :func:`parse_range`); their full product.
    samples, randoms, seed :
        ``samples`` seeded random draws of the ``randoms`` keys (:func:`parse_random`),
        combined with every grid point; ``seed`` also gives every case its own seed.
    command : str, optional
        ``"statics"`` (default for a statics scene) or ``"footprint"``; heave and dynamic
        (``simulate``) scenes have one runner each.
    options : dict, optional
        Runner options (footprint ``directions``, heave ``controllers``).
    out : path, optional
        Write ``OUT.csv``, ``OUT.jsonl`` and ``OUT.meta.json`` as rows arrive.
    resume, overwrite : bool
        Continue the batch stored at ``out`` (skipping finished cases), or replace it.
    workers : int, optional
        Local worker processes (default: every core, ``os.cpu_count()``); 0 runs in this
        process.
    scheduler : str or distributed.Client, optional
        Run on a dask.distributed cluster instead.
    chunk_size : int, optional
        Consecutive cases per task (default: guided, see :func:`_chunks`: chunks of
        1/(2 w) of the cases left, w the local processes or the cluster's worker
        threads).
    max_attempts : int
        How often a case may kill its worker process before it is given up (local pool).
    spec : RunnerSpec, optional
        Replaces the runner (for fault-injection tests and custom studies).
    progress : callable, optional
        ``progress(done, total, row)`` after each row.
    overrides : dict, optional
        Dotted key -> value applied to the base problem before the cases (``--set``);
        recorded in the meta file, so that a resume with other values is refused.
    keep_arrays : bool
        Keep every case's arrays (tension along the line, time series:
        :mod:`cable_ocp.batch.arrays`) in :attr:`BatchResult.arrays` (default False).
    arrays : path, optional
        Also write them to this netCDF file when the batch ends (implies ``keep_arrays``;
        needs xarray, ``pip install -e '.[io]'``); with ``resume`` the stored arrays of the
        cases already done are kept; an existing file needs ``resume`` or ``overwrite``.

    Returns
    -------
    BatchResult
    """
    t0 = time.perf_counter()
    data = problem if isinstance(problem, dict) else read_problem(problem)
    if overrides:
        data = apply_overrides(data, overrides)
    kind = runner_kind(data, command)
    if kind == "heave" and not isinstance(problem, dict):
        # a relative [unit] cable_scene is read from the problem file's folder, also in
        # the workers (an absolute path: a cluster's workers need that file at that path)
        from cable_ocp.scene.heave import resolve_cable_scene

        data = resolve_cable_scene(data, Path(problem).parent)
    cases = build_cases(list(grids) + list(ranges), samples, list(randoms), seed)
    _check_base(data, kind)
    keep_arrays = keep_arrays or arrays is not None
    old_arrays = _check_arrays(kind, arrays, resume, overwrite) if keep_arrays else {}
    spec = spec or RunnerSpec(kind, data, {**dict(options or {}),
                                           **({"arrays": True} if keep_arrays else {})})
    columns_out = spec.make().columns() if kind != "heave" else _heave_columns(spec)
    inputs = [k for k, _ in list(grids) + list(ranges)] + [k for k, _, _ in randoms]
    store = None
    if out is not None:
        meta = _meta(problem, data, kind, command, options, overrides, grids, ranges,
                     samples, randoms, seed, cases)
        meta["columns"] = FIXED + inputs + columns_out + TAIL
        store = Store(out, meta, resume=resume, overwrite=overwrite,
                      case_ids=[c.case_id for c in cases])
    done = set(store.done) if store else set()
    todo = [c for c in cases if c.index not in done]
    first: dict[str, int] = {}
    for c in cases:
        first.setdefault(c.case_id, c.index)
    rows: dict[int, dict[str, Any]] = {}
    count = len(cases) - len(todo)

    kept: dict[int, dict[str, np.ndarray]] = {}

    def on_row(row: dict[str, Any]) -> None:
        nonlocal count
        got = row.pop(ARRAYS, None)  # arrays never go into the row files
        if keep_arrays and got is not None:
            kept[row["case"]] = got
        same = first.get(row.get("case_id", ""), row["case"])
        row["duplicate_of"] = same if same != row["case"] else None
        rows[row["case"]] = row
        if store is not None:
            with interrupt.signals_blocked():  # a Ctrl-C waits for the row to be whole
                store.add(row)
        count += 1
        if progress is not None:
            progress(count, len(cases), row)

    n_workers = (os.cpu_count() or 1) if workers is None else workers
    chunks = _chunks(todo, n_workers, chunk_size)
    try:
        if scheduler is not None:  # chunks for the cluster's own number of workers
            run_dask(spec, lambda n: _chunks(todo, n, chunk_size), on_row, scheduler,
                     max_attempts)
        elif n_workers == 0 or len(todo) <= 1:
            run_serial(spec, chunks, on_row)
        else:
            run_local(spec, chunks, on_row, n_workers, max_attempts)
    except BaseException:
        if store is not None:
            store.abort()  # the CSV in case order as far as the disk allows; lock released
        done_rows = ([store.done[k] for k in sorted(store.done)] if store is not None
                     else [rows[k] for k in sorted(rows)])
        with contextlib.suppress(OSError, CableOCPError):  # the interruption is what ends it
            _write_arrays(arrays, kind, kept, old_arrays, done_rows, inputs, keep_arrays)
        raise
    final = store.finish() if store is not None else [rows[k] for k in sorted(rows)]
    kept = _write_arrays(arrays, kind, kept, old_arrays, final, inputs, keep_arrays)
    return BatchResult(kind, inputs, columns_out, final,
                       paths=(store.csv_path, store.jsonl_path, store.meta_path)
                       if store else None,
                       wall_time_s=time.perf_counter() - t0, skipped=len(cases) - len(todo),
                       notes=list(store.notes) if store else [],
                       random_inputs=[k for k, _, _ in randoms],
                       arrays=kept if keep_arrays else None)


def _write_arrays(path: str | Path | None, kind: str, kept: dict[int, dict[str, np.ndarray]],
                  old: dict[int, dict[str, np.ndarray]], rows: list[dict[str, Any]],
                  inputs: list[str], keep: bool) -> dict[int, dict[str, np.ndarray]]:
    """The kept arrays with those of the stored cases a resume skipped, in case order,
    written to ``path`` (also the finished part of an interrupted batch)."""
    if not keep:
        return kept
    done = {r["case"] for r in rows}
    merged = {**{k: v for k, v in old.items() if k in done}, **kept}
    merged = {k: merged[k] for k in sorted(merged)}
    if path is not None and merged:
        from cable_ocp.batch.arrays import arrays_dataset, write_arrays

        write_arrays(path, arrays_dataset(kind, merged, rows, inputs))
    return merged


def _check_arrays(kind: str, path: str | Path | None, resume: bool, overwrite: bool
                  ) -> dict[int, dict[str, np.ndarray]]:
    """Refuse arrays a kind does not keep, or a file there without resume/overwrite (before
    any work); the arrays stored at ``path`` by case index when resuming (the store refuses
    a resume whose cases differ, so the indices are the same cases)."""
    if kind not in DIMS:
        raise CableOCPError(f"--arrays: a {kind} batch keeps no arrays; valid for "
                            f"{', '.join(DIMS)} batches")
    if path is None:
        return {}
    from cable_ocp.batch.arrays import case_arrays, read_arrays, require_xarray

    require_xarray()
    p = Path(path)
    if not p.exists():
        return {}
    if not (resume or overwrite):
        raise CableOCPError(f"--arrays {p}: a file is already there; give --resume to "
                            "continue that batch, --overwrite to replace it, or another file")
    if not resume:
        return {}
    ds = read_arrays(p)
    if ds.attrs.get("kind") != kind:
        raise CableOCPError(f"--arrays {p}: holds the arrays of a {ds.attrs.get('kind')} "
                            f"batch, not of this {kind} batch; give another file")
    return case_arrays(ds)


def _meta(problem: str | Path | dict[str, Any], data: dict[str, Any], kind: str,
          command: str | None, options: dict[str, Any] | None,
          overrides: dict[str, Any] | None, grids: Sequence[tuple[str, list]],
          ranges: Sequence[tuple[str, list]], samples: int,
          randoms: Sequence[tuple[str, str, tuple[float, float]]], seed: int,
          cases: Sequence[Case]) -> dict[str, Any]:
    """The record of a batch's inputs for ``OUT.meta.json`` (:data:`store.INPUTS`): the
    problem file's path and SHA-256 (of the dictionary's canonical JSON for a dictionary),
    those of the files it reads (a heave scene's ``[unit] cable_scene``),
    every override, sweep and draw, the seed, the options and the package version."""
    version = __version__
    if isinstance(problem, dict):
        source = {"path": None, "sha256": sha256_data(problem)}
    else:
        source = {"path": str(Path(problem).resolve()), "sha256": sha256_file(problem)}
    files = {}  # the other files the problem reads, with their digests
    unit = data.get("unit")
    scene_file = unit.get("cable_scene") if isinstance(unit, dict) else None
    if isinstance(scene_file, str) and Path(scene_file).is_file():
        files["[unit] cable_scene"] = {"path": scene_file, "sha256": sha256_file(scene_file)}
    return {"format": FORMAT, "version": version, "problem": source, "files": files,
            "kind": kind,
            "command": command, "set": dict(overrides or {}),
            "grid": [[k, list(v)] for k, v in grids],
            "range": [[k, list(v)] for k, v in ranges],
            "random": [[k, d, list(p)] for k, d, p in randoms], "samples": samples,
            "seed": seed, "options": dict(options or {}),
            "base_sha256": sha256_data(data),
            "cases": [c.overrides for c in cases],
            "units": {"inputs": "as in the problem file (SI; see docs/problem_files.md)",
                      "outputs": "in brackets in each column name"}}


def _heave_columns(spec: RunnerSpec) -> list[str]:
    return spec.make().columns()


def _check_base(data: dict[str, Any], kind: str) -> None:
    """Validate the base problem before any work (exit 2 for the CLI); a case whose own
    overrides make it invalid becomes a row with status ``"invalid_input"``."""
    from cable_ocp.scene import scene_from_dict
    from cable_ocp.scene.dynamics import dynamic_scene_from_dict
    from cable_ocp.scene.heave import scene_from_dict as heave_from_dict
    from cable_ocp.scene.system import system_from_dict

    check = {"heave": heave_from_dict, "dynamics": dynamic_scene_from_dict,
             "system": system_from_dict}
    check.get(kind, scene_from_dict)(data)
