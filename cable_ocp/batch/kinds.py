"""What one case of each scene kind computes, and the row it gives.

A *runner* is built once per worker from the base problem (a dict, as read from TOML) and
then called per case; it keeps what can be reused between cases (built solvers, the last
solution for a warm start). Every case ends as a row, solved or not: a scene error of the
case itself (an override that makes the scene invalid) is a row with status
``"invalid_input"`` and the message, never an exception.

Row keys: ``case`` (index), ``case_id``, ``status``, ``message``, ``wall_time_s``, the
inputs (the case's dotted keys, in the problem file's units), then the kind's outputs,
named with their unit in brackets (:data:`OUTPUTS`).
"""

from __future__ import annotations

import math
import time
from abc import ABC, abstractmethod
from collections.abc import Callable
from typing import Any

import numpy as np

from cable_ocp.batch.arrays import ARRAYS
from cable_ocp.batch.cases import Case
from cable_ocp.errors import CableOCPError
from cable_ocp.scene.files import apply_overrides, scene_kind

#: kind -> output columns (name with unit), in table order
OUTPUTS: dict[str, list[str]] = {
    "statics": ["length [m]", "max_tension [N]", "end_a_tension [N]", "end_b_tension [N]",
                "end_a_angle [deg]", "end_b_angle [deg]", "end_a_force_x [N]",
                "end_a_force_y [N]", "end_a_force_z [N]", "end_b_force_x [N]",
                "end_b_force_y [N]", "end_b_force_z [N]", "grounded_length [m]",
                "error_estimate [-]", "iterations [-]"],
    "footprint": ["directions [-]", "solved_directions [-]", "min_reach [m]", "max_reach [m]",
                  "mean_reach [m]"],
    "heave": ["sigma_uncontrolled [m]"],  # + per controller, see HeaveRunner.columns
    "system": ["max_tension [N]", "min_safety_factor [-]", "iterations [-]"],  # + per body
    # pose and per line, see SystemRunner.columns
    "dynamics": ["max_top_tension [N]", "min_top_tension [N]", "min_tension [N]",
                 "slack [-]", "first_slack_time [s]", "unit_heave_amplitude [m]",
                 "final_length [m]", "simulation_wall_time [s]"],
}
SUCCESS = {"statics": ("solved",), "footprint": ("solved",), "heave": ("solved",),
           "dynamics": ("solved",), "system": ("solved",)}


def _num(x: Any) -> float | None:
    try:
        v = float(x)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


class Runner(ABC):
    """Base class: ``run(case) -> row``; subclasses implement :meth:`_run`.

    Parameters
    ----------
    data : dict
        The base problem as read from TOML (SI units); each case applies its overrides to
        a copy of it.
    options : dict, optional
        The kind's options (a copy is kept): ``directions`` for the footprint runner
        (default 36), ``controllers`` for the heave runner; ``arrays`` (True) for every
        kind but the footprint: the row also carries the case's arrays under
        :data:`cable_ocp.batch.arrays.ARRAYS` (:mod:`cable_ocp.batch.arrays`). None
        (default): no options.
    """

    kind = ""

    def __init__(self, data: dict[str, Any], options: dict[str, Any] | None = None) -> None:
        self.data = data
        self.options = dict(options or {})

    def columns(self) -> list[str]:
        """Output columns (name [unit])."""
        return list(OUTPUTS.get(self.kind, []))

    def run(self, case: Case) -> dict[str, Any]:
        """The row of ``case`` (never raises for a problem of the case itself)."""
        t0 = time.perf_counter()
        row: dict[str, Any] = {"case": case.index, "case_id": case.case_id}
        try:
            status, message, out = self._run(case)
        except CableOCPError as exc:
            status, message, out = "invalid_input", str(exc), {}
        row.update(status=status, message=message,
                   wall_time_s=time.perf_counter() - t0)
        row.update({k: v for k, v in case.overrides.items()})
        row.update({c: _num(out.get(c)) for c in self.columns()})
        if self.options.get("arrays") and out.get(ARRAYS):
            row[ARRAYS] = {k: np.asarray(v, dtype=float) for k, v in out[ARRAYS].items()}
        return row

    def _data(self, case: Case) -> dict[str, Any]:
        return apply_overrides(self.data, case.overrides)

    @abstractmethod
    def _run(self, case: Case) -> tuple[str, str, dict[str, Any]]:
        """(status, message, outputs by column name) of one case."""


class StaticsRunner(Runner):
    """``cable-ocp solve`` per case; solvers built once per structure, warm starts along
    the batch order (:class:`cable_ocp.statics.solver.SolveSession`).

    Parameters
    ----------
    data : dict
        The base statics problem as read from TOML (SI units).
    options : dict, optional
        Not used by this runner (kept as :attr:`options`); None (default): none.
    """

    kind = "statics"

    def __init__(self, data: dict[str, Any], options: dict[str, Any] | None = None) -> None:
        super().__init__(data, options)
        from cable_ocp.statics.solver import SolveSession

        self.session = SolveSession()
        self._last = -2
        self._last_overrides: dict[str, Any] = {}

    def _run(self, case: Case) -> tuple[str, str, dict[str, Any]]:
        from cable_ocp.scene import scene_from_dict

        # warm from the previous case only when it is this case's neighbour in the batch
        # order (a chunk that starts elsewhere in the grid starts cold: cheaper than a
        # warm start from far); a continuation with a predictor where the two differ in
        # one numeric key (a line of the grid)
        warm = case.index == self._last + 1
        changed = [k for k in case.overrides
                   if case.overrides[k] != self._last_overrides.get(k)]
        along = None
        if warm and len(changed) == 1:
            v = case.overrides[changed[0]]
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                along = (changed[0], float(v))
        self._last = case.index
        self._last_overrides = dict(case.overrides)
        sol = self.session.solve(scene_from_dict(self._data(case)), warm=warm, along=along)
        if not np.all(np.isfinite(sol.tension_vector)):
            return sol.status, sol.message, {}
        ta, tb = sol.tension_vector[0], sol.tension_vector[-1]
        out = {"length [m]": sol.length, "max_tension [N]": sol.max_tension,
               "end_a_tension [N]": np.linalg.norm(ta), "end_b_tension [N]": np.linalg.norm(tb),
               "end_a_angle [deg]": sol.angle_to_horizontal_deg("a"),
               "end_b_angle [deg]": sol.angle_to_horizontal_deg("b"),
               "grounded_length [m]": sol.grounded_length,
               "error_estimate [-]": sol.error_estimate, "iterations [-]": sol.iterations}
        for end, f in (("a", sol.force_a), ("b", sol.force_b)):
            for c, v in zip("xyz", f, strict=True):
                out[f"end_{end}_force_{c} [N]"] = v
        pos = np.asarray(sol.position, dtype=float)
        out[ARRAYS] = {"arc_length": sol.s, "tension": sol.tension, "x": pos[:, 0],
                       "y": pos[:, 1], "z": pos[:, 2]}
        return sol.status, sol.message, out


class FootprintRunner(Runner):
    """``cable-ocp footprint`` per case (``options["directions"]``, default 36)."""

    kind = "footprint"

    def _run(self, case: Case) -> tuple[str, str, dict[str, Any]]:
        from cable_ocp.scene import scene_from_dict
        from cable_ocp.statics.footprint_nlp import footprint

        n = int(self.options.get("directions", 36))
        res = footprint(scene_from_dict(self._data(case)), n)
        ok = np.isfinite(res.reach)
        solved = sum(s == "solved" for s in res.status)
        out = {"directions [-]": n, "solved_directions [-]": solved}
        if ok.any():
            out.update({"min_reach [m]": float(np.min(res.reach[ok])),
                        "max_reach [m]": float(np.max(res.reach[ok])),
                        "mean_reach [m]": float(np.mean(res.reach[ok]))})
        status = "solved" if solved == n else "partial"
        return status, f"{solved} of {n} directions solved", out


class HeaveRunner(Runner):
    """``cable-ocp heave`` per case; the sea realisation's seed is the case seed unless the
    case sets ``simulation.seed``.

    Parameters
    ----------
    data : dict
        The base heave problem as read from TOML (SI units); its ``controller.controllers``
        is the default list of controllers (else passive, lqr, lqg and mpc).
    options : dict, optional
        ``controllers``: the controllers to compare, overriding the problem's list (their
        metrics become columns). None (default): none.
    """

    kind = "heave"
    METRICS = (("heave_rms", "m"), ("reduction_pct", "%"), ("peak_winch_speed", "m/s"),
               ("max_stroke", "m"), ("max_constraint_violation", "-"))

    def __init__(self, data: dict[str, Any], options: dict[str, Any] | None = None) -> None:
        super().__init__(data, options)
        ctrl = (data.get("controller") or {}).get("controllers") or [
            "passive", "lqr", "lqg", "mpc"]
        self.controllers = list(self.options.get("controllers") or ctrl)

    def columns(self) -> list[str]:
        cols = ["sigma_uncontrolled [m]"]
        for c in self.controllers:
            cols += [f"{c}_{m} [{u}]" for m, u in self.METRICS]
        return cols

    def _run(self, case: Case) -> tuple[str, str, dict[str, Any]]:
        from cable_ocp.heave import compare
        from cable_ocp.scene.heave import scene_from_dict

        over = dict(case.overrides)
        over.setdefault("simulation.seed", case.seed % (2**31))
        sc = scene_from_dict(apply_overrides(self.data, over))
        res = compare(sc, tuple(self.controllers))
        out: dict[str, Any] = {"sigma_uncontrolled [m]": res.sigma_uncontrolled}
        out[ARRAYS] = _heave_arrays(res.traces)
        bad = []
        for c, m in res.metrics.items():
            d = m.as_dict()
            for name, unit in self.METRICS:
                out[f"{c}_{name} [{unit}]"] = d.get(name)
            st = d.get("status", "solved")
            if st != "solved" or not all(_num(d.get(n)) is not None for n, _ in
                                          self.METRICS[:1]):
                bad.append(f"{c}: {st if st != 'solved' else 'non_finite'}")
        if bad:
            return bad[0].split(": ")[1], "; ".join(bad), out
        return "solved", "every controller ran", out


class DynamicsRunner(Runner):
    """``cable-ocp simulate`` per case (any model of the scene's ``[simulation]``).

    ``unit_heave_amplitude`` is half the range of the unit's height about its lowering path
    (z + paid-out length, so that a deployment's descent does not count as heave), after
    the first quarter of the run (the start transient); ``slack`` is 1 when a tension
    reached zero (the status is then ``"slack"``)."""

    kind = "dynamics"

    def _run(self, case: Case) -> tuple[str, str, dict[str, Any]]:
        from cable_ocp.dynamics import simulate
        from cable_ocp.scene.dynamics import dynamic_scene_from_dict

        res = simulate(dynamic_scene_from_dict(self._data(case)))
        out: dict[str, Any] = {"simulation_wall_time [s]": res.wall_time_s,
                               "min_tension [N]": res.min_tension}
        slack = res.slack or {}
        out["slack [-]"] = 1.0 if slack.get("occurred") else 0.0
        out["first_slack_time [s]"] = slack.get("first_time")
        tt = np.asarray(res.top_tension, dtype=float)
        if tt.size:
            out["max_top_tension [N]"] = float(np.nanmax(tt))
            out["min_top_tension [N]"] = float(np.nanmin(tt))
            length = np.asarray(res.length, dtype=float)
            heave = np.asarray(res.unit_position, dtype=float)[:, 2] + (length - length[0])
            tail = heave[len(heave) // 4:]
            if tail.size:
                out["unit_heave_amplitude [m]"] = 0.5 * float(np.ptp(tail))
            out["final_length [m]"] = float(length[-1])
            out[ARRAYS] = {"time": res.t, "top_tension": tt, "unit_z":
                           np.asarray(res.unit_position, dtype=float)[:, 2], "length": length}
        return res.status, res.message, out


def _heave_arrays(traces: dict[str, Any]) -> dict[str, np.ndarray]:
    """Time and, per controller, the unit's heave, the winch output and (on the cable
    plant) the tension at the unit, from a comparison's traces."""
    out: dict[str, np.ndarray] = {}
    for name, tr in traces.items():
        out.setdefault("time", np.asarray(tr.t, dtype=float))
        out[f"{name}_unit_heave"] = tr.x
        out[f"{name}_winch_output"] = tr.u
        if getattr(tr, "tension_unit", None) is not None:
            out[f"{name}_unit_tension"] = tr.tension_unit
    return out


class SystemRunner(Runner):
    """``cable-ocp solve`` of a mooring system per case: one model per worker, each case's
    lines warm-started from the previous case's (:class:`cable_ocp.mooring.SystemModel`,
    rebuilt when a case changes the structure). Columns: the largest tension and the
    smallest safety factor, per body its pose (m, deg), per line its largest tension and
    its laid length.

    Parameters
    ----------
    data : dict
        The base system problem as read from TOML (SI units).
    options : dict, optional
        Not used by this runner (kept as :attr:`options`); None (default): none.
    """

    kind = "system"
    POSE = (("x", "m"), ("y", "m"), ("z", "m"), ("roll", "deg"), ("pitch", "deg"),
            ("yaw", "deg"))

    def __init__(self, data: dict[str, Any], options: dict[str, Any] | None = None) -> None:
        super().__init__(data, options)
        self.bodies = [b.get("name", "") for b in data.get("bodies", [])]
        self.lines = [ln.get("name", "") for ln in data.get("lines", [])]
        self._model: Any = None

    def columns(self) -> list[str]:
        cols = list(OUTPUTS["system"])
        for b in self.bodies:
            cols += [f"{b}_{d} [{u}]" for d, u in self.POSE]
        for ln in self.lines:
            cols += [f"{ln}_max_tension [N]", f"{ln}_laid_length [m]"]
        return cols

    def _run(self, case: Case) -> tuple[str, str, dict[str, Any]]:
        from cable_ocp.mooring import SystemModel, solve_system
        from cable_ocp.scene.system import system_from_dict

        sc = system_from_dict(self._data(case))
        if self._model is None or not self._model.update(sc):
            self._model = SystemModel(sc)
        res = solve_system(sc, model=self._model, stiffness=False)
        out: dict[str, Any] = {"max_tension [N]": res.max_tension,
                               "min_safety_factor [-]": res.min_safety_factor,
                               "iterations [-]": res.iterations}
        for b in res.bodies:
            for (d, u), v in zip(self.POSE, [*b["position"], *b["rotation_deg"]], strict=True):
                out[f"{b['name']}_{d} [{u}]"] = v
        for ln in res.lines:
            out[f"{ln['name']}_max_tension [N]"] = ln["max_tension"]
            out[f"{ln['name']}_laid_length [m]"] = ln["laid_length"]
        return res.status, res.message, out


RUNNERS: dict[str, Callable[..., Runner]] = {
    "statics": StaticsRunner, "footprint": FootprintRunner, "heave": HeaveRunner,
    "dynamics": DynamicsRunner, "system": SystemRunner,
}


def runner_kind(data: dict[str, Any], command: str | None = None) -> str:
    """The runner for a problem: ``footprint`` when asked (or the scene has a [footprint]
    table and no command is given), else the scene kind (``simulate`` names the dynamics
    runner).

    Parameters
    ----------
    data : dict
        The base problem as read from TOML; its tables tell its scene kind.
    command : str, optional
        The runner asked for (``--command``): ``"statics"``, ``"footprint"``, ``"heave"``,
        ``"dynamics"`` or ``"simulate"`` (the dynamics runner); it must fit the scene's
        kind. None (default): the scene's kind.
    """
    kind = scene_kind(data)
    if command == "simulate":
        command = "dynamics"
    if command is not None:
        if command not in RUNNERS:
            raise CableOCPError(f"--command {command}: valid are {', '.join(RUNNERS)}")
        if (command in ("statics", "footprint")) != (kind == "statics"):
            raise CableOCPError(f"--command {command} does not fit a {kind} scene")
        return command
    if kind not in RUNNERS:
        raise CableOCPError(f"batch runs of {kind} scenes are not available")
    return kind
