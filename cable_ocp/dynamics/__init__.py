"""Cable dynamics (Huang (1992) ch. 3-5): dynamic scenes, time-domain simulation and
modal analysis.

Public entry points::

    load_dynamic_scene(path, overrides)  -> DynamicScene
    simulate(scene, progress=None)       -> SimulationResult
    modes(scene, count, lengths=None)    -> ModesResult | DeploymentChart
"""

from cable_ocp.dynamics.modes import modes
from cable_ocp.dynamics.result import DeploymentChart, ModesResult, SimulationResult
from cable_ocp.dynamics.simulate import simulate
from cable_ocp.scene.dynamics import (
    DynamicScene,
    dynamic_scene_from_dict,
    is_dynamic_dict,
    load_dynamic_scene,
)

__all__ = [
    "DeploymentChart",
    "DynamicScene",
    "ModesResult",
    "SimulationResult",
    "dynamic_scene_from_dict",
    "is_dynamic_dict",
    "load_dynamic_scene",
    "modes",
    "simulate",
]
