"""Mutations of the frequency-response curves (cable_ocp/dynamics/response.py,
cable_ocp/batch/response.py): the linear transfer function and the periodicity test."""

TESTS = ("tests/dynamics/test_response.py",)

MUTATIONS = [
    dict(name="response_no_base_inertia", area="dynamics",
         file="cable_ocp/dynamics/response.py",
         old="y = np.linalg.solve(dyn, (w * w) * (mmat @ e_vec))",
         new="y = np.linalg.solve(dyn, mmat @ e_vec)", tests=TESTS,
         description="linear response: the base-motion forcing w^2 M e D without its w^2"),
    dict(name="response_damping_per_length", area="dynamics",
         file="cable_ocp/dynamics/response.py",
         old="tt = np.outer(tang[e][axes], tang[e][axes]) * cc[e] / l0[e]",
         new="tt = np.outer(tang[e][axes], tang[e][axes]) * cc[e] * l0[e]", tests=TESTS,
         description="linear response: the internal damping c / l of an element as c l"),
    dict(name="response_top_is_unit_element", area="dynamics",
         file="cable_ocp/dynamics/response.py",
         old='e = n_el - 1 if name == "top_tension" else 0',
         new="e = 0", tests=TESTS,
         description="linear response: the top tension taken from the unit's element"),
    dict(name="response_period_against_itself", area="dynamics",
         file="cable_ocp/dynamics/response.py",
         old="prev = _window(t, t_end - period, 1.0, period)",
         new="prev = _window(t, t_end, 1.0, period)", tests=TESTS,
         description="periodicity test: the last period compared with itself (always "
                     "periodic)"),
]
