"""Mutations of the passive heave compensator and the winch drive (issue 24 item 7)."""

PHC = "tests/heave/test_passive_compensator.py"
DRIVE = "tests/heave/test_winch_drive.py"

MUTATIONS = [
    dict(name="gas-stiffness-without-exponent", area="physics",
         file="cable_ocp/physics/gas_spring.py",
         old="    return (exponent * area**2 * gas_pressure(",
         new="    return (area**2 * gas_pressure(",
         tests=(PHC,),
         description="the gas spring's stiffness loses the polytropic exponent "
                     "(isothermal p0 A^2 / V0 whatever n)"),
    dict(name="phc-lifts-the-line-top", area="heave",
         file="cable_ocp/heave/loop_plants.py",
         old="top = x0 + s[2] - (s[self.nuw] if self.phc else 0.0)",
         new="top = x0 + s[2] + (s[self.nuw] if self.phc else 0.0)",
         tests=(PHC,),
         description="the compensator's compression raises the line's top instead of "
                     "lowering it"),
    dict(name="phc-end-stop-holds-the-wrong-way", area="heave",
         file="cable_ocp/heave/loop_plants.py",
         old="if (d >= self.smax and rate > 0) or (d <= -self.smax and rate < 0):",
         new="if (d >= self.smax and rate < 0) or (d <= -self.smax and rate > 0):",
         tests=(PHC,),
         description="an end stop holds the piston when the force pulls it off the stop "
                     "(it sticks there) instead of when it pushes into it"),
    dict(name="mpc-torque-limit-forgets-the-static-torque", area="heave",
         file="cable_ocp/heave/mpc_drive.py",
         old="add(k, -tz / sc, -tu / sc, -(s.torque_max - R * t0) / sc, cd=-td / sc,",
         new="add(k, -tz / sc, -tu / sc, -s.torque_max / sc, cd=-td / sc,",
         tests=(DRIVE,),
         description="the MPC's upper torque row leaves out the static torque R T0 (the limit "
                     "becomes torque_max + R T0)"),
]
