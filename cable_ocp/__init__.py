"""cable_ocp: marine-cable problems as optimal-control and boundary-value problems in CasADi.

Statics in four lines::

    import cable_ocp as co
    scene = co.load_scene("problems/dezoysa_sea_buggy.toml", {"layout.psi0_deg": 90})
    sol = co.solve(scene)                      # StaticsSolution: arrays + diagnostics
    sols = co.sweep(scene, "layout.psi0_deg", range(0, 181, 10))  # built once, warm-started

The data flow is one way: problem file -> :mod:`cable_ocp.scene` (validated frozen
dataclasses) -> :mod:`cable_ocp.statics.formulation` (CasADi equations, only the terms the
scene needs) -> :mod:`cable_ocp.statics.collocation` (transcription) ->
:mod:`cable_ocp.statics.line_solver` (built once, parametric, warm-started) ->
:mod:`cable_ocp.statics.solver` (solve, sweep, session) ->
:mod:`cable_ocp.statics.solution` -> :mod:`cable_ocp.report` / :mod:`cable_ocp.plots`.

Every result prints a short summary, draws itself (``fig, ax = sol.plot()``) and turns into
arrays and tables (``sol.to_xarray()``, ``sol.to_pandas()``, the extra ``[io]``);
:func:`write_netcdf` writes one whole or not at all (docs/api.md).

Packages
--------
numerics, physics, scene, statics, baselines, dynamics, mooring, heave, batch, schedule
    the library, in its layer order (each imports only from the ones before it; mooring:
    systems of many lines and bodies; schedule: the optimal deployment schedule)
bench, plots, report, cli   the face: benchmarks, figures, text, the command line
errors, status, version   the one exception type, the status vocabulary, the version
"""

# the command line starting up: a Ctrl-C during these imports is recorded, not a traceback
from cable_ocp.numerics import interrupt as _interrupt  # isort: skip

_interrupt.defer_during_launch()

from cable_ocp.errors import CableOCPError  # noqa: E402
from cable_ocp.numerics.export import write_netcdf  # noqa: E402
from cable_ocp.scene import Scene, load, load_scene, scene_from_dict  # noqa: E402
from cable_ocp.statics.footprint_nlp import FootprintResult, footprint  # noqa: E402
from cable_ocp.statics.line_solver import StaticsSolver  # noqa: E402
from cable_ocp.statics.solution import StaticsSolution  # noqa: E402
from cable_ocp.statics.solver import solve, sweep  # noqa: E402
from cable_ocp.status import Status  # noqa: E402

# the baseline methods register themselves (statics.registry) when imported
from cable_ocp import baselines  # noqa: E402, F401  isort: skip

from cable_ocp.version import __version__  # noqa: E402, F401  (the public version)

__all__ = [
    "CableOCPError",
    "FootprintResult",
    "Scene",
    "StaticsSolution",
    "StaticsSolver",
    "Status",
    "load",
    "load_scene",
    "scene_from_dict",
    "footprint",
    "solve",
    "sweep",
    "write_netcdf",
]
