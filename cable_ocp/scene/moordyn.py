"""MoorDyn v2 input files <-> the system problem dict (docs/systems_moordyn.md).

:func:`read_moordyn` turns a MoorDyn v2 input file (also the older section names that
MoorDyn 2 still reads, and the files MoorPy's ``System.unload`` writes) into a system
problem dict of our schema, as if read from TOML (cable_ocp/scene/system.py);
:func:`write_moordyn` writes such a dict as a MoorDyn v2 file; :func:`system_dict_to_toml`
writes the dict as TOML text.

The columns and option names follow MoorDyn 2.7's own reader (FloatingArrayDesign/MoorDyn,
source/MoorDyn2.cpp: ``ReadInFile``, ``readLineProps``, ``readBody``, ``readOptionsLine``,
``findStartOfSection``) and MoorPy 1.3's ``System.load``/``System.unload``:

- z: MoorDyn puts z = 0 at the free surface (the seabed at z = -depth); ours puts z = 0 on
  the seabed: ``z_ours = z_moordyn + depth`` for fixed, coupled and free points and for
  body reference positions. A body point's position is in the body frame, relative to the
  body's reference point, and is not shifted; nor are centres of gravity and buoyancy.
- Line types: Diam -> ``diameter``, MassDen -> ``mass_per_length``, EA ->
  ``axial_stiffness`` (a number, or ``EA|EA_D`` / ``EA|alpha|beta``: the static EA is the
  first value; a tension-strain table file or a Syrope model is refused), Cd ->
  ``normal_drag`` (on d), Ca -> ``added_mass``, CdAx -> ``tangential_drag``, CaAx ->
  ``tangential_added_mass``. MoorDyn's CdAx is already on the wetted perimeter pi d, as ours
  is (source/Line.cpp ``Dq = vq_mag * Cdt * pi * 0.5 * rho_w * d * l * vq``; docs/inputs.rst
  "CdAx - tangential drag coefficient (with respect to surface area, pi*d*l)"; MoorPy
  line.py the same): the value is copied, not divided by pi.
- Points: Fixed/Anchor -> kind ``"fixed"``; Coupled/Vessel/Fairlead (and MoorDyn-F's
  TurbineN) -> kind ``"fixed"`` too: a coupled point is held where the file puts it; BodyN
  -> kind ``"body"`` on body N; Free/Connect/Point -> kind ``"free"`` with Mass, Volume and
  the optional Fx Fy Fz.
- Bodies: Fixed/Coupled/Vessel -> kind ``"fixed"``; CoupledPinned/VesselPinned -> kind
  ``"free"`` with ``held = ["x", "y", "z"]``; anything else is free (MoorDyn's rule).
  MoorDyn applies a body's buoyancy (rho g V) together with its weight at the centre of
  gravity (source/Body.cpp ``doRHS``: ``Fgrav = (V rho g - M g) e_z``, moment
  ``rCG x Fgrav``) and models no waterplane: ``center_of_buoyancy`` is the CG.
- Everything MoorDyn-only (options, outputs, per-line NumSegs and output flags, per-type
  BA, EI and VIV coefficients, per-body inertia, CdA and Ca, per-point CdA and Ca, coupled
  attachment words) is kept under the top-level table ``[moordyn]`` so that a read, write,
  read round trip gives the same dict.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path
from typing import Any

from cable_ocp.errors import CableOCPError
from cable_ocp.numerics.atomic import write_text_atomically

__all__ = ["MOORDYN_DEFAULT_DENSITY", "MOORDYN_DEFAULT_GRAVITY", "read_moordyn",
           "system_dict_to_toml", "write_moordyn"]

#: MoorDyn 2.7's defaults when the file gives no ``rho`` / ``g`` (source/MoorDyn2.cpp,
#: the constructor: ``env->rho_w = 1025.``, ``env->g = 9.80665``), kg/m^3 and m/s^2
MOORDYN_DEFAULT_DENSITY = 1025.0
MOORDYN_DEFAULT_GRAVITY = 9.80665

_MODELLED = "cable_ocp reads line types, points, bodies, lines, options"
# section kind -> the header words MoorDyn 2.7 looks for (findStartOfSection), in its order
_SECTIONS = (
    ("line_types", ("LINE DICTIONARY", "LINE TYPES")),
    ("rod_types", ("ROD DICTIONARY", "ROD TYPES")),
    ("bodies", ("BODIES", "BODY LIST", "BODY PROPERTIES")),
    ("rods", ("RODS", "ROD LIST", "ROD PROPERTIES")),
    ("points", ("POINTS", "POINT LIST", "POINT PROPERTIES", "CONNECTION PROPERTIES",
                "NODE PROPERTIES")),
    ("lines", ("LINES", "LINE LIST", "LINE PROPERTIES")),
    ("options", ("OPTIONS",)),
    ("outputs", ("OUTPUT",)),
    ("failure", ("FAILURE",)),
    ("syrope", ("SYROPE IC",)),
    ("control", ("CONTROL",)),
    ("external", ("EXTERNAL LOADS",)),
)
_UNMODELLED = {"rod_types": "ROD TYPES", "rods": "RODS", "failure": "FAILURE",
               "syrope": "SYROPE IC", "control": "CONTROL", "external": "EXTERNAL LOADS"}
_DEPTH_NAMES = ("wtrdpth", "depth", "wtrdepth")
_RHO_NAMES = ("rho", "wtrdnsty")
_G_NAMES = ("g", "gravity")
_FRICTION = "frictioncoefficient"
_FIXED_WORDS = ("ANCHOR", "FIXED", "FIX")
_COUPLED_WORDS = ("FAIRLEAD", "VESSEL", "VES", "COUPLED", "CPLD", "TURBINE")
_FREE_WORDS = ("POINT", "CONNECT", "CON", "FREE")
_PINNED_WORDS = ("VESSELPINNED", "VESPIN", "CPLDPIN", "COUPLEDPINNED")
_NAME_COMMENT = re.compile(r"#\s*name:\s*(\S.*?)\s*$")
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_INT = re.compile(r"[+-]?\d+")
_BA_DEFAULT = -1.0          # MoorPy's unload default (critical damping ratio 1)
_EI_DEFAULT = 0.0
_SEGMENT_LENGTH = 10.0      # m, NumSegs of a written line without one: one per 10 m
_DOFS = ("x", "y", "z", "roll", "pitch", "yaw")


# -- reading ------------------------------------------------------------------------------
class _Row:
    """One data row of a section: its tokens (up to a ``#``), its line number, a name."""

    def __init__(self, tokens: list[str], lineno: int, name: str | None) -> None:
        self.tokens = tokens
        self.lineno = lineno
        self.name = name


def _split(text: str) -> tuple[list[str], str | None]:
    """Tokens of a line up to the first ``#`` (MoorDyn's ``str::split``) and a ``# name: X``."""
    tokens = []
    for tok in text.split():
        if "#" in tok:
            break
        tokens.append(tok)
    m = _NAME_COMMENT.search(text)
    return tokens, (m.group(1) if m else None)


def _section_kind(text: str) -> str | None:
    upper = text.upper()
    for kind, words in _SECTIONS:
        if any(w in upper for w in words):
            return kind
    return None


def _sections(lines: list[str], fname: str) -> tuple[list[str], dict[str, list[_Row]]]:
    """The text before the first section and each known section's rows."""
    header: list[str] = []
    found: dict[str, list[_Row]] = {}
    kind: str | None = None
    skip = 0
    seen_section = False
    for i, raw in enumerate(lines, start=1):
        text = raw.rstrip()
        if "---" in text:
            seen_section = True
            kind = _section_kind(text)
            if kind is not None:
                if kind in found:
                    raise CableOCPError(f"{fname} line {i}: a second {kind.upper()} section "
                                        "(MoorDyn reads only the first one)")
                found[kind] = []
            # MoorDyn skips the column-name and unit lines of a table section
            skip = 0 if kind in ("options", "outputs") else 2
            continue
        if not seen_section:
            if text.strip():
                header.append(text.strip())
            continue
        if kind is None:
            continue
        if skip:
            skip -= 1
            continue
        tokens, name = _split(text)
        if kind == "outputs" and tokens and tokens[0].upper() == "END":
            kind = None
            continue
        if tokens:
            found[kind].append(_Row(tokens, i, name))
    return header, found


def _num(tok: str, what: str, row: _Row, fname: str) -> float:
    if not _NUMBER.fullmatch(tok):
        raise CableOCPError(f"{fname} line {row.lineno}: {what} = {tok!r} is not a number")
    return float(tok)


def _int(tok: str, what: str, row: _Row, fname: str) -> int:
    if not _INT.fullmatch(tok):
        raise CableOCPError(f"{fname} line {row.lineno}: {what} = {tok!r} is not an integer")
    return int(tok)


def _value(tok: str) -> int | float | str:
    """An option's value: an int or a float where it is one, else the text."""
    if _INT.fullmatch(tok):
        return int(tok)
    if _NUMBER.fullmatch(tok):
        return float(tok)
    return tok


def _bars(tok: str, what: str, row: _Row, fname: str, sizes: tuple[int, ...]) -> list[float]:
    parts = tok.split("|")
    if len(parts) not in sizes:
        raise CableOCPError(f"{fname} line {row.lineno}: {what} = {tok!r}: expected "
                            f"{' or '.join(map(str, sizes))} numbers separated by |")
    return [_num(p, what, row, fname) for p in parts]


def _need(row: _Row, n: int, section: str, columns: str, fname: str) -> None:
    if len(row.tokens) < n:
        raise CableOCPError(f"{fname} line {row.lineno}: {section} needs {n} columns "
                            f"({columns}), got {len(row.tokens)}")


def _attachment(tok: str) -> tuple[str, str]:
    """MoorDyn's ``decomposeString`` for an attachment word: (letters, number)."""
    m = re.fullmatch(r"([A-Za-z]*)_?(\d*)", tok)
    if m is None:
        return tok.upper(), ""
    return m.group(1).upper(), m.group(2)


def _read_options(rows: list[_Row], fname: str) -> tuple[dict[str, Any], dict[str, Any]]:
    env: dict[str, Any] = {}
    options: dict[str, Any] = {}
    for row in rows:
        if len(row.tokens) < 2:
            continue    # MoorDyn ignores an option line without a name
        value, name = row.tokens[0], row.tokens[1]
        low = name.lower()
        if low in _DEPTH_NAMES:
            env["water_depth"] = _num(value, f"option {name}", row, fname)
        elif low in _RHO_NAMES:
            env["water_density"] = _num(value, f"option {name}", row, fname)
        elif low in _G_NAMES:
            env["gravity"] = _num(value, f"option {name}", row, fname)
        elif low == _FRICTION:
            env["friction"] = _num(value, f"option {name}", row, fname)
        elif low == "seafloorfile":
            raise CableOCPError(f"{fname} line {row.lineno}: option {name} (a 3-D seabed "
                                "from a file) is not modelled: cable_ocp's seabed is a plane")
        elif low == "currents" and value not in ("0", "0.0"):
            raise CableOCPError(f"{fname} line {row.lineno}: option {name} = {value} (a "
                                "current from MoorDyn's current files) is not modelled: give "
                                "the current in [environment.current]")
        else:
            options[name] = _value(value)
    return env, options


def _read_line_types(rows: list[_Row], fname: str) -> tuple[dict[str, Any], dict[str, Any]]:
    types: dict[str, Any] = {}
    extra: dict[str, Any] = {}
    cols = "Name Diam MassDen EA BA/-zeta EI Cd Ca CdAx CaAx [Cl [dF cF]]"
    for row in rows:
        _need(row, 10, "a line type", cols, fname)
        t = row.tokens
        if len(t) not in (10, 11, 13):
            raise CableOCPError(f"{fname} line {row.lineno}: a line type has 10, 11 or 13 "
                                f"columns ({cols}), got {len(t)}")
        name = t[0]
        if name in types:
            raise CableOCPError(f"{fname} line {row.lineno}: line type {name!r} is given twice")
        ea_parts = t[3].split("|")
        if ea_parts[0].upper().startswith("SYROPE:") or not _NUMBER.fullmatch(ea_parts[0]):
            raise CableOCPError(
                f"{fname} line {row.lineno}: line type {name!r} EA = {t[3]!r} is a "
                "tension-strain table or a non-linear model: cable_ocp's lines are linear "
                "elastic; give EA as a number (N)")
        if len(ea_parts) > 3:
            raise CableOCPError(f"{fname} line {row.lineno}: line type {name!r} EA = {t[3]!r}: "
                                "at most 3 values separated by | (MoorDyn)")
        ea_dynamic = [_num(p, f"line type {name!r} EA", row, fname) for p in ea_parts[1:]]
        types[name] = {
            "diameter": _num(t[1], f"line type {name!r} Diam", row, fname),
            "mass_per_length": _num(t[2], f"line type {name!r} MassDen", row, fname),
            "axial_stiffness": float(ea_parts[0]),
            "normal_drag": _num(t[6], f"line type {name!r} Cd", row, fname),
            "added_mass": _num(t[7], f"line type {name!r} Ca", row, fname),
            "tangential_drag": _num(t[8], f"line type {name!r} CdAx", row, fname),
            "tangential_added_mass": _num(t[9], f"line type {name!r} CaAx", row, fname),
        }
        md: dict[str, Any] = {}
        if ea_dynamic:
            md["EA_dynamic"] = ea_dynamic       # EA|EA_D or EA|alpha|beta: after the bar
        for key, tok, default in (("BA", t[4], _BA_DEFAULT), ("EI", t[5], _EI_DEFAULT)):
            v = float(tok) if _NUMBER.fullmatch(tok) else tok
            if v != default:
                md[key] = v
        for key, tok in zip(("Cl", "dF", "cF"), t[10:], strict=False):
            md[key] = _num(tok, f"line type {name!r} {key}", row, fname)
        if md:
            extra[name] = md
    return types, extra


def _read_bodies(rows: list[_Row], fname: str, depth: float
                 ) -> tuple[list[dict[str, Any]], dict[str, Any], dict[int, str]]:
    bodies: list[dict[str, Any]] = []
    extra: dict[str, Any] = {}
    names: dict[int, str] = {}
    cols = "ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*"
    for row in rows:
        _need(row, 14, "a body", cols, fname)
        t = row.tokens
        bid = _int(t[0], "body ID", row, fname)
        if bid in names:
            raise CableOCPError(f"{fname} line {row.lineno}: body ID {bid} is given twice")
        name = row.name or f"body{bid}"
        names[bid] = name
        r6 = [_num(v, f"body {bid} {c}", row, fname)
              for v, c in zip(t[2:8], ("X0", "Y0", "Z0", "r0", "p0", "y0"),
                                 strict=True)]
        cg = _bars(t[9], f"body {bid} CG", row, fname, (1, 3))
        cg = [0.0, 0.0, cg[0]] if len(cg) == 1 else cg
        inertia = _bars(t[10], f"body {bid} I", row, fname, (1, 3))
        inertia = inertia * 3 if len(inertia) == 1 else inertia
        volume = _num(t[11], f"body {bid} Volume", row, fname)
        cda = _bars(t[12], f"body {bid} CdA", row, fname, (1, 2, 3, 6))
        ca = _bars(t[13], f"body {bid} Ca", row, fname, (1, 3))
        word, _ = _attachment(t[1])
        body: dict[str, Any] = {"name": name}
        md: dict[str, Any] = {}
        if word in _FIXED_WORDS:
            body["kind"] = "fixed"
        elif word in _COUPLED_WORDS:
            body["kind"] = "fixed"
            md["attachment"] = t[1]
        elif word in _PINNED_WORDS:
            body["kind"] = "free"
            body["held"] = ["x", "y", "z"]
            md["attachment"] = t[1]
        else:
            body["kind"] = "free"
        body["position"] = [r6[0], r6[1], r6[2] + depth]
        body["rotation_deg"] = r6[3:]
        body["mass"] = _num(t[8], f"body {bid} Mass", row, fname)
        body["center_of_gravity"] = cg
        if volume != 0.0:
            body["volume"] = volume
            body["center_of_buoyancy"] = list(cg)   # Body.cpp doRHS: buoyancy at the CG
        if any(inertia):
            md["inertia"] = inertia
        if any(cda):
            md["CdA"] = cda
        if any(ca):
            md["Ca"] = ca
        if md:
            extra[name] = md
        bodies.append(body)
    return bodies, extra, names


def _read_points(rows: list[_Row], fname: str, depth: float, bodies: dict[int, str]
                 ) -> tuple[list[dict[str, Any]], dict[str, Any], dict[int, str]]:
    points: list[dict[str, Any]] = []
    extra: dict[str, Any] = {}
    names: dict[int, str] = {}
    cols = "ID Attachment X Y Z Mass Volume [Fx Fy Fz] CdA Ca"
    for row in rows:
        _need(row, 9, "a point", cols, fname)
        t = row.tokens
        pid = _int(re.sub(r"^[A-Za-z]+", "", t[0]), "point ID", row, fname)
        if pid in names:
            raise CableOCPError(f"{fname} line {row.lineno}: point ID {pid} is given twice")
        name = row.name or f"point{pid}"
        names[pid] = name
        xyz = [_num(v, f"point {pid} {c}", row, fname) for v, c in zip(t[2:5], "XYZ", strict=True)]
        mass = _num(t[5], f"point {pid} Mass", row, fname)
        volume = _num(t[6], f"point {pid} Volume", row, fname)
        force = None
        if len(t) >= 12:
            force = [_num(v, f"point {pid} F{c}", row, fname) for v, c in zip(t[7:10], "xyz",
                                                                       strict=True)]
            cda, ca = t[10], t[11]
        else:
            cda, ca = t[7], t[8]
        md: dict[str, Any] = {}
        for key, tok in (("CdA", cda), ("Ca", ca)):
            v = _num(tok, f"point {pid} {key}", row, fname)
            if v != 0.0:
                md[key] = v
        word, num = _attachment(t[1])
        point: dict[str, Any] = {"name": name}
        if word == "BODY":
            bid = int(num) if num else 0
            if bid not in bodies:
                raise CableOCPError(f"{fname} line {row.lineno}: point {pid} is on {t[1]!r}: "
                                    f"no such body (bodies: "
                                    f"{', '.join(map(str, bodies)) or 'none'})")
            if mass or volume or (force and any(force)):
                raise CableOCPError(
                    f"{fname} line {row.lineno}: point {pid} on body {bid} has a mass, volume "
                    "or force: cable_ocp puts no load on a body point; add it to the body")
            point.update(kind="body", body=bodies[bid], position=xyz)
        elif word in _FIXED_WORDS or word in _COUPLED_WORDS:
            point.update(kind="fixed", position=[xyz[0], xyz[1], xyz[2] + depth])
            if word in _COUPLED_WORDS:
                md["attachment"] = t[1]
            for key, v in (("mass", mass), ("volume", volume)):
                if v != 0.0:
                    md[key] = v
            if force is not None and any(force):
                md["force"] = force
        elif word in _FREE_WORDS:
            point.update(kind="free", position=[xyz[0], xyz[1], xyz[2] + depth], mass=mass,
                         volume=volume)
            if force is not None:
                point["force"] = force
        else:
            raise CableOCPError(f"{fname} line {row.lineno}: point {pid} attachment "
                                f"{t[1]!r} is not one of Fixed, Coupled, Free, Body<N>")
        if md:
            extra[name] = md
        points.append(point)
    return points, extra, names


def _read_lines(rows: list[_Row], fname: str, types: dict[str, Any], points: dict[int, str]
                ) -> tuple[list[dict[str, Any]], dict[str, Any]]:
    lines: list[dict[str, Any]] = []
    extra: dict[str, Any] = {}
    seen: set[int] = set()
    cols = "ID LineType AttachA AttachB UnstrLen NumSegs Outputs"
    for row in rows:
        _need(row, 7, "a line", cols, fname)
        t = row.tokens
        lid = _int(t[0], "line ID", row, fname)
        if lid in seen:
            raise CableOCPError(f"{fname} line {row.lineno}: line ID {lid} is given twice")
        seen.add(lid)
        if t[1] not in types:
            raise CableOCPError(f"{fname} line {row.lineno}: line {lid} has line type "
                                f"{t[1]!r}: no such type (types: "
                                f"{', '.join(types) or 'none: add a LINE TYPES section'})")
        ends = []
        for col, tok in (("AttachA", t[2]), ("AttachB", t[3])):
            m = re.fullmatch(r"([A-Za-z]*)(\d+)([A-Za-z]*)", tok)
            word = m.group(1).upper() if m else "?"
            if m and word in ("R", "ROD"):
                raise CableOCPError(f"{fname} line {row.lineno}: line {lid} {col} = {tok!r} "
                                    f"is a rod: rods are not modelled ({_MODELLED})")
            if m is None or word not in ("", "C", "CON", "P", "POINT") or m.group(3):
                raise CableOCPError(f"{fname} line {row.lineno}: line {lid} {col} = {tok!r}: "
                                    "expected a point ID (e.g. 3 or P3)")
            pid = int(m.group(2))
            if pid not in points:
                raise CableOCPError(f"{fname} line {row.lineno}: line {lid} {col} = {tok!r}: "
                                    f"no such point (points: "
                                    f"{', '.join(map(str, points)) or 'none'})")
            ends.append(points[pid])
        name = row.name or f"line{lid}"
        lines.append({"name": name, "point_a": ends[0], "point_b": ends[1], "type": t[1],
                      "length": _num(t[4], f"line {lid} UnstrLen", row, fname)})
        extra[name] = {"NumSegs": _int(t[5], f"line {lid} NumSegs", row, fname),
                       "outputs": t[6]}
    return lines, extra


def read_moordyn(path: str | Path) -> dict[str, Any]:
    """A MoorDyn v2 input file -> a system problem dict in our schema (as if read from TOML).

    Parameters
    ----------
    path : str or Path
        The MoorDyn input file (text; MoorDyn's z = 0 at the free surface).

    Returns
    -------
    dict
        Tables ``meta`` (the text before the first section as ``title``), ``environment``
        (``water_depth`` m, ``water_density`` kg/m^3, ``gravity`` m/s^2; MoorDyn's defaults
        1025 and 9.80665 where the file gives none; ``seabed.friction`` from
        FrictionCoefficient), ``line_types``, ``points``, ``bodies``, ``lines`` (z shifted
        to ours: ``z_ours = z_moordyn + depth``) and ``moordyn`` (what only MoorDyn uses).

    Raises
    ------
    CableOCPError
        Naming the file and line: a missing water depth (option WtrDpth), a section not
        modelled here with entries (rods, failures, ...), a malformed number, a line
        referencing an unknown point or line type, a non-linear EA.
    """
    path = Path(path)
    fname = path.name
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as exc:
        raise CableOCPError(f"{path}: cannot read the MoorDyn file ({exc.strerror})") from None
    header, sec = _sections(text.splitlines(), fname)
    for kind, title in _UNMODELLED.items():
        if sec.get(kind):
            row = sec[kind][0]
            raise CableOCPError(f"{fname} line {row.lineno}: section {title} is not modelled "
                                f"({_MODELLED})")
    env_t, options = _read_options(sec.get("options", []), fname)
    if "water_depth" not in env_t:
        raise CableOCPError(f"{fname}: no water depth: add the option line '<depth> WtrDpth' "
                            "(m) to the OPTIONS section (cable_ocp needs the seabed)")
    depth = env_t["water_depth"]
    environment: dict[str, Any] = {
        "water_depth": depth,
        "water_density": env_t.get("water_density", MOORDYN_DEFAULT_DENSITY),
        "gravity": env_t.get("gravity", MOORDYN_DEFAULT_GRAVITY),
    }
    # MoorDyn always has a seabed at its water depth (contact with stiffness kb and
    # damping cb; axial friction FrictionCoefficient, 0 unless given): ours is the plane
    # z = 0 with contact
    environment["seabed"] = {"friction": env_t.get("friction", 0.0)}
    types, type_extra = _read_line_types(sec.get("line_types", []), fname)
    bodies, body_extra, body_ids = _read_bodies(sec.get("bodies", []), fname, depth)
    points, point_extra, point_ids = _read_points(sec.get("points", []), fname, depth,
                                                  body_ids)
    lines, line_extra = _read_lines(sec.get("lines", []), fname, types, point_ids)
    data: dict[str, Any] = {}
    if header:
        data["meta"] = {"title": "\n".join(header)}
    data["environment"] = environment
    data["line_types"] = types
    data["points"] = points
    if bodies:
        data["bodies"] = bodies
    data["lines"] = lines
    md: dict[str, Any] = {}
    for key, value in (("options", options), ("line_types", type_extra),
                       ("bodies", body_extra), ("points", point_extra),
                       ("lines", line_extra)):
        if value:
            md[key] = value
    outputs = [tok for row in sec.get("outputs", []) for tok in row.tokens]
    if outputs:
        md["outputs"] = outputs
    if md:
        data["moordyn"] = md
    return data


# -- writing ------------------------------------------------------------------------------
def _fmt(v: Any) -> str:
    """A number as MoorDyn reads it back exactly (repr precision)."""
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return str(v)
    if isinstance(v, float) and not math.isfinite(v):
        raise CableOCPError(f"value {v!r}: MoorDyn needs a finite number")
    return repr(v) if isinstance(v, float) else str(v)


def _rotate(rot_deg: list[float], v: list[float]) -> list[float]:
    """R v with R = Rz(yaw) Ry(pitch) Rx(roll) (CONVENTIONS "Mooring systems")."""
    r, p, y = (math.radians(a) for a in rot_deg)
    x1, y1, z1 = v[0], v[1] * math.cos(r) - v[2] * math.sin(r), \
        v[1] * math.sin(r) + v[2] * math.cos(r)
    x2, z2 = x1 * math.cos(p) + z1 * math.sin(p), -x1 * math.sin(p) + z1 * math.cos(p)
    return [x2 * math.cos(y) - y1 * math.sin(y), x2 * math.sin(y) + y1 * math.cos(y), z2]


def _type_columns(name: str, t: dict[str, Any], md: dict[str, Any], rho: float,
                  g: float) -> list[str]:
    where = f"line_types.{name}"
    if "standard" in t:
        raise CableOCPError(f"{where}.standard: write the type's values (diameter, "
                            "mass_per_length, axial_stiffness, ...) before writing MoorDyn")
    for key in ("diameter", "axial_stiffness"):
        if key not in t:
            raise CableOCPError(f"{where}.{key}: MoorDyn needs it")
    d = float(t["diameter"])
    if "mass_per_length" in t:
        mass = t["mass_per_length"]
    elif "weight_in_water" in t:
        mass = t["weight_in_water"] / g + rho * math.pi * d * d / 4.0
    else:
        raise CableOCPError(f"{where}: needs mass_per_length (kg/m) or weight_in_water (N/m)")
    ea = t["axial_stiffness"]
    if not math.isfinite(float(ea)):
        raise CableOCPError(f"{where}.axial_stiffness = {ea}: MoorDyn needs a finite EA (N)")
    ea_text = _fmt(ea)
    if "EA_dynamic" in md:      # EA|EA_D or EA|alpha|beta, the static EA given here
        ea_text = "|".join([ea_text, *(_fmt(v) for v in md["EA_dynamic"])])
    cols = [name, _fmt(t["diameter"]), _fmt(mass), ea_text, _fmt(md.get("BA", _BA_DEFAULT)),
            _fmt(md.get("EI", _EI_DEFAULT)), _fmt(t.get("normal_drag", 0.0)),
            _fmt(t.get("added_mass", 0.0)), _fmt(t.get("tangential_drag", 0.0)),
            _fmt(t.get("tangential_added_mass", 0.0))]
    cols += [_fmt(md[k]) for k in ("Cl", "dF", "cF") if k in md]
    return cols


def _table(title: str, names: str, units: str, rows: list[list[str]],
           comments: list[str | None]) -> list[str]:
    out = [f"---------------------- {title} ----------------------", names, units]
    for cols, note in zip(rows, comments, strict=True):
        out.append("  ".join(cols) + (f"  # name: {note}" if note else ""))
    return out


def _line_parts(line: dict[str, Any], where: str) -> list[tuple[str, float]]:
    if "parts" in line:
        parts = line["parts"]
        if not isinstance(parts, list) or not parts:
            raise CableOCPError(f"{where}.parts: expected a non-empty list of {{type, length}}")
        return [(p["type"], p["length"]) for p in parts]
    if "type" not in line or "length" not in line:
        raise CableOCPError(f"{where}: needs type and length, or parts")
    return [(line["type"], line["length"])]


def _moordyn_text(data: dict[str, Any]) -> str:
    env = data.get("environment", {})
    if "water_depth" not in env:
        raise CableOCPError("environment.water_depth: MoorDyn needs the water depth (m)")
    depth = float(env["water_depth"])
    rho = float(env.get("water_density", MOORDYN_DEFAULT_DENSITY))
    g = float(env.get("gravity", MOORDYN_DEFAULT_GRAVITY))
    if "current" in env:
        raise CableOCPError("environment.current: MoorDyn reads currents from its own "
                            "files (option Currents); write_moordyn cannot carry it")
    seabed = env.get("seabed", {})
    for key in seabed:
        if key != "friction" and seabed[key] != 0.0:
            raise CableOCPError(f"environment.seabed.{key}: MoorDyn's seabed is flat at "
                                "the water depth; only friction (FrictionCoefficient) is written")
    md = data.get("moordyn", {})
    md_types, md_bodies = md.get("line_types", {}), md.get("bodies", {})
    md_points, md_lines = md.get("points", {}), md.get("lines", {})

    title = data.get("meta", {}).get("title", "MoorDyn v2 input file written by cable_ocp")
    out = [s for s in str(title).splitlines() if s.strip()] or ["MoorDyn v2 input file"]

    types = data.get("line_types", {})
    type_rows = [_type_columns(n, t, md_types.get(n, {}), rho, g) for n, t in types.items()]
    viv = max((len(r) for r in type_rows), default=10)   # MoorDyn reads 10, 11 or 13
    out += _table("LINE TYPES",
                  "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx"
                  + ["", " Cl", "", " Cl dF cF"][viv - 10],
                  "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)"
                  + ["", " (-)", "", " (-) (-) (-)"][viv - 10],
                  type_rows, [None] * len(type_rows))

    bodies = data.get("bodies", [])
    body_id = {b["name"]: i for i, b in enumerate(bodies, start=1)}
    body_by_name = {b["name"]: b for b in bodies}
    rows, notes = [], []
    for i, b in enumerate(bodies, start=1):
        where = f"bodies[{i - 1}]"
        for key in ("waterplane_area", "waterplane_moments", "metacenter",
                    "hydrostatic_matrix", "force", "moment"):
            if key in b:
                raise CableOCPError(f"{where}.{key}: a MoorDyn body has no such input "
                                    "(no waterplane, no steady load)")
        bmd = md_bodies.get(b["name"], {})
        cg = list(b.get("center_of_gravity", [0.0, 0.0, 0.0]))
        volume = b.get("volume", 0.0)
        if volume and list(b.get("center_of_buoyancy", cg)) != cg:
            raise CableOCPError(f"{where}.center_of_buoyancy: MoorDyn applies the buoyancy at "
                                "the centre of gravity (Body.cpp); make them equal")
        held = set(b.get("held", []))
        if b.get("kind", "free") == "fixed":
            word = bmd.get("attachment", "Fixed")
        elif held == {"x", "y", "z"}:
            word = bmd.get("attachment", "CoupledPinned")
        elif not held:
            word = "Free"
        else:
            raise CableOCPError(f"{where}.held = {sorted(held, key=_DOFS.index)}: MoorDyn "
                                "holds all of a body, its translations (CoupledPinned) or none")
        pos = b["position"]
        rot = b.get("rotation_deg", [0.0, 0.0, 0.0])
        inertia = bmd.get("inertia", [0.0, 0.0, 0.0])
        rows.append([str(i), word, _fmt(pos[0]), _fmt(pos[1]), _fmt(pos[2] - depth),
                     *(_fmt(a) for a in rot), _fmt(b.get("mass", 0.0)),
                     "|".join(_fmt(c) for c in cg), "|".join(_fmt(c) for c in inertia),
                     _fmt(volume), "|".join(_fmt(c) for c in bmd.get("CdA", [0.0])),
                     "|".join(_fmt(c) for c in bmd.get("Ca", [0.0]))])
        notes.append(None if b["name"] == f"body{i}" else b["name"])
    if bodies:
        out += _table("BODIES", "ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*",
                      "(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)",
                      rows, notes)

    points = list(data.get("points", []))
    by_point = {p["name"]: p for p in points}

    def global_pos(p: dict[str, Any]) -> list[float]:
        if p["kind"] != "body":
            return list(p["position"])
        b = body_by_name[p["body"]]
        off = _rotate(b.get("rotation_deg", [0.0, 0.0, 0.0]), list(p["position"]))
        return [b["position"][k] + off[k] for k in range(3)]

    # a multi-part line: one MoorDyn line per part, joined by massless free points
    md_line_rows: list[tuple[str, str, str, str, float, dict[str, Any]]] = []
    joints: list[dict[str, Any]] = []
    for i, ln in enumerate(data.get("lines", [])):
        where = f"lines[{i}]"
        for key in ("point_a", "point_b"):
            if ln.get(key) not in by_point:
                raise CableOCPError(f"{where}.{key} = {ln.get(key)!r}: no such point")
        parts = _line_parts(ln, where)
        for tname, _ in parts:
            if tname not in types:
                raise CableOCPError(f"{where}: line type {tname!r} is not in [line_types]")
        lmd = md_lines.get(ln["name"], {})
        if len(parts) == 1:
            md_line_rows.append((ln["name"], parts[0][0], ln["point_a"], ln["point_b"],
                                 parts[0][1], lmd))
            continue
        xa, xb = global_pos(by_point[ln["point_a"]]), global_pos(by_point[ln["point_b"]])
        total = sum(length for _, length in parts)
        done = 0.0
        prev = ln["point_a"]
        for k, (tname, length) in enumerate(parts, start=1):
            done += length
            if k < len(parts):
                jname = f"{ln['name']}.joint{k}"
                s = done / total
                joints.append({"name": jname, "kind": "free", "mass": 0.0, "volume": 0.0,
                               "position": [xa[c] + s * (xb[c] - xa[c]) for c in range(3)]})
                nxt = jname
            else:
                nxt = ln["point_b"]
            segs = max(1, round(lmd["NumSegs"] * length / total)) if "NumSegs" in lmd else None
            part_md = {"outputs": lmd.get("outputs", "-")}
            if segs is not None:
                part_md["NumSegs"] = segs
            md_line_rows.append((f"{ln['name']}.part{k}", tname, prev, nxt, length, part_md))
            prev = nxt
    points += joints
    point_id = {p["name"]: i for i, p in enumerate(points, start=1)}
    with_force = any("force" in p for p in points) or any(
        "force" in v for v in md_points.values())
    rows, notes = [], []
    for i, p in enumerate(points, start=1):
        pmd = md_points.get(p["name"], {})
        x, y, z = p["position"]
        if p["kind"] == "body":
            if p.get("body") not in body_id:
                raise CableOCPError(f"points[{i - 1}].body = {p.get('body')!r}: no such body")
            word = f"Body{body_id[p['body']]}"
        elif p["kind"] == "fixed":
            word, z = pmd.get("attachment", "Fixed"), z - depth
        else:
            word, z = "Free", z - depth
        mass = p.get("mass", pmd.get("mass", 0.0))
        volume = p.get("volume", pmd.get("volume", 0.0))
        cols = [str(i), word, _fmt(x), _fmt(y), _fmt(z), _fmt(mass), _fmt(volume)]
        if with_force:
            cols += [_fmt(f) for f in p.get("force", pmd.get("force", [0.0, 0.0, 0.0]))]
        cols += [_fmt(pmd.get("CdA", 0.0)), _fmt(pmd.get("Ca", 0.0))]
        rows.append(cols)
        notes.append(None if p["name"] == f"point{i}" else p["name"])
    force_cols = " Fx Fy Fz" if with_force else ""
    out += _table("POINTS", f"ID Attachment X Y Z Mass Volume{force_cols} CdA Ca",
                  "(#) (-) (m) (m) (m) (kg) (m^3)" + (" (N) (N) (N)" if with_force else "")
                  + " (m^2) (-)", rows, notes)

    rows, notes = [], []
    for i, (name, tname, pa, pb, length, lmd) in enumerate(md_line_rows, start=1):
        segs = lmd.get("NumSegs", max(1, math.ceil(length / _SEGMENT_LENGTH)))
        rows.append([str(i), tname, str(point_id[pa]), str(point_id[pb]), _fmt(length),
                     str(segs), str(lmd.get("outputs", "-"))])
        notes.append(None if name == f"line{i}" else name)
    out += _table("LINES", "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
                  "(#) (name) (#) (#) (m) (-) (-)", rows, notes)

    out.append("---------------------- OPTIONS ----------------------")
    out += [f"{_fmt(depth)}  WtrDpth", f"{_fmt(rho)}  WtrDnsty", f"{_fmt(g)}  g"]
    if "friction" in seabed:
        out.append(f"{_fmt(seabed['friction'])}  FrictionCoefficient")
    taken = set(_DEPTH_NAMES + _RHO_NAMES + _G_NAMES + (_FRICTION,))
    for name, value in md.get("options", {}).items():
        if name.lower() not in taken:
            out.append(f"{_fmt(value)}  {name}")
    if md.get("outputs"):
        out.append("---------------------- OUTPUTS ----------------------")
        out += [str(o) for o in md["outputs"]]
    # MoorDyn reads each section up to the next dashed line: the file ends with one
    out.append("---------------------- END ----------------------")
    return "\n".join(out) + "\n"


def write_moordyn(data: dict[str, Any], path: str | Path) -> None:
    """A system problem dict (our schema) -> a MoorDyn v2 input file (written atomically).

    Parameters
    ----------
    data : dict
        A system problem dict (cable_ocp/scene/system.py's schema, with an optional
        ``[moordyn]`` table as :func:`read_moordyn` makes it). z is converted back:
        ``z_moordyn = z_ours - depth``. A line of several parts becomes one MoorDyn line per
        part, joined by massless free points named ``<line>.joint<k>`` (their initial
        positions on the chord), the parts named ``<line>.part<k>``; names that are not
        MoorDyn's ``point<ID>``/``body<ID>``/``line<ID>`` are kept in ``# name:`` comments.
    path : str or Path
        The file to write (its directory must exist); the earlier file is kept when the
        write fails.

    Raises
    ------
    CableOCPError
        A value MoorDyn cannot carry: an inextensible line type, a current, a sloping
        seabed, a waterplane or hydrostatic matrix, a centre of buoyancy away from the
        centre of gravity, a body holding a subset of its degrees of freedom other than
        its translations.
    """
    try:
        text = _moordyn_text(data)
    except KeyError as exc:
        raise CableOCPError(f"write_moordyn: a table lacks the key {exc.args[0]!r} (the "
                            "system schema, cable_ocp/scene/system.py)") from None
    write_text_atomically(path, text)


# -- TOML ---------------------------------------------------------------------------------
_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def _toml_key(key: str) -> str:
    return key if _BARE_KEY.fullmatch(key) else _toml_str(key)


def _toml_str(s: str) -> str:
    return json.dumps(s, ensure_ascii=False).replace("\x7f", "\\u007f")


def _toml_value(v: Any, where: str) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        return repr(v)     # 'inf', '-inf' and repr's digits are TOML floats
    if isinstance(v, str):
        return _toml_str(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x, where) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_toml_key(str(k))} = {_toml_value(x, where)}"
                               for k, x in v.items()) + "}"
    raise CableOCPError(f"{where} = {v!r}: not a TOML value (numbers, strings, booleans, "
                        "lists and tables)")


def _toml_table(table: dict[str, Any], prefix: str, out: list[str], top: bool) -> None:
    scalars = [(k, v) for k, v in table.items() if not isinstance(v, dict)
               and not (top and isinstance(v, list) and v and all(isinstance(x, dict)
                                                                  for x in v))]
    for k, v in scalars:
        out.append(f"{_toml_key(str(k))} = {_toml_value(v, prefix + str(k))}")
    for k, v in table.items():
        name = f"{prefix}{_toml_key(str(k))}"
        if isinstance(v, dict):
            if not v or any(not isinstance(x, dict) for x in v.values()):
                out += ["", f"[{name}]"]    # a table of tables only needs no header
            _toml_table(v, name + ".", out, False)
        elif (top and isinstance(v, list) and v and all(isinstance(x, dict) for x in v)):
            for item in v:
                out += ["", f"[[{name}]]"]
                _toml_table(item, name + ".", out, False)


def system_dict_to_toml(data: dict[str, Any]) -> str:
    """The dict as TOML text (our schema); ``tomllib.loads`` reads it back equal.

    Tables are ``[a.b]`` tables, top-level arrays of tables (points, bodies, lines) are
    ``[[...]]``, deeper lists of tables (a line's parts) inline tables; floats are written
    with repr precision, so every number comes back exactly.

    Parameters
    ----------
    data : dict
        Strings, ints, floats, booleans, lists and dicts (keys strings).

    Returns
    -------
    str
        The TOML text, ending with a newline.
    """
    out: list[str] = []
    _toml_table(data, "", out, True)
    while out and out[0] == "":
        out.pop(0)
    return "\n".join(out) + "\n"
