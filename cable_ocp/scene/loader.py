"""One loader for every problem file: :func:`load` reads a file, tells its kind (statics,
dynamics, heave: :func:`cable_ocp.scene.files.scene_kind`) and returns its validated scene.

The kind-specific loaders (:func:`cable_ocp.scene.statics.load_scene`,
:func:`cable_ocp.scene.dynamics.load_dynamic_scene`, :func:`cable_ocp.scene.heave.load_scene`)
refuse a file of another kind and name the right command; this one takes any.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from cable_ocp.scene import dynamics, heave, statics, system  # the modules, not the package
from cable_ocp.scene.files import apply_overrides, read_problem, scene_kind

__all__ = ["KINDS", "load"]

#: the scene kinds :func:`load` returns, and their types
KINDS = {"statics": statics.Scene, "dynamics": dynamics.DynamicScene,
         "heave": heave.HeaveScene, "system": system.SystemScene}


def load(path: str | Path, overrides: dict[str, Any] | None = None
         ) -> statics.Scene | dynamics.DynamicScene | heave.HeaveScene | system.SystemScene:
    """Read any problem file (UTF-8 TOML, SI units) and return its validated scene.

    Parameters
    ----------
    path : str or Path
        The problem file; a heave file's ``[unit] cable_scene`` is resolved relative to it.
    overrides : dict, optional
        Dotted keys applied before validation, as ``--set`` does, e.g.
        ``{"layout.psi0_deg": 45}`` or ``{"simulation.segments": 40}``.

    Returns
    -------
    Scene, DynamicScene, HeaveScene or SystemScene
        By the file's tables (a MoorDyn file: a system;
        :func:`cable_ocp.scene.files.scene_kind`); its kind is ``type(scene)`` (see :data:`KINDS`).

    Raises
    ------
    CableOCPError
        When the file cannot be read or does not validate (the key is named).
    """
    if system.is_moordyn_path(path):
        return system.load_system(path, overrides)
    data = read_problem(path)
    kind = scene_kind(data)
    if kind == "system":
        return system.load_system(path, overrides)
    if overrides:
        data = apply_overrides(data, overrides)
    if kind == "heave":
        return heave.scene_from_dict(data, Path(path).parent)
    if kind == "dynamics":
        return dynamics.dynamic_scene_from_dict(data)
    return statics.scene_from_dict(data)
