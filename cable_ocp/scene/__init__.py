"""Problem files (TOML, SI units) -> validated scenes (frozen dataclasses).

The only place that reads user input. Everything it returns is validated: downstream code
may assume finite numbers, consistent end conditions and SI units. Every user error raises
:class:`~cable_ocp.errors.CableOCPError` with a message that names the offending key and
says what would be valid.

Modules
-------
files    reading a file (UTF-8 TOML), ``--set`` overrides, telling scene kinds apart
fields   validation of single values (numbers with ranges, integers, choices, vectors)
parts    what the scene kinds share: environment, current, seabed, cable, segments,
         bodies, end conditions
statics  the statics scene (:class:`Scene`), its schema and :func:`load_scene`
dynamics the dynamic scene (:class:`~cable_ocp.scene.dynamics.DynamicScene`) and its
         prescribed top motion (``motion``)
dynamic_parts  the parts of a dynamic scene (a segment's dynamics, the top motion, ...)
response the ``[response]`` table of a dynamic scene (defaults of ``cable-ocp response``)
deployment the ``[deployment]`` table of a dynamic scene (the optimal pay-out problem)
heave    the heave-compensation scene (:class:`HeaveScene`)
system   mooring systems: line types, points, bodies, lines (:class:`SystemScene`)
loader   :func:`load`: any problem file -> its scene (statics, dynamics or heave)
moordyn  MoorDyn v2 input files <-> the system problem dict (read_moordyn,
         write_moordyn) and that dict as TOML text (system_dict_to_toml)
"""

from cable_ocp.scene.fields import FREE
from cable_ocp.scene.files import apply_overrides, parse_override, read_problem, scene_kind
from cable_ocp.scene.parts import Body, Cable, Current, End, Environment, Seabed
from cable_ocp.scene.statics import (
    METHODS,
    Footprint,
    Scene,
    SolverOptions,
    load_scene,
    scene_from_dict,
)

# last: the dynamic and heave scenes import the modules above
from cable_ocp.scene.loader import load  # noqa: E402  isort: skip

__all__ = [
    "FREE",
    "METHODS",
    "Body",
    "Cable",
    "Current",
    "End",
    "Environment",
    "Footprint",
    "Scene",
    "Seabed",
    "SolverOptions",
    "apply_overrides",
    "load",
    "load_scene",
    "parse_override",
    "read_problem",
    "scene_from_dict",
    "scene_kind",
]

