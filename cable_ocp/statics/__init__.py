"""Statics of one line: the formulation, its transcriptions, the solver built once and the
drivers; the entry points are :func:`cable_ocp.solve` and :func:`cable_ocp.sweep`, the
result :class:`~cable_ocp.statics.solution.StaticsSolution`.

Modules
-------
formulation     the static cable equations of a scene (CasADi; no discretisation)
collocation     direct collocation on sigma = s/L; mesh, kink_mesh and kinks its mesh
shooting        multiple shooting with a CasADi integrator
line_solver     build once, solve many: the solver of one discretised line
newton, ipopt   Newton's method on the collocated system, and IPOPT as its fallback
solver          the drivers: solve, sweep, session; predictor their continuation
solution        the result type; line_solution builds it from a discretised line
error_estimate  the a-posteriori error estimate; checks the method-free checks
stiffness       end stiffness from the sensitivities
catenary        the elastic catenary with point loads in closed form; initial_guess
catenary_line   the uniform line in still water with seabed contact in closed form, with
                its exact 6x6 end Jacobian (a mooring system's line model where exact)
optimize        optimisation through the statics (StaticsNLP)
footprint_nlp   the footprint of a tethered unit (:func:`cable_ocp.footprint`)
registry        the methods by name (``[solver] method``); cache the function cache
"""
