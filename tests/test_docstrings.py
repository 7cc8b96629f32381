"""Meta-test of the documentation, as python-control's ``docstrings_test.py`` does: every
public function or method of the package with two or more parameters has a numpy-style
``Parameters`` section, and that section names every parameter.

Public: a module-level function or a method of a module-level class whose name has no
leading underscore, in a module whose path has none either (``__init__`` and ``__main__``
files count as public); properties are attributes, not functions. A class whose explicit
``__init__`` takes two or more parameters documents them in the class docstring or in
``__init__``'s. Dataclasses document their fields under ``Attributes`` instead (their
generated ``__init__`` is not checked). Numpy style: a line ``Parameters``, a line of
dashes, then entries ``name : type`` (or ``a, b : type`` for several, or a bare ``name``).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

PKG = Path(__file__).resolve().parents[1] / "cable_ocp"

_HEADER = re.compile(r"^\s*([A-Z][A-Za-z ]+)\s*\n\s*-{3,}\s*$", re.M)
_ENTRY = re.compile(r"^\s*(\*{0,2}[A-Za-z_]\w*(?:\s*,\s*\*{0,2}[A-Za-z_]\w*)*)\s*(?::.*)?$")


def parameters_section(doc: str) -> set[str] | None:
    """The names documented in ``doc``'s Parameters section (None: there is none)."""
    heads = list(_HEADER.finditer(doc))
    for i, m in enumerate(heads):
        if m.group(1).strip() != "Parameters":
            continue
        end = heads[i + 1].start() if i + 1 < len(heads) else len(doc)
        lines = doc[m.end():end].splitlines()
        indent = min((len(x) - len(x.lstrip()) for x in lines if x.strip()), default=0)
        names: set[str] = set()
        for line in lines:
            if line.strip() and len(line) - len(line.lstrip()) == indent:
                e = _ENTRY.match(line)
                if e:
                    names |= {n.strip().lstrip("*") for n in e.group(1).split(",")}
        return names
    return None


def _parameters(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> list[str]:
    a = fn.args
    names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]
    names += [x.arg for x in (a.vararg, a.kwarg) if x is not None]
    return [n for n in names if n not in ("self", "cls")]


def _is_property(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    return any((isinstance(d, ast.Name) and d.id in ("property", "cached_property"))
               or (isinstance(d, ast.Attribute) and d.attr in ("setter", "deleter"))
               for d in fn.decorator_list)


def _is_dataclass(cls: ast.ClassDef) -> bool:
    return any("dataclass" in ast.unparse(d) for d in cls.decorator_list)


def undocumented(source: str, module: str) -> list[str]:
    """Every public function of ``source`` with >= 2 parameters that lacks a Parameters
    section or leaves a parameter out of it, as ``module:line name: what``."""
    out = []

    def check(fn: ast.FunctionDef | ast.AsyncFunctionDef, name: str, doc: str) -> None:
        ps = _parameters(fn)
        if len(ps) < 2:
            return
        documented = parameters_section(doc)
        if documented is None:
            out.append(f"{module}:{fn.lineno} {name}({', '.join(ps)}): no Parameters section")
        elif missing := [p for p in ps if p not in documented]:
            out.append(f"{module}:{fn.lineno} {name}: Parameters leaves out {missing}")

    for node in ast.parse(source).body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            if not node.name.startswith("_"):
                check(node, node.name, ast.get_docstring(node) or "")
        elif isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
            for fn in node.body:
                if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    continue
                if fn.name == "__init__" and not _is_dataclass(node):
                    doc = (ast.get_docstring(node) or "") + "\n" + (ast.get_docstring(fn) or "")
                    check(fn, f"{node.name}()", doc)
                elif not fn.name.startswith("_") and not _is_property(fn):
                    check(fn, f"{node.name}.{fn.name}", ast.get_docstring(fn) or "")
    return out


def _public_modules() -> dict[str, Path]:
    out = {}
    for path in sorted(PKG.rglob("*.py")):
        parts = path.relative_to(PKG.parent).with_suffix("").parts
        if all(not p.startswith("_") or p in ("__init__", "__main__") for p in parts):
            out[".".join(parts)] = path
    return out


def test_every_public_function_documents_its_parameters() -> None:
    bad = [line for m, p in _public_modules().items()
           for line in undocumented(p.read_text(encoding="utf-8"), m)]
    assert not bad, f"{len(bad)} public functions without full Parameters sections:\n" + \
        "\n".join(bad)


def test_the_check_sees_a_missing_section_and_a_missing_name() -> None:
    """Not blind: constructed sources with no section, a left-out name, a documented
    function, a one-parameter function, a property, a private function and a grouped
    entry ``a, b : float``."""
    src = '''
def no_section(a, b):
    """Nothing."""

def left_out(a, b, *, c=1):
    """Doc.

    Parameters
    ----------
    a : float
        The a.
    b : float
        The b.

    Returns
    -------
    c : float
        Not a parameter.
    """

def grouped(a, b):
    """Doc.

    Parameters
    ----------
    a, b : float
        Both, m.
    """

def one(a):
    """One parameter: no section needed."""

def _private(a, b):
    pass

class Thing:
    def __init__(self, x, y):
        """No section."""

    @property
    def size(self):
        return 1

    def method(self, p, q):
        """Doc.

        Parameters
        ----------
        p
            The p.
        q : int
            The q.
        """
'''
    found = undocumented(src, "m")
    assert [f.split(" ", 1)[1] for f in found] == [
        "no_section(a, b): no Parameters section",
        "left_out: Parameters leaves out ['c']",
        "Thing()(x, y): no Parameters section",
    ]
