"""cable_ocp.numerics.compile.compile_functions: several CasADi functions in one cached library, and
the silent fallback to the interpreted functions."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from cable_ocp.numerics import compile as cc


def _fns() -> list[ca.Function]:
    x = ca.SX.sym("x", 3)
    return [ca.Function("cf_sq", [x], [x * x]), ca.Function("cf_sum", [x], [ca.sum1(x)])]


def test_fallback_without_compiler_or_with_compiling_off(monkeypatch, tmp_path) -> None:
    """No compiler (``CC`` names a missing program) or ``CABLE_OCP_CACHE=0``: the very same
    Function objects come back, nothing is written."""
    fns = _fns()
    monkeypatch.setenv("CABLE_OCP_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv("CC", "/nonexistent/cc")
    assert cc.compile_functions(fns) is fns
    monkeypatch.delenv("CC")
    monkeypatch.setenv("CABLE_OCP_CACHE", "0")
    assert cc.compile_functions(fns) is fns
    assert not any(tmp_path.iterdir())


@pytest.mark.skipif(cc.c_compiler() is None, reason="no C compiler")
def test_compiled_functions_equal_the_interpreted_ones(monkeypatch, tmp_path) -> None:
    """With a compiler: one library in the cache folder, both functions compiled, the same
    numbers as the CasADi virtual machine (to rounding: 1e-15 relative)."""
    monkeypatch.setenv("CABLE_OCP_CACHE_DIR", str(tmp_path))
    fns = _fns()
    out = cc.compile_functions(fns, prefix="t_")
    assert all(cc.is_compiled(f) for f in out)
    assert len(list(tmp_path.glob("t_cf_sq_*.so"))) == 1
    v = np.array([1.5, -2.0, 0.25])
    for a, b in zip(fns, out, strict=True):
        np.testing.assert_allclose(np.array(b(v)), np.array(a(v)), rtol=1e-15)
