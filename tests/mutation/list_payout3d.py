"""Mutations for issue 24 item 1 ("pay-out and haul-in in 3D"): the split's balanced strain
step and interpolated velocity, the merge's momentum, and the step's masses at the mean
lengths (cable_ocp/dynamics/lumped_payout.py; see tests/mutation/run.py)."""

_T = "tests/dynamics/test_lumped_payout.py::test_"

MUTATIONS = [
    dict(name="payout-split-keeps-one-strain", area="dynamics",
         file="cable_ocp/dynamics/lumped_payout.py",
         old="eps_low = eps - w_t * (ltop - le) / (2.0 * tangent)",
         new="eps_low = eps - 0.0 * w_t * (ltop - le) / (2.0 * tangent)",
         tests=(_T + "split_bookkeeping", _T + "vertical_payout_equals_axial"),
         description="3D pay-out split: both parts keep the old strain (the new node and the "
                     "one below lose their balance; an axial wave at every split)"),
    dict(name="payout-split-velocity-of-node-below", area="dynamics",
         file="cable_ocp/dynamics/lumped_payout.py",
         old="vn = state.v[-2] + f * (state.v[-1] - state.v[-2])",
         new="vn = state.v[-2]",
         tests=(_T + "split_bookkeeping",),
         description="3D pay-out split: the new node takes the velocity of the node below, "
                     "not the interpolated one (the momentum is not conserved)"),
    dict(name="payout-merge-drops-the-leaving-momentum", area="dynamics",
         file="cable_ocp/dynamics/lumped_payout.py",
         old="v[n - 2] = (m[n - 2] * v[n - 2] + give * v[n - 1]) / (m[n - 2] + give)",
         new="v[n - 2] = v[n - 2]",
         tests=(_T + "merge_bookkeeping",),
         description="3D haul-in merge: the node below keeps its velocity (the leaving node's "
                     "momentum is lost)"),
    dict(name="payout-step-masses-at-start-lengths", area="dynamics",
         file="cable_ocp/dynamics/lumped_payout.py",
         old="terms = self._terms(n, rm, vel, lm)",
         new="terms = self._terms(n, rm, vel, l0)",
         tests=(_T + "energy_balance_with_payout_and_haul_in",),
         description="3D pay-out step: masses and weights at the step's start lengths, not "
                     "the mean ones (the energy balance no longer closes)"),
]
