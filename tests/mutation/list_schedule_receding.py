"""Mutations of the receding-horizon deployment (cable_ocp/schedule/receding.py), issue 25,
caught by tests/schedule/test_receding.py."""

_T = "tests/schedule/test_receding.py::test_"
REC = "cable_ocp/schedule/receding.py"

MUTATIONS = [
    dict(name="receding-braking-distance-halved", area="schedule", file=REC,
         old="need = need + vel[-1] ** 2 / (2.0 * pb.accel_max)",
         new="need = need + vel[-1] ** 2 / (4.0 * pb.accel_max)",
         tests=(_T + "receding_horizon_reaches_the_target_within_a_step_of_the_trapezoid",
                _T + "receding_horizon_keeps_the_winch_limits_and_its_grid"),
         description="the terminal braking distance halved: the plan cannot stop in time "
                     "(overshoot, a re-plan fails or the arrival is late)"),
    dict(name="receding-preview-heave-from-zero", area="schedule", file=REC,
         old="hv = motion.heave(tk + np.arange(n_h + 1) * dt)",
         new="hv = motion.heave(np.arange(n_h + 1) * dt)",
         tests=(_T + "receding_horizon_reaches_the_target_within_a_step_of_the_trapezoid",),
         description="the preview always from t = 0 (not from the re-plan's time): "
                     "a still sea cannot tell, so this one is expected to survive"),
]
