"""The unit of every numeric dotted key of a problem file (the keys ``--set``, ``--grid``,
``--range`` and ``--random`` take), in the problem file's own SI units: one table, read by
the batch summaries and the axes of the batch figures. The tables of keys in
docs/problem_files.md and docs/dynamics.md give the same units with their meanings.

An index into an array of tables is ignored (``cable.segments.0.length`` is a
``cable.segments.length``); a key not in the table takes the unit of its last part where
that part means one thing in every table (``..._deg`` is in degrees), else none (``""``).
"""

from __future__ import annotations

__all__ = ["KEY_UNITS", "key_label", "key_unit"]

#: dotted key (array indices left out) -> unit; "-" for a dimensionless number
KEY_UNITS: dict[str, str] = {
    # statics scenes (docs/problem_files.md)
    "layout.psi0_deg": "deg",
    "environment.water_depth": "m",
    "environment.water_density": "kg/m^3",
    "environment.gravity": "m/s^2",
    "environment.current.speed": "m/s",
    "environment.current.heading_deg": "deg",
    "environment.seabed.depth_offset": "m",
    "environment.seabed.friction": "-",
    "environment.seabed.slope_deg": "deg",
    "environment.seabed.slope_heading_deg": "deg",
    "cable.length": "m",
    "cable.diameter": "m",
    "cable.weight_in_water": "N/m",
    "cable.axial_stiffness": "N",
    "cable.normal_drag": "-",
    "cable.tangential_drag": "-",
    "cable.segments.length": "m",
    "cable.segments.diameter": "m",
    "cable.segments.weight_in_water": "N/m",
    "cable.segments.axial_stiffness": "N",
    "cable.segments.normal_drag": "-",
    "cable.segments.tangential_drag": "-",
    "cable.segments.bending_stiffness": "N m^2",
    "end_a.position": "m", "end_b.position": "m",
    "end_a.force": "N", "end_b.force": "N",
    "end_a.tension": "N", "end_b.tension": "N",
    "bodies.weight_in_water": "N",
    "bodies.net_buoyancy": "N",
    "bodies.drag_area": "m^2",
    "bodies.drag_coefficient": "-",
    "bodies.thrust": "N",
    "solver.intervals": "-",
    "solver.degree": "-",
    "solver.tolerance": "-",
    "solver.smoothing": "m/s",
    "solver.accuracy": "-",
    # dynamic scenes (docs/dynamics.md)
    "cable.mass_per_length": "kg/m",
    "cable.segments.mass_per_length": "kg/m",
    "cable.added_mass_coefficient": "-",
    "cable.tangential_added_mass_coefficient": "-",
    "cable.axial_damping": "N s",
    "unit.mass": "kg",
    "unit.added_mass": "kg",
    "unit.weight_in_water": "N",
    "unit.volume": "m^3",
    "unit.drag_area": "m^2",
    "unit.drag_coefficient": "-",
    "bodies.mass": "kg",
    "bodies.added_mass": "kg",
    "top_motion.heave_amplitude": "m",
    "top_motion.heave_frequency": "rad/s",
    "top_motion.horizontal_amplitude": "m",
    "top_motion.horizontal_frequency": "rad/s",
    "top_motion.circular_radius": "m",
    "top_motion.circular_frequency": "rad/s",
    "top_motion.ramp_time": "s",
    "top_motion.payout_speed": "m/s",
    "top_motion.payout_acceleration": "m/s^2",
    "top_motion.payout_amplitude": "m",
    "top_motion.payout_frequency": "rad/s",
    "top_motion.tow.speed": "m/s",
    "top_motion.tow.straight_length": "m",
    "top_motion.tow.turn_diameter": "m",
    "simulation.duration": "s",
    "simulation.time_step": "s",
    "simulation.output_step": "s",
    "simulation.segments": "-",
    "simulation.tolerance": "-",
    # heave scenes (docs/problem_files.md, "Heave scenes")
    "sea.significant_wave_height": "m",
    "sea.modal_frequency": "rad/s",
    "sea.zero_crossing_period": "s",
    "sea.peak_period": "s",
    "sea.peak_enhancement": "-",
    "vessel.natural_frequency": "rad/s",
    "vessel.damping_ratio": "-",
    "vessel.gain": "-",
    "winch.gain": "1/s",
    "winch.natural_frequency": "rad/s",
    "winch.damping_ratio": "-",
    "winch.delay": "s",
    "winch.stroke_max": "m",
    "winch.speed_max": "m/s",
    "winch.command_rate_max": "m/sample",
    "winch.accel_max": "m/s^2",
    "winch.tension_min": "N",
    "unit.a": "s^2",
    "unit.b": "s",
    "unit.b_quadratic": "s^2/m",
    "unit.static_tension": "N",
    "controller.q": "1/m^2",
    "controller.r": "1/m^2",
    "controller.horizon": "-",
    "controller.sample_time": "s",
    "controller.preview_time": "s",
    "controller.measurement_noise": "m",
    "controller.winch_noise": "m",
    "controller.boom_tip_noise": "m",
    "controller.depth_bias_time": "s",
    "simulation.seed": "-",
    "simulation.substeps": "-",
    "simulation.warmup": "s",
    "identification.duration": "s",
    "identification.amplitude": "m",
    "identification.noise": "m",
    "identification.seed": "-",
    "deployment.final_length": "m",
    "deployment.payout_speed": "m/s",
    "deployment.fixed_length": "m",
    "deployment.window": "m",
    "deployment.ramp_time": "s",
}

#: last parts of a key that mean one quantity in every table
_LEAF_UNITS = {"length": "m", "diameter": "m", "duration": "s", "mass": "kg",
               "weight_in_water": "N", "tension": "N", "position": "m", "force": "N"}


def key_unit(key: str) -> str:
    """The unit of a dotted key (``"m/s"`` for ``environment.current.speed``), ``""`` when
    the key is not known (see the module docstring)."""
    parts = [p for p in key.strip().split(".") if not p.isdigit()]
    unit = KEY_UNITS.get(".".join(parts))
    if unit is not None:
        return unit
    leaf = parts[-1] if parts else ""
    return _LEAF_UNITS.get(leaf, "deg" if leaf.endswith("_deg") else "")


def key_label(key: str) -> str:
    """An axis label for a dotted key: ``environment.current.speed (m/s)``, the figures' way
    of writing units (the key alone when its unit is not known)."""
    unit = key_unit(key)
    return f"{key} ({unit})" if unit else key
