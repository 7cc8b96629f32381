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


def _imports(name: str, path: Path) -> set[str]:
    """Every cable_ocp module ``name`` imports, at module level or inside functions (not
    the ``if TYPE_CHECKING:`` imports, which exist for annotations only)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    pkg = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    typing_only = {id(n) for block in ast.walk(tree) if isinstance(block, ast.If)
                   and "TYPE_CHECKING" in ast.unparse(block.test)
                   for stmt in block.body for n in ast.walk(stmt)}
    for node in ast.walk(tree):
        if id(node) in typing_only:  # `if TYPE_CHECKING:` imports never run
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


def test_the_graph_sees_known_edges() -> None:
    """The parser is not blind: edges known to exist are found (else the tests above would
    pass on an empty graph)."""
    assert "cable_ocp.statics.formulation" in GRAPH["cable_ocp.statics.solver"]
    assert "cable_ocp.scene" in GRAPH["cable_ocp.statics.registry"]
    assert "cable_ocp.cli.output" in GRAPH["cable_ocp.cli.statics"]
    assert "cable_ocp.heave.mpc" in GRAPH["cable_ocp.heave.simulate"]
