"""Compile CasADi functions to C and cache the shared libraries on disk.

Used by the lumped-mass dynamics (its segment kernel and chunked integrators) and by the
statics solver's Newton kernel when ``solver.compile = "auto"``. A compiled function
computes the same numbers as the CasADi virtual machine (the same graph, the same
operations) several times faster, at the price of a C compilation (seconds for a large
graph) the first time; the library is kept, so a later process loads it in milliseconds.

Where: ``$CABLE_OCP_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/cable_ocp``, else
``~/.cache/cable_ocp``. ``CABLE_OCP_CACHE=0`` (or off/false/no) turns compiling off.
The compiler is ``$CC`` (it may carry words, e.g. "ccache gcc"), else ``cc`` or ``gcc``.

Every failure (no compiler, a folder that cannot be written, the compiler or the loading
failing) falls back to the interpreted function, silently.

A library that loads can still be damaged (truncated by a full disk, a flipped bit, another
structure's library under this name), and loading it can crash the process (SIGBUS,
SIGSEGV). So every library is written with a record beside it (``LIB.sha256``: its SHA-256
and its own file name), after the compiler's output was checked to be a complete ELF file
(its section headers, the last part the linker writes, inside the file), and a library is
loaded only when its record matches it (:func:`library_ok`); otherwise it and its record
are removed and it is built again (:func:`install_library`, :func:`forget_library`).
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile
from collections.abc import Callable

import casadi as ca

from cable_ocp.numerics import interrupt
from cable_ocp.numerics.atomic import write_text_atomically

__all__ = ["cache_dir", "c_compiler", "compile_function", "compile_functions", "forget_library",
           "install_library", "is_compiled", "library_ok"]

#: values of ``CABLE_OCP_CACHE`` that turn the compilation to C off
CACHE_OFF = ("0", "off", "false", "no")


def cache_dir() -> str | None:
    """Directory of the compiled-C cache, or None when compiling is turned off.

    ``CABLE_OCP_CACHE=0`` (or off/false/no) turns it off (everything interpreted);
    ``CABLE_OCP_CACHE_DIR`` names the directory; an older ``CABLE_OCP_CACHE=PATH`` is read
    as the directory too; default ``$XDG_CACHE_HOME/cable_ocp`` or ~/.cache/cable_ocp.
    """
    flag = os.environ.get("CABLE_OCP_CACHE", "").strip()
    if flag.lower() in CACHE_OFF:
        return None
    if os.environ.get("CABLE_OCP_CACHE_DIR"):
        return os.environ["CABLE_OCP_CACHE_DIR"]
    if flag and flag.lower() not in ("1", "on", "true", "yes"):
        return flag
    return os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"),
        "cable_ocp")


def c_compiler() -> list[str] | None:
    """The C compiler command: ``$CC`` (may carry words, e.g. "ccache gcc") if its program
    exists, else ``cc`` or ``gcc`` on the PATH; None when there is none."""
    env = os.environ.get("CC", "").strip()
    if env:
        try:
            words = shlex.split(env)
        except ValueError:
            return None
        return words if words and shutil.which(words[0]) else None
    found = shutil.which("cc") or shutil.which("gcc")
    return [found] if found else None


def is_compiled(fn: ca.Function) -> bool:
    """True when ``fn`` runs from a compiled shared library (``casadi.external``)."""
    return fn.is_a("External")


def _library(cache: str, name: str, digest: str) -> str:
    return os.path.join(cache, f"{name}_{digest}.so")


def _record(lib: str) -> str:
    return lib + ".sha256"


def _sha256(path: str) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _elf_complete(path: str) -> bool:
    """True when ``path`` is an ELF file whose section header table (written last by the
    linker) lies inside the file; off Linux, any non-ELF file passes (other formats)."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(64)
            size = os.fstat(fh.fileno()).st_size
    except OSError:
        return False
    if head[:4] != b"\x7fELF":
        return not sys.platform.startswith("linux") and size > 0
    if len(head) < 52 or head[4] not in (1, 2) or head[5] not in (1, 2):
        return False
    end = "<" if head[5] == 1 else ">"
    if head[4] == 2:  # 64-bit
        if len(head) < 64:
            return False
        shoff, = struct.unpack_from(end + "Q", head, 0x28)
        shentsize, shnum = struct.unpack_from(end + "HH", head, 0x3A)
    else:
        shoff, = struct.unpack_from(end + "I", head, 0x20)
        shentsize, shnum = struct.unpack_from(end + "HH", head, 0x2E)
    return shnum > 0 and shoff + shentsize * shnum <= size


def library_ok(lib: str) -> bool:
    """True when the library ``lib`` exists and matches its record (its SHA-256 and its
    name in ``lib.sha256``): only then may it be loaded.

    Parameters
    ----------
    lib : str
        Path of the shared library.
    """
    try:
        with open(_record(lib), encoding="ascii") as fh:
            recorded = fh.read().split()
        return (len(recorded) == 2 and recorded[1] == os.path.basename(lib)
                and _elf_complete(lib) and recorded[0] == _sha256(lib))
    except (OSError, UnicodeDecodeError):
        return False


def forget_library(lib: str) -> None:
    """Remove the library ``lib`` and its record (what does not exist is skipped).

    Parameters
    ----------
    lib : str
        Path of the shared library.
    """
    for path in (lib, _record(lib)):
        with contextlib.suppress(OSError):
            os.remove(path)


def install_library(part: str, lib: str) -> None:
    """Check the freshly written library ``part`` (a complete ELF file), record its digest
    beside ``lib`` and rename it onto ``lib``. Raises ``OSError`` when ``part`` is
    incomplete (e.g. a compiler that exited 0 on a full disk with a file 8 bytes short) or
    the record cannot be written; ``lib`` is then not installed.

    Parameters
    ----------
    part : str
        The written library, in the directory of ``lib``.
    lib : str
        Where it goes.
    """
    if not _elf_complete(part):
        raise OSError(f"{part}: the compiler's output is not a complete shared library")
    write_text_atomically(_record(lib), f"{_sha256(part)} {os.path.basename(lib)}\n")
    os.replace(part, lib)


def _build_library(fns: list[ca.Function], name: str, cache: str, cc: list[str], opt: str,
                   lib: str | None = None) -> str:
    """Generate the C code of ``fns`` as one file, compile it into ``lib`` (default: named
    by the hash of the code) unless that library exists, and return its path. Raises on
    any failure (the callers fall back to the interpreted functions)."""
    tmp = tempfile.mkdtemp(prefix="cable_ocp_")
    try:
        cg = ca.CodeGenerator(f"{name}.c", {"with_header": False})
        for fn in fns:
            cg.add(fn)
        cg.generate(tmp + os.sep)
        src = os.path.join(tmp, f"{name}.c")
        if lib is None:
            with open(src, "rb") as fh:
                digest = hashlib.sha256(fh.read() + ca.__version__.encode()
                                        + opt.encode()).hexdigest()[:16]
            lib = _library(cache, name, digest)
        os.makedirs(cache, exist_ok=True)
        if not library_ok(lib):
            forget_library(lib)
            compile_shared(cc, opt, src, lib)
        return lib
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def compile_shared(cc: list[str], opt: str, src: str, lib: str, timeout: float = 600.0
                   ) -> None:
    """Compile the C file ``src`` into the shared library ``lib`` with ``cc`` and ``opt``,
    atomically: into a file of this process, checked and recorded
    (:func:`install_library`), then renamed, so that another process never loads a
    half-written library (and a failed compile leaves nothing). Raises on any failure (the
    compiler's error, an incomplete output, a timeout in seconds).

    Parameters
    ----------
    cc : list of str
        The compiler command as words, e.g. ``["ccache", "gcc"]`` (:func:`c_compiler`).
    opt : str
        Optimisation flag passed to the compiler, e.g. ``"-O2"``.
    src : str
        Path of the C source file.
    lib : str
        Path of the shared library to write (replaced if it exists).
    timeout : float
        Longest the compiler may run, s (default 600); longer raises
        ``subprocess.TimeoutExpired``.
    """
    part = lib + f".{os.getpid()}.tmp"
    try:
        subprocess.run([*cc, opt, "-fPIC", "-shared", src, "-o", part, "-lm"],
                       check=True, capture_output=True, timeout=timeout,
                       stdin=subprocess.DEVNULL)
        install_library(part, lib)
    finally:
        if os.path.exists(part):
            os.remove(part)


def compile_function(fn: ca.Function | Callable[[], ca.Function], opt: str = "-O2",
                     key: str | None = None, name: str | None = None) -> ca.Function:
    """Compile a CasADi Function to a shared library cached in :func:`cache_dir`; return
    it as ``casadi.external``.

    Parameters
    ----------
    fn : casadi.Function or callable
        The function, or a callable that builds it (called only when the library is not
        cached under ``key``, or when compiling is impossible).
    opt : str
        Optimisation flag of the C compiler.
    key : str, optional
        Text that determines the function completely (e.g. a structure key). With a key,
        the library is named by its hash and a cached library is loaded *without*
        generating the C code (generating the code of a large graph takes a good part of
        a second); without one, the library is named by the hash of the generated code.
    name : str, optional
        The function's name (needed with ``key`` when ``fn`` is a callable).

    Returns
    -------
    casadi.Function
        The compiled function, or the interpreted one (the same numbers, slower) when
        compiling is off (``CABLE_OCP_CACHE=0``), no C compiler is found (``$CC`` names a
        missing program, or neither ``cc`` nor ``gcc`` is on the PATH), the cache
        directory cannot be created or written, or the compiler or the loading fails.
        Silent.
    """
    def built() -> ca.Function:
        return fn if isinstance(fn, ca.Function) else fn()

    cache = cache_dir()
    cc = c_compiler()
    if cache is None or cc is None:
        return built()
    fname = name or (fn.name() if isinstance(fn, ca.Function) else None)
    if key is not None and fname is not None:
        digest = hashlib.sha256((key + "\0" + fname + "\0" + ca.__version__ + "\0" + opt
                                 ).encode()).hexdigest()[:16]
        lib = _library(cache, fname, digest)
        if library_ok(lib):
            try:
                return ca.external(fname, lib)
            except Exception as exc:  # noqa: BLE001 - a broken library: compile it again
                interrupt.reraise_interruption(exc)
                forget_library(lib)
        else:
            forget_library(lib)  # damaged, foreign or without its record: never loaded
    else:
        lib = None
    f = built()
    try:
        return ca.external(f.name(), _build_library([f], f.name(), cache, cc, opt, lib))
    except Exception as exc:  # noqa: BLE001 - any failure: fall back to the interpreted function
        interrupt.reraise_interruption(exc)  # a compiler killed by the Ctrl-C: no fallback
        return f


def compile_functions(fns: list[ca.Function], opt: str = "-O1",
                      prefix: str = "") -> list[ca.Function]:
    """Compile several CasADi Functions into one shared library cached in
    :func:`cache_dir` (named by the hash of the generated code); return them as
    ``casadi.external``.

    The library is named ``prefix`` + the first function's name. Returns ``fns`` unchanged
    (interpreted: the same numbers, slower) whenever :func:`compile_function` would fall
    back: compiling off, no compiler, an unwritable cache, a failing compiler or loading.
    Silent.

    Parameters
    ----------
    fns : list of casadi.Function
        The functions, compiled into one C file; an empty list is returned as is.
    opt : str
        Optimisation flag of the C compiler (default ``"-O1"``: a large graph compiles
        much faster than with ``-O2``).
    prefix : str
        Prefix of the library's name, before the first function's name (default none).
    """
    cache = cache_dir()
    cc = c_compiler()
    if cache is None or cc is None or not fns:
        return fns
    name = prefix + fns[0].name()
    try:
        lib = _build_library(fns, name, cache, cc, opt)
        return [ca.external(fn.name(), lib) for fn in fns]
    except Exception as exc:  # noqa: BLE001 - any failure: the interpreted functions
        interrupt.reraise_interruption(exc)
        return fns
