"""What every result type shares for its users: a short summary as its ``repr``, the optional
table and array libraries (pandas, xarray: the extra ``[io]``) imported on first use, and
netCDF files written whole or not at all.

Nothing here knows about cables: a result passes its own kind, status, key numbers (with
their units) and arrays, and its own ``to_xarray()``.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterable, Mapping
from importlib import import_module
from pathlib import Path
from types import ModuleType
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.atomic import replace_atomically

__all__ = ["IO_EXTRA", "netcdf_engine", "optional_module", "summary_repr", "write_netcdf"]

#: the install line that brings the optional libraries of this module
IO_EXTRA = "pip install -e '.[io]'"
#: summary lines are wrapped at this width (characters)
WIDTH = 96
#: the message is cut to this many characters in a summary
MESSAGE_CHARS = 160


def _number(value: Any) -> str:
    """A number with 6 significant digits ('-' where it does not exist)."""
    if value is None:
        return "-"
    if isinstance(value, (bool, str)):
        return str(value)
    try:
        v = float(value)
    except (TypeError, ValueError):
        return str(value)
    if not math.isfinite(v):
        return "-" if math.isnan(v) else str(v)
    return f"{v:.6g}"


def _shape(value: Any) -> str:
    shape = getattr(value, "shape", None)
    if shape is None:
        return f"len {len(value)}" if hasattr(value, "__len__") else type(value).__name__
    return "(" + ", ".join(str(n) for n in shape) + ("," if len(shape) == 1 else "") + ")"


def _wrap(head: str, items: Iterable[str]) -> list[str]:
    """``items`` joined by commas on lines of at most :data:`WIDTH` characters, the first
    starting with ``head``, the others indented under it."""
    lines, cur = [], head
    for item in items:
        sep = "" if cur == head else ", "
        if cur != head and len(cur) + len(sep) + len(item) > WIDTH:
            lines.append(cur + ",")
            cur, sep = " " * len(head), ""
        cur += sep + item
    if cur.strip():
        lines.append(cur)
    return lines


def summary_repr(kind: str, status: Any, message: str = "",
                 numbers: Iterable[tuple[str, Any, str]] = (),
                 arrays: Mapping[str, Any] | None = None) -> str:
    """A result's short summary: its kind and status, its key numbers with units, the
    shapes of its arrays (a few lines, whatever the size of the arrays).

    Parameters
    ----------
    kind : str
        The result's type name, e.g. ``"StaticsSolution"``.
    status : str
        Its status.
    message : str
        The status's detail (cut to :data:`MESSAGE_CHARS` characters).
    numbers : iterable of (name, value, unit)
        Key numbers, written with 6 significant digits and their unit (``""``: none);
        a value that does not exist is written ``-``.
    arrays : mapping of name to array, optional
        The result's arrays, written as their shapes (None values are left out).

    Returns
    -------
    str
        E.g. ``"<StaticsSolution solved: converged>\\n  length = 3000 m, ..."``.
    """
    msg = " ".join(str(message).split())
    if len(msg) > MESSAGE_CHARS:
        msg = msg[: MESSAGE_CHARS - 3] + "..."
    lines = [f"<{kind} {status}" + (f": {msg}>" if msg else ">")]
    nums = [f"{name} = {_number(v)}" + (f" {unit}" if unit else "")
            for name, v, unit in numbers]
    lines += _wrap("  ", nums)
    shapes = [f"{name} {_shape(a)}" for name, a in (arrays or {}).items() if a is not None]
    if shapes:
        lines += _wrap("  arrays: ", shapes)
    return "\n".join(lines)


def optional_module(name: str, purpose: str) -> ModuleType:
    """Import an optional library of the extra ``[io]`` (``pandas``, ``xarray``,
    ``netCDF4``) on first use.

    Parameters
    ----------
    name : str
        The module to import.
    purpose : str
        What needs it, for the message (e.g. ``"SimulationResult.to_xarray()"``).

    Raises
    ------
    CableOCPError
        When it is not installed, naming ``purpose``, the module and :data:`IO_EXTRA`.
    """
    try:
        return import_module(name)
    except ImportError:
        raise CableOCPError(f"{purpose} needs {name}, which is not installed: it comes with "
                            f"the optional extra io, {IO_EXTRA}") from None


def netcdf_engine(purpose: str) -> str:
    """The netCDF engine xarray will write with: ``netcdf4`` (the extra ``[io]``), else
    ``h5netcdf`` (netCDF-4 too), else ``scipy`` (netCDF-3, which scipy can write).

    Parameters
    ----------
    purpose : str
        What needs it, for the message.

    Raises
    ------
    CableOCPError
        When xarray is missing (see :func:`optional_module`).
    """
    optional_module("xarray", purpose)
    for module, engine in (("netCDF4", "netcdf4"), ("h5netcdf", "h5netcdf")):
        try:
            import_module(module)
            return engine
        except ImportError:
            continue
    import_module("scipy.io")
    return "scipy"


def write_netcdf(result: Any, path: str | os.PathLike[str],
                 encoding: Callable[[str, Any], dict[str, Any]] | None = None) -> Path:
    """Write ``result.to_xarray()`` (or an ``xarray.Dataset``) to the netCDF file ``path``,
    whole or not at all (:func:`cable_ocp.numerics.atomic.replace_atomically`).

    Parameters
    ----------
    result : result with ``to_xarray()``, or xarray.Dataset
        What to write: a simulation's time series, a statics profile, modes, ...
    path : str or path-like
        The file (its directory must exist); an earlier file there is replaced.
    encoding : callable, optional
        ``encoding(engine, dataset)``: xarray's per-variable encoding for that engine
        (e.g. chunks for netCDF-4); None (default): xarray's defaults.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    CableOCPError
        When xarray is missing (the extra ``[io]``).
    OSError
        When the file cannot be written (a full disk, ...): ``path`` is then unchanged.
    """
    engine = netcdf_engine("write_netcdf")
    ds = result.to_xarray() if hasattr(result, "to_xarray") else result
    extra = {"encoding": enc} if encoding is not None and (enc := encoding(engine, ds)) else {}
    return replace_atomically(path, lambda tmp: ds.to_netcdf(tmp, engine=engine, **extra))
