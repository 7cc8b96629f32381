"""``simulate(scene) -> SimulationResult``: the scene's model
(:func:`cable_ocp.dynamics.model.model_for`, on ``[simulation] model``) runs its
:meth:`~cable_ocp.dynamics.model.CableModel.simulate`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

from cable_ocp.dynamics.model import model_for
from cable_ocp.dynamics.result import SimulationResult
from cable_ocp.scene.dynamics import DynamicScene, load_dynamic_scene

__all__ = ["Progress", "excitation", "simulate"]

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
        failed ("failed"); never raises on a numerical failure. A scene with nothing that
        moves the line (:func:`excitation` empty) still runs, with a warning in
        ``warnings`` (the status is unchanged) and ``diagnostics["excitation"]`` empty.

    Raises
    ------
    CableOCPError
        An invalid scene (the key is named).
    """
    if not isinstance(scene, DynamicScene):
        scene = load_dynamic_scene(scene, overrides)
    elif overrides:
        scene = scene.with_overrides(overrides)
    res = model_for(scene).simulate(progress)
    excited = excitation(scene)
    warnings = list(res.warnings)
    if not excited:
        warnings.append(NO_EXCITATION.format(duration=scene.simulation.duration))
    return replace(res, warnings=warnings,
                   diagnostics={**res.diagnostics, "excitation": excited})


#: the warning of a scene in which nothing moves the line
NO_EXCITATION = ("nothing excites the line: no top motion, no pay-out, a static start; the "
                 "{duration:g} s simulated stay at the static state (set [top_motion], "
                 "e.g. heave_amplitude and heave_frequency)")


def excitation(scene: DynamicScene) -> list[str]:
    """What drives the line away from its static state: the names of the scene's active
    excitations, empty when the run can only stay at rest.

    ``"top motion"`` (end_b moves: heave, horizontal, circular, a tow or a series),
    ``"pay-out"`` (the unstretched length changes) and ``"unstrained start"`` (the run
    starts away from equilibrium). A steady current is not one: the static state
    already balances it.

    Parameters
    ----------
    scene : DynamicScene
        The validated scene.
    """
    tm = scene.top_motion
    out = []
    if tm.moves:
        out.append("top motion")
    if tm.varying_length:
        out.append("pay-out")
    if scene.simulation.start != "static":
        out.append("unstrained start")
    return out
