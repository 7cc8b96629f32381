"""The figure of an optimal pay-out schedule (``cable-ocp deploy --plot``).

Four panels against time: (a) the paid-out length, with the resonant lengths of the
deployment chart (where the first natural frequency omega_1(L) meets the heave's
frequency or an edge of the wave band) as horizontal lines and the constant-speed
schedules for comparison; (b) the pay-out speed, ``speed_max`` dashed; (c) the tension
envelope (the smallest and largest element tension per step, the unit and the top
tension), ``tension_min`` and ``tension_max`` dashed, and with the forward check
(:func:`cable_ocp.schedule.planning.verified_schedule`) the re-simulated smallest tension
along the line and the limits as the OCP kept them (moved in by the check's margins),
dotted; (d) the winch's power
|T_top dL/dt|, ``power_max`` dashed.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from cable_ocp.plots.common import force_scale, legend_below, new_figure, save, wrap

__all__ = ["plot_schedule", "resonant_lengths", "schedule_figure"]


def resonant_lengths(chart: Any, frequencies: Sequence[float] = ()
                     ) -> list[tuple[float, float, str]]:
    """Where the first mode's frequency omega_1(L) of a deployment chart meets each of
    ``frequencies`` and the edges of its wave band (linear interpolation between the
    chart's lengths, as :meth:`cable_ocp.dynamics.result.DeploymentChart.crossings`).

    Parameters
    ----------
    chart : DeploymentChart
        Natural frequencies (rad/s) against unstretched length (m).
    frequencies : sequence of float
        The heave's frequencies, rad/s.

    Returns
    -------
    list of (float, float, str)
        (length (m), frequency (rad/s), what it is), sorted by length.
    """
    if chart is None or chart.frequencies.size == 0:
        return []
    lengths = np.asarray(chart.lengths, dtype=float)
    f = np.asarray(chart.frequencies, dtype=float)[:, 0]
    lo, hi = chart.wave_band
    targets = [(float(w), "heave") for w in frequencies]
    targets += [(float(lo), "band low edge"), (float(hi), "band high edge")]
    found = []
    for w, what in targets:
        d = f - w
        for i in range(len(d) - 1):
            if np.isfinite(d[i]) and np.isfinite(d[i + 1]) and d[i] * d[i + 1] < 0:
                a = d[i] / (d[i] - d[i + 1])
                found.append((float(lengths[i] + a * (lengths[i + 1] - lengths[i])), w, what))
    return sorted(found)


def _limit(ax: Any, value: float | None, label: str, scale: float = 1.0) -> None:
    if value is not None:
        ax.axhline(value / scale, color="0.25", ls="--", lw=1.0, label=label)


def schedule_figure(res: Any, title: str = "", chart: Any = None,
                    constant: Sequence[tuple[str, np.ndarray, np.ndarray, np.ndarray]] = (),
                    heave_frequencies: Sequence[float] = (),
                    names: Sequence[str] = ()) -> Figure:
    """The figure of :func:`plot_schedule`, built and not saved (module docstring).

    Parameters
    ----------
    res : ScheduleResult
        A solved schedule (:func:`cable_ocp.schedule.planning.solve_schedule`).
    title : str
        Start of the title; default empty.
    chart : DeploymentChart, optional
        omega_1 against length over the lowering, for the resonant lengths in (a).
    constant : sequence of (str, ndarray, ndarray, ndarray)
        Constant-speed schedules for comparison: (label, time (s), length (m), speed (m/s)).
    heave_frequencies : sequence of float
        The heave's frequencies, rad/s (the resonant lengths of (a)).
    names : sequence of str
        The realisations' names (legend), default ``r0``, ``r1``, ...
    """
    sol = res.solution
    pb = res.problem
    t = sol.time
    fig = new_figure(10.0, 7.6)
    (a, b), (c, d) = fig.subplots(2, 2, sharex=True)
    handles: list[Any] = []

    # (a) length, the resonant lengths, the constant-speed schedules
    a.plot(t, sol.length, color="C0", lw=1.8, label=f"optimal ({sol.duration:.4g} s)")
    for k, (lab, tc, lc, _) in enumerate(constant):
        a.plot(tc, lc, color=f"C{k + 1}", lw=1.2, ls="-.",
               label=f"{lab}, {float(tc[-1]):.4g} s")
    res_l = resonant_lengths(chart, heave_frequencies)
    for length, w, what in res_l:
        color = "firebrick" if what == "heave" else "darkorange"
        a.axhline(length, color=color, lw=0.9, ls=":", label=f"omega_1 = {what}"
                  if what != "heave" else "omega_1 = heave frequency")
        a.annotate(f"{length:.0f} m ({w:.3g} rad/s)", (0.01, length), xycoords=("axes fraction",
                   "data"), fontsize=7.5, va="bottom", color=color)
    if chart is not None and not res_l:
        f1 = np.asarray(chart.frequencies, dtype=float)[:, 0]
        if np.any(np.isfinite(f1)):
            a.text(0.98, 0.04, f"no resonant length here:\nomega_1 {np.nanmax(f1):.3g} .. "
                               f"{np.nanmin(f1):.3g} rad/s", transform=a.transAxes,
                   ha="right", va="bottom", fontsize=8, color="0.3")
    a.set_ylabel("paid-out length L (m)")
    a.set_title("(a) length", fontsize=10, loc="left")

    # (b) speed
    b.plot(t, sol.speed, color="C0", lw=1.8, label="_optimal")
    for k, (_, tc, _, vc) in enumerate(constant):
        b.plot(tc, vc, color=f"C{k + 1}", lw=1.2, ls="-.", label="_constant")
    _limit(b, pb.speed_max, "limit")
    if pb.speed_max is not None and pb.target_length < sol.length[0]:
        _limit(b, -pb.speed_max, "limit")
    b.set_ylabel("pay-out speed dL/dt (m/s)")
    b.set_title("(b) speed", fontsize=10, loc="left")

    # (c) tension envelope
    peak = float(np.nanmax(sol.tensions))
    if pb.tension_max is not None:
        peak = max(peak, pb.tension_max)
    scale, unit = force_scale(peak)
    n_r = sol.tensions.shape[0]
    for r in range(n_r):
        name = names[r] if r < len(names) else f"r{r}"
        tag = f" ({name})" if n_r > 1 else ""
        lo = np.nanmin(sol.tensions[r], axis=1) / scale
        hi = np.nanmax(sol.tensions[r], axis=1) / scale
        c.fill_between(t, lo, hi, color=f"C{r}", alpha=0.25 if n_r == 1 else 0.12,
                       label=f"min..max along the line{tag}")
        c.plot(t, sol.outputs[r, :, 2] / scale, color=f"C{r}", lw=1.0, ls="-",
               label=f"unit tension{tag}")
        c.plot(t, sol.outputs[r, :, 3] / scale, color=f"C{r}", lw=1.0, ls="--",
               label=f"top tension{tag}")
    _limit(c, pb.tension_min, "limit", scale)
    _limit(c, pb.tension_max, "limit", scale)
    if res.checks:
        last = res.checks[-1]
        for k, run in enumerate(last.runs[:n_r]):
            c.plot(run.t, run.tension_min_line / scale, color="k", lw=0.8,
                   label="re-simulated, smallest along the line" if k == 0 else "_sim")
        for name, sign in (("tension_min", 1.0), ("tension_max", -1.0)):
            limit, m = getattr(pb, name), last.margins.get(name, 0.0) + pb.tension_margin
            if limit is not None and m > 0.0:
                c.axhline((limit + sign * m) / scale, color="0.25", ls=":", lw=1.0,
                          label=f"the OCP's {name} (check's margin {m:.3g} N)")
    c.set_ylim(bottom=0.0)
    c.set_ylabel(f"tension ({unit})")
    c.set_xlabel("time t (s)")
    c.set_title("(c) tension", fontsize=10, loc="left")

    # (d) power
    v_mid = np.concatenate([[0.0], 0.5 * (sol.speed[1:] + sol.speed[:-1])])
    power = np.abs(sol.outputs[:, :, 3] * v_mid[None, :])
    pmax = float(np.nanmax(power)) if power.size else 0.0
    if pb.power_max is not None:
        pmax = max(pmax, pb.power_max)
    pscale, punit = (1e6, "MW") if pmax >= 1e6 else (1e3, "kW")
    for r in range(n_r):
        d.plot(t, power[r] / pscale, color=f"C{r}", lw=1.2, label="_power")
    _limit(d, pb.power_max, "limit", pscale)
    d.set_ylim(bottom=0.0)
    d.set_ylabel(f"winch power |T_top dL/dt| ({punit})")
    d.set_xlabel("time t (s)")
    d.set_title("(d) power", fontsize=10, loc="left")

    for ax in (a, b, c, d):
        ax.grid(True, alpha=0.3)
        handles += ax.get_lines() + list(ax.collections)
    legend_below(fig, handles, ncols=3)
    binding = ", ".join(res.binding) if res.binding else "none"
    fig.suptitle(wrap(f"{title}: optimal schedule, {sol.length[0]:.4g} -> "
                      f"{pb.target_length:.4g} m in {sol.duration:.4g} s (binding: {binding})",
                      10.0, 11), fontsize=11)
    return fig


def plot_schedule(res: Any, path: str | Path, title: str = "", chart: Any = None,
                  constant: Sequence[tuple[str, np.ndarray, np.ndarray, np.ndarray]] = (),
                  heave_frequencies: Sequence[float] = (),
                  names: Sequence[str] = ()) -> Figure:
    """Save :func:`schedule_figure` (the optimal schedule's four panels) to ``path``.

    Parameters
    ----------
    res : ScheduleResult
        A solved schedule.
    path : str or Path
        Where to save the figure (format from the suffix).
    title : str
        Start of the title; default empty.
    chart : DeploymentChart, optional
        omega_1 against length over the lowering.
    constant : sequence of (str, ndarray, ndarray, ndarray)
        Constant-speed schedules: (label, time (s), length (m), speed (m/s)).
    heave_frequencies : sequence of float
        The heave's frequencies, rad/s.
    names : sequence of str
        The realisations' names.
    """
    fig = schedule_figure(res, title, chart, constant, heave_frequencies, names)
    save(fig, path)
    return fig
