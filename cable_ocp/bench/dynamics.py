"""Benchmark of the 3D lumped-mass dynamics on the system of Huang (1992) 5.7.

The 300 m cable and 3 t unit of Huang (1992) 5.7 (``problems/dynamics/huang_5_7.toml``),
its top moved by x = y = z = sin(1.256 t) m (the faster case of 5.7.1), ramped in over 5 s.
For 20, 40, 80 and 160 segments :func:`run` returns, in one run, the wall time per simulated
second of cable_ocp's implicit midpoint scheme at a few time steps, and optionally of
MoorDyn (``pip install moordyn``; benchmark only, never needed by the tests) at its
stable time steps, each with its error against ONE converged reference for both models
(:func:`reference`: cable_ocp at 160 and 320 segments, Richardson-extrapolated, at a 4 ms
step), so that the error counts the spatial and the time discretisation together, and the
amplitude of the top force of each.

The compared quantity is the same force in both codes: the force of the top's attachment
on the cable, which moves the top node (cable_ocp's ``top_force``; MoorDyn's coupled-point
force is the net force on that node without its inertia, so its top node's M a is added,
:func:`top_force_as_cable_ocp`). MoorDyn starts from cable_ocp's static start (the unit at
its static height: the line stretched at equilibrium, :func:`_moordyn_input`), and is driven
through its ``Step`` at a 4 ms coupling step (:data:`COUPLING_STEP`) with the mean velocity
over each step (it moves the coupled point linearly within a step, so the point ends each
step on the prescribed path); its force is sampled at the time its last RK2 stage was
evaluated. A coarse coupling step costs amplitude (see :func:`linear_check`) and leaves an
error floor (about 3e-3 of the amplitude at 4 ms, from the piecewise-constant velocity of
the top through the internal damping; docs/benchmarks.md).

To make the two models the same line: the unit's drag is isotropic (MoorDyn's point drag
1/2 rho CdA |u| u), its added mass the same in every direction (MoorDyn's point
Ca rho V), and both carry the same internal damping T = EA e + c de/dt with c = 3.4e4 N s
(MoorDyn's BA; MoorDyn's explicit RK2 needs some: without it its undamped axial modes
grow), about half of critical for the shortest segment's axial mode at 40 segments and
0.3 % for the first axial mode. Remaining differences of formulation: MoorDyn takes the
cable's drag and added mass at the nodes with node tangents, Huang's ch. 5 (and
cable_ocp) on the segments; both converge to the same line as the segments shrink.

Nothing here prints (MoorDyn writes to stdout and stderr on every call: both are silenced
at the file-descriptor level). Timings are wall-clock and noisy on a shared machine:
compare ratios from one run.
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from contextlib import contextmanager
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.numerics import interrupt
from cable_ocp.numerics.text_table import table
from cable_ocp.scene.dynamics import DynamicScene, load_dynamic_scene

__all__ = ["QUICK", "BenchRow", "Reference", "as_dicts", "format_reference", "format_summary",
           "format_table", "linear_check", "moordyn_available", "planned_rows", "reference",
           "row_ok", "run", "scene", "static_unit_height", "summary",
           "top_force_as_cable_ocp"]

PROBLEM = Path(__file__).resolve().parents[2] / "problems" / "dynamics" / "huang_5_7.toml"
FREQUENCY = 1.256  # rad/s, Huang 5.7.1 (Figure 5.5)
RAMP = 5.0  # s
DAMPING = 3.4e4  # N s, internal damping of both models (MoorDyn's BA)
OUTPUT_STEP = 0.05  # s, the sampling of cable_ocp's top tension
#: s, MoorDyn's coupling step (its top tension is sampled at each): MoorDyn moves a coupled
#: point linearly within a coupling step, and a coarse one costs accuracy that no dtM
#: recovers (the linear check's amplitude: -7.5 % at 0.05 s, -3.0 % at 0.01 s, -1.5 % at
#: 2.5 ms of the closed form; the 5.7 case at 40 segments: -4.2 % at 0.05 s, -0.5 % at
#: 0.01 s, +0.2 % at 2 ms of cable_ocp's). 4 ms: a multiple of every dtM used here
COUPLING_STEP = 0.004
#: MoorDyn's initial-condition generator: 0, its stationary solver (from the static start,
#: see :func:`_moordyn_input`)
IC_GEN_DYNAMIC = 0
DURATION = 60.0  # s
WINDOW = 10.0  # s: errors and amplitudes over the last WINDOW seconds
LINEAR_DAMPING = 2.0e6  # N s, internal damping of the closed-form check
#: the project's targets: simulated seconds per wall second at 40 segments, and the accuracy
#: (top-tension error over its amplitude) at which the two models' speeds are compared
TARGET_REALTIME = 100.0
TARGET_SEGMENTS = 40
EQUAL_ACCURACY = 0.01
#: cable_ocp's default time steps, s
TIME_STEPS = (0.1, 0.075, 0.05, 0.025)
#: Newton tolerance of cable_ocp's timed runs (scaled residual: 1e-8 of the force scale,
#: here ~0.3 mN on a 30 kN line, far below the 1 % accuracy compared; the scene's default
#: 1e-10 costs a third more matrix evaluations per step)
TOLERANCE = 1e-8
#: a seconds-long configuration (a smoke run for the tests; its numbers mean little)
QUICK: dict[str, Any] = {"segments": (6,), "time_steps": (0.1,), "duration": 20.0,
                         "repeats": 1, "compile_mode": "kernel",
                         "moordyn_steps": {6: (4e-3,)}, "reference_segments": (6, 12),
                         "reference_step": 0.01}
DEFAULT_MOORDYN_STEPS: dict[int, tuple[float, ...]] = {20: (4e-3, 2e-3), 40: (4e-3, 2e-3),
                                                       80: (2e-3, 1e-3), 160: (2.5e-4,)}
#: the benchmark's numbers of segments (160: MoorDyn's convergence to the reference)
SEGMENTS = (20, 40, 80, 160)
#: the reference (:func:`reference`): cable_ocp at 160 and 320 segments, Richardson-
#: extrapolated (80: the check of the O(1/N^2) rate), at a 4 ms step (its time error
#: ~2e-5 of the amplitude: the midpoint error, 7.6e-4 at 0.025 s, falls as dt^2), sampled
#: every 8 ms
REFERENCE_SEGMENTS = (80, 160, 320)
REFERENCE_STEP = 0.004
REFERENCE_OUTPUT = 0.008


@dataclass
class BenchRow:
    """One line of the benchmark table.

    Attributes
    ----------
    model : str
        ``"cable_ocp midpoint"`` or ``"MoorDyn <scheme>"``.
    segments : int
    time_step : float
        Integration step, s.
    wall_per_simulated_s : float
        Wall time per simulated second, s (stepping only, fastest of the repeats).
    realtime_factor : float
        Simulated seconds per wall second.
    top_tension_amplitude_N : float
        Half the peak-to-peak top tension over the last 10 s, N.
    error : float
        Largest top-force difference from the one converged reference of both models
        (:func:`reference`) over the last 10 s, over the reference's amplitude (-): the
        spatial and the time error together.
    amplitude_vs_reference : float
        Relative difference of the top-force amplitude from the reference's (-).
    amplitude_vs_other : float or None
        Relative difference of the top-force amplitude of this model's finest-step row at
        these segments from the other model's (-); None without MoorDyn.
    status : str
        ``"ok"`` or why not.
    """

    model: str
    segments: int
    time_step: float
    wall_per_simulated_s: float
    realtime_factor: float
    top_tension_amplitude_N: float
    error: float
    amplitude_vs_reference: float
    amplitude_vs_other: float | None
    status: str


def scene(segments: int, time_step: float, duration: float = DURATION,
          linear: bool = False) -> DynamicScene:
    """The benchmark scene (see the module docstring) with ``segments`` and ``time_step``.

    ``linear``: the closed-form check of :func:`linear_check` instead: heave only, no drag,
    internal damping 2e6 N s (a Kelvin-Voigt rod).

    Parameters
    ----------
    segments : int
        Number of lumped segments of the line.
    time_step : float
        Integration time step, s (also the output step).
    duration : float
        Simulated time, s (default :data:`DURATION`, 60 s).
    linear : bool
        Build the linear case of :func:`linear_check` (default False: the benchmark
        scene of Huang (1992) 5.7 with drag).
    """
    ov: dict[str, Any] = {
        "top_motion.heave_frequency": FREQUENCY, "top_motion.horizontal_frequency": FREQUENCY,
        "top_motion.ramp_time": RAMP, "unit.drag_area": 0.5, "unit.drag_coefficient": 1.5,
        "unit.added_mass": 3000.0, "cable.axial_damping": DAMPING,
        "simulation.segments": segments, "simulation.time_step": time_step,
        "simulation.output_step": time_step, "simulation.duration": duration}
    if linear:
        ov.update({"top_motion.horizontal_amplitude": 0.0, "unit.drag_area": 0.0,
                   "unit.drag_coefficient": 0.0, "cable.normal_drag": 0.0,
                   "cable.tangential_drag": 0.0, "cable.axial_damping": LINEAR_DAMPING})
    return load_dynamic_scene(PROBLEM, ov)


def _cable_ocp(segments: int, time_step: float, compile_mode: str | bool,
               duration: float, linear: bool = False, tolerance: float | None = None,
               output_step: float = OUTPUT_STEP) -> tuple[np.ndarray, np.ndarray, float, str]:
    """(t, |top force|, wall time of the stepping, status) of cable_ocp's run; the top
    force is :attr:`LumpedMassModel.top_force`: the attachment's force on the cable, the
    top node's inertia included."""
    from cable_ocp.dynamics.lumped import LumpedMassModel
    from cable_ocp.dynamics.lumped_run import run
    from cable_ocp.dynamics.lumped_scene import lumped_params, lumped_start

    sc = scene(segments, time_step, duration, linear)
    model = LumpedMassModel(lumped_params(sc))
    x0, info = lumped_start(sc, model)
    if x0 is None:
        return np.zeros(0), np.zeros(0), math.nan, info["message"]
    every = max(1, int(round(output_step / time_step)))
    out = run(model, x0, None, duration, time_step, record_every=every,
              chunk_records=max(1, int(round(duration / output_step)) // 10),
              compile=compile_mode,
              tol=sc.simulation.tolerance if tolerance is None else tolerance)
    status = "ok" if out.success else out.status
    return out.t, np.linalg.norm(out.top_force, axis=1), out.wall_time_s, status


def moordyn_available() -> bool:
    """True when the optional ``moordyn`` package imports."""
    try:
        import moordyn  # noqa: F401
    except Exception:  # noqa: BLE001 - optional
        return False
    return True


@contextmanager
def _silenced() -> Any:
    """Redirect the C-level stdout and stderr to /dev/null (MoorDyn writes there)."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, 1)
        os.dup2(null, 2)
        yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (*saved, null):
            os.close(fd)


def static_unit_height(segments: int, linear: bool = False) -> float:
    """Height of the unit (m, z up from the seabed) in cable_ocp's static start of the
    benchmark scene at ``segments``: the discrete equilibrium MoorDyn starts from.

    Parameters
    ----------
    segments : int
        Number of lumped segments.
    linear : bool
        The linear case of :func:`linear_check` (the same statics).
    """
    from cable_ocp.dynamics.lumped import LumpedMassModel
    from cable_ocp.dynamics.lumped_scene import lumped_params, lumped_start

    sc = scene(segments, OUTPUT_STEP, DURATION, linear)
    x0, info = lumped_start(sc, LumpedMassModel(lumped_params(sc)))
    if x0 is None:
        from cable_ocp.errors import CableOCPError

        raise CableOCPError(f"bench dynamics: no static start: {info['message']}")
    return float(x0[2])  # free node 0 is the unit (end_a)


def _moordyn_input(sc: DynamicScene, segments: int, dtm: float, unit_height: float) -> str:
    """MoorDyn v2 input file of the benchmark scene (z = 0 at the surface, end_b there).

    The unit (MoorDyn's free point 1) starts at ``unit_height`` (m above the seabed, the
    static start's, :func:`static_unit_height`), so that the line starts stretched at its
    static equilibrium; ``ICgenDynamic 0`` (MoorDyn's stationary solver, its default,
    written out) then has nothing left to do. From the unstretched length instead, the
    stationary solver stops early at dtM <= 1 ms (the line at 8.4-63 kN during the first
    second instead of the static 36.5 kN) and ``ICgenDynamic 1`` (its drag-scaled dynamic
    relaxation) leaves it ringing at 35.9-37.1 kN; from the static start both give 36.53
    kN (docs/benchmarks.md).
    """
    st = sc.statics
    cab = st.cable
    dyn = sc.cable[0]
    unit = sc.unit
    rho = st.environment.water_density
    depth = st.environment.water_depth
    top = sc.top_position
    z_top = top[2] - depth
    volume = unit.volume if unit.volume is not None else (
        unit.mass - unit.weight_in_water / st.environment.gravity) / rho
    ca_point = unit.added_mass[0] / (rho * volume)
    cda = unit.drag_area[0] * unit.drag_coefficient[0]
    return f"""--------------------- MoorDyn Input File ------------------------------------
cable_ocp benchmark: Huang (1992) 5.7 system
---------------------- LINE TYPES ----------------------------------------------------------
TypeName Diam MassDen EA BA EI Cd Ca CdAx CaAx
(name) (m) (kg/m) (N) (N-s) (N-m^2) (-) (-) (-) (-)
cable {cab.diameter} {dyn.mass_per_length} {cab.axial_stiffness} {dyn.axial_damping} 0 \
{cab.normal_drag} {dyn.added_mass_coefficient} {cab.tangential_drag} \
{dyn.tangential_added_mass_coefficient}
---------------------- POINTS ---------------------------------------
ID Attachment X Y Z Mass Volume CdA Ca
(#) (word) (m) (m) (m) (kg) (m^3) (m^2) (-)
1 Free {top[0]} {top[1]} {unit_height - depth!r} {unit.mass} {volume} {cda} {ca_point}
2 Coupled {top[0]} {top[1]} {z_top} 0 0 0 0
---------------------- LINES ----------------------------------------
ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs
(#) (name) (ID) (ID) (m) (-) (-)
1 cable 1 2 {cab.length} {segments} -
---------------------- OPTIONS -----------------------------------------
{dtm} dtM
{depth} WtrDpth
{rho} rho
{st.environment.gravity} g
{IC_GEN_DYNAMIC} ICgenDynamic
120 TmaxIC
1e-6 threshIC
0 writeLog
------------------------- need this line -------------------------------------
"""


def _moordyn(segments: int, dtm: float, duration: float, scheme: str = "RK2",
             linear: bool = False, stage_time: bool = True
             ) -> tuple[np.ndarray, np.ndarray, float, str]:
    """(sample times, |top force| as cable_ocp defines it, wall time of the ``Step`` calls,
    status) of MoorDyn's run.

    The coupled top is given, at each coupling step [t_k, t_k+1], the position x_k and the
    mean velocity (x_k+1 - x_k) / dt_c: MoorDyn moves it as x_k + v (t - t_k) within the
    step (its ``Point::updateFairlead``), so it ends the step where the motion is. The force
    ``Step`` returns is the net force on the top node without its inertia (``Line::Fnet``,
    the cable's pull, its weight in water and drag), evaluated at the last stage of RK2,
    t_k+1 - dtM / 2 (``stage_time``: the sample's time is that one): cable_ocp's top
    force is the attachment's force on the cable, M a - F, so MoorDyn's is taken as
    M_N a(t) - F with M_N its top node's mass matrix (``GetLineNodeM``, added mass
    included) and a the prescribed acceleration (:func:`top_force_as_cable_ocp`).
    """
    import casadi as ca
    import moordyn

    from cable_ocp.scene.motion import top_offset_expr

    sc = scene(segments, OUTPUT_STEP, duration, linear)
    ts = ca.SX.sym("t")
    off = top_offset_expr(sc.top_motion, ts)
    vel = ca.jacobian(off, ts)
    motion = ca.Function("m", [ts], [off, vel, ca.jacobian(vel, ts)])
    top = np.asarray(sc.top_position, float)
    z_shift = np.array([0.0, 0.0, -sc.statics.environment.water_depth])
    text = _moordyn_input(sc, segments, dtm, static_unit_height(segments, linear))
    n_c = int(round(duration / COUPLING_STEP))
    tc = COUPLING_STEP * np.arange(n_c + 1)
    # the prescribed top at the coupling instants and its mean velocity over each step;
    # the acceleration at the sampled instants (all computed before the timing)
    pos = (top + z_shift)[:, None] + np.asarray(motion.map(n_c + 1)(tc[None, :])[0])
    v_mean = (np.diff(pos, axis=1) / COUPLING_STEP).T.tolist()
    t_s = tc[1:] - (0.5 * dtm if stage_time else 0.0)
    _, v0, _ = motion(0.0)
    acc_s = np.asarray(motion.map(n_c)(t_s[None, :])[2]).T
    pos_l = pos.T.tolist()
    forces, masses = np.empty((n_c, 3)), np.empty((n_c, 3, 3))
    status = "ok"
    wall = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "huang_5_7.txt")
        with open(path, "w") as fh:
            fh.write(text)
        with _silenced():
            try:
                system = moordyn.Create(path)
                if scheme != "RK2":
                    moordyn.SetTimeScheme(system, scheme)
                moordyn.Init(system, pos_l[0], np.asarray(v0).ravel().tolist())
                line = moordyn.GetLine(system, 1)
                top_node = moordyn.GetLineN(line)
                clock = time.perf_counter
                for k in range(n_c):
                    t0 = clock()
                    f = moordyn.Step(system, pos_l[k], v_mean[k], float(tc[k]), COUPLING_STEP)
                    wall += clock() - t0
                    forces[k] = f
                    masses[k] = moordyn.GetLineNodeM(line, top_node)
                moordyn.Close(system)
            except Exception as exc:  # noqa: BLE001 - MoorDyn's failure is a result
                interrupt.reraise_interruption(exc)
                wall = math.nan
                status = f"failed: {exc}"
    tens_a = np.linalg.norm(top_force_as_cable_ocp(forces, masses, acc_s), axis=1)
    if status == "ok" and (not np.all(np.isfinite(tens_a)) or tens_a.max() > 1e7):
        status = "unstable"
    return t_s, tens_a, wall, status


def top_force_as_cable_ocp(point_force: np.ndarray, node_mass: np.ndarray,
                           acceleration: np.ndarray) -> np.ndarray:
    """MoorDyn's coupled-point force turned into cable_ocp's top force, M a - F, N.

    MoorDyn returns the net force F on the line's top node without its inertia (what a
    coupled program adds its own inertia to); cable_ocp's
    :attr:`~cable_ocp.dynamics.lumped.LumpedMassModel.top_force` is the force the
    attachment applies to the cable, which moves the top node: M a - F with M the node's
    mass matrix (added mass included) and a its acceleration. The two differ by M a.

    Parameters
    ----------
    point_force : ndarray (n, 3)
        MoorDyn's ``Step`` force of the coupled point, N.
    node_mass : ndarray (n, 3, 3)
        MoorDyn's mass matrix of the line's top node (``GetLineNodeM``), kg.
    acceleration : ndarray (n, 3)
        The top's prescribed acceleration at the same instants, m/s^2.
    """
    return np.einsum("nij,nj->ni", node_mass, acceleration) - point_force


def _window(t: np.ndarray, y: np.ndarray, duration: float) -> tuple[np.ndarray, np.ndarray]:
    keep = t >= duration - WINDOW - 1e-9
    return t[keep], y[keep]


def _amplitude(t: np.ndarray, y: np.ndarray, duration: float) -> float:
    _, yw = _window(t, y, duration)
    return 0.5 * float(np.ptp(yw)) if yw.size else math.nan


def _error(t: np.ndarray, y: np.ndarray, ref: Reference, duration: float) -> float:
    tw, yw = _window(t, y, duration)
    if yw.size == 0 or ref.t.size == 0:
        return math.nan
    return float(np.max(np.abs(yw - ref(tw))) / ref.amplitude)


@dataclass
class Reference:
    """The converged top force both models' rows are compared with (:func:`reference`).

    Attributes
    ----------
    t : ndarray
        Sample times, s.
    y : ndarray
        Top-force magnitude, N (Richardson-extrapolated in the number of segments).
    amplitude : float
        Half its peak-to-peak over the last :data:`WINDOW` seconds, N.
    info : dict
        ``segments``, ``time_step``, ``output_step``, ``status``, ``richardson_correction``
        (largest change of the extrapolation over the finer run, over the amplitude: the
        finer run's own spatial error estimate) and ``halving_ratio`` (the coarser pair's
        difference over the finer pair's: 4 for O(1/N^2); None with two runs).
    """

    t: np.ndarray
    y: np.ndarray
    amplitude: float
    info: dict[str, Any]

    def __call__(self, times: np.ndarray) -> np.ndarray:
        """The reference at ``times`` (s): a cubic spline through its samples (its 8 ms
        samples interpolated linearly would err by ~1e-4 of the amplitude)."""
        from scipy.interpolate import CubicSpline

        return CubicSpline(self.t, self.y)(times)


def reference(duration: float = DURATION, segments: Sequence[int] = REFERENCE_SEGMENTS,
              time_step: float = REFERENCE_STEP, compile_mode: str | bool = "kernel"
              ) -> Reference:
    """One converged top force for both models: cable_ocp at ``segments`` (the last two
    Richardson-extrapolated for a spatial error O(1/N^2), y = y2 + (y2 - y1) / (r^2 - 1),
    r = N2 / N1) at a small step (the time error O(dt^2): ~2e-5 of the amplitude at 4 ms).

    Why cable_ocp's model and not MoorDyn's: its time step can be small at many segments
    without an explicit stability limit; MoorDyn's rows converge to the same reference as
    their segments grow (the benchmark's 160-segment rows show it). A third (coarser) entry
    of ``segments`` gives ``halving_ratio``, the check of the O(1/N^2) assumption.

    Parameters
    ----------
    duration : float
        Simulated time, s.
    segments : sequence of int
        Two or three numbers of segments, increasing by the same ratio.
    time_step : float
        Time step, s.
    compile_mode : {"kernel", "step", False}
        See :func:`run` (default ``"kernel"``: not timed, and the C compilation of a whole
        step at 320 segments takes minutes).
    """
    runs = [_cable_ocp(n, time_step, compile_mode, duration, output_step=REFERENCE_OUTPUT)
            for n in segments]
    status = next((r[3] for r in runs if r[3] != "ok"), "ok")
    t, y1, y2 = runs[-1][0], runs[-2][1], runs[-1][1]
    info: dict[str, Any] = {"segments": list(segments), "time_step": time_step,
                            "output_step": REFERENCE_OUTPUT, "status": status,
                            "richardson_correction": None, "halving_ratio": None}
    if status != "ok" or y1.shape != y2.shape:
        return Reference(t, y2, _amplitude(t, y2, duration), info)
    ratio = segments[-1] / segments[-2]
    y = y2 + (y2 - y1) / (ratio**2 - 1.0)
    amp = _amplitude(t, y, duration)
    keep = t >= duration - WINDOW - 1e-9
    info["richardson_correction"] = float(np.max(np.abs(y - y2)[keep]) / amp)
    if len(runs) >= 3 and runs[0][1].shape == y1.shape:
        info["halving_ratio"] = float(np.max(np.abs(runs[0][1] - y1)[keep])
                                      / np.max(np.abs(y1 - y2)[keep]))
    return Reference(t, y, amp, info)


def run(segments: Sequence[int] = SEGMENTS,
        time_steps: Sequence[float] = TIME_STEPS,
        moordyn_steps: dict[int, Sequence[float]] | None = None, *,
        with_moordyn: bool = True, compile_mode: str | bool = "step", repeats: int = 2,
        duration: float = DURATION, tolerance: float = TOLERANCE,
        reference_segments: Sequence[int] = REFERENCE_SEGMENTS,
        reference_step: float = REFERENCE_STEP,
        progress: Callable[[str], None] | None = None) -> tuple[list[BenchRow], Reference]:
    """Run the benchmark and return its rows and the reference (prints nothing).

    Every row's ``error`` is against the one :func:`reference` (the spatial and the time
    error together); ``amplitude_vs_other`` compares the finest-step rows of the two models
    at the same segments.

    Parameters
    ----------
    segments : sequence of int
        Numbers of lumped segments.
    time_steps : sequence of float
        cable_ocp's time steps, s.
    moordyn_steps : dict, optional
        MoorDyn's dtM per number of segments, s; default :data:`DEFAULT_MOORDYN_STEPS`
        (its largest stable step, found by halving from 8 ms, and half of it).
    with_moordyn : bool
        Include MoorDyn when it is installed.
    compile_mode : {"step", "kernel", False}
        See :func:`cable_ocp.dynamics.lumped_run.run` (``"step"``: a few seconds of C
        compilation per new scene and step, cached, not counted in the wall time).
    repeats : int
        Timed runs per row; the fastest is kept.
    duration : float
        Simulated time, s (the errors and amplitudes use its last 10 s).
    tolerance : float
        Newton tolerance of cable_ocp's timed runs (scaled residual, -; the reference
        uses the scene's, 1e-10, so that the errors include the Newton error).
    reference_segments : sequence of int
        Segments of :func:`reference`.
    reference_step : float
        Time step of :func:`reference`, s.
    progress : callable, optional
        Called with a short label before each row (and before the reference).
    """
    if moordyn_steps is None:
        moordyn_steps = {n: DEFAULT_MOORDYN_STEPS.get(n, (1e-3,)) for n in segments}
    use_md = with_moordyn and moordyn_available()
    if progress:
        progress(f"reference: cable_ocp at {', '.join(map(str, reference_segments))} "
                 f"segments, dt = {reference_step:g} s")
    ref = reference(duration, reference_segments, reference_step,
                    "kernel" if compile_mode == "step" else compile_mode)
    bad_ref = "" if ref.info["status"] == "ok" else f" (reference {ref.info['status']})"
    rows: list[BenchRow] = []
    for n in segments:
        for dt in time_steps:
            if progress:
                progress(f"cable_ocp, {n} segments, dt = {dt} s")
            best = None
            for _ in range(max(1, repeats)):
                res = _cable_ocp(n, dt, compile_mode, duration, tolerance=tolerance)
                if best is None or res[2] < best[2]:
                    best = res
            t, y, wall, status = best  # type: ignore[misc]
            amp = _amplitude(t, y, duration)
            rows.append(BenchRow(
                model="cable_ocp midpoint", segments=n, time_step=dt,
                wall_per_simulated_s=wall / duration, realtime_factor=duration / wall,
                top_tension_amplitude_N=amp, error=_error(t, y, ref, duration),
                amplitude_vs_reference=amp / ref.amplitude - 1.0, amplitude_vs_other=None,
                status=status + bad_ref))
        if not use_md:
            if with_moordyn:  # asked for but absent: say so in the table
                for dtm in moordyn_steps.get(n, ()):
                    rows.append(BenchRow(
                        model="MoorDyn RK2", segments=n, time_step=dtm,
                        wall_per_simulated_s=math.nan, realtime_factor=math.nan,
                        top_tension_amplitude_N=math.nan, error=math.nan,
                        amplitude_vs_reference=math.nan, amplitude_vs_other=None,
                        status="not installed (pip install moordyn)"))
            continue
        for dtm in moordyn_steps.get(n, ()):
            if progress:
                progress(f"MoorDyn, {n} segments, dtM = {dtm} s")
            best = None
            for _ in range(max(1, repeats)):
                res = _moordyn(n, dtm, duration)
                if best is None or not (res[2] >= best[2]):
                    best = res
            t, y, wall, status = best  # type: ignore[misc]
            ok = status == "ok"
            amp = _amplitude(t, y, duration) if ok else math.nan
            rows.append(BenchRow(
                model="MoorDyn RK2", segments=n, time_step=dtm,
                wall_per_simulated_s=wall / duration if ok else math.nan,
                realtime_factor=duration / wall if ok else math.nan,
                top_tension_amplitude_N=amp,
                error=_error(t, y, ref, duration) if ok else math.nan,
                amplitude_vs_reference=amp / ref.amplitude - 1.0, amplitude_vs_other=None,
                status=status))
    _compare_amplitudes(rows)
    return rows, ref


def _compare_amplitudes(rows: list[BenchRow]) -> None:
    """``amplitude_vs_other`` of every row: its model's finest-step amplitude at its
    segments against the other model's (None where either has no good row)."""
    finest: dict[tuple[str, int], float] = {}
    for r in sorted(rows, key=lambda r: -r.time_step):
        if r.status == "ok" and math.isfinite(r.top_tension_amplitude_N):
            finest[(r.model.split()[0], r.segments)] = r.top_tension_amplitude_N
    for r in rows:
        me, other = r.model.split()[0], ("MoorDyn" if r.model.startswith("cable") else
                                         "cable_ocp")
        if (me, r.segments) in finest and (other, r.segments) in finest:
            r.amplitude_vs_other = finest[(me, r.segments)] / finest[(other, r.segments)] - 1


def format_table(rows: Sequence[BenchRow]) -> str:
    """The rows as a plain-text table (for the CLI; this module prints nothing), by
    :func:`cable_ocp.numerics.text_table.table`."""
    def num(v: float, spec: str, scale: float = 1.0) -> str:
        return "-" if not math.isfinite(v) else format(v * scale, spec)

    def pct(v: float | None) -> str:
        return "" if v is None else ("-" if not math.isfinite(v) else f"{100 * v:+.2f} %")

    cells = [[r.model, r.segments, f"{r.time_step:.4g}",
              num(r.wall_per_simulated_s, ".2f", 1e3), num(r.realtime_factor, ".0f"),
              num(r.top_tension_amplitude_N, ".3f", 1e-3), num(r.error, ".2e"),
              pct(r.amplitude_vs_reference), pct(r.amplitude_vs_other),
              r.status] for r in rows]
    return table(["model", "N", "dt", "wall/sim", "x real", "F amp", "error",
                  "amp-ref", "amp-other", "status"], cells,
                 ["", "", "[s]", "[ms/s]", "time", "[kN]", "[-]", "", "", ""], left=1)


def format_reference(ref: Reference) -> str:
    """One line on the reference of :func:`run` (for the CLI)."""
    i = ref.info
    text = (f"reference: cable_ocp at {'/'.join(map(str, i['segments'][-2:]))} segments "
            f"Richardson-extrapolated, dt = {i['time_step']:g} s, amplitude "
            f"{ref.amplitude / 1e3:.3f} kN")
    if i["richardson_correction"] is not None:
        text += f"; extrapolation changed the finer run by {i['richardson_correction']:.1e}"
    if i["halving_ratio"] is not None:
        text += (f"; differences {i['segments'][0]}-{i['segments'][1]} over "
                 f"{i['segments'][1]}-{i['segments'][2]}: {i['halving_ratio']:.2f} (4 for "
                 "O(1/N^2))")
    return text if i["status"] == "ok" else text + f"; status {i['status']}"


def as_dicts(rows: Sequence[BenchRow]) -> list[dict[str, Any]]:
    """The rows as JSON-ready dictionaries."""
    return [asdict(r) for r in rows]


def _first_harmonic(t: np.ndarray, y: np.ndarray, w: float) -> float:
    basis = np.column_stack([np.ones_like(t), np.sin(w * t), np.cos(w * t),
                             np.sin(2 * w * t), np.cos(2 * w * t)])
    coef = np.linalg.lstsq(basis, y, rcond=None)[0]
    return float(np.hypot(coef[1], coef[2]))


def linear_check(segments: int = 20, duration: float = 60.0, with_moordyn: bool = True
                 ) -> dict[str, Any]:
    """The top-tension amplitude of a linear case against its closed form.

    The benchmark line heaving alone (no drag, internal damping 2e6 N s): a viscoelastic rod
    with a tip mass M (unit mass + added mass), whose steady response to z_b = sin(w t)
    is closed-form (EA* = EA + i w c, k^2 = mu w^2 / EA*, u = B cos(k s) + C sin(k s),
    -M w^2 B = EA* k C, u(L) = 1; top tension EA* u'(L)). Returns the first-harmonic
    amplitudes of the top tension (N) over the last 20 s: ``closed_form``,
    ``cable_ocp`` (dt = 0.0125 s) and ``moordyn`` (dtM = 0.25 ms; None without it).

    Parameters
    ----------
    segments : int
        Number of lumped segments of both models (default 20).
    duration : float
        Simulated time, s (default 60); the amplitudes are fitted over its last 20 s, so
        it should be well above 20 s (the start transient must have decayed).
    with_moordyn : bool
        Also run MoorDyn when it is installed (default True).
    """
    import cmath

    sc = scene(segments, 0.0125, duration, linear=True)
    st = sc.statics
    ea = st.cable.axial_stiffness
    mu = sc.cable[0].mass_per_length
    big_m = sc.unit.mass + sc.unit.added_mass[2]  # type: ignore[union-attr]
    w = FREQUENCY
    es = ea + 1j * w * LINEAR_DAMPING
    k = w * cmath.sqrt(mu / es)
    length = float(st.cable.length)  # type: ignore[arg-type]
    b = 1.0 / (cmath.cos(k * length) - big_m * w * w / (es * k) * cmath.sin(k * length))
    c = -big_m * w * w * b / (es * k)
    closed = abs(es * k * (-b * cmath.sin(k * length) + c * cmath.cos(k * length)))
    t, y, _, status = _cable_ocp(segments, 0.0125, "kernel", duration, linear=True)
    keep = t >= duration - 20.0
    out: dict[str, Any] = {"closed_form": closed,
                           "cable_ocp": _first_harmonic(t[keep], y[keep], w),
                           "cable_ocp_status": status, "moordyn": None}
    if with_moordyn and moordyn_available():
        tm, ym, _, st_md = _moordyn(segments, 2.5e-4, duration, linear=True)
        keep = tm >= duration - 20.0
        out["moordyn"] = _first_harmonic(tm[keep], ym[keep], w) if st_md == "ok" else None
        out["moordyn_status"] = st_md
    return out


def planned_rows(segments: Sequence[int], time_steps: Sequence[float],
                 moordyn_steps: dict[int, Sequence[float]] | None, with_moordyn: bool
                 ) -> int:
    """How many ``progress`` calls :func:`run` makes (references included).

    Parameters
    ----------
    segments : sequence of int
        Numbers of lumped segments, as given to :func:`run`.
    time_steps : sequence of float
        cable_ocp's time steps, s, as given to :func:`run`.
    moordyn_steps : dict or None
        MoorDyn's dtM (s) per number of segments, as given to :func:`run`; None: the
        defaults :func:`run` uses (:data:`DEFAULT_MOORDYN_STEPS`).
    with_moordyn : bool
        As given to :func:`run`; MoorDyn rows count only when it is also installed.
    """
    use_md = with_moordyn and moordyn_available()
    md = moordyn_steps or {n: DEFAULT_MOORDYN_STEPS.get(n, (1e-3,)) for n in segments}
    return 1 + sum(len(time_steps) + (len(md.get(n, ())) if use_md else 0) for n in segments)


def row_ok(r: BenchRow) -> bool:
    """The row ran and has a finite time and error."""
    return r.status == "ok" and math.isfinite(r.wall_per_simulated_s) and math.isfinite(r.error)


def summary(rows: Sequence[BenchRow], accuracy: float = EQUAL_ACCURACY) -> dict[str, Any]:
    """The project's two speed targets from the rows of :func:`run`.

    * ``realtime``: at :data:`TARGET_SEGMENTS` segments, cable_ocp's fastest row whose
      top-tension error is within ``accuracy`` of the amplitude: its real-time factor
      against :data:`TARGET_REALTIME`.
    * ``versus_moordyn``: per number of segments, the fastest row of each model within
      ``accuracy`` (both against the one reference of :func:`run`) and the ratio of
      MoorDyn's wall time to cable_ocp's (>= 1: cable_ocp no slower at equal accuracy);
      where no MoorDyn row is within ``accuracy``, MoorDyn's fastest row against cable_ocp's
      fastest row at least as accurate (``basis`` says which); plus the
      relative difference of the two models' finest-step top-force amplitudes (the target
      is 2 %).
    * ``overall``: the same at any number of segments: the fastest row of each model within
      ``accuracy`` of the reference, whatever its segments (what a user choosing a
      discretisation for that accuracy gets).

    Parameters
    ----------
    rows : sequence of BenchRow
        The rows of :func:`run`.
    accuracy : float
        Largest relative top-tension error (-) for "equal accuracy" (default
        :data:`EQUAL_ACCURACY`, 0.01 = 1 %).
    """
    out: dict[str, Any] = {"accuracy": accuracy, "target_realtime": TARGET_REALTIME,
                           "target_segments": TARGET_SEGMENTS, "realtime": None,
                           "versus_moordyn": [], "overall": None}

    def brief(r: BenchRow) -> dict[str, Any]:
        return {"segments": r.segments, "time_step": r.time_step,
                "wall_per_simulated_s": r.wall_per_simulated_s, "error": r.error}

    good = [r for r in rows if row_ok(r) and r.error <= accuracy]
    best = {m: min((r for r in good if r.model.startswith(m)),
                   key=lambda r: r.wall_per_simulated_s, default=None)
            for m in ("cable_ocp", "MoorDyn")}
    if best["cable_ocp"] is not None and best["MoorDyn"] is not None:
        ratio = best["MoorDyn"].wall_per_simulated_s / best["cable_ocp"].wall_per_simulated_s
        out["overall"] = {"cable_ocp": brief(best["cable_ocp"]),
                          "moordyn": brief(best["MoorDyn"]), "speed_ratio": ratio,
                          "met": ratio >= 1.0}

    def fastest(model_prefix: str, n: int) -> BenchRow | None:
        cand = [r for r in rows if r.model.startswith(model_prefix) and r.segments == n
                and row_ok(r) and r.error <= accuracy]
        return min(cand, key=lambda r: r.wall_per_simulated_s) if cand else None

    ours40 = fastest("cable_ocp", TARGET_SEGMENTS)
    if ours40 is not None:
        out["realtime"] = {"time_step": ours40.time_step,
                           "realtime_factor": ours40.realtime_factor,
                           "error": ours40.error,
                           "met": ours40.realtime_factor >= TARGET_REALTIME}
    for n in dict.fromkeys(r.segments for r in rows):
        ours = fastest("cable_ocp", n)
        md = fastest("MoorDyn", n)
        md_rows = [r for r in rows if r.model.startswith("MoorDyn") and r.segments == n]
        entry: dict[str, Any] = {
            "segments": n,
            "cable_ocp": None if ours is None else {
                "time_step": ours.time_step, "wall_per_simulated_s": ours.wall_per_simulated_s,
                "error": ours.error},
            "moordyn": None if md is None else {
                "time_step": md.time_step, "wall_per_simulated_s": md.wall_per_simulated_s,
                "error": md.error},
            "moordyn_status": ("not run" if not md_rows else "ok" if md is not None else
                               md_rows[0].status if not md_rows[0].status == "ok" else
                               f"has no row within {accuracy:.0%}"),
            "speed_ratio": None, "met": None, "amplitude_difference": None,
            "basis": f"error <= {accuracy:.0%}"}
        md_ok = [r for r in md_rows if row_ok(r)]
        if md is None and md_ok:
            # MoorDyn reaches no row within the accuracy: compare at its own accuracy,
            # its fastest row against cable_ocp's fastest row that is at least as accurate
            md = min(md_ok, key=lambda r: r.wall_per_simulated_s)
            cand = [r for r in rows if r.model.startswith("cable_ocp") and r.segments == n
                    and row_ok(r) and r.error <= md.error]
            ours = min(cand, key=lambda r: r.wall_per_simulated_s) if cand else None
            entry.update(basis=f"MoorDyn's own accuracy ({md.error:.2g})", moordyn_status="ok",
                         moordyn={"time_step": md.time_step,
                                  "wall_per_simulated_s": md.wall_per_simulated_s,
                                  "error": md.error},
                         cable_ocp=None if ours is None else {
                             "time_step": ours.time_step,
                             "wall_per_simulated_s": ours.wall_per_simulated_s,
                             "error": ours.error})
        if ours is not None and md is not None:
            ratio = md.wall_per_simulated_s / ours.wall_per_simulated_s
            entry.update(speed_ratio=ratio, met=ratio >= 1.0)
        amp = [r.amplitude_vs_other for r in rows if r.model.startswith("cable_ocp")
               and r.segments == n and r.amplitude_vs_other is not None]
        if amp:
            entry["amplitude_difference"] = amp[0]
        out["versus_moordyn"].append(entry)
    return out


def format_summary(sm: dict[str, Any]) -> str:
    """The targets of :func:`summary` as text lines."""
    acc = sm["accuracy"]
    lines = []
    rt = sm["realtime"]
    if rt is None:
        lines.append(f"target {sm['target_realtime']:.0f}x real time at "
                     f"{sm['target_segments']} segments: no cable_ocp row at that many "
                     f"segments within {acc:.0%} (not run or not accurate enough)")
    else:
        lines.append(f"target {sm['target_realtime']:.0f}x real time at "
                     f"{sm['target_segments']} segments (error <= {acc:.0%}): "
                     f"{rt['realtime_factor']:.0f}x at dt = {rt['time_step']:g} s -> "
                     f"{'met' if rt['met'] else 'NOT met'}")
    for e in sm["versus_moordyn"]:
        head = (f"{e['segments']} segments vs MoorDyn at equal accuracy "
                f"({e.get('basis', f'error <= {acc:.0%}')}): ")
        if e["cable_ocp"] is None or e["moordyn"] is None:
            why = ("MoorDyn " + e["moordyn_status"]) if e["moordyn"] is None else \
                "no cable_ocp row within the accuracy"
            lines.append(head + why)
        else:
            lines.append(head + f"cable_ocp {e['cable_ocp']['wall_per_simulated_s'] * 1e3:.2f}"
                         f" ms (dt {e['cable_ocp']['time_step']:g} s) vs MoorDyn "
                         f"{e['moordyn']['wall_per_simulated_s'] * 1e3:.2f} ms (dtM "
                         f"{e['moordyn']['time_step']:g} s): MoorDyn/cable_ocp = "
                         f"{e['speed_ratio']:.2f} -> {'met' if e['met'] else 'NOT met'}")
        if e["amplitude_difference"] is not None:
            lines.append(f"    finest-step top-force amplitudes differ by "
                         f"{100 * e['amplitude_difference']:+.2f} % (target within 2 %)")
    o = sm.get("overall")
    if o is not None:
        c, m = o["cable_ocp"], o["moordyn"]
        lines.append(f"at any segments within {acc:.0%} of the reference: cable_ocp "
                     f"{c['wall_per_simulated_s'] * 1e3:.2f} ms ({c['segments']} segments, dt "
                     f"{c['time_step']:g} s, error {c['error']:.2g}) vs MoorDyn "
                     f"{m['wall_per_simulated_s'] * 1e3:.2f} ms ({m['segments']} segments, "
                     f"dtM {m['time_step']:g} s, error {m['error']:.2g}): MoorDyn/cable_ocp "
                     f"= {o['speed_ratio']:.2f}")
    return "\n".join(lines)
