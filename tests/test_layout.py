"""The package layout: the library never imports its face, and no module imports itself
back through a circle.

Library packages (physics, scene, statics, baselines, heave, dynamics) compute; the face
(cli, report, plots, bench) formats and prints. Data flows one way, so the library must
work with the face absent, and the import graph must have no cycle (a cycle makes import
order matter and hides a layering mistake).
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

PKG = Path(__file__).resolve().parents[1] / "cable_ocp"
FACE = ("cable_ocp.cli", "cable_ocp.report", "cable_ocp.plots", "cable_ocp.bench",
        "cable_ocp.__main__")
LIBRARY = ("numerics", "physics", "scene", "statics", "baselines", "heave", "dynamics", "batch")


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted(PKG.rglob("*.py")):
        rel = path.relative_to(PKG.parent).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _is_face(name: str) -> bool:
    return any(name == f or name.startswith(f + ".") for f in FACE)


#: the one import from the library into the face: a result's ``plot`` method imports the
#: accessors of the figures when it is called (the accessor pattern of pandas'
#: ``DataFrame.plot`` and xarray's ``Dataset.plot``), never when the library is imported
#: (test_importing_the_library_loads_no_face_module still holds). Such an import is an
#: edge of ACCESSOR_EDGES, not of GRAPH: it is a call into the face, not a dependency.
ACCESSOR_MODULE = "cable_ocp.plots.accessors"
ACCESSOR_METHOD = "plot"
ACCESSOR_EDGES: set[tuple[str, str]] = set()


def _accessor_nodes(tree: ast.AST) -> set[int]:
    """The import nodes inside a method named :data:`ACCESSOR_METHOD` that import
    :data:`ACCESSOR_MODULE` and nothing else."""
    out = set()
    for fn in ast.walk(tree):
        if isinstance(fn, ast.FunctionDef) and fn.name == ACCESSOR_METHOD:
            for n in ast.walk(fn):
                if isinstance(n, ast.ImportFrom) and n.module == ACCESSOR_MODULE:
                    out.add(id(n))
    return out


def _imports(name: str, path: Path) -> set[str]:
    """Every cable_ocp module ``name`` imports, at module level or inside functions (not
    the ``if TYPE_CHECKING:`` imports, which exist for annotations only, nor a result's
    ``plot`` accessor: :data:`ACCESSOR_EDGES`)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    pkg = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    typing_only = {id(n) for block in ast.walk(tree) if isinstance(block, ast.If)
                   and "TYPE_CHECKING" in ast.unparse(block.test)
                   for stmt in block.body for n in ast.walk(stmt)}
    accessors = _accessor_nodes(tree) if not _is_face(name) else set()
    for node in ast.walk(tree):
        if id(node) in typing_only:  # `if TYPE_CHECKING:` imports never run
            continue
        if id(node) in accessors:
            ACCESSOR_EDGES.add((name, ACCESSOR_MODULE))
            continue
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = pkg.split(".")[: len(pkg.split(".")) - node.level + 1]
                base = ".".join(up + ([base] if base else []))
            # "from pkg import sub" names a submodule when pkg.sub is a module
            targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in MODULES else base
                       for a in node.names]
        else:
            continue
        for t in targets:
            while t and t not in MODULES:  # "cable_ocp.x.y.attr" -> the module part
                t = t.rpartition(".")[0]
            if t.startswith("cable_ocp") and t != name:
                found.add(t)
    return found


GRAPH = {name: _imports(name, path) for name, path in MODULES.items()}


def test_library_modules_import_no_face_module() -> None:
    """Statically: no library module imports cli, report, plots or bench (even lazily)."""
    bad = [f"{m} imports {t}" for m, ts in GRAPH.items() for t in ts
           if not _is_face(m) and _is_face(t)]
    assert not bad, "\n".join(bad)


def test_importing_the_library_loads_no_face_module() -> None:
    """Dynamically, in a fresh interpreter: importing every library module leaves the face
    modules unloaded (catches imports made by third-party hooks or __init__ files too)."""
    lib = [m for m in MODULES if m.split(".")[1:2] and m.split(".")[1] in LIBRARY]
    code = ("import importlib, sys\n"
            f"for m in {lib!r}:\n    importlib.import_module(m)\n"
            f"print([m for m in sys.modules if m.startswith({FACE!r})])")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=PKG.parent)
    assert res.stdout.strip() == "[]", res.stdout + res.stderr



def test_the_command_line_parser_loads_no_model_package() -> None:
    """Building the ``cable-ocp`` parser (every command's options) in a fresh interpreter
    loads neither the heave, dynamics nor batch packages nor python-control: each command
    imports what it runs, so the start-up of a statics command stays the import of the
    statics (a heave-inverse option list that imported cable_ocp.heave cost every command
    1.3 s of CPU, and moved test_interrupt's moments)."""
    heavy = ["cable_ocp.heave", "cable_ocp.dynamics", "cable_ocp.batch", "control"]
    code = ("import sys\nfrom cable_ocp.cli.app import build_parser\nbuild_parser()\n"
            f"print([m for m in {heavy!r} if m in sys.modules])")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=PKG.parent)
    assert res.stdout.strip() == "[]", res.stdout + res.stderr

def test_no_import_cycles() -> None:
    """The import graph between cable_ocp modules (module-level and function-level imports;
    a package's __init__ counts as the package) has no cycle."""
    color: dict[str, int] = {}
    stack: list[str] = []
    cycles: list[str] = []

    def visit(m: str) -> None:
        color[m] = 1
        stack.append(m)
        for t in sorted(GRAPH.get(m, ())):
            if color.get(t) == 1:
                cycles.append(" -> ".join(stack[stack.index(t):] + [t]))
            elif t not in color:
                visit(t)
        stack.pop()
        color[m] = 2

    for m in sorted(GRAPH):
        if m not in color:
            visit(m)
    assert not cycles, "\n".join(cycles)


def test_the_plot_accessors_are_the_only_calls_into_the_face() -> None:
    """Every result type with a ``plot`` method reaches the face through the accessor
    module only (the exemption above is used, and used for nothing else: any other import
    of a face module from the library is still an edge of GRAPH and fails the tests
    around this one)."""
    users = {m for m, _ in ACCESSOR_EDGES}
    assert {"cable_ocp.statics.solution", "cable_ocp.statics.footprint_nlp",
            "cable_ocp.dynamics.result", "cable_ocp.heave.metrics",
            "cable_ocp.batch.study"} <= users
    assert {t for _, t in ACCESSOR_EDGES} == {ACCESSOR_MODULE}


def test_the_graph_sees_known_edges() -> None:
    """The parser is not blind: edges known to exist are found (else the tests above would
    pass on an empty graph)."""
    assert "cable_ocp.statics.formulation" in GRAPH["cable_ocp.statics.solver"]
    assert "cable_ocp.scene" in GRAPH["cable_ocp.statics.registry"]
    assert "cable_ocp.cli.output" in GRAPH["cable_ocp.cli.statics"]
    assert "cable_ocp.heave.mpc" in GRAPH["cable_ocp.heave.design_loop"]


# -- the layer order ---------------------------------------------------------------------
#: each package's layer: a module imports only from lower layers, from its own package, and
#: ``cable_ocp.errors`` (the one exception type, below everything). baselines and dynamics
#: are peers (neither imports the other), so are batch and schedule, plots and report.
LAYERS = {"numerics": 0, "physics": 1, "scene": 2, "statics": 3, "baselines": 4,
          "dynamics": 4, "mooring": 4, "heave": 5, "batch": 6, "schedule": 6, "bench": 7,
          "plots": 8, "report": 8,
          "cli": 9, "__main__": 10}
#: modules that sit outside the layers: the error type, the status vocabulary and the version
#: (imported
#: by every layer) and the package's own __init__ (the public face of ``import cable_ocp``,
#: which only the CLI imports, for its version)
OUTSIDE = ("cable_ocp", "cable_ocp.errors", "cable_ocp.status", "cable_ocp.version")
#: the modules of OUTSIDE that every layer may import
EVERYWHERE = ("cable_ocp.errors", "cable_ocp.status", "cable_ocp.version")
#: the largest module a newcomer should have to read whole (lines)
MAX_LINES = 900
#: modules allowed beyond MAX_LINES, each with its reason
LONG_MODULES: dict[str, str] = {}


def _package(module: str) -> str | None:
    """The layer package of ``cable_ocp.<pkg>[.<mod>]``, None outside the layers."""
    if module in OUTSIDE:
        return None
    return module.split(".")[1]


def test_every_package_has_a_layer() -> None:
    """A new package must be placed in LAYERS (else the order below would not see it)."""
    missing = sorted({p for m in MODULES if (p := _package(m)) is not None} - set(LAYERS))
    assert not missing, f"packages without a layer in LAYERS: {missing}"


def test_imports_follow_the_layer_order() -> None:
    """numerics < physics < scene < statics < {baselines, dynamics} < heave < batch < bench <
    {plots, report} < cli: every import (module level or inside a function) goes to a lower
    layer or stays in its package."""
    bad = []
    for m, targets in GRAPH.items():
        pm = _package(m)
        if pm is None:
            continue
        for t in sorted(targets):
            pt = _package(t)
            if pt is None:  # errors, status: anyone; the package (its version): the CLI only
                if t not in EVERYWHERE and not (t == "cable_ocp" and LAYERS[pm] >= 9):
                    bad.append(f"{m} imports {t} (the package's face)")
                continue
            if pt != pm and LAYERS[pt] >= LAYERS[pm]:
                bad.append(f"{m} ({pm}, layer {LAYERS[pm]}) imports {t} ({pt}, layer "
                           f"{LAYERS[pt]})")
    assert not bad, "\n".join(bad)


def _private_imports(name: str, path: Path) -> list[str]:
    """``from cable_ocp.<other package>... import _name`` in module ``name``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    pkg = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.ImportFrom):
            continue
        base = node.module or ""
        if node.level:
            up = pkg.split(".")[: len(pkg.split(".")) - node.level + 1]
            base = ".".join(up + ([base] if base else []))
        if not base.startswith("cable_ocp"):
            continue
        for alias in node.names:
            if alias.name.startswith("_") and not alias.name.startswith("__"):
                if base.split(".")[:2] != name.split(".")[:2]:
                    out.append(f"{name} imports {alias.name} from {base}")
    return out


def test_no_private_name_is_imported_across_packages() -> None:
    """A leading underscore means "this package's own": another package that needs it needs
    a public name (tests are not checked: they may reach into a module they test)."""
    bad = [line for m, p in MODULES.items() for line in _private_imports(m, p)]
    assert not bad, "\n".join(bad)


def test_private_import_check_sees_one() -> None:
    """The check above is not blind: a constructed module that imports a private name
    from another package is reported, one from its own package is not."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        f = Path(tmp) / "m.py"
        f.write_text("from cable_ocp.statics.solver import _x\nfrom cable_ocp.heave.a import _y\n")
        assert _private_imports("cable_ocp.heave.m", f) == [
            "cable_ocp.heave.m imports _x from cable_ocp.statics.solver"]


def test_no_module_is_longer_than_a_newcomer_reads() -> None:
    """Every module has at most MAX_LINES lines, or a reason in LONG_MODULES."""
    long = {m: len(p.read_text(encoding="utf-8").splitlines()) for m, p in MODULES.items()}
    bad = [f"{m}: {n} lines" for m, n in sorted(long.items())
           if n > MAX_LINES and m not in LONG_MODULES]
    assert not bad, "\n".join(bad)
    stale = [m for m in LONG_MODULES if long.get(m, 0) <= MAX_LINES]
    assert not stale, f"LONG_MODULES lists modules that are short now: {stale}"
