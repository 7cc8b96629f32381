"""A damaged compiled library is never loaded (issue 22, fault 1).

A truncated or bit-flipped ``.so`` in the cache killed every later run with SIGBUS or
SIGSEGV until the user deleted the cache, and another structure's library under the right
name gave exit 3 every run; only an empty file was rebuilt. Now every library carries a
record of its SHA-256 and name (``numerics/compile.py``), and one that does not match is
removed and built again; a compiler output that is not a complete ELF file (a compiler
that exited 0 on a nearly full disk with a file 8 bytes short) is never installed.

The damage is done for real to the cached files and each load runs in a subprocess, so
that a regression shows as a crashed child (its exit status) instead of killing pytest.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from cable_ocp.numerics.compile import c_compiler

pytestmark = pytest.mark.skipif(c_compiler() is None, reason="needs a C compiler")

#: one child: compile (or load) f(x) = x sin(x) under each key given, check its value, and
#: say for each whether it is compiled and its library matches its record; then the same
#: for the sparse-LU helper
CHILD = textwrap.dedent("""
    import glob, math, sys
    import casadi as ca
    from cable_ocp.numerics.compile import compile_function, is_compiled, library_ok
    from cable_ocp.numerics import sparse_lu
    x = ca.SX.sym("x")
    cache, keys = sys.argv[1], sys.argv[2:]
    out = []
    for key in keys:
        f = compile_function(lambda: ca.Function("f_" + key, [x], [x * ca.sin(x)]), "-O1",
                             key=key, name="f_" + key)
        assert abs(float(f(0.7)) - 0.7 * math.sin(0.7)) < 1e-15
        libs = glob.glob(cache + "/f_" + key + "_*.so")
        out += [is_compiled(f), len(libs) == 1 and library_ok(libs[0])]
    lu = sparse_lu.available()
    lus = glob.glob(cache + "/cable_ocp_sparse_lu_*.so")
    out += [lu, len(lus) == 1 and library_ok(lus[0])]
    print(*out)
""")
DAMAGES = {"t": "truncated", "f": "bit flipped", "o": "another library", "r": "record lost"}


def _child(cache: Path, keys: list[str], env_extra: dict | None = None) -> list[str]:
    env = {**os.environ, "CABLE_OCP_CACHE_DIR": str(cache), **(env_extra or {})}
    r = subprocess.run([sys.executable, "-c", CHILD, str(cache), *keys], env=env,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, (r.returncode, r.stderr[-2000:])
    return r.stdout.split()


def _damage(path: Path, how: str, other: Path) -> None:
    data = path.read_bytes()
    if how == "truncated":
        path.write_bytes(data[:-8])
    elif how == "bit flipped":
        i = len(data) // 2
        path.write_bytes(data[:i] + bytes([data[i] ^ 0x10]) + data[i + 1:])
    elif how == "another library":
        path.write_bytes(other.read_bytes())
    elif how == "record lost":
        Path(str(path) + ".sha256").unlink()


def test_a_damaged_library_is_rebuilt_never_loaded(tmp_path: Path) -> None:
    """Four libraries damaged four ways (cut by 8 bytes, one bit flipped, another
    function's library under the name, the record lost) and the sparse-LU helper cut by 8
    bytes: the next process rebuilds each, loads the new one (the same value) and each
    matches its record again."""
    keys = [*DAMAGES, "other"]
    assert _child(tmp_path, keys) == ["True"] * (2 * len(keys) + 2)
    other = next(tmp_path.glob("f_other_*.so"))
    damaged = {}
    for key, how in DAMAGES.items():
        lib = next(tmp_path.glob(f"f_{key}_*.so"))
        _damage(lib, how, other)
        damaged[lib] = lib.read_bytes()
    lu = next(tmp_path.glob("cable_ocp_sparse_lu_*.so"))
    _damage(lu, "truncated", other)
    damaged[lu] = lu.read_bytes()
    assert _child(tmp_path, list(DAMAGES)) == ["True"] * (2 * len(DAMAGES) + 2)
    # rebuilt, not loaded as it was (the old code loaded all four damaged files as they
    # were: whatever they computed, or a crash); the library whose record was lost is the
    # same file, recorded again
    for lib, data in damaged.items():
        if "f_r_" in lib.name:
            assert Path(str(lib) + ".sha256").exists()
        else:
            assert lib.read_bytes() != data, lib.name


def test_an_incomplete_compiler_output_is_not_installed(tmp_path: Path) -> None:
    """A compiler that exits 0 but leaves its output 8 bytes short: the function falls back
    to the interpreted one (the same value), the sparse-LU helper is unavailable (CasADi's
    solvers are used), and no library is left."""
    cc = c_compiler()
    assert cc is not None
    wrapper = tmp_path / "short_cc"
    wrapper.write_text("#!/bin/sh\n"
                       f"{' '.join(cc)} \"$@\" || exit $?\n"
                       "while [ $# -gt 1 ]; do [ \"$1\" = -o ] && out=$2; shift; done\n"
                       "truncate -s -8 \"$out\"\n")
    wrapper.chmod(0o755)
    cache = tmp_path / "cache"
    assert _child(cache, ["c"], {"CC": str(wrapper)}) == ["False"] * 4
    assert not list(cache.glob("*.so")) and not list(cache.glob("*.tmp"))
