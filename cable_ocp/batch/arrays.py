"""The arrays of every case of a batch in one netCDF file (``batch --arrays FILE.nc``), and
the envelope of a quantity along the line over the cases (the *range graph*).

What a case keeps, by scene kind (dimension, variables):

* statics: ``point`` (the solution's nodes from end_a): ``arc_length`` (unstretched, m),
  ``tension`` (N), ``x``, ``y``, ``z`` (m);
* dynamics: ``sample``: ``time`` (s), ``top_tension`` (N), ``unit_z`` (m), ``length``
  (unstretched paid-out length, m);
* heave: ``sample``: ``time`` (s) and, per controller C, ``C_unit_heave`` and
  ``C_winch_output`` (m) and, on the cable plant, ``C_unit_tension`` (N).

The file has the dimensions ``case`` (the batch's case indices) and the kind's own; cases
of different lengths are padded with NaN after their ``{dim}_count`` samples. With
netCDF4 (the ``io`` extra) every variable is stored in chunks of one case (a case reads
without the others). The swept inputs, each case's status and identifier are variables
along ``case``. The file is written once, whole or not at all
(:func:`cable_ocp.numerics.atomic.replace_atomically`), when the batch ends (also when it
is interrupted: the finished cases); ``--resume`` keeps the stored cases of the cases it
skips.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.export import write_netcdf
from cable_ocp.scene.units import key_unit

__all__ = ["ARRAYS", "DIMS", "arrays_dataset", "case_arrays", "envelope", "read_arrays",
           "require_xarray", "write_arrays"]

#: the row key under which a runner hands its arrays to ``run_batch`` (never in the rows
#: that are stored or returned)
ARRAYS = "_arrays"
#: scene kind -> the dimension of its arrays
DIMS = {"statics": "point", "dynamics": "sample", "heave": "sample"}
_UNITS = {"arc_length": "m", "tension": "N", "x": "m", "y": "m", "z": "m", "time": "s",
          "top_tension": "N", "unit_z": "m", "length": "m"}
_SUFFIX_UNITS = {"_unit_heave": "m", "_winch_output": "m", "_unit_tension": "N"}


def array_unit(name: str) -> str:
    """The unit of a stored array (``"N"`` for ``tension``, ``"m"`` for ``lqr_unit_heave``)."""
    if name in _UNITS:
        return _UNITS[name]
    return next((u for s, u in _SUFFIX_UNITS.items() if name.endswith(s)), "")


def require_xarray(option: str = "--arrays") -> Any:
    """The xarray module, or a :class:`CableOCPError` (exit 2) naming the extra to install.

    Parameters
    ----------
    option : str
        The option that needs it, for the message (default ``"--arrays"``).
    """
    try:
        import xarray
    except ImportError:
        raise CableOCPError(f"{option} needs xarray (the io extra): pip install -e '.[io]'"
                            ) from None
    return xarray


def arrays_dataset(kind: str, arrays: Mapping[int, Mapping[str, np.ndarray]],
                   rows: Sequence[Mapping[str, Any]], inputs: Sequence[str] = ()) -> Any:
    """The per-case arrays of a batch as one :class:`xarray.Dataset` (module docstring).

    Parameters
    ----------
    kind : str
        The batch's scene kind (a key of :data:`DIMS`).
    arrays : mapping
        Case index -> {variable name: 1-D array}, as the runners give them.
    rows : sequence of dict
        The batch's rows (``case``, ``case_id``, ``status`` and the inputs are read from the
        rows of the cases in ``arrays``).
    inputs : sequence of str
        The swept dotted keys, stored per case with their units (:mod:`cable_ocp.scene.units`).
    """
    xr = require_xarray()
    dim = DIMS[kind]
    cases = sorted(arrays)
    by_case = {r["case"]: r for r in rows}
    names: list[str] = []
    for c in cases:
        names += [n for n in arrays[c] if n not in names]
    counts = np.array([max((len(v) for v in arrays[c].values()), default=0) for c in cases],
                      dtype=np.int64)
    width = int(counts.max()) if counts.size else 0
    data_vars: dict[str, Any] = {}
    for name in names:
        block = np.full((len(cases), width), np.nan)
        for i, c in enumerate(cases):
            v = np.asarray(arrays[c].get(name, ()), dtype=float).ravel()
            block[i, :v.size] = v
        data_vars[name] = (("case", dim), block, {"units": array_unit(name)})
    data_vars[f"{dim}_count"] = ("case", counts, {"long_name": f"samples of each case "
                                                               f"along {dim}"})
    for key in inputs:
        vals = [by_case.get(c, {}).get(key) for c in cases]
        col = np.array([np.nan if v is None else v for v in vals])
        data_vars[key] = ("case", col, {"units": key_unit(key), "long_name": "swept input"})
    data_vars["status"] = ("case", np.array([str(by_case.get(c, {}).get("status", ""))
                                             for c in cases], dtype=object))
    data_vars["case_id"] = ("case", np.array([str(by_case.get(c, {}).get("case_id", ""))
                                              for c in cases], dtype=object))
    return xr.Dataset(data_vars, coords={"case": np.asarray(cases, dtype=np.int64)},
                      attrs={"kind": kind, "dimension": dim,
                             "conventions": "SI; z up; arc length from end_a; NaN after "
                                            f"each case's {dim}_count samples"})


def write_arrays(path: str | Path, dataset: Any) -> Path:
    """Write a dataset of :func:`arrays_dataset` to ``path`` (netCDF), whole or not at all.

    Parameters
    ----------
    path : str or Path
        The file (``.nc``); an earlier file is replaced only when the new one is complete.
    dataset : xarray.Dataset
        The arrays; with netCDF4 or h5netcdf every case-dimensioned float variable is
        chunked one case per chunk.

    Raises
    ------
    CableOCPError
        When the file cannot be written (a full disk: the earlier file is kept).
    """
    def by_case(engine: str, ds: Any) -> dict[str, dict[str, Any]]:
        if engine == "scipy":  # netCDF-3 has no chunks
            return {}
        return {str(name): {"chunksizes": (1, *[max(1, n) for n in var.shape[1:]]),
                            "zlib": True}
                for name, var in ds.data_vars.items()
                if var.dims and var.dims[0] == "case" and var.dtype.kind == "f"}

    try:
        return write_netcdf(dataset, path, encoding=by_case)
    except OSError as exc:
        why = exc.strerror or str(exc) or type(exc).__name__
        raise CableOCPError(f"--arrays {path}: could not be written ({why}); the earlier file, "
                            "if any, is kept") from exc


def read_arrays(path: str | Path) -> Any:
    """The dataset stored at ``path`` by :func:`write_arrays`, loaded into memory (the file
    is closed again).

    Parameters
    ----------
    path : str or Path
        A netCDF file written by ``batch --arrays``.
    """
    xr = require_xarray()
    try:
        with xr.open_dataset(path, engine=_engine_for(path)) as ds:
            return ds.load()
    except (OSError, ValueError) as exc:
        raise CableOCPError(f"--arrays {path}: cannot be read as a batch's arrays ({exc})"
                            ) from None


def _engine_for(path: str | Path) -> str | None:
    """The engine that reads ``path``: scipy for netCDF-3 (b"CDF"), else the default."""
    with open(path, "rb") as fh:
        return "scipy" if fh.read(3) == b"CDF" else None


def case_arrays(dataset: Any) -> dict[int, dict[str, np.ndarray]]:
    """Case index -> {name: 1-D array} from a dataset of :func:`arrays_dataset` (each cut
    to the case's own ``{dim}_count`` samples): the runners' form, for merging and plots."""
    dim = dataset.attrs.get("dimension") or DIMS[dataset.attrs["kind"]]
    names = [str(n) for n, v in dataset.data_vars.items() if v.dims == ("case", dim)]
    counts = dataset[f"{dim}_count"].values
    out: dict[int, dict[str, np.ndarray]] = {}
    for i, c in enumerate(dataset["case"].values):
        n = int(counts[i])
        out[int(c)] = {name: np.asarray(dataset[name].values[i, :n], dtype=float)
                       for name in names}
    return out


def envelope(arrays: Mapping[int, Mapping[str, np.ndarray]], name: str = "tension",
             along: str = "arc_length", max_points: int = 20000
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The range graph's data: min, max and mean of ``name`` over the cases, against
    ``along`` (statics: tension against arc length).

    Every case is evaluated on one grid, the union of the cases' own nodes (a uniform grid
    of ``max_points`` when the union is larger), by linear interpolation between its nodes
    (exact at them); a case counts only within its own span (a shorter line ends early).

    Parameters
    ----------
    arrays : mapping
        Case index -> {variable: 1-D array} (:attr:`BatchResult.arrays` or
        :func:`case_arrays` of a stored file); cases without ``name`` are left out.
    name, along : str
        The quantity and the abscissa (defaults ``"tension"``, ``"arc_length"``).
    max_points : int
        Largest grid (default 20000).

    Returns
    -------
    s, low, high, mean : numpy.ndarray
        The grid and the envelope on it (NaN where no case reaches).
    """
    pairs = []
    for c in sorted(arrays):
        a = arrays[c]
        if name in a and along in a:
            x, y = np.asarray(a[along], float), np.asarray(a[name], float)
            ok = np.isfinite(x) & np.isfinite(y)
            if ok.any():
                pairs.append((x[ok], y[ok]))
    if not pairs:
        raise CableOCPError(f"no case has the arrays {name!r} and {along!r} for a range graph")
    grid = np.unique(np.concatenate([x for x, _ in pairs]))
    if grid.size > max_points:
        grid = np.linspace(grid[0], grid[-1], max_points)
    table = np.full((len(pairs), grid.size), np.nan)
    for i, (x, y) in enumerate(pairs):
        inside = (grid >= x.min()) & (grid <= x.max())
        order = np.argsort(x, kind="stable")
        table[i, inside] = np.interp(grid[inside], x[order], y[order])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN columns stay NaN
        return (grid, np.nanmin(table, axis=0), np.nanmax(table, axis=0),
                np.nanmean(table, axis=0))
