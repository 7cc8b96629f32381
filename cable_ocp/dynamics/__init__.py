"""Cable dynamics (Huang (1992) ch. 3-5): dynamic scenes, time-domain simulation and
modal analysis.

Public entry points::

    load_dynamic_scene(path, overrides)  -> DynamicScene
    simulate(scene, progress=None)       -> SimulationResult
    modes(scene, count, lengths=None)    -> ModesResult | DeploymentChart

``cable_ocp.dynamics.simulate`` and ``cable_ocp.dynamics.modes`` are these functions; their
modules are :mod:`~cable_ocp.dynamics.simulation` and :mod:`~cable_ocp.dynamics.modal`.

Modules
-------
model             the model interface that simulate and modes dispatch on; checks, the
                  checks that a scene fits a model
result            the result types (SimulationResult, ModesResult, DeploymentChart)
simulation        simulate: the time integration of any model
modal             modes: the linearisation about the static state, the deployment chart
response          the frequency response to a harmonic top motion: the outputs, the harmonic
                  fit of a time run and the linear transfer function of the modes
static            the static start of a dynamic scene
bending_terms     bending stiffness (EI) in the planar and lumped lines: the hinges of
                  cable_ocp.physics.bending on the nodes, the clamped top
planar_line       the planar line's properties per element (segments on the grid)
axial, planar     the axial and planar lines; vertical_line their coefficients, stepping
                  their chunked time loop, driven their steps with the top as an input,
                  axial_thesis Huang's own axial scheme
snap              the snap loads that end a slack spell (SimulationResult.snap)
lumped            the 3D lumped-mass line: lumped_params, lumped_equations, lumped_kernel,
                  lumped_run, lumped_scene, lumped_driven, lumped_thesis (Huang's (5.21));
                  lumped_payout its pay-out and haul-in (nodes enter and leave at the
                  winch), lumped_payout_run a lumped3d scene with a pay-out run
"""

from cable_ocp.dynamics.modal import modes
from cable_ocp.dynamics.result import DeploymentChart, ModesResult, SimulationResult
from cable_ocp.dynamics.simulation import simulate
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
