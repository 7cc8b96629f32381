"""``simulate(scene) -> SimulationResult``: dispatch on ``[simulation] model``.

Each model registers its simulator in :data:`SIMULATORS` as ``"module:function"`` (imported
on first use, so a model being built elsewhere does not break the others). A simulator is
called as ``fn(scene, progress=progress)`` and returns a
:class:`~cable_ocp.dynamics.result.SimulationResult`.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

from cable_ocp.dynamics.result import SimulationResult
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import DynamicScene, load_dynamic_scene

__all__ = ["SIMULATORS", "Progress", "simulate"]

#: progress(done, total): called a bounded number of times (about once per chunk of steps)
Progress = Callable[[int, int], None]

#: model name -> "module:function" of its simulator
SIMULATORS: dict[str, str] = {
    "axial": "cable_ocp.dynamics.axial:simulate_axial",
    "axial:thesis": "cable_ocp.dynamics.axial_thesis:simulate_thesis",
    "planar": "cable_ocp.dynamics.planar:simulate_planar",
    "lumped3d": "cable_ocp.dynamics.lumped_scene:simulate_lumped",
}


def _resolve(table: dict[str, str], model: str, what: str) -> Callable[..., Any]:
    target = table.get(model)
    if target is None:
        raise CableOCPError(f'simulation.model = "{model}": {what} for this model is not built '
                            f"yet; valid now: {', '.join(sorted(table))}")
    mod_name, fn_name = target.split(":")
    try:
        mod = importlib.import_module(mod_name)
    except ModuleNotFoundError as exc:
        if exc.name == mod_name:
            raise CableOCPError(f'simulation.model = "{model}": {what} for this model is not '
                                "built yet") from None
        raise
    return getattr(mod, fn_name)


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
        An invalid scene (the key is named), or a model that is not built yet.
    """
    if not isinstance(scene, DynamicScene):
        scene = load_dynamic_scene(scene, overrides)
    elif overrides:
        scene = scene.with_overrides(overrides)
    model = scene.simulation.model
    if scene.simulation.scheme == "thesis" and f"{model}:thesis" in SIMULATORS:
        model = f"{model}:thesis"  # the thesis' own scheme, a separate implementation
    fn = _resolve(SIMULATORS, model, "time-domain simulation")
    return fn(scene, progress=progress)
