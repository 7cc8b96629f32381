"""Values that strict JSON can hold (no NaN or infinity), for every output of the package.

The results' ``to_dict()`` (dynamics) and the CLI's ``--json`` writer
(:func:`cable_ocp.cli.output.json_text`) both convert with :func:`json_safe`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["json_safe"]


def json_safe(value: Any) -> Any:
    """A copy of ``value`` that strict JSON can hold: numpy arrays and scalars as Python
    lists and numbers, NaN and +-inf as None, tuples as lists, dict keys as strings.

    Parameters
    ----------
    value : Any
        A number, array, dict, list or tuple of them (nested), or anything else (returned
        as it is).
    """
    if isinstance(value, dict):
        return {str(k): json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if isinstance(value, np.ndarray):
        return json_safe(value.tolist())
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        x = float(value)
        return x if math.isfinite(x) else None
    return value
