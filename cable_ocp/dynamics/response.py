"""Frequency response of a dynamic scene to a harmonic top motion: the outputs, the
harmonic analysis of a time run and the linear transfer function of the modes.

The thesis' experimental figures (Huang (1992), 004: Figs 3.3-3.7 of 3.3.1-3.3.4 and
Figs 4.2-4.6 of 4.5.1-4.5.2) are the steady-state tension or motion amplitude against the
excitation frequency. This module holds what one frequency needs; the sweep over
frequencies and amplitudes, run on the batch machinery, is
:func:`cable_ocp.batch.response.frequency_response`.

Excitation (``[top_motion]``, offsets of end_b from its static position, A the amplitude):

* ``"heave"``: z = A sin(w t) (``heave_amplitude``, ``heave_frequency``; 3.3.1-3.3.4);
* ``"horizontal"``: (x, y) = A sin(w t) (cos psi, sin psi) (``horizontal_amplitude``;
  4.5.1's Figs 4.2-4.3);
* ``"circular"``: z = A sin(w t), (x, y) = A (1 - cos(w t)) (cos psi, sin psi)
  (``circular_radius``; 4.5.1's Figs 4.4-4.5, 4.5.2's Fig. 4.6).

Outputs (:func:`parse_outputs`): ``top_tension`` and ``unit_tension`` (the tensions of the
top element and of the element at the unit, N), ``unit_x``, ``unit_y``, ``unit_z`` (the
unit's position, m) and ``node_x:K``, ``node_y:K``, ``node_z:K`` (node K from end_a, m).
Their amplitude divided by A is the response amplitude operator (RAO): N/m for a tension,
m/m for a motion.

Linear transfer function (:func:`linear_response`). About the static state the model's
linearisation (:meth:`~cable_ocp.dynamics.model.CableModel.linearize`, the K and M of
:mod:`~cable_ocp.dynamics.modal`) gives, for the free nodes' displacement
r = e D e^{iwt} + y relative to the rigid translation e D of the top's complex amplitude D
(a line that hangs from the top with a free unit is translation invariant: moving
everything with the top costs no force),

    (K + i w C - w^2 M) Y = w^2 M e D,

the sum over every mode phi_j (K phi_j = w_j^2 M phi_j, mass-normalised) of
phi_j phi_j^T M e w^2 D / (w_j^2 - w^2 + i w phi_j^T C phi_j) when C is modal, solved here
as one complex system (which is that sum over all modes, without truncation). C holds the
cable's internal damping c (T = EA e + c de/dt, assembled along the static tangents) and,
optionally, a modal damping ratio zeta on every mode (2 zeta w_j in modal coordinates).
Drag is quadratic in the velocity and adds no linear damping about rest: in water the
linear curve is undamped at resonance, while the time runs carry the drag. The element
tension is dT_e = (EA_e + i w c_e) / l_e t_e . (dR_{e+1} - dR_e) (Hooke's law about the
static tangent t_e, l_e the unstretched element length).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.dynamics import DynamicScene

__all__ = ["EXCITATIONS", "LinearResponse", "check_response_scene", "excitation_kind",
           "excitation_keys", "harmonic_fit", "linear_response", "output_series",
           "output_unit", "parse_outputs", "period_change", "top_phasor"]

#: excitation -> (amplitude key, frequency key, heading key) of [top_motion]
EXCITATIONS: dict[str, tuple[str, str, str | None]] = {
    "heave": ("heave_amplitude", "heave_frequency", None),
    "horizontal": ("horizontal_amplitude", "horizontal_frequency", "horizontal_heading_deg"),
    "circular": ("circular_radius", "circular_frequency", "circular_heading_deg"),
}

_OUTPUT = re.compile(r"^(top_tension|unit_tension|unit_[xyz]|node_[xyz]:\d+)$")


def excitation_keys(kind: str) -> tuple[str, str]:
    """The ``[top_motion]`` keys (amplitude, frequency) of an excitation.

    Raises
    ------
    CableOCPError
        An excitation that is not one of :data:`EXCITATIONS`.
    """
    if kind not in EXCITATIONS:
        raise CableOCPError(f"--excitation {kind}: valid are {', '.join(EXCITATIONS)}")
    amp, freq, _ = EXCITATIONS[kind]
    return amp, freq


def excitation_kind(scene: DynamicScene) -> str:
    """The harmonic top motion the scene gives (``"heave"`` when it gives none).

    Raises
    ------
    CableOCPError
        When the scene gives more than one of them (the sweep varies one).
    """
    tm = scene.top_motion
    given = [k for k, v in (("heave", tm.heave_amplitude),
                            ("horizontal", tm.horizontal_amplitude),
                            ("circular", tm.circular_radius)) if v != 0.0]
    if len(given) > 1:
        raise CableOCPError(f"[top_motion] gives {' and '.join(given)} motion: a frequency "
                            "response sweeps one; set --excitation or keep one amplitude")
    return given[0] if given else "heave"


def check_response_scene(scene: DynamicScene, kind: str) -> None:
    """Raise when the scene has a motion other than the swept harmonic one.

    Parameters
    ----------
    scene : DynamicScene
        The scene.
    kind : str
        The swept excitation (:data:`EXCITATIONS`).

    Raises
    ------
    CableOCPError
        A pay-out, a tow, a series or another harmonic component (the key is named).
    """
    excitation_keys(kind)
    tm = scene.top_motion
    if tm.varying_length:
        raise CableOCPError("top_motion: a frequency response needs a fixed length; remove "
                            "the pay-out (payout_speed, payout_amplitude, ...)")
    if tm.tow is not None:
        raise CableOCPError("top_motion.tow: a frequency response needs a harmonic top "
                            "motion only; remove [top_motion.tow]")
    if tm.series:
        raise CableOCPError("top_motion.series: a frequency response needs a harmonic top "
                            "motion only; remove series")
    for other, (akey, _, _) in EXCITATIONS.items():
        if other != kind and getattr(tm, akey) != 0.0:
            raise CableOCPError(f"top_motion.{akey} = {getattr(tm, akey)}: the sweep "
                                f"excites {kind} motion only; set it to 0")
    if scene.simulation.start != "static":
        raise CableOCPError('simulation.start: a frequency response starts from the static '
                            'state; set start = "static"')


def top_phasor(scene: DynamicScene, kind: str) -> np.ndarray:
    """The top's complex displacement amplitude per unit amplitude (x, y, z), -: the top
    moves as Re(D e^{i w t}) about its static position (and its mean offset).

    Parameters
    ----------
    scene : DynamicScene
        The scene (its heading of the horizontal and circular motion).
    kind : str
        The excitation (:data:`EXCITATIONS`).
    """
    _, _, hkey = EXCITATIONS[kind]
    psi = math.radians(getattr(scene.top_motion, hkey)) if hkey else 0.0
    eh = np.array([math.cos(psi), math.sin(psi), 0.0])
    ez = np.array([0.0, 0.0, 1.0])
    if kind == "heave":  # sin = Re(-i e^{iwt})
        return -1j * ez
    if kind == "horizontal":
        return -1j * eh
    return -1j * ez - eh  # circular: z sin, horizontal 1 - cos (mean 1, varying -cos)


def parse_outputs(names: str | Sequence[str], nodes: int) -> list[str]:
    """The output names, checked (see the module docstring).

    Parameters
    ----------
    names : str or sequence of str
        Comma-separated names or a list.
    nodes : int
        Number of nodes of the line (elements + 1): node indices go 0..nodes-1.

    Raises
    ------
    CableOCPError
        An unknown name or a node index out of range.
    """
    items = [s.strip() for s in names.split(",")] if isinstance(names, str) else list(names)
    out = []
    for name in items:
        if not isinstance(name, str) or not _OUTPUT.match(name):
            raise CableOCPError(f"--outputs {name!r}: valid are top_tension, unit_tension, "
                                "unit_x, unit_y, unit_z and node_x:K, node_y:K, node_z:K "
                                f"(K a node index 0..{nodes - 1} from end_a)")
        if name.startswith("node_") and not 0 <= int(name.split(":")[1]) < nodes:
            raise CableOCPError(f"--outputs {name}: the node index must be 0..{nodes - 1} "
                                f"({nodes - 1} elements)")
        if name not in out:
            out.append(name)
    if not out:
        raise CableOCPError("--outputs: give at least one output")
    return out


def output_unit(name: str) -> str:
    """``"N"`` for a tension, ``"m"`` for a motion."""
    return "N" if name.endswith("tension") else "m"


def _node_axis(name: str) -> tuple[int | None, int]:
    """(node index or None for the unit, axis 0..2) of a motion output."""
    axis = "xyz".index(name.split(":")[0][-1])
    if name.startswith("unit_"):
        return None, axis
    return int(name.split(":")[1]), axis


def output_series(res: Any, name: str) -> np.ndarray:
    """The time series of an output from a :class:`~cable_ocp.dynamics.result.
    SimulationResult` (N or m).

    Parameters
    ----------
    res : SimulationResult
        The time run.
    name : str
        An output (:func:`parse_outputs`).
    """
    if name == "top_tension":
        return np.asarray(res.segment_tensions, dtype=float)[:, -1]
    if name == "unit_tension":
        return np.asarray(res.segment_tensions, dtype=float)[:, 0]
    node, axis = _node_axis(name)
    if node is None:
        return np.asarray(res.unit_position, dtype=float)[:, axis]
    return np.asarray(res.node_positions, dtype=float)[:, node, axis]


def harmonic_fit(t: np.ndarray, y: np.ndarray, omega: float) -> dict[str, float]:
    """Least-squares fit y ~ m + a cos(w t) + b sin(w t) over the samples given (whole
    periods for an unbiased amplitude), with the samples' range.

    Parameters
    ----------
    t : ndarray
        Times, s.
    y : ndarray
        Values (any unit).
    omega : float
        The excitation frequency, rad/s.

    Returns
    -------
    dict
        ``amplitude`` sqrt(a^2 + b^2), ``phase`` (rad, of y ~ m + amplitude
        sin(w t + phase)), ``mean`` m, ``half_range`` (max - min) / 2, ``max``, ``min``.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    basis = np.column_stack([np.ones_like(t), np.cos(omega * t), np.sin(omega * t)])
    coef = np.linalg.lstsq(basis, y, rcond=None)[0]
    return {"amplitude": float(math.hypot(coef[1], coef[2])),
            "phase": float(math.atan2(coef[1], coef[2])), "mean": float(coef[0]),
            "half_range": float(0.5 * (np.max(y) - np.min(y))), "max": float(np.max(y)),
            "min": float(np.min(y))}


def _window(t: np.ndarray, t_end: float, periods: float, period: float) -> np.ndarray:
    """Mask of the samples in [t_end - periods T, t_end) (half-open: whole periods)."""
    eps = 1e-9 * period
    return (t >= t_end - periods * period - eps) & (t < t_end - eps)


def period_change(t: np.ndarray, y: np.ndarray, omega: float) -> tuple[float, float, float]:
    """(amplitude over the last period, over the one before, their relative change) of the
    harmonic fit at ``omega``: the periodicity test of a time run.

    The change is the larger of |a_1 - a_0| (the Fourier amplitudes at ``omega``) and
    |h_1 - h_0| (the half ranges (max - min) / 2), over max(h_1, h_0, floor),
    floor = 1e-9 max(|mean|, 1): measured against the size of the oscillation, so that an
    output that moves at 2 w (a pendulum's tension under horizontal motion) is judged by
    its half range, and one that does not move (a sway under pure heave) counts as
    periodic. NaN when the samples do not cover two periods.

    Parameters
    ----------
    t : ndarray
        Times, s (uniformly sampled, whole periods at the end).
    y : ndarray
        Values.
    omega : float
        The excitation frequency, rad/s.
    """
    t = np.asarray(t, dtype=float)
    period = 2.0 * math.pi / omega
    t_end = float(t[-1]) + (float(t[-1] - t[-2]) if t.size > 1 else 0.0)
    if t.size < 8 or t_end - float(t[0]) < 2.0 * period * (1.0 - 1e-9):
        return math.nan, math.nan, math.nan
    last = _window(t, t_end, 1.0, period)
    prev = _window(t, t_end - period, 1.0, period)
    if last.sum() < 4 or prev.sum() < 4:
        return math.nan, math.nan, math.nan
    f1 = harmonic_fit(t[last], y[last], omega)
    f0 = harmonic_fit(t[prev], y[prev], omega)
    a1, a0 = f1["amplitude"], f0["amplitude"]
    h1, h0 = f1["half_range"], f0["half_range"]
    floor = 1e-9 * max(abs(f1["mean"]), 1.0)
    return a1, a0, max(abs(a1 - a0), abs(h1 - h0)) / max(h1, h0, floor)


def window_fit(t: np.ndarray, y: np.ndarray, omega: float, periods: int
               ) -> dict[str, float]:
    """:func:`harmonic_fit` over the last ``periods`` whole periods of a time run.

    Parameters
    ----------
    t : ndarray
        Times, s (uniformly sampled).
    y : ndarray
        Values.
    omega : float
        The excitation frequency, rad/s.
    periods : int
        Whole periods at the end of the run.
    """
    t = np.asarray(t, dtype=float)
    period = 2.0 * math.pi / omega
    t_end = float(t[-1]) + (float(t[-1] - t[-2]) if t.size > 1 else 0.0)
    mask = _window(t, t_end, float(periods), period)
    return harmonic_fit(t[mask], np.asarray(y, dtype=float)[mask], omega)


# --------------------------------------------------------------------------------------
# The linear transfer function
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class LinearResponse:
    """The linear transfer function of the modes about the static state.

    Attributes
    ----------
    frequencies : ndarray (n_f,)
        Excitation frequencies w, rad/s.
    outputs : list of str
        Output names (:func:`parse_outputs`).
    transfer : ndarray (n_f, n_o), complex
        Complex output amplitude per unit excitation amplitude (N/m or m/m): the output
        varies as Re(transfer A e^{i w t}) about its static value.
    natural_frequencies : ndarray (n_modes,)
        Undamped natural frequencies of the linearisation, rad/s, ascending.
    status : str
        ``"solved"``, or ``"failed"`` (the static state, an anchored end_a, a model that
        cannot take the excitation): then ``transfer`` is NaN and ``message`` says why.
    message : str
        Detail of the status.
    diagnostics : dict
        ``model``, ``coordinates`` (free coordinates), ``damping_ratio``,
        ``internal_damping`` (bool).
    """

    frequencies: np.ndarray
    outputs: list[str]
    transfer: np.ndarray
    natural_frequencies: np.ndarray
    status: str = "solved"
    message: str = ""
    diagnostics: dict[str, Any] = field(default_factory=dict)

    @property
    def rao(self) -> np.ndarray:
        """|transfer|: the response amplitude operator (N/m or m/m), (n_f, n_o)."""
        return np.abs(self.transfer)


def _element_data(model: Any, kmat: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[int]]:
    """(axial stiffness EA (N), damping c (N s), unstretched length (m)) per element and the
    free nodes. The axial model's EA is the one its K holds (the tangent of a
    tension-strain table, the standard linear solid's dynamic stiffness): K[e, e+1] = -EA/h.

    Raises
    ------
    CableOCPError
        A planar or lumped3d line with a tension-strain table (its tangent EA along the
        line is not formed here).
    """
    if model.name != "axial" and getattr(getattr(model, "scene", None), "statics", None) \
            is not None and model.scene.statics.cable.strain_table is not None:
        raise CableOCPError("cable.tension_strain: the linear tension of a planar or "
                            "lumped3d line with a tension-strain table is not formed")
    if model.name == "lumped3d":
        p = model.params
        return (np.asarray(p.axial_stiffness, float), np.asarray(p.axial_damping, float),
                np.asarray(p.segment_length, float), list(model.free))
    n = model.n
    h = float(model.length0) / n
    if model.name == "planar":
        rows = model.line.rows
        return (np.asarray(rows["ea"], float), np.asarray(rows["c"], float), np.full(n, h),
                list(model.free))
    k = np.empty(n)  # axial: element e joins nodes e and e + 1 (node n the fixed top)
    for e in range(n - 1):
        k[e] = -kmat[e, e + 1]
    k[n - 1] = kmat[n - 1, n - 1] - (k[n - 2] if n >= 2 else 0.0)
    return k * h, np.full(n, float(model.c)), np.full(n, h), list(range(n))


def linear_response(scene: DynamicScene, frequencies: Sequence[float] | np.ndarray,
                    outputs: Sequence[str], kind: str | None = None,
                    damping_ratio: float = 0.0, count: int | None = None) -> LinearResponse:
    """The transfer function of the modes from the top's harmonic motion to the outputs
    (module docstring), at ``frequencies``.

    Parameters
    ----------
    scene : DynamicScene
        The scene; its model (``[simulation] model``) is linearised about the static state.
    frequencies : sequence of float
        Excitation frequencies, rad/s (> 0).
    outputs : sequence of str
        Output names (:func:`parse_outputs`).
    kind : str, optional
        The excitation (default :func:`excitation_kind`).
    damping_ratio : float
        Modal damping ratio zeta added on every mode (-), default 0.
    count : int, optional
        Natural frequencies to report (default ``[modes] count``).

    Returns
    -------
    LinearResponse
        A failure (the static state, an anchored end_a, an excitation the model cannot
        take) comes back as its status with NaN transfer, never raised.

    Raises
    ------
    CableOCPError
        An invalid output name or a negative damping ratio.
    """
    from scipy.linalg import eigh

    from cable_ocp.dynamics.model import model_for

    kind = excitation_kind(scene) if kind is None else kind
    excitation_keys(kind)
    if not (math.isfinite(damping_ratio) and damping_ratio >= 0.0):
        raise CableOCPError(f"--damping-ratio {damping_ratio}: give a number >= 0")
    freqs = np.asarray(frequencies, dtype=float).ravel()
    outputs = list(outputs)
    count = scene.modes.count if count is None else int(count)
    nan = np.full((freqs.size, len(outputs)), np.nan + 0j)

    def failed(msg: str, nat: np.ndarray | None = None) -> LinearResponse:
        return LinearResponse(frequencies=freqs, outputs=outputs, transfer=nan,
                              natural_frequencies=np.zeros(0) if nat is None else nat,
                              status="failed", message=msg,
                              diagnostics={"model": scene.simulation.model})

    if scene.unit is None:
        return failed("the linear transfer function needs a free unit at end_a (the line "
                      "then translates with the top); end_a is anchored")
    model = model_for(scene)
    modes = model.modes(1)
    if modes.status != "solved":
        return failed(f"the static state: {modes.message}")
    kmat, mmat = model.linearize()
    try:
        ea, cc, l0, free = _element_data(model, kmat)
    except CableOCPError as exc:
        return failed(str(exc))
    n_el = ea.size
    dim = kmat.shape[0] // len(free)
    axes = {1: [2], 2: [0, 2], 3: [0, 1, 2]}[dim]
    u = top_phasor(scene, kind)
    if any(abs(u[k]) > 0.0 for k in range(3) if k not in axes):
        return failed(f"the {model.name} model moves in {'xyz'[axes[0]] if dim == 1 else 'xz'}"
                      f" only: it cannot take {kind} motion (use lumped3d)")
    nodes = np.asarray(modes.node_positions, dtype=float)
    d_el = nodes[1:] - nodes[:-1]
    tang = d_el / np.linalg.norm(d_el, axis=1, keepdims=True)
    # the coordinates of the free nodes: node-major, the model's axes
    e_vec = np.tile(u[axes], len(free))
    lam, phi = eigh(kmat, mmat)
    omega_n = np.sign(lam) * np.sqrt(np.abs(lam))
    # internal damping along the static tangents: C = sum c_e/l_e B_e^T t t^T B_e
    cmat = np.zeros_like(kmat)
    index = {node: i for i, node in enumerate(free)}
    for e in range(n_el):
        if cc[e] == 0.0:
            continue
        tt = np.outer(tang[e][axes], tang[e][axes]) * cc[e] / l0[e]
        for a, sa in ((e, -1.0), (e + 1, 1.0)):
            for b, sb in ((e, -1.0), (e + 1, 1.0)):
                if a in index and b in index:
                    ia, ib = index[a] * dim, index[b] * dim
                    cmat[ia:ia + dim, ib:ib + dim] += sa * sb * tt
    if damping_ratio > 0.0:
        mp = mmat @ phi  # mass-normalised phi: phi^T M phi = I
        cmat = cmat + mp @ np.diag(2.0 * damping_ratio * np.abs(omega_n)) @ mp.T
    transfer = np.zeros((freqs.size, len(outputs)), dtype=complex)
    for i, w in enumerate(freqs):
        dyn = kmat + 1j * w * cmat - w * w * mmat
        y = np.linalg.solve(dyn, (w * w) * (mmat @ e_vec))
        disp = np.tile(u, (n_el + 1, 1)).astype(complex)  # every node translates with D
        for node, j in index.items():
            disp[node, axes] += y[j * dim:(j + 1) * dim]
        for k, name in enumerate(outputs):
            if name.endswith("tension"):
                e = n_el - 1 if name == "top_tension" else 0
                stiff = (ea[e] + 1j * w * cc[e]) / l0[e]
                transfer[i, k] = stiff * tang[e] @ (disp[e + 1] - disp[e])
            else:
                node, axis = _node_axis(name)
                transfer[i, k] = disp[0 if node is None else node, axis]
    nat = np.sort(omega_n[omega_n > 0.0])[:max(1, count)]
    return LinearResponse(
        frequencies=freqs, outputs=outputs, transfer=transfer, natural_frequencies=nat,
        message=f"{model.name}: {kmat.shape[0]} free coordinates, {nat.size} natural "
                "frequencies reported",
        diagnostics={"model": model.name, "coordinates": int(kmat.shape[0]),
                     "damping_ratio": float(damping_ratio),
                     "internal_damping": bool(np.any(cc != 0.0))})
