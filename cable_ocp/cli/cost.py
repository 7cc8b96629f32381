"""Cost estimates of a validated scene, and the limits above which a command refuses it.

A value can be legal and still cost hours or gigabytes (a fine statics mesh of a high
degree, a long MPC horizon, a long delay in samples, many plant substeps over a long
duration). The commands estimate the cost before any work and refuse above
:data:`TIME_LIMIT_S` or :data:`MEMORY_LIMIT_B`, with the estimate and the key to change in
the message; ``--force`` runs it anyway.

The constants are CPU seconds and bytes measured on the development machine (one x86 core
of 2024, Python 3.11, CasADi 3.8, scipy 1.17) with the shipped scenes; the estimates are
rough, good to a factor of about 2-3, which is enough to tell a minute from an hour.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cable_ocp.errors import CableOCPError

#: refuse above 10 minutes of estimated run time: longer than a user waits without
#: suspecting a hang, and ~30x the shipped examples
TIME_LIMIT_S = 600.0
#: refuse above 4 GB of estimated memory: half of a small laptop's RAM
MEMORY_LIMIT_B = 4e9

# --- statics (collocation: unit = one interval of degree d, (d + 1)^2 Jacobian blocks) ----
#: CPU seconds per unit N (d + 1)^2 of a collocation solve (1.7e-4 at N = 640, d = 3;
#: 1.4e-4 at N = 320, d = 9; 2.6e-4 at N = 5000, d = 3; rounded up)
COLLOCATION_S_PER_UNIT = 3e-4
#: bytes per unit N (d + 1)^2 (0.64 GB at N = 5000, d = 3; 1.46 GB at N = 2560, d = 9)
COLLOCATION_B_PER_UNIT = 6.5e3
#: CPU seconds per interval of the other methods (N = 160-640 on De Zoysa)
METHOD_S_PER_INTERVAL = {"multiple_shooting": 1e-3, "solve_bvp": 1e-3,
                         "huang_semianalytic": 1e-3, "wang_shooting_optimization": 0.015,
                         "chucheepsakul_fem": 0.02}
#: an error estimate re-solves on N/2 and N/4 (collocation) or N/2 (the others)
ESTIMATE_FACTOR = {"collocation": 1.75, "multiple_shooting": 1.75}
#: a footprint direction is one NLP over the collocated statics, ~2 solves
FOOTPRINT_SOLVES_PER_DIRECTION = 2.0

# --- heave ---------------------------------------------------------------------------
#: CPU seconds per plant step (RK4 of unit and winch, one run)
HEAVE_S_PER_FINE_STEP = 5.5e-5
#: CPU seconds of a discrete Riccati design on n + d states: 0.5 + 3e-7 (n + d)^3
#: (20 s at n + d = 411)
DARE_S_CUBE = 3e-7
#: MPC: build 7e-7 N^3 s, each step 2e-3 max(1, N/50)^3 s (qpOASES, condensed QP)
MPC_BUILD_S_CUBE = 7e-7
MPC_STEP_S = 2e-3
#: CPU seconds per element and midpoint step of the axial cable plant (compiled block
#: tridiagonal Newton: 0.035 ms per step of 50 elements, 7e-7 per element; the estimator
#: and the loop's Python roughly double it)
CABLE_S_PER_ELEMENT_STEP = 1.5e-6
#: the same per cable model: the planar and lumped3d plants (compiled sparse-QR Newton)
#: cost 2-5 times the axial one per sample at 20-50 elements (0.1-0.3 ms per step; the
#: loop around it as for the axial one), rounded up
CABLE_S_PER_ELEMENT_STEP_BY_MODEL = {"axial": CABLE_S_PER_ELEMENT_STEP, "planar": 1e-5,
                                     "lumped3d": 1.2e-5}
#: the lumped3d deployment plant (heave/lumped_deploy.py: CasADi's rootfinder, not compiled,
#: Python per sample): measured 3.3 ms per step at about 10 segments on the loaded machine
LUMPED_PAYOUT_S_PER_ELEMENT_STEP = 3e-4


@dataclass
class Cost:
    """An estimate: CPU seconds and bytes, with its parts (what, s, bytes, the keys that
    drive it)."""

    seconds: float = 0.0
    bytes: float = 0.0
    parts: list[tuple[str, float, float, str]] = field(default_factory=list)

    def add(self, what: str, seconds: float, nbytes: float, keys: str) -> None:
        """Add a part.

        Parameters
        ----------
        what : str
            What the part is, for the message (e.g. ``"a collocation solve on 640
            intervals of degree 3"``).
        seconds : float
            Its estimated CPU time, s (added to :attr:`seconds`).
        nbytes : float
            Its estimated memory, bytes (added to :attr:`bytes`).
        keys : str
            The scene keys or options that drive it, named in a refusal as what to change
            (e.g. ``"solver.intervals = 640 with solver.degree = 3"``).
        """
        self.seconds += seconds
        self.bytes += nbytes
        self.parts.append((what, seconds, nbytes, keys))

    @property
    def main(self) -> tuple[str, float, float, str]:
        """The part nearest to (or furthest over) a limit."""
        return max(self.parts, key=lambda p: max(p[1] / TIME_LIMIT_S, p[2] / MEMORY_LIMIT_B))

    @property
    def too_much(self) -> bool:
        """True above :data:`TIME_LIMIT_S` or :data:`MEMORY_LIMIT_B`."""
        return self.seconds > TIME_LIMIT_S or self.bytes > MEMORY_LIMIT_B

    def describe(self) -> str:
        """``about 25 min of CPU and 1.2 GB of memory (mostly ...)``."""
        what, sec, nb, _ = self.main
        return (f"about {_duration(self.seconds)} of CPU and {_size(self.bytes)} of memory "
                f"(mostly {what}: {_duration(sec)}, {_size(nb)})")


def _duration(s: float) -> str:
    if s < 120:
        return f"{s:.0f} s"
    if s < 7200:
        return f"{s / 60:.0f} min"
    if s < 2 * 86400:
        return f"{s / 3600:.1f} h"
    return f"{s / 86400:.3g} days"


def _size(b: float) -> str:
    return f"{b / 1e9:.3g} GB" if b >= 1e8 else f"{b / 1e6:.0f} MB"


def check_cost(cost: Cost, force: bool = False) -> None:
    """Raise :class:`CableOCPError` when ``cost`` is above the limits and not ``force``.

    Parameters
    ----------
    cost : Cost
        The run's estimate; refused above :data:`TIME_LIMIT_S` (s of CPU) or
        :data:`MEMORY_LIMIT_B` (bytes), the message naming its largest part's keys.
    force : bool
        Run anyway (``--force``); default False.
    """
    if force or not cost.too_much:
        return
    raise CableOCPError(
        f"{cost.main[3]}: this run would take {cost.describe()}, above the limits of "
        f"{_duration(TIME_LIMIT_S)} and {_size(MEMORY_LIMIT_B)}: lower them, or pass --force "
        "to run it anyway")


def _mesh_total(scene: Any, n: int) -> int:
    """Intervals in all on a mesh of ``n``: a multi-segment line gives each segment its own
    ``intervals`` or a share of ``solver.intervals`` (at least 2), scaled by
    ``n / solver.intervals`` on other meshes (as the collocation does)."""
    if not scene.segments:
        return n
    total = sum(c.length for c in scene.segments)
    base = [iv if iv is not None else max(2, round(scene.solver.intervals * c.length / total))
            for c, iv in zip(scene.segments, scene.segment_intervals, strict=True)]
    return max(round(sum(base) * n / scene.solver.intervals), len(base))


def statics_cost(scene: Any, directions: int | None = None) -> Cost:
    """Estimate of the largest statics solve a scene allows (its mesh, or the refinement's
    ``max_intervals``), with its error estimate; with ``directions``, of a footprint.

    Parameters
    ----------
    scene : Scene
        The validated statics scene (:class:`cable_ocp.scene.Scene`): its ``solver``
        options and segments set the mesh.
    directions : int, optional
        Number of footprint directions (``--directions``): the estimate is then of that
        many footprint NLPs on the scene's mesh (no refinement, no error estimate). None
        (default): one solve.
    """
    opts = scene.solver
    n = opts.intervals
    if opts.refine and opts.error_estimate and directions is None:
        n = max(n, opts.max_intervals)
    cost = Cost()
    method = opts.method
    n = _mesh_total(scene, n)
    if method == "collocation":
        units = n * (opts.degree + 1) ** 2
        sec = COLLOCATION_S_PER_UNIT * units
        nbytes = COLLOCATION_B_PER_UNIT * units
        what = f"a collocation solve on {n} intervals of degree {opts.degree}"
    else:
        sec = METHOD_S_PER_INTERVAL.get(method, 1e-3) * n
        nbytes = 2e4 * n
        what = f"a {method} solve on {n} intervals"
    keys = (f"solver.intervals = {opts.intervals}" if n == _mesh_total(scene, opts.intervals)
            else f"solver.max_intervals = {opts.max_intervals} (refinement)")
    if any(iv is not None for iv in scene.segment_intervals):
        keys += " and the segments' intervals"
    if method == "collocation":
        keys += f" with solver.degree = {opts.degree}"
    if directions is not None:
        cost.add(f"{directions} footprint directions, each {what}",
                 directions * FOOTPRINT_SOLVES_PER_DIRECTION * sec, nbytes,
                 f"--directions {directions} and {keys}")
    elif opts.error_estimate:
        cost.add(f"{what} and its error estimate", ESTIMATE_FACTOR.get(method, 1.5) * sec,
                 nbytes, keys)
    else:
        cost.add(what, sec, nbytes, keys)
    return cost


def heave_cost(scene: Any) -> Cost:
    """Estimate of a heave comparison: plant steps, Riccati designs, MPC."""
    from cable_ocp.heave.discrete import delay_steps

    c, sim = scene.controller, scene.simulation
    h = c.sample_time
    steps = int(round(sim.duration / h))
    fine = steps * sim.substeps
    ctrls = tuple(c.controllers)
    runs = len(ctrls) + (0 if "passive" in ctrls else 1)
    # states: unit + winch (3-4), vessel (2), sea filter (2 per section, <= 12)
    n_sea = 2 if scene.vessel.model == "second_order" else 0
    n_sea += 2 * (3 if scene.sea.shaping_filter == "thesis" else scene.sea.filter_order)
    n = (3 if scene.winch.model == "first_order" else 4) + n_sea
    d = delay_steps(scene.winch.delay, h)
    nz = n + d
    fine_all = fine + int(round(c.preview_time / h + 1)) * sim.substeps
    cost = Cost()
    cost.add(f"{runs} runs x {fine} plant steps ({steps} samples x {sim.substeps} substeps)",
             HEAVE_S_PER_FINE_STEP * fine * runs,
             8.0 * fine_all * (2 * n_sea + 2) + 8.0 * 6 * fine * len(ctrls),
             f"simulation.duration = {sim.duration:g} s with simulation.substeps = "
             f"{sim.substeps} and controller.sample_time = {h:g} s")
    designs = 1 + ("lqg" in ctrls) + ("mpc" in ctrls)
    cost.add(f"{designs} Riccati design(s) on {nz} states ({d} delay samples)",
             designs * (0.5 + DARE_S_CUBE * nz**3), 8.0 * 8 * nz**2,
             f"winch.delay = {scene.winch.delay:g} s over controller.sample_time = {h:g} s "
             f"({d} samples)")
    if "mpc" in ctrls:
        hz = c.horizon
        cost.add(f"the MPC with a {hz}-sample horizon over {steps} samples",
                 MPC_BUILD_S_CUBE * hz**3 + steps * MPC_STEP_S * max(1.0, hz / 50) ** 3,
                 8.0 * hz**2 * (nz + 8), f"controller.horizon = {hz}")
    if scene.unit.cable_scene is not None:
        _cable_cost(scene, cost, runs)
    return cost


def _cable_cost(sc: Any, cost: Cost, runs: int) -> None:
    """The cable parts of a heave scene with ``unit.cable_scene``: the identification
    experiment(s) and the closed-loop runs on the cable scene's line."""
    from cable_ocp.scene.heave import load_cable_scene

    dyn = load_cable_scene(sc)
    n, dt = dyn.simulation.segments, dyn.simulation.time_step
    per_step = CABLE_S_PER_ELEMENT_STEP_BY_MODEL.get(dyn.simulation.model,
                                                     CABLE_S_PER_ELEMENT_STEP) * n
    dep = sc.deployment
    n_ident = 1
    if dep is not None:
        n_ident = 1 + (len(dep.schedule_lengths) if dep.schedule_lengths else 7)
    ident = sc.identification.duration / dt
    cost.add(f"{n_ident} identification run(s) of {ident:.0f} steps of a {n}-element line",
             n_ident * ident * per_step, 8.0 * ident * 4 * n,
             f"identification.duration = {sc.identification.duration:g} s with the cable "
             f"scene's simulation.time_step = {dt:g} s and segments = {n}")
    if dep is not None and dep.final_length is not None:
        dur = (sc.simulation.warmup + abs(dep.final_length - dyn.length) / dep.payout_speed
               + dep.ramp_time + 20.0)
        what, nruns = f"3 deployment runs of {dur:.0f} s", 3
        keys = (f"deployment.payout_speed = {dep.payout_speed:g} m/s from {dyn.length:g} to "
                f"deployment.final_length = {dep.final_length:g} m")
    elif sc.simulation.plant == "cable":
        dur, nruns = sc.simulation.duration, runs
        what = f"{runs} runs of {dur:g} s on the cable"
        keys = f"simulation.duration = {dur:g} s with simulation.plant = \"cable\""
    else:
        return
    steps = dur / dt
    if dep is not None and dyn.simulation.model == "lumped3d":  # the pay-out plant
        le = dyn.simulation.element_length or dyn.length / n
        n = max(1, int(round(0.5 * (dyn.length + dep.final_length) / le)))  # on average
        per_step = LUMPED_PAYOUT_S_PER_ELEMENT_STEP * n
    cost.add(f"{what} ({steps:.0f} steps of a {n}-element line each)",
             nruns * steps * per_step, 8.0 * steps * 12 * nruns, keys)


# --- dynamics --------------------------------------------------------------------------
#: CPU seconds per segment and time step, by model (measured: axial 20 elements at dt
#: 0.05 s, 8.5 ms per simulated second -> 2e-5; planar ~2.5x that; lumped3d 40 segments
#: 0.4-0.6 ms per compiled step -> 1.5e-5, ~5x more interpreted; rounded up)
DYNAMICS_S_PER_SEGMENT_STEP = {"axial": 2e-5, "planar": 5e-5, "lumped3d": 5e-5}
#: CPU seconds per segment to build (and, for the lumped-mass model, compile) the step
#: (7 s for 40 segments compiled at -O1)
DYNAMICS_BUILD_S_PER_SEGMENT = {"axial": 0.01, "planar": 0.02, "lumped3d": 0.2}
#: bytes per segment of the symbolic step (graph, generated code), rounded up
DYNAMICS_B_PER_SEGMENT = 2e5
#: CPU seconds of a dense symmetric eigenproblem of size n: ~1e-9 n^3 (LAPACK)
EIG_S_CUBE = 1e-9


def dynamics_cost(scene: Any, lengths: int = 0) -> Cost:
    """Estimate of a dynamic scene's simulation (``lengths = 0``) or of its modal analysis
    (``lengths`` = the number of lengths of a deployment chart, 1 for one length).

    Parameters
    ----------
    scene : DynamicScene
        The validated dynamic scene: its ``simulation`` model, segments, steps and output
        interval drive the estimate.
    lengths : int
        0 (default): a time simulation; n > 0: a modal analysis at n cable lengths (one
        eigenproblem each).
    """
    sim = scene.simulation
    n = sim.segments
    model = sim.model
    dof = n * (1 if model == "axial" else 2 if model == "planar" else 3)
    cost = Cost()
    keys = f"simulation.segments = {n} ({model} model)"
    cost.add(f"building the {model} step for {n} segments",
             DYNAMICS_BUILD_S_PER_SEGMENT.get(model, 0.2) * n,
             DYNAMICS_B_PER_SEGMENT * n, keys)
    if lengths:
        cost.add(f"{lengths} eigenproblem(s) of {2 * dof} states",
                 lengths * EIG_S_CUBE * (2 * dof) ** 3, 8.0 * 4 * (2 * dof) ** 2, keys)
        return cost
    steps = sim.steps
    samples = steps // max(1, sim.output_every) + 1
    cost.add(f"{steps} steps of {n} segments",
             DYNAMICS_S_PER_SEGMENT_STEP.get(model, 5e-5) * n * steps,
             8.0 * 2 * samples * (n + 1) * 4,
             f"{keys}, simulation.duration = {sim.duration:g} s and simulation.time_step = "
             f"{sim.time_step:g} s")
    return cost
