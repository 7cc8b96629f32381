"""Public names of the package namespaces are functions, classes or values, never a module
a user could call by mistake (``cable_ocp.heave.simulate(...)`` was a module).

A package's namespace holds what its ``__init__`` binds and, once imported, each of its
submodules (the import system sets them as attributes). The rules, for every package:

* nothing in ``__all__`` is a module;
* a module among the public names (no leading underscore) is the package's own submodule
  (not ``np``, ``os`` or ``argparse`` left behind by an ``import``), named in the package's
  docstring (its "Modules" list), and its name is not one a user calls: not the name of a
  public function or class of any package (``simulate``, ``modes``, ``footprint``,
  ``solve_bvp``...). A function and a module of one name (``cable_ocp.dynamics.simulate``)
  is the trap itself: ``import cable_ocp.dynamics.simulate as m`` binds the function, so
  the modules carry other names (``simulation``, ``modal``, ``design_loop``, ``scipy_bvp``).
"""

from __future__ import annotations

import importlib
import pkgutil
import re
import types

import cable_ocp

#: modules that need an optional peer at import time (none today)
OPTIONAL: tuple[str, ...] = ()


def _import_everything() -> list[types.ModuleType]:
    """Import every module of the package (so that every submodule attribute is set) and
    return the packages."""
    packages = [cable_ocp]
    for info in pkgutil.walk_packages(cable_ocp.__path__, "cable_ocp."):
        if info.name in OPTIONAL or info.name.endswith("__main__"):
            continue
        mod = importlib.import_module(info.name)
        if info.ispkg:
            packages.append(mod)
    return packages


PACKAGES = _import_everything()


def _public(pkg: types.ModuleType) -> dict[str, object]:
    names = set(getattr(pkg, "__all__", ())) | {n for n in dir(pkg) if not n.startswith("_")}
    return {n: getattr(pkg, n) for n in sorted(names)}


def _callable_names() -> set[str]:
    """Names of the public functions and classes of every package namespace."""
    return {n for pkg in PACKAGES for n, v in _public(pkg).items()
            if isinstance(v, (types.FunctionType, type))}


def namespace_problems(packages: list[types.ModuleType]) -> list[str]:
    """Every breach of the rules of the module docstring in ``packages``.

    Parameters
    ----------
    packages : list of module
        The packages to check.
    """
    calls = _callable_names()
    bad = []
    for pkg in packages:
        doc = pkg.__doc__ or ""
        for name in getattr(pkg, "__all__", ()):
            if isinstance(getattr(pkg, name, None), types.ModuleType):
                bad.append(f"{pkg.__name__}.__all__ lists the module {name!r}")
        for name, value in _public(pkg).items():
            if not isinstance(value, types.ModuleType):
                continue
            where = f"{pkg.__name__}.{name}"
            if value.__name__ != where:
                bad.append(f"{where} is the module {value.__name__} (an import left public)")
            elif not re.search(rf"\b{re.escape(name)}\b", doc):
                bad.append(f"{where} is a module the package's docstring does not name")
            elif name in calls:
                bad.append(f"{where} is a module named like a public function or class")
    return bad


def test_public_names_are_not_modules_a_user_would_call() -> None:
    """The rules hold for every package; the names the issue met are functions now:
    ``cable_ocp.heave.simulate`` is the closed loop (:func:`cable_ocp.heave.compare`),
    ``cable_ocp.dynamics.simulate`` and ``modes`` are functions, and so is
    ``cable_ocp.baselines.solve_bvp``; their modules stay importable under their names."""
    assert not namespace_problems(PACKAGES), "\n".join(namespace_problems(PACKAGES))
    import cable_ocp.baselines as bl
    import cable_ocp.dynamics as dy
    import cable_ocp.heave as hv
    from cable_ocp.dynamics import simulation
    from cable_ocp.heave import design_loop

    assert hv.simulate is hv.compare and isinstance(hv.simulate, types.FunctionType)
    for f in (dy.simulate, dy.modes, bl.solve_bvp, cable_ocp.footprint):
        assert isinstance(f, types.FunctionType), f
    assert isinstance(design_loop, types.ModuleType) and hasattr(design_loop, "compare")
    assert simulation.simulate is dy.simulate


def test_the_namespace_check_sees_a_module_to_call_by_mistake() -> None:
    """The check is not blind: a package whose namespace holds a stray ``np``, an
    undocumented submodule and a submodule named like a public function is reported on
    each, and a clean one is not."""
    pkg = types.ModuleType("cable_ocp.fake", "Modules\n-------\nsolve  named like a function")
    sub = types.ModuleType("cable_ocp.fake.solve")
    hidden = types.ModuleType("cable_ocp.fake.hidden")
    pkg.np, pkg.solve, pkg.hidden = importlib.import_module("numpy"), sub, hidden
    pkg.__all__ = ["hidden"]
    found = namespace_problems([pkg])
    assert len(found) == 4, found
    assert any("np is the module numpy" in f for f in found)
    assert any("hidden is a module the package's docstring" in f for f in found)
    assert any("solve is a module named like" in f for f in found)
    assert any("__all__ lists the module 'hidden'" in f for f in found)
    clean = types.ModuleType("cable_ocp.clean", "no modules")
    clean.f = namespace_problems
    assert namespace_problems([clean]) == []
