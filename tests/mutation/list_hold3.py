"""Mutations of the hold's defaults (cable_ocp/schedule/planning.py: verified_schedule models
the forward check's hold, solve_schedule none, ``deployment.hold`` either; the key's parse in
cable_ocp/scene/deployment.py), hold3."""

_H = "tests/schedule/test_hold.py::test_"
PLAN = "cable_ocp/schedule/planning.py"

MUTATIONS = [
    dict(name="hold-verified-default-none", area="schedule", file=PLAN,
         old="_hold(scene, problem, hold, CHECK_HOLD), start_speeds)",
         new="_hold(scene, problem, hold, 0.0), start_speeds)",
         tests=(_H + "the_hold_defaults_to_the_checks_in_verified_schedule_and_to_none_alone",),
         description="schedule hold: verified_schedule's OCP ends at the arrival by default "
                     "(the check's 20 s hold never bounded)"),
    dict(name="hold-key-ignored", area="schedule", file=PLAN,
         old="    return default if pb is None or pb.hold is None else float(pb.hold)",
         new="    return default",
         tests=(_H + "the_hold_defaults_to_the_checks_in_verified_schedule_and_to_none_alone",),
         description="schedule hold: deployment.hold read but not used"),
    dict(name="hold-argument-ignored", area="schedule", file=PLAN,
         old="    if hold is not None:\n        return float(hold)\n",
         new="",
         tests=(_H + "the_hold_defaults_to_the_checks_in_verified_schedule_and_to_none_alone",),
         description="schedule hold: an explicit hold (0) loses to deployment.hold"),
    dict(name="hold-key-negative-accepted", area="scene",
         file="cable_ocp/scene/deployment.py",
         old='"deployment.hold", low=0.0, high=MAX_HOLD,',
         new='"deployment.hold", high=MAX_HOLD,',
         tests=(_H + "a_bad_deployment_hold_names_the_key_and_the_valid_values",),
         description="deployment.hold: a negative hold accepted"),
]
