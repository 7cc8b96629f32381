"""Mooring systems: many lines, connection points and floating bodies (docs/systems.md).

Modules
-------
model        the state, the lines' solver sessions, the net loads and their exact Jacobian
equilibrium  Newton's method on the free points and bodies
stiffness    a body's 6x6 stiffness (the Schur complement of the free points)
result       the system result (poses, line table, points, stiffness)
checks       the design checks: restoring curve, loads per heading, one line failed
design       design optimisation (lengths, clumps, anchors) with exact gradients through
             the equilibrium
"""

from cable_ocp.mooring.equilibrium import solve_system
from cable_ocp.mooring.model import State, SystemModel
from cable_ocp.mooring.result import SystemResult
from cable_ocp.mooring.stiffness import body_stiffness

__all__ = ["State", "SystemModel", "SystemResult", "body_stiffness", "solve_system"]
