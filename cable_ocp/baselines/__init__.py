"""Other statics methods for the same scenes, each returning a StaticsSolution.

Every method has the signature ``solve(scene, warm_start=None) -> StaticsSolution``, registers
itself in :mod:`cable_ocp.statics.registry` when its module is imported, and is selected with
``[solver] method = NAME`` (or ``--set solver.method=NAME``). Its accuracy knob
is ``solver.intervals`` (RK4 steps, elements, segments or shooting intervals; see each
module), except ``solve_bvp``, which refines its own mesh to ``solver.tolerance``.

Contract, shared with the main solver:

* ``status == "solved"`` only when the method's own convergence test passed *and* the end
  conditions hold to the method's tolerance; otherwise a failure status with a message.
* A scene the method cannot represent (e.g. Wang's z-formulation needs a cable that rises
  monotonically from end_a to end_b) raises :class:`~cable_ocp.errors.CableOCPError` naming
  ``solver.method`` and the reason: that is a user choice, not a numerical failure.
* ``diagnostics["method"]`` is the method name; ``wall_time_s`` excludes file parsing;
  ``constraint_violation`` is the largest end-condition mismatch, relative (-).
"""

from cable_ocp.baselines import chucheepsakul, huang, solve_bvp, wang

__all__ = ["chucheepsakul", "huang", "solve_bvp", "wang"]
