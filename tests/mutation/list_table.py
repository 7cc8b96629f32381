"""Mutations of the piecewise-linear tables of time (cable_ocp/numerics/table.py): the
one home of the heave series and the pay-out tables' lookups."""

_T = "tests/test_table.py::test_"
LIB = "cable_ocp/numerics/table.py"

MUTATIONS = [
    dict(name="table-segment-ceil", area="numerics", file=LIB,
         old="return ca.fmin(ca.floor(s), float(n - 2))",
         new="return ca.fmin(ca.ceil(s), float(n - 2))",
         tests=(_T + "piecewise_linear_is_numpys_interpolation_and_its_slope",),
         description="tables: the segment right of t (its line extended back), not the one "
                     "holding t"),
    dict(name="table-not-held-after-last-row", area="numerics", file=LIB,
         old="expr = ca.if_else(t < float(ts[-1]), seg, float(vs[-1]))",
         new="expr = seg",
         tests=(_T + "piecewise_linear_is_numpys_interpolation_and_its_slope",),
         description="tables: the last segment extended past the last row, not held"),
    dict(name="table-speed-quadratic-term", area="numerics", file=LIB,
         old="seg = l0 + v0 * tau + (v1 - v0) * tau * tau / (2.0 * w)",
         new="seg = l0 + v0 * tau + (v1 - v0) * tau * tau / w",
         tests=(_T + "speed_table_length_is_the_exact_integral_of_the_speed_with_a_jump",),
         description="tables: the speed's integral with twice its quadratic term"),
    dict(name="table-speed-jump-kept", area="numerics", file=LIB,
         old="keep = np.flatnonzero(width > 0.0)",
         new="keep = np.flatnonzero(width >= 0.0)",
         tests=(_T + "speed_table_length_is_the_exact_integral_of_the_speed_with_a_jump",),
         description="tables: a jump's zero-width segment kept (a division by zero width)"),
]
