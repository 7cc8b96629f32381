"""Mutations of the long run's case (cable_ocp/bench/deployment.py ``long_run``'s
speed and target length), issue 25."""

_T = "tests/test_bench_long.py::test_"
LIB = "cable_ocp/bench/deployment.py"

MUTATIONS = [
    dict(name="bench-long-target-not-set", area="bench", file=LIB,
         old='over["deployment.target_length"] = base.length + sign * dist',
         new='over["deployment.target_length"] = pb.target_length',
         tests=(_T + "long_run_speed_sets_the_target_length",),
         description="bench long: the speed set but the scene's target kept (the warm "
                     "start no longer lasts the duration)"),
    dict(name="bench-long-speed-ignored", area="bench", file=LIB,
         old='    if speed is None:\n        dist = abs(pb.target_length - base.length)',
         new='    if True:\n        dist = abs(pb.target_length - base.length)',
         tests=(_T + "long_run_speed_sets_the_target_length",),
         description="bench long: the given speed ignored (the old 6.3.6-style distance "
                     "and solved speed)"),
]
