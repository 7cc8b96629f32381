"""Other statics methods for the same scenes, each returning a StaticsSolution.

Every method has the signature ``solve(scene, warm_start=None) -> StaticsSolution``, registers
itself in :mod:`cable_ocp.statics.registry` when its module is imported, and is selected with
``[solver] method = NAME`` (or ``--set solver.method=NAME``). Its resolution is
``solver.intervals`` (RK4 steps, elements or segments; see each module), except
``solve_bvp``, whose resolution is its tolerance (``solver.tolerance``; it places its own
mesh).

Contract, shared with the main solver (docs/baselines.md):

* ``status == "solved"`` only when the method's own convergence test passed, the end
  conditions hold to the method's tolerance, *and* its error estimate is <=
  ``solver.accuracy`` (relative: the larger of the end-force error over the largest
  tension and the position error over the length). The estimate is honest (true error
  within 3x on the benchmark scenes, tests/test_baseline_accuracy.py). Above the accuracy
  the resolution is refined (``solver.refine``) up to the method's limit
  (``solver.max_intervals``, or a smaller one stated by the method), and a result still
  above it is ``"inaccurate"``, with the estimate, the accuracy and the limit in the
  message (:func:`cable_ocp.baselines.common.refine_to_accuracy`). With
  ``solver.error_estimate = false`` there is no estimate and no refinement.
* Other failures have a failure status with a message.
* A scene the method cannot represent (e.g. Wang's z-formulation needs a cable that rises
  monotonically from end_a to end_b) raises :class:`~cable_ocp.errors.CableOCPError` naming
  ``solver.method`` and the reason: that is a user choice, not a numerical failure.
* ``diagnostics["method"]`` is the method name; ``wall_time_s`` excludes file parsing;
  ``constraint_violation`` is the largest end-condition mismatch, relative (-).

Modules
-------
chucheepsakul  Chucheepsakul & Subwonglee (1991): variational finite elements in z
huang          Huang's catenary segments with the drag iterated (1992, ch. 2)
wang           Wang, Cheong & Chucheepsakul (1993): shooting-optimization in z
scipy_bvp      the same equations through :func:`scipy.integrate.solve_bvp`
common         what they share: the refinement to an accuracy, the error estimate

:func:`solve_bvp` (``cable_ocp.baselines.solve_bvp``) is the scipy method's function.
"""

from cable_ocp.baselines import chucheepsakul, huang, scipy_bvp, wang  # noqa: F401  (register)
from cable_ocp.baselines.scipy_bvp import solve_bvp

__all__ = ["solve_bvp"]
