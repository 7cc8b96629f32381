"""Optimal pay-out and haul-in schedules (docs/deployment.md): the deployment and recovery
of a subsea unit posed as an optimal-control problem on the axial or planar varying-length
line, the vessel's motion given.

Modules
-------
ocp        the OCP: implicit multiple shooting on the line model's own midpoint step
planning   solve_schedule: the static check, the warm start, the OCP (the Python API)
sea        the vessel's heave: the scene's own motion or seeded realisations of a sea
forward    a schedule re-simulated on the forward simulator at a finer step, the limits
           checked; the fastest constant speed by bisection
robust     schedules tallied on unseen seas (slack, over/under the tension limits), the
           same-duration trapezoid, the nominal against the robust schedule
receding   the receding-horizon form (re-planned from the measured state with a preview
           of the heave) and its comparison with the open-loop schedule
"""
