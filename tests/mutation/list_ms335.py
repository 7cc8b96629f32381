"""Mutations of the OCP's multi-start warm start (cable_ocp/schedule/planning.py
``start_speeds``, ``best_start``) that tests/schedule/test_multistart.py must catch,
issue 25."""

_T = "tests/schedule/test_multistart.py::test_"
PLAN = "cable_ocp/schedule/planning.py"

MUTATIONS = [
    dict(name="ms335-best-start-ignores-status", area="schedule", file=PLAN,
         old='        if status == "solved" and math.isfinite(dur) and (',
         new="        if math.isfinite(dur) and (",
         tests=(_T + "best_start_is_the_shortest_solved_else_the_first",
                _T + "the_ocp_lines_start_is_kept_when_the_given_one_fails"),
         description="the selection keeps a failed start's (shorter) iterate"),
    dict(name="ms335-best-start-keeps-the-longest", area="schedule", file=PLAN,
         old="                best < 0 or dur < results[best][1]):",
         new="                best < 0 or dur > results[best][1]):",
         tests=(_T + "best_start_is_the_shortest_solved_else_the_first",),
         description="the selection keeps the longest solved schedule"),
    dict(name="ms335-first-start-always-kept", area="schedule", file=PLAN,
         old="    sol = sols[best]\n", new="    sol = sols[0]\n",
         tests=(_T + "the_given_start_is_kept_when_the_ocp_lines_start_fails",),
         description="the OCP line's start's solve is returned whichever start won"),
    dict(name="ms335-diagnostics-name-the-first", area="schedule", file=PLAN,
         old="    label, speed = starts[best]\n", new="    label, speed = starts[0]\n",
         tests=(_T + "the_given_start_is_kept_when_the_ocp_lines_start_fails",),
         description="the diagnostics name the OCP line's start whichever won"),
    dict(name="ms335-given-starts-dropped", area="schedule", file=PLAN,
         old="[(EXTRA_START, v) for v in extra]", new="[]",
         tests=(_T + "the_given_start_is_kept_when_the_ocp_lines_start_fails",
                _T + "the_ocp_lines_start_is_kept_when_the_given_one_fails"),
         description="start_speeds accepted but never solved from"),
    dict(name="ms335-start-above-speed-max-accepted", area="schedule", file=PLAN,
         old="and v > pb.speed_max * (1.0 + 1e-12)):",
         new="and v > 2.0 * pb.speed_max):",
         tests=(_T + "a_start_speed_outside_0_speed_max_is_refused",),
         description="a start speed above speed_max accepted"),
    dict(name="ms335-bench-compare-without-forward-start", area="schedule",
         file="cable_ocp/bench/deployment.py",
         old='start_speeds=[fc.speed] if (', new='start_speeds=[] if (',
         tests=("tests/test_bench_deploy.py::"
                "test_bench_deploy_compare_keeps_each_finished_row",),
         description="the compare's OCP not started from the forward simulator's constant "
                     "speed"),
]
