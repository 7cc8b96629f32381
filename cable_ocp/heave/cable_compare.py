"""Heave compensation on a cable scene: identification, the comparison on the cable plant,
and the deployment through resonance.

A heave scene with ``[unit] cable_scene`` is compared here: the design model is identified
from the cable (Huang (1992), section 6.2.3; :mod:`cable_ocp.heave.identify_cable`) unless
``[unit] a, b`` are given; ``[simulation] plant = "model"`` runs the usual comparison
(:func:`cable_ocp.heave.design_loop.compare`) on that model, ``"cable"`` runs every controller
against the cable (the axial, planar or lumped3d model of the cable scene,
:func:`cable_ocp.heave.cable_models.cable_plant`) and against the design model
for the prediction (the ``phc*`` controllers with the passive compensator at the line's top,
designed on the design model with it), and a ``[deployment]`` table lowers the unit through
resonance (:mod:`cable_ocp.heave.deployment`). :func:`compare` takes any heave scene.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.heave import design_loop as sm
from cable_ocp.heave import identify_cable as idc
from cable_ocp.heave import mpc as mpc_mod
from cable_ocp.heave.cable_models import cable_plant, check_plant_scene
from cable_ocp.heave.closed_loop import (
    INTERRUPTED,
    make_wave,
    run_loop,
    run_status,
    unstable_bound,
)
from cable_ocp.heave.deployment import deploy
from cable_ocp.heave.design import cable_controller, design_damping, design_scene, design_table
from cable_ocp.heave.loop_plants import CableLine, ModelLine, Piston, WinchedLine
from cable_ocp.heave.metrics import (
    CableComparison,
    CableMetrics,
    cable_run_metrics,
    cable_status,
    limit_excess,
    limit_warning,
    no_cable_metrics,
    reduction_pct,
)
from cable_ocp.numerics import interrupt
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.heave import HeaveScene, check_compensator_load, load_cable_scene

__all__ = ["compare", "compare_cable"]


def compare(scene: HeaveScene, controllers: tuple | None = None,
            progress: Callable[[int, int, Any], None] | None = None) -> Any:
    """:func:`cable_ocp.heave.design_loop.compare` for any heave scene: a scene with
    ``[unit] cable_scene`` goes to :func:`compare_cable`, the others to
    :func:`cable_ocp.heave.design_loop.compare`. Returns a
    :class:`~cable_ocp.heave.metrics.Comparison` or a
    :class:`~cable_ocp.heave.metrics.CableComparison` (the same fields, and the
    cable's).

    Parameters
    ----------
    scene : HeaveScene
        Any heave scene.
    controllers : tuple of str, optional
        The controllers (default the scene's).
    progress : callable, optional
        ``progress(done, total, None)`` every 100 samples.
    """
    if scene.unit.cable_scene is not None:
        return compare_cable(scene, controllers, progress)
    return sm.compare(scene, controllers, progress)


def compare_cable(scene: HeaveScene, controllers: tuple | None = None,
                  progress: Callable[[int, int, Any], None] | None = None) -> Any:
    """:func:`cable_ocp.heave.design_loop.compare` for a scene with ``[unit] cable_scene``.

    The design model is identified from the cable scene (Huang (1992), section 6.2.3,
    :func:`cable_ocp.heave.identify_cable.identify_from_cable`) unless ``[unit] a, b`` are
    given. With ``[simulation] plant = "model"`` the usual comparison runs on that model;
    with ``"cable"`` every controller runs against the cable (the cable scene's axial,
    planar or lumped3d model, :func:`cable_ocp.heave.cable_models.cable_plant`), and
    against the design model with the same estimator for the prediction.

    Parameters
    ----------
    scene : HeaveScene
        A heave scene with ``[unit] cable_scene``.
    controllers : tuple of str, optional
        The controllers (default the scene's).
    progress : callable, optional
        ``progress(done, total, None)`` every 100 samples.
    """
    dyn = load_cable_scene(scene)
    check_plant_scene(str(scene.unit.cable_scene), dyn)
    ident = idc.identify_from_cable(scene, dyn)
    sd, source = design_scene(scene, ident, dyn)
    warn = design_damping(ident.linear.b, "design model")[1] if source == "identified" else None
    extra = {"plant": scene.simulation.plant,
             "design_model": {"a": sd.unit.a, "b": sd.unit.b,
                              "b_quadratic": sd.unit.b_quadratic, "source": source,
                              "mass": sd.unit.mass, "static_tension": sd.unit.static_tension},
             "identified": idc.identified_json(ident)}
    if scene.deployment is not None:
        res = deploy(scene, sd, dyn, ident, extra, progress)
    elif scene.simulation.plant == "model":
        if sd.passive_compensator is not None:
            check_compensator_load(sd, sd.unit.static_tension, "unit.static_tension")
        r = sm.compare(sd, controllers, progress)
        res = CableComparison(r.sigma_uncontrolled, r.metrics, r.traces, r.models,
                              r.mpc_solve_times, r.mpc_failures, r.statuses, r.messages,
                              r.passive_heave_rms, r.warnings, r.interrupted,
                              json_extra=extra)
    else:
        res = _compare_on_cable(scene, sd, dyn, controllers, progress, extra)
    if warn is not None and warn not in res.warnings:
        res.warnings.insert(0, warn)
    return res


def _compensator_design(sd: HeaveScene, length: float, t_top0: float, dyn: DynamicScene
                        ) -> tuple[Any, Any, str | None, HeaveScene, Any]:
    """The phc* designs on the cable plant: ``(table, plant, design error or None, the
    design scene with the compensator's pressure, the cable plant one time step per
    call)``.

    The cylinder sits at the line's top and carries its static top tension ``t_top0`` (N):
    ``[passive_compensator] pressure`` defaults to ``t_top0 / area`` and a given one must
    carry it (:func:`cable_ocp.scene.heave.check_compensator_load`). The design is
    :func:`cable_ocp.heave.design.design_table` on the design model with the compensator.
    """
    pc = sd.passive_compensator
    check_compensator_load(sd, t_top0, "the cable's static top tension")
    if pc.pressure is None:
        sd = replace(sd, passive_compensator=replace(pc, pressure=t_top0 / pc.area))
    try:
        with np.errstate(all="ignore"):
            table, p = design_table(sd, np.array([length]), np.array([sd.unit.a]),
                                    np.array([sd.unit.b]), compensator=True)
        err = None
    except CableOCPError:
        raise
    except sm._DESIGN_ERRORS as exc:
        table, p = None, None
        err = (f"the design on the design model with the compensator failed: "
               f"{type(exc).__name__}: {exc}")
    return table, p, err, sd, cable_plant(dyn, dyn.simulation.time_step)


def _compare_on_cable(sc: HeaveScene, sd: HeaveScene, dyn: DynamicScene,
                      controllers: tuple | None, progress: Callable | None, extra: dict
                      ) -> CableComparison:
    c = sc.controller
    h = c.sample_time
    T = sc.simulation.duration
    n_ctrl = int(round(T / h))
    controllers = tuple(controllers or c.controllers)
    valid = ("passive", "lqr", "lqg", "mpc", "phc", "phc+lqr", "phc+lqg", "phc+mpc")
    for name in controllers:
        if name not in valid:
            raise CableOCPError(f"controller {name!r} is unknown; valid: {', '.join(valid)}")
    with_phc = any(sm.base_controller(name)[1] for name in controllers)
    if with_phc and sd.passive_compensator is None:
        raise CableOCPError(f"controllers {', '.join(controllers)}: the phc* controllers need "
                            "a [passive_compensator] table in the scene")
    # the passive run is the baseline of every reduction, run when not asked for
    runs_of = controllers if "passive" in controllers else controllers + ("passive",)
    models = sm.build_models(sd)
    plant_c = cable_plant(dyn, h)
    m = plant_c.substeps
    hs = h / sc.simulation.substeps
    t_f, x0_f, _ = sm.wave_realisation(models.plant, T + c.preview_time + 2 * h, hs,
                                       sc.simulation.seed)
    L0 = dyn.length
    wave = make_wave(t_f, x0_f, h, m, n_ctrl, lambda t: np.full_like(t, L0),
                     0.5 * sc.simulation.warmup)
    rng = np.random.default_rng(sc.simulation.seed + 1000)
    noise = rng.standard_normal((n_ctrl + 1, 3)) * np.array(
        [c.measurement_noise, c.winch_noise, c.boom_tip_noise])
    try:
        with np.errstate(all="ignore"):
            table, p = design_table(sd, np.array([L0]), np.array([sd.unit.a]),
                                    np.array([sd.unit.b]))
        design_error = None
    except CableOCPError:
        raise
    except sm._DESIGN_ERRORS as exc:  # a Riccati equation without a stabilising solution
        table, p = None, models.plant
        design_error = f"the design on the design model failed: {type(exc).__name__}: {exc}"
    settings = mpc_mod.settings_from_scene(sd)
    bound = unstable_bound(wave.x0)
    t_u0, t_t0 = plant_c.static_tensions()
    quad = sd.unit.model == "quadratic"
    # the compensator (phc*): at the line's top it carries the static top tension; designed
    # on the design model with it, stepped with the cable one time step at a time
    phc_design = _compensator_design(sd, L0, t_t0, dyn) if with_phc else None
    total = 2 * n_ctrl * len(runs_of)
    metrics, traces, predicted, statuses, messages = {}, {}, {}, {}, {}
    solve_times, failures = None, 0
    warnings: list[str] = []
    top_range = getattr(plant_c, "top_range", None)  # the lumped3d plant's top segment
    stroke = sc.winch.stroke_max
    if top_range is not None and stroke is not None:
        haul, pay = plant_c.l_top0 - top_range[0], top_range[1] - plant_c.l_top0
        if stroke > min(haul, pay):
            warnings.append(
                f"winch.stroke_max = {stroke:g} m: the lumped3d plant pays cable through its "
                f"top segment ({plant_c.l_top0:.4g} m), which takes {haul:.3g} m of haul-in "
                f"and {pay:.3g} m of pay-out; a run whose winch goes further stops as failed "
                "(fewer simulation.segments in the cable scene lengthen that segment)")
    empty = no_cable_metrics()
    stopped = None  # the index in runs_of where a Ctrl-C stopped the comparison
    for idx, name in enumerate(runs_of):
        kind_of, phc = sm.base_controller(name)
        tbl, pn, err = (table, p, design_error) if not phc else phc_design[:3]
        if err is not None and kind_of != "passive":
            statuses[name], messages[name] = "failed", err
            metrics[name] = (empty, empty)
            continue
        runs = {}
        try:
            for j, kind in enumerate(("model", "cable")):
                base = (2 * idx + j) * n_ctrl

                def prog(k: int, base: int = base) -> None:
                    if progress is not None:
                        progress(base + k, total, None)

                mpc = (mpc_mod.LinearMPC(pn, sc.winch.delay, settings) if kind_of == "mpc"
                       else None)
                ctrl = cable_controller(kind_of, None if kind_of == "passive" else tbl, mpc)
                ctrl.name = name
                piston = Piston(phc_design[3]) if phc else None
                if kind == "model":
                    line: Any = ModelLine(sd.unit.a, sd.unit.b, sd.unit.b_quadratic, quad, m,
                                          h / m, sd.unit.mass, t_u0, t_t0, piston)
                elif phc:
                    line = CableLine(phc_design[4], piston)
                else:
                    line = CableLine(plant_c)
                runs[kind] = run_loop(WinchedLine(sc, line, wave, noise), ctrl, n_ctrl,
                                      bound, prog)
        except (KeyboardInterrupt, Exception) as exc:  # a CasADi error may be a Ctrl-C
            # an interruption: keep the runs finished; this one and the rest: interrupted
            if not interrupt.is_interruption(exc):
                raise
            stopped = idx
            break
        mc = cable_run_metrics(sd, runs["cable"], ctrl.energy_index)
        mm = cable_run_metrics(sd, runs["model"], ctrl.energy_index)
        metrics[name] = (mc, mm)
        if name not in controllers:
            continue
        statuses[name], messages[name] = cable_status(runs["cable"], mc, plant_c.model_name)
        pst, pmsg = run_status(runs["model"], "design-model")
        if pst != "solved":
            warnings.append(f"{name}: on the design model (the prediction): {pst}: {pmsg}")
        if run_status(runs["cable"])[0] == "solved":
            lim = limit_warning(name, limit_excess(sd, runs["cable"].trace,
                                                   runs["cable"].commands, h))
            if lim:
                warnings.append(lim)
        traces[name] = runs["cable"].trace
        predicted[name] = runs["model"].trace
        if kind_of == "mpc" and (name == "mpc" or solve_times is None):
            solve_times = runs["cable"].times
            failures = runs["cable"].failures
            if failures:
                warnings.append(f"mpc: the QP failed at {failures} of {solve_times.size} "
                                "samples on the cable; the shifted previous plan was applied")
    if stopped is not None:
        for name in runs_of[stopped:]:
            if name in controllers:
                statuses[name], messages[name] = INTERRUPTED
            metrics[name] = (empty, empty)
    elif progress is not None:  # (after a Ctrl-C the progress would raise it again)
        progress(total, total, None)
    out = {}
    base_c = metrics["passive"][0]["heave_rms"]
    base_m = metrics["passive"][1]["heave_rms"]

    for name in controllers:
        mc, mm = metrics[name]
        d = dict(mc)
        d["reduction_pct"] = reduction_pct(mc["heave_rms"], base_c)
        d["heave_rms_predicted"] = mm["heave_rms"]
        d["reduction_predicted_pct"] = reduction_pct(mm["heave_rms"], base_m)
        d["tension_unit_min_predicted"] = mm["tension_unit_min"]
        d["tension_unit_max_predicted"] = mm["tension_unit_max"]
        out[name] = CableMetrics(d)
    extra = dict(extra)
    extra["cable_plant"] = {"model": plant_c.model_name, "segments": plant_c.model.n,
                            "time_step": plant_c.dt,
                            "substeps": m, "length": L0,
                            "static_tension_unit": t_u0, "static_tension_top": t_t0}
    extra["passive_heave_rms_predicted"] = base_m
    if models.sigma_uncontrolled is None:
        warnings.append("sigma_uncontrolled: the Lyapunov equation of the sea and vessel "
                        "filters gives no valid variance (ill-conditioned); reported as null")
    return CableComparison(models.sigma_uncontrolled, out, traces, models, solve_times,
                           failures, statuses, messages, base_c, warnings,
                           stopped is not None, json_extra=extra, predicted_traces=predicted)
