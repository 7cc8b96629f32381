"""Mutations of the bending stiffness in the dynamics (issue 24 item 6): the hinge law
(cable_ocp/physics/bending.py) and its placement on the models' nodes
(cable_ocp/dynamics/bending_terms.py)."""

_T = "tests/dynamics/test_bending.py::test_"

MUTATIONS = [
    dict(name="bending-hinge-half-force", area="physics", file="cable_ocp/physics/bending.py",
         old="b = _spread(2.0 * _row(ei, jump)", new="b = _spread(1.0 * _row(ei, jump)",
         tests=(_T + "taut_string_with_bending_stiffness_dispersion",),
         description="bending: the hinge force is half the gradient of its energy (EI halved "
                     "in the dynamics)"),
    dict(name="bending-clamp-one-sided", area="physics", file="cable_ocp/physics/bending.py",
         old="return -2.0 * ei / h**3 * _normal_part(d, t_c)",
         new="return -1.0 * ei / h**3 * _normal_part(d, t_c)",
         tests=(_T + "cantilever_frequencies", _T + "energy_conserved_with_bending_in_air"),
         description="bending: the clamp hinge of half an element taken as a one-sided "
                     "(first-order) hinge"),
    dict(name="bending-hinge-stiffness-mean", area="dynamics",
         file="cable_ocp/dynamics/bending_terms.py",
         old="return np.where(s > 0.0, 2.0 * a * b / np.where(s > 0.0, s, 1.0), 0.0)",
         new="return 0.5 * s",
         tests=(_T + "a_flexible_segment_meets_a_stiff_one_at_a_pin",),
         description="bending: a hinge between a flexible and a stiff element takes the mean "
                     "EI (no pin where the rope meets the object)"),
    dict(name="bending-lumped-jacobian-dropped", area="dynamics",
         file="cable_ocp/dynamics/lumped_kernel.py",
         old="            diag_b = diag_b + beta * ca.DM(kd)\n",
         new="            diag_b = diag_b + 0.0 * ca.DM(kd)\n",
         tests=(_T + "lumped3d_run_with_bending_equals_planar",),
         description="bending: the lumped3d Newton matrix leaves out the hinges' diagonal "
                     "blocks (Newton converges slowly or not at all)"),
]
