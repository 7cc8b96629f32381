"""Physics of a cable in water, as CasADi expressions: drag laws, current, smooth modulus.

Nothing here knows about discretisation or solvers; a new drag law is one function in
:mod:`cable_ocp.physics.drag`.
"""

from cable_ocp.physics.current import current_velocity
from cable_ocp.physics.drag import DRAG_LAWS, drag_per_length
from cable_ocp.physics.smooth import smooth_abs, smooth_abs_error_bound

__all__ = [
    "DRAG_LAWS",
    "current_velocity",
    "drag_per_length",
    "smooth_abs",
    "smooth_abs_error_bound",
]
