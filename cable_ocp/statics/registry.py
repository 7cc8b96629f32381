"""The statics methods by name: ``[solver] method = NAME`` picks one.

The scene knows the valid names (:data:`cable_ocp.scene.METHODS`) without importing any
method; each method registers its solve function here when its module is imported
(:mod:`cable_ocp.statics.solver` registers ``collocation`` and ``multiple_shooting``, the
modules of :mod:`cable_ocp.baselines` register theirs; importing :mod:`cable_ocp` imports
them all). Every registered function has the signature
``solve(scene, warm_start=None) -> StaticsSolution``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.scene import METHODS

_REGISTRY: dict[str, Callable[..., Any]] = {}


def register(name: str, solve: Callable[..., Any]) -> Callable[..., Any]:
    """Register ``solve`` under ``name`` (one of :data:`cable_ocp.scene.METHODS`).

    Parameters
    ----------
    name : str
        The method's name, as ``[solver] method`` gives it; a name not in
        :data:`cable_ocp.scene.METHODS` raises ValueError. A name registered before is
        replaced.
    solve : callable
        The method's solve function, ``solve(scene, warm_start=None) -> StaticsSolution``;
        returned unchanged.
    """
    if name not in METHODS:  # a programming error, not a user's
        raise ValueError(f"{name!r} is not in cable_ocp.scene.METHODS")
    _REGISTRY[name] = solve
    return solve


def get_method(name: str) -> Callable[..., Any]:
    """Return the solve function registered under ``name``."""
    if name not in METHODS:
        raise CableOCPError(f"solver.method = {name!r}: valid are {', '.join(METHODS)}")
    if name not in _REGISTRY:  # pragma: no cover - cable_ocp/__init__ imports every method
        raise RuntimeError(f"statics method {name!r} is valid but was never registered")
    return _REGISTRY[name]


def registered() -> tuple[str, ...]:
    """Names with a registered function, in registration order."""
    return tuple(_REGISTRY)
