"""Mutations of the face of the pay-out schedule: ``cable-ocp deploy``
(cable_ocp/cli/deploy.py) and its figure's resonant lengths (cable_ocp/plots/deploy.py),
issue 25."""

_T = "tests/test_deploy_cli.py::test_"
CLI = "cable_ocp/cli/deploy.py"
FIG = "cable_ocp/plots/deploy.py"

MUTATIONS = [
    dict(name="deploy-csv-accel-shifted", area="schedule", file=CLI,
         old="acc = np.append(sol.accel, np.nan)", new="acc = np.insert(sol.accel, 0, np.nan)",
         tests=(_T + "deploy_csv_schedule_keeps_its_kinematics_and_limits",),
         description="deploy CSV: the step's acceleration one row late (v_{k+1} - v_k no "
                     "longer a_k dt)"),
    dict(name="deploy-csv-line-min-is-mean", area="schedule", file=CLI,
         old='"tension_min_line": np.min(tens, axis=1)',
         new='"tension_min_line": np.mean(tens, axis=1)',
         tests=(_T + "deploy_csv_schedule_keeps_its_kinematics_and_limits",),
         description="deploy CSV: the smallest tension along the line taken as the mean "
                     "(at rest not W + w L / 10)"),
    dict(name="deploy-csv-unit-is-top", area="schedule", file=CLI,
         old='"unit_tension": sol.outputs[r, :, 2]', new='"unit_tension": sol.outputs[r, :, 3]',
         tests=(_T + "deploy_csv_schedule_keeps_its_kinematics_and_limits",),
         description="deploy CSV: the unit's tension column carries the top tension (at rest "
                     "W + w L, not W)"),
    dict(name="deploy-saving-over-optimal", area="schedule", file=CLI,
         old="100.0 * (other - optimal) / other", new="100.0 * (other - optimal) / optimal",
         tests=(_T + "deploy_text_reports_status_times_and_binding_limits",),
         description="deploy text: the saving in % relative to the optimal duration, not "
                     "to the constant speed's"),
    dict(name="deploy-infeasible-exit-0", area="schedule", file=CLI,
         old="        return out.EXIT_NOT_SUCCESS\n    out.emit_csv",
         new="        return out.EXIT_OK\n    out.emit_csv",
         tests=(_T + "deploy_infeasible_tension_max_exits_1_and_writes_no_schedule",),
         description="deploy: an infeasible problem exits 0 (reported as a success)"),
    dict(name="deploy-failure-writes-schedule", area="schedule", file=CLI,
         old="    if not res.success:\n        if args.csv or args.plot:",
         new="    if False:\n        if args.csv or args.plot:",
         tests=(_T + "deploy_infeasible_tension_max_exits_1_and_writes_no_schedule",),
         description="deploy: an infeasible result goes on to write a CSV and a figure"),
    dict(name="deploy-interrupted-compare-exit-0", area="schedule", file=CLI,
         old="        except KeyboardInterrupt:  # the schedule is whole: written, then exit 130\n"
             "            stopped = True",
         new="        except KeyboardInterrupt:  # the schedule is whole: written, then exit 130\n"
             "            stopped = False",
         tests=(_T + "deploy_interrupted_comparison_writes_the_schedule_then_130",),
         description="deploy --compare: a Ctrl-C in the bisection is swallowed (exit 0, "
                     "the comparison missing)"),
    dict(name="deploy-resonance-interpolation", area="schedule", file=FIG,
         old="a = d[i] / (d[i] - d[i + 1])", new="a = d[i + 1] / (d[i] - d[i + 1])",
         tests=(_T + "resonant_lengths_meet_the_rod_with_a_tip_mass",),
         description="deploy figure: the resonant length interpolated from the wrong end "
                     "(not L = EA / (w^2 M))"),
    dict(name="output-onto-a-device-accepted", area="faults",
         file="cable_ocp/cli/output.py",
         old="    if p.exists() and not p.is_file():",
         new="    if False:",
         tests=("tests/test_cli.py::test_an_output_onto_a_pipe_is_refused_and_the_pipe_kept",),
         description="an output onto a FIFO or a device is renamed over (the pipe, or for "
                     "root /dev/full, replaced by a regular file)"),
]
