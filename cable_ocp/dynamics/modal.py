"""``modes(scene, count, lengths) -> ModesResult | DeploymentChart``: natural frequencies
and mode shapes linearised about the static state: the scene's model
(:func:`cable_ocp.dynamics.model.model_for`, on ``[simulation] model``) runs its
:meth:`~cable_ocp.dynamics.model.CableModel.modes` for the scene's length. With
``lengths`` the scene is re-solved at each length (overriding ``cable.length``, or the top
segment's length of a multi-segment line) and the frequencies are collected into a
:class:`~cable_ocp.dynamics.result.DeploymentChart`.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.dynamics.model import model_for
from cable_ocp.dynamics.result import DeploymentChart, ModesResult
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt
from cable_ocp.scene.dynamics import DynamicScene, load_dynamic_scene

__all__ = ["at_length", "modes"]

def at_length(scene: DynamicScene, length: float) -> DynamicScene:
    """The scene with the unstretched length set to ``length`` (m); a multi-segment line
    changes its top segment (where pay-out happens).

    Parameters
    ----------
    scene : DynamicScene
        The scene.
    length : float
        The unstretched length of the whole line, m.

    Raises
    ------
    CableOCPError
        When the length is out of the scene's bounds or not longer than the segments below
        the top one.
    """
    st = scene.statics
    if st.segments:
        top = len(st.segments) - 1
        rest = sum(c.length for c in st.segments[:-1])  # type: ignore[misc]
        if length <= rest:
            raise CableOCPError(f"--lengths: {length} m is not longer than the segments below "
                                f"the top one ({rest} m); pay-out changes the top segment only")
        return scene.with_overrides({f"cable.segments.{top}.length": length - rest})
    return scene.with_overrides({"cable.length": length})


def modes(scene: DynamicScene | str | Path, count: int | None = None,
          lengths: Sequence[float] | np.ndarray | None = None,
          overrides: dict[str, Any] | None = None) -> ModesResult | DeploymentChart:
    """Natural frequencies and mode shapes about the static state.

    Parameters
    ----------
    scene : DynamicScene or path
        A validated scene or a TOML dynamic problem file; ``[simulation] model`` picks
        the model and ``segments`` its discretisation.
    count : int, optional
        Number of modes (default ``[modes] count``).
    lengths : sequence of float, optional
        Unstretched lengths, m: return a :class:`DeploymentChart` of the frequencies
        against length, with ``[modes] wave_band`` as the band.
    overrides : dict, optional
        Dotted-key overrides applied before validation.

    Returns
    -------
    ModesResult or DeploymentChart
        A failed static state comes back as a status, never raised.

    Raises
    ------
    CableOCPError
        An invalid scene, count or length (named).
    """
    if not isinstance(scene, DynamicScene):
        scene = load_dynamic_scene(scene, overrides)
    elif overrides:
        scene = scene.with_overrides(overrides)
    if count is None:
        count = scene.modes.count
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
        raise CableOCPError(f"--count = {count!r}: expected a positive integer")
    def fn(sc: DynamicScene, count: int) -> ModesResult:
        return model_for(sc).modes(count)

    if lengths is None:
        return fn(scene, int(count))
    lengths = np.asarray(lengths, dtype=float).ravel()
    if lengths.size == 0 or not np.all(np.isfinite(lengths)) or np.any(lengths <= 0.0):
        raise CableOCPError(f"--lengths: expected positive finite lengths (m), got "
                            f"{lengths.tolist()}")
    freqs = np.full((lengths.size, int(count)), np.nan)
    failed = []
    done = lengths.size
    for i, length in enumerate(lengths):
        try:
            res = fn(at_length(scene, float(length)), int(count))
            interrupt.check()  # a Ctrl-C that a native solve swallowed
        except KeyboardInterrupt:  # the lengths finished so far are the chart
            done = i
            break
        if res.status != "solved":
            failed.append((float(length), res.message))
            continue
        n = min(int(count), res.frequencies.size)
        freqs[i, :n] = res.frequencies[:n]
    if done < lengths.size:
        msg = f"interrupted after {done} of {lengths.size} lengths"
        lengths, freqs, status = lengths[:done], freqs[:done], "interrupted"
    else:
        status = "solved" if not failed else "failed"
        msg = (f"{lengths.size} lengths" if not failed else
               f"{len(failed)} of {lengths.size} lengths failed (first at {failed[0][0]} m: "
               f"{failed[0][1]})")
    return DeploymentChart(lengths=lengths, frequencies=freqs, wave_band=scene.modes.wave_band,
                           model=scene.simulation.model, status=status, message=msg,
                           diagnostics={"failed_lengths": [f[0] for f in failed]})
