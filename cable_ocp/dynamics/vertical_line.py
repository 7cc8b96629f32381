"""The coefficients of a vertical line with a unit, read from its scene once for both axial
schemes: the discretised model (:class:`cable_ocp.dynamics.axial.AxialModel`) and Huang's
finite-difference scheme (:class:`cable_ocp.dynamics.axial_thesis.ThesisAxialModel`)."""

from __future__ import annotations

from dataclasses import dataclass

from cable_ocp.physics.drag import body_drag_factor, line_drag_factors
from cable_ocp.scene.dynamics import DynamicScene

__all__ = ["VerticalLine", "vertical_line"]


@dataclass(frozen=True)
class VerticalLine:
    """A vertical line's coefficients (Huang (1992) (3.1)-(3.3)).

    Attributes
    ----------
    axial_stiffness : float
        EA, N.
    mass_per_length : float
        mu = m + m_at: mass per length with the tangential added mass, kg/m.
    weight_per_length : float
        Weight in water per length w, N/m.
    drag_factor : float
        k of the tangential drag k |u| u per length, kg/m^2
        (:func:`cable_ocp.physics.drag.line_drag_factors`).
    unit_mass : float
        The unit's heave virtual mass (with its added mass), kg.
    unit_weight : float
        The unit's weight in water, N.
    unit_drag : float
        The unit's heave drag factor, kg/m (:func:`cable_ocp.physics.drag.body_drag_factor`).
    length : float
        Unstretched length at the start, m.
    top_height : float
        Height of the top (end_b) at the start, m.
    """

    axial_stiffness: float
    mass_per_length: float
    weight_per_length: float
    drag_factor: float
    unit_mass: float
    unit_weight: float
    unit_drag: float
    length: float
    top_height: float


def vertical_line(scene: DynamicScene) -> VerticalLine:
    """The coefficients of a vertical-line scene with a unit (as checked by
    :func:`cable_ocp.dynamics.checks.check_axial`).

    Parameters
    ----------
    scene : DynamicScene
        The scene: its single cable, its unit, the water density and the top's start.
    """
    st = scene.statics
    cab = st.cable
    dyn = scene.cable[0]
    unit = scene.unit
    assert unit is not None
    rho = st.environment.water_density
    return VerticalLine(
        axial_stiffness=float(cab.axial_stiffness),
        mass_per_length=dyn.mass_per_length + dyn.tangential_added_mass_per_length(
            cab.diameter, rho),
        weight_per_length=float(cab.weight_in_water),
        drag_factor=line_drag_factors(rho, cab.diameter, cab.normal_drag,
                                      cab.tangential_drag)[1],
        unit_mass=unit.virtual_mass[2],
        unit_weight=unit.weight_in_water,
        unit_drag=body_drag_factor(rho, unit.drag_coefficient[2], unit.drag_area[2]),
        length=scene.length,
        top_height=float(scene.top_position[2]))
