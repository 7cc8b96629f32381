"""Mutations of the long run's bookkeeping (cable_ocp/bench/deployment.py ``long_run``),
issue 25."""

_T = "tests/test_bench_long.py::test_"
LIB = "cable_ocp/bench/deployment.py"

MUTATIONS = [
    dict(name="bench-long-rss-kilobytes", area="bench", file=LIB,
         old='scale = 1 if sys.platform == "darwin" else 1024',
         new='scale = 1 if sys.platform == "darwin" else 1',
         tests=(_T + "peak_memory_is_the_process_peak_in_bytes",),
         description="bench long: the peak memory in kB reported as bytes"),
    dict(name="bench-long-no-expand", area="bench", file=LIB,
         old='LONG_IPOPT: dict[str, Any] = {"expand": True, "ipopt.mumps_pivtol": 1e-4}',
         new='LONG_IPOPT: dict[str, Any] = {"ipopt.mumps_pivtol": 1e-4}',
         tests=(_T + "long_run_defaults_to_the_measured_options",),
         description="bench long: the long run on the unexpanded MX graph (twice the "
                     "Hessian's structural nonzeros)"),
    dict(name="bench-long-memory-unit", area="bench", file="cable_ocp/cli/bench_deploy.py",
         old="row.get('peak_rss_bytes', math.nan) / 1e9:.2f} GB",
         new="row.get('peak_rss_bytes', math.nan) / 1e6:.2f} GB",
         tests=(_T + "long_line_reports_memory_and_options",),
         description="bench long: the peak memory printed in MB labelled GB"),
    dict(name="bench-long-scan-past-max-steps", area="schedule",
         file="cable_ocp/schedule/planning.py",
         old="time_step)[3].size - 1 > MAX_STEPS:",
         new="time_step)[3].size - 1 > 10 * MAX_STEPS:",
         tests=(_T + "warm_start_scan_stops_before_max_steps",),
         description="warm start: the constant-speed scan rolls out speeds whose trapezoid "
                     "exceeds MAX_STEPS (10^5-10^6-step rollouts, out of memory)"),
]
