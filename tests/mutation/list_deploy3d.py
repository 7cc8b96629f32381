"""Mutations for issue 24 item 1 ("the heave plant can then deploy in 3D"): the top's rise
in the pay-out line's step, the events of the deployment plant and its static reference
(cable_ocp/dynamics/lumped_payout.py, cable_ocp/heave/lumped_deploy.py; see
tests/mutation/run.py)."""

_T = "tests/heave/test_deployment_lumped3d.py::test_"

MUTATIONS = [
    dict(name="deploy3d-top-rise-lags-a-step", area="heave",
         file="cable_ocp/dynamics/lumped_payout.py",
         old="r0, r1 = self._nodes(n, q0, t0, z0), self._nodes(n, q1, t0 + dt, z1)",
         new="r0, r1 = self._nodes(n, q0, t0, z0), self._nodes(n, q1, t0 + dt, z0)",
         tests=(_T + "vertical_deployment_equals_axial_plant",),
         description="3D deployment plant: the top ends each step at its height at the "
                     "step's start (the boom-tip heave lags one sub-step)"),
    dict(name="deploy3d-no-node-enters", area="heave",
         file="cable_ocp/heave/lumped_deploy.py",
         old="if ltop > line.split_at:",
         new="if ltop > 10.0 * line.split_at:",
         tests=(_T + "vertical_deployment_equals_axial_plant",),
         description="3D deployment plant: no node enters at the winch (the top segment "
                     "grows without a split)"),
    dict(name="deploy3d-static-reference-of-the-start", area="heave",
         file="cable_ocp/heave/lumped_deploy.py",
         old="z[k] = float(x[2])",
         new="z[k] = z0",
         tests=(_T + "vertical_deployment_equals_axial_plant",),
         description="3D deployment plant: the heave measured from the static depth at the "
                     "start length at every length"),
]
