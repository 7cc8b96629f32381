"""``cable-ocp response``: frequency-response curves of a dynamic scene (parse, call,
format)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import numpy as np

from cable_ocp.cli import output as out
from cable_ocp.errors import CableOCPError
from cable_ocp.numerics import interrupt


def register(sub: argparse._SubParsersAction, parent: argparse.ArgumentParser) -> None:
    """Add ``response``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``cable-ocp`` parser's subparsers, to which the command is added.
    parent : argparse.ArgumentParser
        The common options (``--quiet``, ``--debug``), a parent of every parser added.
    """
    p = sub.add_parser(
        "response", parents=[parent],
        help="frequency-response curves: steady-state amplitudes against the excitation "
             "frequency, time runs beside the linear transfer function (Huang 1992, Figs "
             "3.3-3.7, 4.2-4.6)",
        description="Run the dynamic scene with a harmonic top motion (heave, horizontal or "
                    "circular) at each frequency and amplitude until the response is "
                    "periodic, take the amplitude of each output from a Fourier fit at the "
                    "excitation frequency over whole periods, and set it beside the "
                    "transfer function of the modes linearised about the static state. "
                    "Exit 0 every run periodic, 1 some run not periodic, slack or failed "
                    "(the JSON status says which), 2 invalid input.")
    p.add_argument("file", help="dynamic scene (UTF-8 TOML), e.g. "
                                "problems/dynamics/huang_3_3_3.toml")
    p.add_argument("--frequencies", metavar="START:STOP:N",
                   help="excitation frequencies in rad/s, N of them evenly spaced (default "
                        "[response] frequencies of the file)")
    p.add_argument("--amplitudes", metavar="A1,A2,...",
                   help="excitation amplitudes in m (default [response] amplitudes, else "
                        "the file's amplitude of the excitation)")
    p.add_argument("--outputs", metavar="NAME,...",
                   help="top_tension, unit_tension, unit_x, unit_y, unit_z, node_x:K, "
                        "node_y:K, node_z:K (K a node from end_a; default top_tension, "
                        "unit_tension and the unit's motion along the excitation)")
    p.add_argument("--excitation", choices=("heave", "horizontal", "circular"),
                   help="the harmonic top motion swept (default the one the file gives)")
    p.add_argument("--damping-ratio", type=float, metavar="ZETA",
                   help="modal damping ratio of the linear transfer function (default 0)")
    p.add_argument("--tolerance", type=float, metavar="REL",
                   help="relative change of the amplitude over the last two periods that "
                        "counts as periodic (default 0.01)")
    p.add_argument("--max-periods", type=int, metavar="N",
                   help="cap on the periods of a run after the ramp (default 192)")
    p.add_argument("--ramp-periods", type=float, metavar="N",
                   help="periods of the smooth ramp-in of the motion (default 10; longer for "
                        "an undamped line, whose free vibration a short ramp starts)")
    p.add_argument("--workers", type=int, metavar="N",
                   help="local worker processes (default: every core; 0 = in this process)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on a dask.distributed scheduler, e.g. tcp://10.0.0.5:8786 "
                        "(needs pip install -e '.[cluster]')")
    out.add_set_option(p)
    out.add_json_option(p, "the amplitudes, ratios and statuses per run, the linear curve "
                           "and the natural frequencies")
    out.add_csv_option(p, "one row per amplitude and frequency")
    out.add_plot_option(p, "the amplitude ratio against frequency per output, linear curve "
                           "and time runs, natural frequencies marked")
    p.set_defaults(func=cmd_response)


def _options(args: argparse.Namespace, defaults: Any) -> dict[str, Any]:
    """The sweep's inputs from the command line, else the file's ``[response]``."""
    from cable_ocp.batch.response import ResponseSettings, parse_amplitudes, parse_frequencies

    if args.frequencies is not None:
        freqs = parse_frequencies(args.frequencies)
    elif defaults.frequencies is not None:
        freqs = np.linspace(*defaults.frequencies[:2], int(defaults.frequencies[2]))
    else:
        raise CableOCPError("--frequencies START:STOP:N is missing (rad/s), and the file "
                            "gives no [response] frequencies")
    amps = (parse_amplitudes(args.amplitudes) if args.amplitudes is not None
            else (np.asarray(defaults.amplitudes) if defaults.amplitudes else None))
    outputs = args.outputs if args.outputs is not None else (list(defaults.outputs) or None)
    tol = args.tolerance if args.tolerance is not None else defaults.tolerance
    cap = args.max_periods if args.max_periods is not None else defaults.max_periods
    if args.workers is not None and not 0 <= args.workers <= 1024:
        raise CableOCPError(f"--workers {args.workers}: give 0..1024")
    zeta = args.damping_ratio if args.damping_ratio is not None else defaults.damping_ratio
    ramp = args.ramp_periods if args.ramp_periods is not None else defaults.ramp_periods
    base = ResponseSettings()
    settings = ResponseSettings(
        tolerance=base.tolerance if tol is None else float(tol),
        max_periods=base.max_periods if cap is None else int(cap),
        ramp_periods=base.ramp_periods if ramp is None else float(ramp))
    return {"frequencies": freqs, "amplitudes": amps, "outputs": outputs,
            "excitation": args.excitation or defaults.excitation, "settings": settings,
            "damping_ratio": float(zeta or 0.0)}


def cmd_response(args: argparse.Namespace) -> int:
    """``cable-ocp response FILE``."""
    from cable_ocp.batch.response import frequency_response
    from cable_ocp.scene.dynamics import load_dynamic_scene

    out.check_outputs(args)
    scene = load_dynamic_scene(args.file, out.overrides(args))
    opts = _options(args, scene.response)
    n_runs = len(opts["frequencies"]) * (1 if opts["amplitudes"] is None
                                         else len(opts["amplitudes"]))
    with out.progress(args, n_runs, "response", "run") as bar:
        res = frequency_response(scene.raw, opts["frequencies"], opts["amplitudes"],
                                 opts["outputs"], excitation=opts["excitation"],
                                 settings=opts["settings"],
                                 damping_ratio=opts["damping_ratio"], workers=args.workers,
                                 scheduler=args.scheduler,
                                 progress=lambda done, total: bar(done, total))
    title = scene.meta.get("title", Path(args.file).stem)
    with interrupt.deferred():
        return _outputs(args, res, title, scene.response)


def _outputs(args: argparse.Namespace, res: Any, title: str, defaults: Any) -> int:
    """The text, JSON, CSV and figure of a finished (or interrupted) sweep."""
    lin = res.linear
    if out.stdout_free(args):
        print(title)
        print(f"status        {res.status}: {res.message}")
        print(f"excitation    {res.excitation}, model {res.diagnostics['model']}")
        nat = ", ".join(f"{w:.4g}" for w in lin.natural_frequencies[:4])
        print(f"linear        {lin.status}: natural frequencies {nat or '-'} rad/s"
              + ("" if lin.status == "solved" else f" ({lin.message})"))
        head = ["A (m)", "w (rad/s)", "status"] + [
            f"{n} / A ({u}/m) run | linear" for n, u in zip(res.outputs, res.units,
                                                          strict=True)]
        print("  ".join(head))
        for a, amp in enumerate(res.amplitudes):
            for f, w in enumerate(res.frequencies):
                cells = [f"{amp:<5g}", f"{w:<9.4g}", f"{res.run_status[a, f]:<13}"]
                for k in range(len(res.outputs)):
                    cells.append(f"{res.rao[a, f, k]:>11.5g} | {lin.rao[f, k]:<11.5g}")
                print("  ".join(cells))
    out.emit_json(args, out.envelope(res.status, res.message, res.to_dict()))
    if args.csv:
        out.emit_csv(args, *res.table(), partial=res.status == "interrupted")
    if res.status == "interrupted":
        raise KeyboardInterrupt
    if args.plot:
        from cable_ocp.plots.response import plot_response

        out.emit_plot(args, lambda path: plot_response(
            res, path, title=title, tension_scale=defaults.tension_scale,
            frequency_scale=defaults.frequency_scale))
    return out.EXIT_OK if res.success else out.EXIT_NOT_SUCCESS
