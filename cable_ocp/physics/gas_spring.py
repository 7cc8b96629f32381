"""The gas spring of a passive heave compensator: a cylinder on a gas volume.

A piston of area ``A`` (m^2) closes a gas volume ``V0`` (m^3) at the pressure ``p0`` (Pa) in the
static position. Compressed by the stroke ``s`` (m, positive into the gas), the gas follows the
polytropic law ``p V^n = const`` (``n = 1`` isothermal, ``n = 1.4`` adiabatic air or nitrogen),
so with ``V = V0 - A s``

    p(s) = p0 (V0 / (V0 - A s))^n,      F(s) = p(s) A,
    k(s) = dF/ds = n p(s) A^2 / (V0 - A s),      k(0) = n p0 A^2 / V0.

The cylinder's damping (the orifice between cylinder and accumulator, seal friction) is linear,
``c s'`` (N s/m). The force is what the compensator carries: the line tension of an in-line
compensator (Huang (1992), 004_7da4a1ee8042db40.txt, section 6.1.4: the passive "soft spring
with a natural period significantly longer than the period of the boom tip motion", and 7.3 (4):
"investigate a passive compensator and integrate the passive one with the active one"). The
thesis gives no compensator equations; this is the textbook polytropic accumulator.

Every function works on numbers, numpy arrays and CasADi symbols.
"""

from __future__ import annotations

from typing import Any

__all__ = ["compensator_force", "gas_force", "gas_pressure", "gas_stiffness"]


def gas_pressure(stroke: Any, pressure: float, volume: float, area: float,
                 exponent: float) -> Any:
    """The gas pressure ``p0 (V0 / (V0 - A s))^n`` at the stroke ``s``, Pa.

    Parameters
    ----------
    stroke : float or array or casadi symbol
        Compression from the static position, m (positive into the gas).
    pressure : float
        ``p0``: the pressure at ``s = 0``, Pa.
    volume : float
        ``V0``: the gas volume at ``s = 0``, m^3.
    area : float
        ``A``: the piston area, m^2.
    exponent : float
        ``n``: the polytropic exponent (1 isothermal, 1.4 adiabatic for a diatomic gas).
    """
    return pressure * (volume / (volume - area * stroke)) ** exponent


def gas_force(stroke: Any, pressure: float, volume: float, area: float,
              exponent: float) -> Any:
    """The gas force ``p(s) A`` on the piston at the stroke ``s``, N (:func:`gas_pressure`).

    Parameters
    ----------
    stroke : float or array or casadi symbol
        Compression from the static position, m.
    pressure, volume, area, exponent : float
        ``p0`` (Pa), ``V0`` (m^3), ``A`` (m^2), ``n`` (-), as :func:`gas_pressure`.
    """
    return area * gas_pressure(stroke, pressure, volume, area, exponent)


def gas_stiffness(stroke: Any, pressure: float, volume: float, area: float,
                  exponent: float) -> Any:
    """The tangent stiffness ``dF/ds = n p(s) A^2 / (V0 - A s)``, N/m; at ``s = 0`` it is
    ``n p0 A^2 / V0``.

    Parameters
    ----------
    stroke : float or array or casadi symbol
        Compression from the static position, m.
    pressure, volume, area, exponent : float
        ``p0`` (Pa), ``V0`` (m^3), ``A`` (m^2), ``n`` (-), as :func:`gas_pressure`.
    """
    return (exponent * area**2 * gas_pressure(stroke, pressure, volume, area, exponent)
            / (volume - area * stroke))


def compensator_force(stroke: Any, rate: Any, pressure: float, volume: float, area: float,
                      exponent: float, damping: float) -> Any:
    """The force the compensator carries: the gas force and the damping ``c s'``, N.

    Parameters
    ----------
    stroke : float or array or casadi symbol
        Compression from the static position, m.
    rate : float or array or casadi symbol
        ``s'``: the compression rate, m/s.
    pressure, volume, area, exponent : float
        ``p0`` (Pa), ``V0`` (m^3), ``A`` (m^2), ``n`` (-), as :func:`gas_pressure`.
    damping : float
        ``c``: the linear damping of the cylinder, N s/m.
    """
    return gas_force(stroke, pressure, volume, area, exponent) + damping * rate
