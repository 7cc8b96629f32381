"""The checks that a dynamic scene fits a model, one per model: they need the model's
limits (what it can represent), so they live with the models, not in the scene
(:mod:`cable_ocp.scene.dynamics` validates the keys alone). Each model runs its check when
it is built; the heave plant's check (:func:`cable_ocp.heave.cable_models.check_plant_scene`)
runs them on the cable scene before any work.
"""

from __future__ import annotations

import math

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import DynamicScene

__all__ = ["check_axial", "check_lumped", "check_lumped_plant", "check_material",
           "check_planar"]


def check_material(scene: DynamicScene, model: str) -> None:
    """Raise :class:`CableOCPError` (naming the key) when the cable's material law is one
    that ``model`` does not carry: the three models have the table and the viscoelastic
    law, not with the ``thesis`` schemes (Huang's (3.8)-(3.10) and (5.21) with Hooke's
    law), the lumped model's viscoelastic law with its midpoint scheme only.

    Parameters
    ----------
    scene : DynamicScene
        The scene.
    model : str
        ``"axial"``, ``"planar"`` or ``"lumped3d"``.
    """
    lines = scene.statics.lines
    table = any(c.tension_strain for c in lines)
    visco = any(c.viscoelastic is not None for c in lines)
    if (table or visco) and scene.simulation.scheme == "thesis":
        key = "tension_strain" if table else "viscoelastic"
        raise CableOCPError(f'cable.{key}: simulation.scheme = "thesis" (Huang\'s own '
                            "scheme, (3.8)-(3.10) or (5.21)) has the linear law; use the "
                            "model's other schemes (midpoint, trapezoidal, bdf2)")
    if visco and model == "lumped3d" and scene.simulation.scheme != "midpoint":
        raise CableOCPError(f'cable.viscoelastic: simulation.scheme = '
                            f'"{scene.simulation.scheme}": the lumped3d model steps the '
                            'viscoelastic law with the midpoint rule (valid: "midpoint")')


def check_axial(scene: DynamicScene) -> None:
    """Raise :class:`CableOCPError` (naming the key) when the scene is not a vertical line
    with a unit that the axial model can represent."""
    st = scene.statics
    tm = scene.top_motion
    why = 'simulation.model = "axial" is a vertical line: '
    if scene.unit is None:
        raise CableOCPError(why + "it needs a [unit] at end_a (an anchored end_a is a "
                            'lumped3d scene)')
    if st.segments or st.bodies:
        raise CableOCPError(why + "[[cable.segments]] and [[bodies]] are not supported; give a "
                            'single [cable] (or use model = "lumped3d")')
    if st.environment.current is not None:
        raise CableOCPError(why + "remove [environment.current] (or use model = \"lumped3d\")")
    for key in ("horizontal_amplitude", "circular_radius"):
        if getattr(tm, key) != 0.0:
            raise CableOCPError(why + f"top_motion.{key} must be 0 (only heave and pay-out)")
    if tm.tow is not None:
        raise CableOCPError(why + "remove [top_motion.tow] (or use model = \"lumped3d\")")
    if any(r[1] != 0.0 or r[2] != 0.0 for r in tm.series):
        raise CableOCPError(why + "top_motion.series: the horizontal offsets dx, dy must be 0")
    check_material(scene, "axial")
    unit = scene.unit
    if unit.weight_in_water <= 0.0 and st.cable.weight_in_water <= 0.0:
        raise CableOCPError(why + f"unit.weight_in_water = {unit.weight_in_water} N and "
                            f"cable.weight_in_water = {st.cable.weight_in_water} N/m: nothing "
                            "keeps the line taut")
    if unit.weight_in_water <= 0.0:
        raise CableOCPError(why + f"unit.weight_in_water = {unit.weight_in_water} N: the line "
                            "is slack at the unit in its static state (it needs a weight > 0)")
    if st.cable.weight_in_water < 0.0:
        low = unit.weight_in_water + st.cable.weight_in_water * scene.length
        if low <= 0.0:
            raise CableOCPError(why + f"cable.weight_in_water = {st.cable.weight_in_water} "
                                "N/m: the buoyant cable is slack at the top in its static state")


#: a horizontal direction counts as along x when its y-component is below this (-)
_PLANE_TOL = 1e-12


def _off_plane(heading_deg: float) -> bool:
    return abs(math.sin(math.radians(heading_deg))) > _PLANE_TOL


def check_planar(scene: DynamicScene) -> None:
    """Raise :class:`CableOCPError` (naming the key) when the scene leaves the x-z plane
    or has what the planar model cannot represent."""
    check_material(scene, "planar")
    st = scene.statics
    tm = scene.top_motion
    why = 'simulation.model = "planar" moves in the vertical x-z plane: '
    if st.bodies:
        raise CableOCPError(why + "[[bodies]] are not supported (or use model = "
                            '"lumped3d")')
    if st.environment.seabed is not None:
        raise CableOCPError(why + "[environment.seabed]: the model has no seabed contact; "
                            "remove the table")
    cur = st.environment.current
    if cur is not None and any(abs(u) > _PLANE_TOL * max(cur.max_speed, 1.0) for u in cur.uy):
        raise CableOCPError(why + "environment.current must flow along x (heading_deg 0 or "
                            '180); use model = "lumped3d" for a cross-flow')
    if tm.horizontal_amplitude != 0.0 and _off_plane(tm.horizontal_heading_deg):
        raise CableOCPError(why + f"top_motion.horizontal_heading_deg = "
                            f"{tm.horizontal_heading_deg}: must be 0 or 180")
    if tm.circular_radius != 0.0 and _off_plane(tm.circular_heading_deg):
        raise CableOCPError(why + f"top_motion.circular_heading_deg = "
                            f"{tm.circular_heading_deg}: must be 0 or 180")
    if tm.tow is not None:
        tow = tm.tow
        if _off_plane(tow.heading_deg):
            raise CableOCPError(why + f"top_motion.tow.heading_deg = {tow.heading_deg}: must "
                                "be 0 or 180")
        if math.isfinite(tow.straight_length) and tow.turn_angle_deg != 0.0:
            raise CableOCPError(why + "top_motion.tow: a turn leaves the plane; give no "
                                'straight_length (a straight tow) or use model = "lumped3d"')
    if any(r[2] != 0.0 for r in tm.series):
        raise CableOCPError(why + "top_motion.series: the offsets dy must be 0")
    if scene.unit is None:
        ya = st.end_a.position[1]
        if ya != scene.top_position[1]:
            raise CableOCPError(why + f"end_a.position[1] = {ya} must equal end_b.position[1] "
                                f"= {scene.top_position[1]} (the plane y = const)")
    else:
        unit = scene.unit
        cantilever = (scene.simulation.top_end == "clamped"
                      and any(c.bending_stiffness > 0.0 for c in st.lines))
        if unit.weight_in_water <= 0.0 and cur is None and not cantilever:
            raise CableOCPError(why + f"unit.weight_in_water = {unit.weight_in_water} N: "
                                "without a current nothing keeps the line taut (it needs a "
                                "weight > 0)")


def check_lumped(scene: DynamicScene) -> None:
    """Raise :class:`CableOCPError` (naming the key) when the scene has what the lumped-mass
    model cannot run: what :func:`check_lumped_plant` refuses, the viscoelastic law aside,
    and the viscoelastic law with a pay-out (a pay-out runs on
    :mod:`cable_ocp.dynamics.lumped_payout_run`, whose nodes carry no dashpot strain)."""
    visco = any(c.viscoelastic is not None for c in scene.statics.lines)
    if visco and scene.top_motion.varying_length:
        raise CableOCPError('cable.viscoelastic: simulation.model = "lumped3d" with a '
                            "pay-out (nodes entering and leaving at the winch) has the "
                            'elastic laws only; use model = "axial" for a vertical '
                            "viscoelastic pay-out, or give axial_stiffness alone")
    _check_lumped_line(scene)


def check_lumped_plant(scene: DynamicScene) -> None:
    """Raise :class:`CableOCPError` (naming the key) when the scene's line has what the
    lumped-mass model cannot represent, its ``[top_motion]`` aside (the heave plant,
    :class:`cable_ocp.heave.cable_models.LumpedCablePlant`, moves the top and pays cable
    out itself; its driven step has the elastic laws only)."""
    if any(c.viscoelastic is not None for c in scene.statics.lines):
        raise CableOCPError('cable.viscoelastic: the lumped3d heave plant (its driven step) '
                            "has the elastic laws only; give axial_stiffness alone")
    _check_lumped_line(scene)


def _check_lumped_line(scene: DynamicScene) -> None:
    check_material(scene, "lumped3d")
    if scene.statics.environment.seabed is not None:
        raise CableOCPError('[environment.seabed]: simulation.model = "lumped3d" has no '
                            "seabed contact; remove the table (the seabed is then only "
                            "checked in the static start)")
    if scene.simulation.top_end != "pinned":
        raise CableOCPError(f'simulation.top_end = "{scene.simulation.top_end}": '
                            'simulation.model = "lumped3d" has a pinned top (valid: "pinned"; '
                            'a clamped top needs model = "planar")')
