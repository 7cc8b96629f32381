"""State-space blocks of the heave-compensation plant and their assembly (Huang 1992, section
6.2-6.3).

Blocks (python-control ``StateSpace`` with named signals, composed by ``control.interconnect``):

=====================  ==================================  ==========================
block                  equation (Huang (1992))                      signals (in -> out)
=====================  ==================================  ==========================
:func:`unit_block`     (6.2)/(6.4) ``a x'' + b x' + x =    ``x0, u -> x, x_dot,
                       x0 + u``                            stretch``
:func:`winch_first`    (6.1)/(6.5) ``u' + K u = K u0d``    ``u0d -> u, u_dot``
:func:`winch_second`   ``u'' + 2 z w u' + w^2 u = w^2 u0d``  ``u0d -> u, u_dot, u_ddot``
                       (section 6.5 recommendation)
:func:`delay_block`    exact (none), Taylor (6.13)-(6.14),  ``u0 -> u0d``
                       Pade
:func:`vessel_block`   (6.25)-(6.26)                       ``eta -> x0``
sea filter             (6.21)-(6.23), :mod:`.sea`           ``w -> eta``
=====================  ==================================  ==========================

The passive compensator (section 6.1.4; :func:`compensator_block`, ``x0, u, x -> delta``):
``c delta' + k_p delta = k_c (x0 + u - delta - x)``, the unit then sees ``x0 + u - delta``.

``x`` is the unit's heave (m, up), ``x0`` the boom-tip heave (m, up), ``u`` the winch output
(m, counted like ``x0``: ``u > 0`` hauls the unit up), ``u0`` the winch command (m), ``u0d`` the
command after the delay ``tau``. ``stretch = x0 + u - x`` (m) is the cable's extension beyond its
static value; with a unit of mass ``m`` the dynamic tension is ``m/a * stretch`` (N).

:func:`assemble_plant` orders the states ``[unit (2), winch (1|2), delay (0|2|n), vessel (2|0),
sea (2 n_s)]``; without delay and with the first-order winch this is exactly (6.28):
``[x, x', u, x_b (2), x_s (6)]``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import control as ct
import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.physics.drag import quadratic_drag


def unit_block(a: float, b: float) -> ct.StateSpace:
    """Linear cable/subsea-unit model (Huang 1992, eq. (6.2), with the winch output added as in
    (6.4)).

    Parameters
    ----------
    a : float
        Inertia coefficient, s^2 (> 0).
    b : float
        Damping coefficient, s (>= 0).

    Returns
    -------
    control.StateSpace
        States ``[x, x_dot]``; inputs ``[x0, u]``; outputs ``[x, x_dot, stretch]``.
    """
    if not a > 0 or b < 0:
        raise CableOCPError(f"unit.a = {a!r}, unit.b = {b!r}: a must be > 0 (s^2) and b >= 0 (s), "
                            "eq. (6.2)")
    A = np.array([[0.0, 1.0], [-1.0 / a, -b / a]])
    B = np.array([[0.0, 0.0], [1.0 / a, 1.0 / a]])
    C = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]])
    D = np.array([[0.0, 0.0], [0.0, 0.0], [1.0, 1.0]])
    return ct.ss(A, B, C, D, inputs=["x0", "u"], outputs=["x", "x_dot", "stretch"],
                 states=["x", "x_dot"], name="unit")


def unit_acceleration(x: float, v: float, inp: float, a: float, b: float,
                      b_quadratic: float = 0.0, quadratic: bool = False) -> float:
    """The unit model's acceleration ``x''`` (m/s^2), on numbers: (6.2)
    ``a x'' + b x' + x = x0 + u`` or, with ``quadratic``, (6.3) ``a x'' + b_q |x'| x' + x =
    x0 + u`` (Huang (1992), 004_7da4a1ee8042db40.txt, eqs. (6.2)-(6.4)).

    Parameters
    ----------
    x, v : float
        The unit's heave (m) and its rate (m/s).
    inp : float
        ``x0 + u``: boom-tip heave plus winch output, m.
    a : float
        ``a``, s^2.
    b : float
        Linear damping ``b``, s (used without ``quadratic``).
    b_quadratic : float
        Quadratic damping ``b_q``, s^2/m (used with ``quadratic``).
    quadratic : bool
        (6.3) instead of (6.2).
    """
    damp = quadratic_drag(b_quadratic, v) if quadratic else b * v
    return (inp - x - damp) / a


def winch_first(K: float) -> ct.StateSpace:
    """First-order winch (Huang 1992, eqs. (6.1), (6.5), (6.12)): ``u' + K u = K u0d``.

    Parameters
    ----------
    K : float
        Winch bandwidth, 1/s (> 0).

    Returns
    -------
    control.StateSpace
        State ``[u]``; input ``u0d``; outputs ``[u, u_dot]``.
    """
    if not K > 0:
        raise CableOCPError(f"winch.gain = {K!r}: must be > 0 (1/s), eq. (6.1)")
    return ct.ss([[-K]], [[K]], [[1.0], [-K]], [[0.0], [K]], inputs=["u0d"],
                 outputs=["u", "u_dot"], states=["u"], name="winch")


def winch_second(omega: float, zeta: float) -> ct.StateSpace:
    """Second-order winch ``u'' + 2 zeta omega u' + omega^2 u = omega^2 u0d``.

    Section 6.5 of Huang (1992) recommends a second-order winch without giving an equation; this
    form is the one settled in docs/conventions.md ("Heave compensation").

    Parameters
    ----------
    omega : float
        Natural frequency, rad/s (> 0).
    zeta : float
        Damping ratio (> 0).

    Returns
    -------
    control.StateSpace
        States ``[u, u_dot]``; input ``u0d``; outputs ``[u, u_dot, u_ddot]``.
    """
    if not (omega > 0 and zeta > 0):
        raise CableOCPError(
            f"winch.natural_frequency = {omega!r}, winch.damping_ratio = {zeta!r}: both "
            "must be > 0 (rad/s, -)"
        )
    A = np.array([[0.0, 1.0], [-(omega**2), -2.0 * zeta * omega]])
    B = np.array([[0.0], [omega**2]])
    C = np.vstack([np.eye(2), A[1]])
    D = np.array([[0.0], [0.0], [omega**2]])
    return ct.ss(A, B, C, D, inputs=["u0d"], outputs=["u", "u_dot", "u_ddot"],
                 states=["u", "u_dot"], name="winch")


def compensator_block(stiffness: float, damping: float, line_stiffness: float
                      ) -> ct.StateSpace:
    """The passive compensator linearised about its static position: a massless piston on the
    gas spring ``k_p`` (:func:`cable_ocp.physics.gas_spring.gas_stiffness` at zero stroke) and
    the damper ``c``, in series with the line of stiffness ``k_c = m / a`` (the design model's,
    docs/heave.md, "Passive compensator"):

        c delta' + k_p delta = k_c (x0 + u - delta - x),

    ``delta`` the compression (m; it lowers the line's top, which is at ``x0 + u - delta``).

    Parameters
    ----------
    stiffness : float
        ``k_p``, N/m (> 0).
    damping : float
        ``c``, N s/m (> 0).
    line_stiffness : float
        ``k_c``, N/m (> 0).

    Returns
    -------
    control.StateSpace
        State ``[delta]``; inputs ``[x0, u, x]``; output ``delta``.
    """
    if not (stiffness > 0 and damping > 0 and line_stiffness > 0):
        raise CableOCPError(
            f"passive compensator: stiffness = {stiffness!r} N/m, damping = {damping!r} N s/m, "
            f"line stiffness = {line_stiffness!r} N/m: all must be > 0")
    kc, c = line_stiffness, damping
    return ct.ss([[-(stiffness + kc) / c]], [[kc / c, kc / c, -kc / c]], [[1.0]],
                 [[0.0, 0.0, 0.0]], inputs=["x0", "u", "x"], outputs=["delta"],
                 states=["delta"], name="comp")


def delay_block(kind: str, tau: float, order: int = 2) -> ct.StateSpace:
    """A model of the command delay ``u0d(t) = u0(t - tau)``.

    Parameters
    ----------
    kind : {"none", "taylor", "pade"}
        ``"none"``: ``u0d = u0`` (no delay, or the delay is handled elsewhere, e.g. exactly in
        discrete time). ``"taylor"``: the thesis' second-order Taylor model (Huang 1992, eq.
        (6.13)), ``y'' = 2/tau^2 (u0 - y) - 2/tau y'``, i.e. ``1/(1 + tau s + tau^2 s^2 / 2)``, with
        states ``[u0(t - tau), u0'(t - tau)]`` as in (6.14). ``"pade"``: ``control.pade(tau,
        order)``.
    tau : float
        Delay, s (>= 0; 0 gives the identity for every kind).
    order : int
        Pade order (numerator and denominator degree).

    Returns
    -------
    control.StateSpace
        Input ``u0``, output ``u0d``.
    """
    if tau < 0:
        raise CableOCPError(f"winch.delay = {tau!r}: must be >= 0 (s)")
    if kind == "none" or tau == 0:
        return ct.ss(np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((1, 0)), [[1.0]],
                     inputs=["u0"], outputs=["u0d"], name="delay")
    if kind == "taylor":
        A = np.array([[0.0, 1.0], [-2.0 / tau**2, -2.0 / tau]])
        B = np.array([[0.0], [2.0 / tau**2]])
        C = np.array([[1.0, 0.0]])
        return ct.ss(A, B, C, 0, inputs=["u0"], outputs=["u0d"], states=["u0d", "u0d_dot"],
                     name="delay")
    if kind == "pade":
        if not (isinstance(order, int) and 1 <= order <= 10):
            raise CableOCPError(f"Pade order = {order!r} is invalid; give an integer 1..10")
        num, den = ct.pade(tau, order)
        sys = ct.ss(ct.tf(num, den))
        return ct.ss(sys.A, sys.B, sys.C, sys.D, inputs=["u0"], outputs=["u0d"],
                     states=[f"pade{i + 1}" for i in range(sys.nstates)], name="delay")
    raise CableOCPError(f"delay model {kind!r} is unknown; valid: 'none', 'taylor', 'pade'")


def vessel_block(omega_v: float, zeta_v: float, gain: float) -> ct.StateSpace:
    """Boom-tip heave filter (Huang 1992, eqs. (6.25)-(6.26)).

    ``x0'' + 2 zeta_v omega_v x0' + omega_v^2 x0 = K_v omega_v^2 eta`` in the realisation (6.26):
    ``A_b = [[0, 1], [-w^2, -2 z w]]``, ``B_b = [0, 1]^T``, ``C_b = [K_v w^2, 0]``.

    Parameters
    ----------
    omega_v : float
        Natural frequency, rad/s.
    zeta_v : float
        Damping ratio.
    gain : float
        Static gain ``K_v`` (boom-tip heave per wave elevation), dimensionless.
    """
    if not (omega_v > 0 and zeta_v > 0):
        raise CableOCPError(
            f"vessel.natural_frequency = {omega_v!r}, vessel.damping_ratio = {zeta_v!r}: "
            "both must be > 0 (rad/s, -)"
        )
    A = np.array([[0.0, 1.0], [-(omega_v**2), -2.0 * zeta_v * omega_v]])
    B = np.array([[0.0], [1.0]])
    C = np.array([[gain * omega_v**2, 0.0]])
    return ct.ss(A, B, C, 0, inputs=["eta"], outputs=["x0"], states=["xb1", "xb2"],
                 name="vessel")


def direct_vessel() -> ct.StateSpace:
    """``[vessel] model = "none"``: the boom tip follows the sea surface, ``x0 = eta``."""
    return ct.ss(np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((1, 0)), [[1.0]],
                 inputs=["eta"], outputs=["x0"], name="vessel")


@dataclass(frozen=True)
class HeavePlant:
    """An assembled heave plant.

    Attributes
    ----------
    sys : control.StateSpace
        Inputs ``["u0", d]`` with ``d = "w"`` (unit white noise into the sea filter) or ``"x0"``
        (boom-tip motion as an exogenous signal, the regulator of Huang (1992) (6.6)/(6.14));
        outputs ``["x", "x_dot", "stretch", "u", "u_dot", ("u_ddot",) "x0"]``.
    blocks : dict
        Slices of the state vector per block: ``"unit"``, ``"winch"``, ``"delay"``, (``"comp"``,
        the passive compensator,) ``"vessel"``, ``"sea"``.
    a, b, K : float
        Unit coefficients (s^2, s) and winch gain (1/s; 0 for the second-order winch).
    winch_model : str
        ``"first_order"`` or ``"second_order"``.
    """

    sys: ct.StateSpace
    blocks: dict = field(hash=False)
    a: float
    b: float
    K: float
    winch_model: str

    @property
    def A(self) -> np.ndarray:  # noqa: N802 - control-theory notation
        """State matrix."""
        return np.asarray(self.sys.A)

    @property
    def B1(self) -> np.ndarray:  # noqa: N802
        """Control input column (``u0``), shape (n, 1)."""
        return np.asarray(self.sys.B[:, :1])

    @property
    def B2(self) -> np.ndarray:  # noqa: N802
        """Disturbance column (``w`` or ``x0``), shape (n, 1)."""
        return np.asarray(self.sys.B[:, 1:2])

    @property
    def n(self) -> int:
        """Number of states."""
        return int(self.sys.nstates)

    def output_row(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """``(C_row, D_row)`` of the named output, shapes ``(n,)`` and ``(2,)``."""
        i = self.sys.output_labels.index(name)
        return np.asarray(self.sys.C[i]), np.asarray(self.sys.D[i])

    def e(self, name: str) -> np.ndarray:
        """Row vector that picks output ``name`` from the state (its ``C`` row), shape (1, n)."""
        c, d = self.output_row(name)
        if np.any(d != 0):
            raise CableOCPError(f"output {name!r} has direct feedthrough; use output_row()")
        return c.reshape(1, -1)


def assemble_plant(
    a: float,
    b: float,
    winch: ct.StateSpace,
    *,
    delay: ct.StateSpace | None = None,
    vessel: ct.StateSpace | None = None,
    sea: ct.StateSpace | None = None,
    compensator: ct.StateSpace | None = None,
) -> HeavePlant:
    """Assemble the plant from blocks (Huang 1992, eq. (6.28) when ``vessel`` and ``sea`` are
    given).

    Parameters
    ----------
    a, b : float
        Unit coefficients of (6.2), s^2 and s.
    winch : control.StateSpace
        :func:`winch_first` or :func:`winch_second`.
    delay : control.StateSpace, optional
        :func:`delay_block`; default no delay.
    vessel, sea : control.StateSpace, optional
        Both or neither. With both, the disturbance input is the unit white noise ``w``; with
        neither, it is the boom-tip motion ``x0`` (the regulator plant (6.6)/(6.14)).
    compensator : control.StateSpace, optional
        :func:`compensator_block`: the passive compensator between the boom tip and the line
        (the unit then sees ``x0 + u - delta``; its block ``"comp"`` after the delay's).

    Returns
    -------
    HeavePlant
    """
    if (vessel is None) != (sea is None):
        raise CableOCPError("give both a vessel block and a sea filter, or neither")
    unit = unit_block(a, b)
    if delay is None:
        delay = delay_block("none", 0.0)
    blocks = [unit, winch, delay]
    names = ["unit", "winch", "delay"]
    if compensator is not None:
        blocks.append(compensator)
        names.append("comp")
    if sea is not None:
        blocks += [vessel, sea]
        names += ["vessel", "sea"]
        dist = "w"
    else:
        dist = "x0"
    outputs = ["x", "x_dot", "stretch", "u", "u_dot"]
    if "u_ddot" in winch.output_labels:
        outputs.append("u_ddot")
    outputs.append("x0")
    outs = [f"{blk}.{sig}" for blk, sig in
            [("unit", "x"), ("unit", "x_dot"), ("unit", "stretch"), ("winch", "u"),
             ("winch", "u_dot")]]
    if "u_ddot" in winch.output_labels:
        outs.append("winch.u_ddot")
    outs.append("vessel.x0" if sea is not None else "unit.x0")
    conns = [["unit.u", "winch.u"], ["winch.u0d", "delay.u0d"]]
    inplist = [["delay.u0"], ["sea.w"] if sea is not None else ["unit.x0"]]
    if sea is not None:
        conns += [["unit.x0", "vessel.x0"], ["vessel.eta", "sea.eta"]]
    if compensator is not None:
        # the line's top is at x0 + u - delta
        conns[0] = ["unit.u", "winch.u", "-comp.delta"]
        conns += [["comp.u", "winch.u"], ["comp.x", "unit.x"]]
        if sea is not None:
            conns.append(["comp.x0", "vessel.x0"])
        else:
            inplist[1] = ["unit.x0", "comp.x0"]
    sys = ct.interconnect(blocks, connections=conns, inplist=inplist, inputs=["u0", dist],
                          outlist=outs, outputs=outputs, name="plant")
    sizes = [blk.nstates for blk in blocks]
    offs = np.concatenate([[0], np.cumsum(sizes)])
    slices = {nm: slice(int(offs[i]), int(offs[i + 1])) for i, nm in enumerate(names)}
    model = "second_order" if winch.nstates == 2 else "first_order"
    K = float(-winch.A[0, 0]) if model == "first_order" else 0.0
    return HeavePlant(sys=ct.ss(sys.A, sys.B, sys.C, sys.D, inputs=["u0", dist],
                                outputs=outputs, states=list(sys.state_labels), name="plant"),
                      blocks=slices, a=a, b=b, K=K, winch_model=model)
