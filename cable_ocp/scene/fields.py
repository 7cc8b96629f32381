"""Validation of single values read from a problem file.

Every function raises :class:`~cable_ocp.errors.CableOCPError` with a message that names
the dotted key, the offending value and what would be valid, e.g.
``winch.delay = -1.0: must be >= 0 (s)``. The scene kinds (:mod:`cable_ocp.scene.statics`,
:mod:`cable_ocp.scene.heave`, ...) build on these.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

from cable_ocp.errors import CableOCPError

FREE = "free"


def _unit(unit: str) -> str:
    return f" ({unit})" if unit else ""


def number(value: Any, key: str, *, positive: bool = False, nonneg: bool = False,
           allow_inf: bool = False, low: float | None = None, high: float | None = None,
           unit: str = "", why: str = "") -> float:
    """A finite number (or ``"inf"`` where ``allow_inf``), optionally signed or bounded.

    Parameters
    ----------
    value : Any
        The value as read from TOML.
    key : str
        Dotted key for the message, e.g. ``"cable.length"``.
    positive, nonneg : bool
        Require > 0 or >= 0.
    allow_inf : bool
        Accept ``"inf"`` or ``"infinity"`` (any case) and an infinite float, returned as
        ``math.inf``; an infinite value passes ``high``. Default False: finite only.
    low, high : float, optional
        Inclusive bounds; ``why`` says where the bound comes from. In the value's own
        unit; None (default): unbounded on that side.
    unit : str
        The unit, printed in the message (e.g. ``"m"``; empty, the default: none).
    why : str
        Where a ``low``/``high`` bound comes from, appended to its message; empty
        (default): nothing appended.
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise CableOCPError(f"{key} = {value!r}: expected a number{_unit(unit)}")
    if isinstance(value, str):
        if allow_inf and value.strip().lower() in ("inf", "infinity"):
            return math.inf
        raise CableOCPError(
            f"{key} = {value!r}: expected a number{_unit(unit)}"
            + (' or "inf"' if allow_inf else ""))
    x = float(value)
    if math.isnan(x) or (math.isinf(x) and not allow_inf):
        raise CableOCPError(f"{key} = {value!r}: expected a finite number{_unit(unit)}")
    if positive and not x > 0:
        raise CableOCPError(f"{key} = {value!r}: must be > 0{_unit(unit)}")
    if nonneg and x < 0:
        raise CableOCPError(f"{key} = {value!r}: must be >= 0{_unit(unit)}")
    if (low is not None and x < low) or (high is not None and x > high and math.isfinite(x)):
        lo = "" if low is None else f"{low:g}"
        hi = "" if high is None else f"{high:g}"
        rng = (f"in [{lo}, {hi}]" if low is not None and high is not None
               else f">= {lo}" if low is not None else f"<= {hi}")
        raise CableOCPError(f"{key} = {value!r}: must be {rng}{_unit(unit)}"
                            + (f"; {why}" if why else ""))
    return x


def integer(value: Any, key: str, low: int, high: int | None = None, why: str = "") -> int:
    """An integer in ``[low, high]`` (TOML integers only, not floats or booleans).

    Parameters
    ----------
    value : Any
        The value as read from TOML.
    key : str
        Dotted key for the message, e.g. ``"solver.degree"``.
    low : int
        Smallest valid value (inclusive).
    high : int, optional
        Largest valid value (inclusive); None (default): no upper bound.
    why : str
        Why the range is what it is, appended to the message; empty (default): nothing.
    """
    ok = not isinstance(value, bool) and isinstance(value, int)
    if ok and value >= low and (high is None or value <= high):
        return int(value)
    rng = f"{low}..{high}" if high is not None else f">= {low}"
    raise CableOCPError(f"{key} = {value!r}: expected an integer {rng}"
                        + (f"; {why}" if why else ""))


def boolean(value: Any, key: str) -> bool:
    """``true`` or ``false``.

    Parameters
    ----------
    value : Any
        The value as read from TOML; only a TOML boolean passes (not 0/1 or a string).
    key : str
        Dotted key for the message.
    """
    if not isinstance(value, bool):
        raise CableOCPError(f"{key} = {value!r}: expected true or false")
    return value


def choice(value: Any, key: str, options: Iterable[str]) -> str:
    """One of ``options`` (listed plainly in the message).

    Parameters
    ----------
    value : Any
        The value as read from TOML; must be a string equal to one of ``options``
        (case-sensitive).
    key : str
        Dotted key for the message.
    options : iterable of str
        The valid strings, in the order the message lists them.
    """
    options = list(options)
    if not isinstance(value, str) or value not in options:
        raise CableOCPError(f"{key} = {value!r}: valid are "
                            + ", ".join(f'"{o}"' for o in options))
    return value


def require(table: dict[str, Any], key: str, where: str) -> Any:
    """``table[key]``, or an error naming ``where.key`` as missing.

    Parameters
    ----------
    table : dict
        The TOML table to read from.
    key : str
        The key that must be present.
    where : str
        Dotted name of ``table`` for the message, e.g. ``"end_b"``; ``"problem"`` means the
        top level, and the message then names ``[key]`` as a missing table.
    """
    if key not in table:
        if where == "problem":
            raise CableOCPError(f"the [{key}] table is missing (required)")
        raise CableOCPError(f"{where}.{key} is missing (required, SI units)")
    return table[key]


def check_keys(table: Any, allowed: set[str], where: str) -> dict[str, Any]:
    """``table`` itself, after checking that it is a table with only ``allowed`` keys.

    Parameters
    ----------
    table : Any
        The value read for the table; anything but a dict is an error.
    allowed : set of str
        The valid keys; the message for an unknown key lists them.
    where : str
        Dotted name of the table for the message, e.g. ``"environment.current"``.
    """
    if not isinstance(table, dict):
        raise CableOCPError(f"[{where}] must be a table, got {table!r}")
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise CableOCPError(
            f"unknown key {where}.{unknown[0]}; valid keys in [{where}]: "
            f"{', '.join(sorted(allowed))}"
        )
    return table


def vector3(value: Any, key: str, *, bound: float | None = None, unit: str = "",
            why: str = "") -> tuple[float | None, float | None, float | None]:
    """``[x, y, z]`` numbers, each entry a number in ``[-bound, bound]`` or ``"free"``
    (returned as None).

    Parameters
    ----------
    value : Any
        The value as read from TOML: a list of 3 entries, each a number or ``"free"`` (any
        case).
    key : str
        Dotted key for the message; an entry's message names ``key[i]``.
    bound : float, optional
        Largest magnitude of each entry (inclusive), in ``unit``; None (default): unbounded.
    unit : str
        The unit, printed in the message (e.g. ``"m"``, ``"N"``); empty (default): none.
    why : str
        Where ``bound`` comes from, appended to its message; empty (default): nothing.
    """
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        raise CableOCPError(f"{key} = {value!r}: expected a list of 3 entries [x, y, z]")
    out: list[float | None] = []
    for i, v in enumerate(value):
        if isinstance(v, str) and v.strip().lower() == FREE:
            out.append(None)
        else:
            out.append(number(v, f"{key}[{i}]", low=None if bound is None else -bound,
                              high=bound, unit=unit, why=why))
    return tuple(out)  # type: ignore[return-value]
