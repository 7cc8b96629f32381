"""Mutations of the compensated constant-speed baseline (cable_ocp/schedule/forward.py
``fastest_constant_speed(ahc_gain=...)``, the forward check's compensation limits) and of
the bench's compared gain (cable_ocp/bench/deployment.py ``comparison_gain``), issue 25."""

_T = "tests/schedule/test_schedule_ahc_constant.py::test_"
FWD = "cable_ocp/schedule/forward.py"
BENCH = "cable_ocp/bench/deployment.py"

MUTATIONS = [
    dict(name="s636-constant-speed-gain-dropped", area="schedule", file=FWD,
         old="        sched = trapezoid_schedule(scene.length, dp.target_length, v, dp.accel_max,\n"
             "                                   ahc_gain=ahc_gain)",
         new="        sched = trapezoid_schedule(scene.length, dp.target_length, v, dp.accel_max,\n"
             "                                   ahc_gain=0.0)",
         tests=(_T + "constant_speed_with_gain_is_the_compensated_trapezoid_resimulated",),
         description="forward: the bisection's trapezoids lose the compensation's gain"),
    dict(name="s636-trapezoid-gain-lost", area="schedule", file=FWD,
         old="accel=sched.accel,\n                    ahc_gain=float(ahc_gain))",
         new="accel=sched.accel,\n                    ahc_gain=0.0)",
         tests=(_T + "constant_speed_with_gain_is_the_compensated_trapezoid_resimulated",
                _T + "forward_check_bounds_the_payout_and_the_compensation_apart"),
         description="forward: trapezoid_schedule drops its ahc_gain"),
    dict(name="s636-gain-upper-bound", area="schedule", file=FWD,
         old="if not 0.0 <= gain <= 1.0:", new="if not 0.0 <= gain:",
         tests=(_T + "gain_outside_zero_one_is_refused",),
         description="forward: a gain above 1 accepted"),
    dict(name="s636-speed-max-with-compensation", area="schedule", file=FWD,
         old='("speed_max", dp.speed_max, [np.abs(own)], True),',
         new='("speed_max", dp.speed_max, [np.abs(speed)], True),',
         tests=(_T + "forward_check_bounds_the_payout_and_the_compensation_apart",),
         description="forward: speed_max measured on the winch's table with g dz/dt (not "
                     "the OCP's pay-out speed)"),
    dict(name="s636-stroke-unscaled-by-gain", area="schedule", file=FWD,
         old='[np.abs(g * motion.heave(t))]', new='[np.abs(motion.heave(t))]',
         tests=(_T + "forward_check_bounds_the_payout_and_the_compensation_apart",),
         description="forward: the stroke measured on the heave, not on g times it"),
    dict(name="s636-comparison-gain-ignores-speed", area="bench", file=BENCH,
         old="(dp.ahc_speed, np.max(np.abs(m.heave_rate(t))))",
         new="(None, np.max(np.abs(m.heave_rate(t))))",
         tests=(_T + "comparison_gain_is_the_largest_the_compensator_allows",),
         description="bench: the fallback gain forgets the compensator's speed limit"),
]
