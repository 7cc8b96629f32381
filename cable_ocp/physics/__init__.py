"""Physics of a cable in water: each law once, on numbers (floats, arrays, CasADi).

Nothing here knows about scenes, discretisation or solvers (layer order: numerics <
physics < scene). The homes (docs/laws.md lists them with their equations and sources):

* :mod:`~cable_ocp.physics.drag`: line drag (both laws) in its CasADi, numpy, column,
  local-basis and kernel (value + Jacobian) forms; point-body drag (vector and per axis);
* :mod:`~cable_ocp.physics.current`: the current profile (CasADi and numpy) and its kinks;
* :mod:`~cable_ocp.physics.elasticity`: axial tension (EA, damping, no compression);
* :mod:`~cable_ocp.physics.viscoelastic`: the standard linear solid (a spring-dashpot rope
  law with an internal strain per element) and its midpoint step;
* :mod:`~cable_ocp.physics.bending`: bending stiffness of a discretised line (the hinge law
  between adjacent elements, EI and the turning angle);
* :mod:`~cable_ocp.physics.added_mass`: added mass of a line element and a body, weight in
  water and buoyancy;
* :mod:`~cable_ocp.physics.seabed`: the seabed plane and the grounded line;
* :mod:`~cable_ocp.physics.line_types`: standard mooring line types (chain, wire, fibre
  ropes) from a nominal diameter, MoorPy's scaling laws;
* :mod:`~cable_ocp.physics.smooth`: the smooth modulus and its bound;
* :mod:`~cable_ocp.physics.hydrostatics`: a rigid body's weight, buoyancy, waterplane
  restoring and their exact derivatives;
* :mod:`~cable_ocp.physics.gas_spring`: the polytropic gas spring of a passive heave
  compensator (force, stiffness, damping);
* :mod:`~cable_ocp.physics.winch_drive`: the winch drum's torque and power.
"""

from cable_ocp.physics.current import current_velocity, profile_velocity, profile_velocity_np
from cable_ocp.physics.drag import DRAG_LAWS, drag_per_length, drag_per_length_np
from cable_ocp.physics.smooth import smooth_abs, smooth_abs_error_bound

__all__ = [
    "DRAG_LAWS",
    "current_velocity",
    "drag_per_length",
    "drag_per_length_np",
    "profile_velocity",
    "profile_velocity_np",
    "smooth_abs",
    "smooth_abs_error_bound",
]
