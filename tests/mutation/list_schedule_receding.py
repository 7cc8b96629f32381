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
    dict(name="receding-hold-one-node-late", area="schedule", file=REC,
         old="keep = int(at_rest[0]) + 1 if at_rest.size else n",
         new="keep = int(at_rest[0]) + 2 if at_rest.size else n",
         tests=(_T + "receding_records_are_the_plants_and_the_hold_ends_at_the_first_rest",),
         description="the hold's chunk kept one node past the first at rest: the end is "
                     "no longer the first node at rest"),
    dict(name="receding-chunk-records-shifted", area="schedule", file=REC,
         old="record(t1, vs[1:keep + 1], outs[:, :keep])",
         new="record(t1, vs[:keep], outs[:, :keep])",
         tests=(_T + "receding_records_are_the_plants_and_the_hold_ends_at_the_first_rest",
                _T + "receding_horizon_reaches_the_target_within_a_step_of_the_trapezoid"),
         description="an interval's speeds recorded one node early (the plant's own are "
                     "right): the applied schedule is not what the plant saw"),
]
