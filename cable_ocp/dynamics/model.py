"""One interface for the dynamic cable models: what ``simulate``, ``modes`` and the heave
plants ask of a model.

A model is built from a :class:`~cable_ocp.scene.dynamics.DynamicScene` and implements
:class:`CableModel`:

* its **state layout**: ``n`` elements (or segments), ``state_size()`` numbers in the state
  vector, ``free`` the nodes the state holds (end_a to end_b);
* its **static state**: ``static_state()``, the rest state of the scene at t = 0 (the
  ``simulation.start``), with how it was found;
* **one step with the top motion and the top length as inputs**: ``driven_step()``, a
  :class:`DrivenStep`: the implicit step of the model's own scheme over ``(0, dt)`` where the
  unstretched length goes linearly from ``L_a`` to ``L_b`` and the top's height from
  ``z_a`` to ``z_b`` (its x and y stay at the static top): the step the heave plants take,
  the winch paying cable through the top;
* its **outputs**: the step's outputs at its end (:attr:`DrivenStep.outputs`), and a
  :class:`~cable_ocp.dynamics.result.SimulationResult` from ``simulate(progress)``;
* **linearisation and modes**: ``linearize()`` (stiffness and mass about the static state)
  and ``modes(count)`` (a :class:`~cable_ocp.dynamics.result.ModesResult`).

:func:`model_for` builds the scene's model (``[simulation] model``); ``simulate`` and
``modes`` dispatch on it.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np

from cable_ocp.dynamics.result import ModesResult, SimulationResult
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import DynamicScene

__all__ = ["MODELS", "CableModel", "DrivenStep", "model_for"]


@dataclass(frozen=True)
class DrivenStep:
    """One implicit step of a model with the top motion and the top length as inputs, as
    CasADi SX expressions.

    Over the step ``(0, dt)`` the unstretched length goes linearly from ``L_a`` to ``L_b``
    and the top's height from ``z_a`` to ``z_b`` (m); its x and y stay at the static top.

    Attributes
    ----------
    unknown : casadi.SX
        The step's unknowns ``y`` (what Newton solves for).
    state : casadi.SX
        The state at the start of the step (the model's layout).
    inputs : casadi.SX (4,)
        ``[L_a, L_b, z_a, z_b]``, m.
    dt : casadi.SX or float
        The step, s (a symbol where one built step serves every step size).
    residual : casadi.SX
        The step's equations in ``y`` (scaled, dimensionless): zero at the solution.
    next_state : casadi.SX
        The state at the end of the step, from ``y``, the state, the inputs and ``dt``.
    guess : casadi.SX
        The model's predictor of ``y`` (from the state, the inputs and ``dt``).
    outputs : casadi.SX (5,)
        At the end of the step: the unit's height (m) and vertical velocity (m/s), the
        tension at the unit and at the top (N), and the smallest element tension (N; the
        Hooke tension where the model's law cannot go negative, so that ``<= 0`` is slack).
    start : ndarray
        The static state at rest under the static top, in this step's layout (relative to
        the top: a displaced top carries the line with it).
    residual_scale : casadi.DM or None
        Where the residual is not scaled itself: the row scale of its convergence measure
        ``max |residual * residual_scale|`` (-).
    tensions : casadi.SX or None
        Every element's tension at the end of the step (N, from the unit to the top; the
        law's own tension, ``<= 0`` slack): the tension along the whole line of the
        deployment schedule's limits (:mod:`cable_ocp.schedule.ocp`).
    """

    unknown: Any
    state: Any
    inputs: Any
    dt: Any
    residual: Any
    next_state: Any
    guess: Any
    outputs: Any
    start: np.ndarray
    residual_scale: Any = None
    tensions: Any = None


@runtime_checkable
class CableModel(Protocol):
    """The interface of a dynamic cable model (module docstring)."""

    #: the scene's ``simulation.model`` value of this model
    name: str
    scene: DynamicScene
    #: number of elements (or segments) from end_a to end_b
    n: int

    def state_size(self) -> int:
        """Length of the state vector."""
        ...

    def static_state(self) -> tuple[np.ndarray | None, dict[str, Any]]:
        """The state at rest at t = 0 (``simulation.start``; None where it failed) and how it
        was found (``message`` and the model's details)."""
        ...

    def driven_step(self, dt: float | None = None) -> DrivenStep:
        """One step with the top motion and the top length as inputs (``dt`` s, or None: a
        symbol)."""
        ...

    def linearize(self) -> tuple[np.ndarray, np.ndarray]:
        """Stiffness (N/m) and mass (kg) matrices of the free coordinates about the static
        state (symmetric, dense)."""
        ...

    def modes(self, count: int) -> ModesResult:
        """Natural frequencies and mode shapes about the static state."""
        ...

    def simulate(self, progress: Callable[[int, int], None] | None = None
                 ) -> SimulationResult:
        """The time history of the scene."""
        ...


#: ``simulation.model`` -> "module:class" of the model (imported on first use)
MODELS: dict[str, str] = {
    "axial": "cable_ocp.dynamics.axial:AxialModel",
    "planar": "cable_ocp.dynamics.planar:PlanarModel",
    "lumped3d": "cable_ocp.dynamics.lumped_scene:LumpedSceneModel",
}


def model_for(scene: DynamicScene, segments: int | None = None) -> CableModel:
    """The scene's model (``[simulation] model``), built (its CasADi functions on first use).

    Parameters
    ----------
    scene : DynamicScene
        A validated dynamic scene.
    segments : int, optional
        Elements or segments (default ``simulation.segments``).

    Raises
    ------
    CableOCPError
        A model name that is not one of :data:`MODELS`, or a scene the model refuses (the
        key is named).
    """
    name = scene.simulation.model
    target = MODELS.get(name)
    if target is None:
        raise CableOCPError(f'simulation.model = "{name}": valid are '
                            f"{', '.join(sorted(MODELS))}")
    mod_name, cls_name = target.split(":")
    cls = getattr(importlib.import_module(mod_name), cls_name)
    return cls(scene, segments)
