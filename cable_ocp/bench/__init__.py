"""Benchmarks beside the peers (``cable-ocp bench ...``): part of the face, not the library.

Modules
-------
accuracy       work precision of every statics method; common its references and errors
estimates      honesty of the baselines' error estimates
robustness     every statics method on every extreme scene
statics_sweep  De Zoysa's psi0 sweep, collocation against solve_bvp
batch          load-case batches on a pool and on dask
dynamics       the 3D lumped-mass dynamics against MoorDyn
heave_mpc      the MPC's solve time per step
moorpy_systems mooring systems in MoorPy: equilibrium, 6x6 stiffness, timings
systems        mooring systems beside MoorPy in one run: pose, tensions, 6x6, times
moorpy_current a current on one line: ours against MoorPy's smeared load and a closed form
deployment     the deployment schedule beside the constant speed and today's deployment; its cost
"""
