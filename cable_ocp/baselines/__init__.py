"""Other statics methods for the same scenes, each returning a StaticsSolution.

Every method has the signature ``solve(scene, warm_start=None) -> StaticsSolution`` and is
selected with ``[solver] method = NAME`` (or ``--set solver.method=NAME``). Its accuracy knob
is ``solver.intervals`` (RK4 steps, elements, segments or shooting intervals; see each
module), except ``solve_bvp``, which refines its own mesh to ``solver.tolerance``.

Contract, shared with the main solver:

* ``status == "solved"`` only when the method's own convergence test passed *and* the end
  conditions hold to the method's tolerance; otherwise a failure status with a message.
* A scene the method cannot represent (e.g. Wang's z-formulation needs a cable that rises
  monotonically from end_a to end_b) raises :class:`~cable_ocp.errors.CableOCPError` naming
  ``solver.method`` and the reason: that is a user choice, not a numerical failure.
* ``diagnostics["method"]`` is the method name; ``wall_time_s`` excludes file parsing;
  ``constraint_violation`` is the largest end-condition mismatch, relative (-).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import TYPE_CHECKING

from cable_ocp.errors import CableOCPError

if TYPE_CHECKING:
    from cable_ocp.scene import Scene

# name -> "module:function"; imported on first use
METHODS: dict[str, str] = {
    "collocation": "cable_ocp.statics.solver:solve_collocation",
    "multiple_shooting": "cable_ocp.statics.shooting:solve",
    "solve_bvp": "cable_ocp.baselines.solve_bvp:solve",
    "wang_shooting_optimization": "cable_ocp.baselines.wang:solve",
    "huang_semianalytic": "cable_ocp.baselines.huang:solve",
    "chucheepsakul_fem": "cable_ocp.baselines.chucheepsakul:solve",
}


def unsupported(method: str, reason: str) -> CableOCPError:
    """The error a method raises for a scene it cannot represent (names solver.method)."""
    return CableOCPError(f"solver.method = {method!r} cannot represent this scene: {reason}")


def rising_fixed_ends(scene: Scene, method: str, why: str) -> tuple[float, float]:
    """Heights (m) of end_a and end_b for the z-parametrised methods (000, 001), which
    need both ends fixed and end_b above end_a; ``why`` cites the method's equations."""
    ea, eb = scene.end_a, scene.end_b
    if not all(ea.fixed_mask) or not all(eb.fixed_mask):
        raise unsupported(method, f"both end_a and end_b need a fully fixed position ({why})")
    za, zb = float(ea.position[2]), float(eb.position[2])  # type: ignore[arg-type]
    if not zb > za:
        raise unsupported(method, f"end_b (z = {zb} m) must lie above end_a (z = {za} m): z "
                                  "is the independent variable and the cable must rise "
                                  "monotonically from end_a to end_b")
    return za, zb


def get_method(name: str) -> Callable:
    """Return the solve function registered under ``name``."""
    if name not in METHODS:
        raise CableOCPError(f"solver.method = {name!r}: valid are {', '.join(METHODS)}")
    module, func = METHODS[name].split(":")
    try:
        return getattr(importlib.import_module(module), func)
    except (ImportError, AttributeError) as exc:  # pragma: no cover - a broken install
        raise CableOCPError(f"solver.method = {name!r} is not available: {exc}") from None
