"""``simulate(scene) -> SimulationResult``: the scene's model
(:func:`cable_ocp.dynamics.model.model_for`, on ``[simulation] model``) runs its
:meth:`~cable_ocp.dynamics.model.CableModel.simulate`.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from cable_ocp.dynamics.model import model_for
from cable_ocp.dynamics.result import SimulationResult
from cable_ocp.scene.dynamics import DynamicScene, load_dynamic_scene

__all__ = ["Progress", "simulate"]

#: progress(done, total): called a bounded number of times (about once per chunk of steps)
Progress = Callable[[int, int], None]


def simulate(scene: DynamicScene | str | Path, progress: Progress | None = None,
             overrides: dict[str, Any] | None = None) -> SimulationResult:
    """Simulate a dynamic scene in the time domain.

    Parameters
    ----------
    scene : DynamicScene or path
        A validated scene, or a TOML dynamic problem file.
    progress : callable, optional
        ``progress(done, total)`` with integration steps done and in total (ints), called
        a bounded number of times (after each chunk of steps, at most about 200 times).
        The library never prints.
    overrides : dict, optional
        Dotted-key overrides applied before validation, e.g.
        ``{"simulation.segments": 40}``.

    Returns
    -------
    SimulationResult
        Its ``status`` says whether the run is usable ("solved"), hit slack ("slack"), or
        failed ("failed"); never raises on a numerical failure.

    Raises
    ------
    CableOCPError
        An invalid scene (the key is named).
    """
    if not isinstance(scene, DynamicScene):
        scene = load_dynamic_scene(scene, overrides)
    elif overrides:
        scene = scene.with_overrides(overrides)
    return model_for(scene).simulate(progress)
