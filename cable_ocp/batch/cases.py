"""Case matrices of a load-case study: full grids, ranges and seeded random samples of any
dotted key (the keys ``--set`` takes).

A batch is a list of :class:`Case` objects, each with the overrides that make it from the
base problem file, a stable identifier (for ``--resume``) and its own seed, derived from
the batch seed with :class:`numpy.random.SeedSequence` (so reruns reproduce bit for bit on
one machine). Grid cases come in *snake* (boustrophedon) order: consecutive cases differ in
one key by one step, so each case can be warm-started from its neighbour.
"""

from __future__ import annotations

import itertools
import json
import math
import re
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.scene.files import parse_override

#: distributions for ``--random KEY=DIST(a,b)``: name -> (parameter names, meaning)
DISTRIBUTIONS = {
    "uniform": ("low, high", "uniform on [low, high]"),
    "normal": ("mean, std", "normal with that mean and standard deviation"),
    "lognormal": ("mu, sigma", "exp of a normal(mu, sigma): median exp(mu)"),
}


@dataclass(frozen=True)
class Case:
    """One load case.

    Attributes
    ----------
    index : int
        Position in the batch (0-based), the order of the output table.
    overrides : dict
        Dotted key -> value, applied to the base problem (as ``--set`` does).
    seed : int
        The case's own seed (for seeded scenes: the heave sea realisation), from the batch
        seed; a grid or sample that sets ``simulation.seed`` itself wins.
    """

    index: int
    overrides: dict[str, Any] = field(hash=False)
    seed: int = 0

    @property
    def case_id(self) -> str:
        """A stable identifier of the case's inputs (for ``--resume``)."""
        return json.dumps(self.overrides, sort_keys=True, separators=(",", ":"))


def _values(text: str, key: str) -> list[Any]:
    """``V1,V2,...`` -> TOML scalars (bare words stay strings); a list value needs brackets."""
    parts, depth, cur = [], 0, ""
    for ch in text:
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        depth += ch in "[" and 1 or ch in "]" and -1 or 0
        cur += ch
    parts.append(cur)
    vals = [parse_override(f"{key}={p.strip()}")[1] for p in parts if p.strip()]
    if not vals:
        raise CableOCPError(f"--grid {key}=: give at least one value, e.g. {key}=1,2,3")
    return vals


def parse_grid(text: str) -> tuple[str, list[Any]]:
    """``KEY=V1,V2,...`` -> (key, values)."""
    if "=" not in text:
        raise CableOCPError(f"--grid {text!r}: expected KEY=V1,V2,..., e.g. "
                            "environment.current.speed=0.5,1.0")
    key, vals = text.split("=", 1)
    return key.strip(), _values(vals, key.strip())


def parse_range(text: str) -> tuple[str, list[float]]:
    """``KEY=START:STOP:N`` -> (key, N evenly spaced values from START to STOP inclusive)."""
    m = re.fullmatch(r"\s*([^=]+?)\s*=\s*([^:]+):([^:]+):([^:]+)\s*", text)
    if not m:
        raise CableOCPError(f"--range {text!r}: expected KEY=START:STOP:N, e.g. "
                            "layout.psi0_deg=0:180:19")
    key = m.group(1)
    try:
        start, stop = float(m.group(2)), float(m.group(3))
        n = int(m.group(4))
    except ValueError:
        raise CableOCPError(f"--range {text!r}: START and STOP must be numbers and N an "
                            "integer") from None
    if not (math.isfinite(start) and math.isfinite(stop)) or not 1 <= n <= 100000:
        raise CableOCPError(f"--range {text!r}: finite START, STOP and N in 1..100000")
    return key, [float(v) for v in np.linspace(start, stop, n)]


def parse_random(text: str) -> tuple[str, str, tuple[float, float]]:
    """``KEY=DIST(a,b)`` -> (key, distribution, parameters); see :data:`DISTRIBUTIONS`."""
    m = re.fullmatch(r"\s*([^=]+?)\s*=\s*([a-z]+)\(([^,()]+),([^,()]+)\)\s*", text)
    valid = ", ".join(f"{k}({v[0]})" for k, v in DISTRIBUTIONS.items())
    if not m or m.group(2) not in DISTRIBUTIONS:
        raise CableOCPError(f"--random {text!r}: expected KEY=DIST(a,b) with DIST one of "
                            f"{valid}")
    try:
        a, b = float(m.group(3)), float(m.group(4))
    except ValueError:
        raise CableOCPError(f"--random {text!r}: the parameters must be numbers") from None
    dist = m.group(2)
    if not (math.isfinite(a) and math.isfinite(b)):
        raise CableOCPError(f"--random {text!r}: the parameters must be finite")
    if dist == "uniform" and not a < b:
        raise CableOCPError(f"--random {text!r}: uniform(low, high) needs low < high")
    if dist == "uniform" and not math.isfinite(b - a):
        raise CableOCPError(f"--random {text!r}: uniform(low, high) needs high - low to be a "
                            "finite number (at most about 1.8e308)")
    if dist in ("normal", "lognormal") and not b > 0:
        raise CableOCPError(f"--random {text!r}: {dist}(.., spread) needs a spread > 0")
    return m.group(1), dist, (a, b)


def _snake(grids: list[tuple[str, list[Any]]]) -> list[dict[str, Any]]:
    """Cartesian product in boustrophedon order: the last key runs fastest and reverses
    direction each time an earlier key steps, so neighbours differ in one key by one step."""
    if not grids:
        return [{}]
    head, *rest = grids
    inner = _snake(rest)
    out = []
    for i, v in enumerate(head[1]):
        block = inner if i % 2 == 0 else inner[::-1]
        out += [{head[0]: v, **c} for c in block]
    return out


def build_cases(grids: list[tuple[str, list[Any]]] | None = None,
                samples: int = 0, randoms: list[tuple[str, str, tuple[float, float]]]
                | None = None, seed: int = 0, max_cases: int = 1_000_000) -> list[Case]:
    """The cases of a batch: the full grid of ``grids`` (snake order), times ``samples``
    seeded random draws of the ``randoms`` keys (each sample combined with every grid
    point), each case with its own seed from ``seed``.

    Parameters
    ----------
    grids : list of (str, list), optional
        ``(dotted key, values)`` per swept key, as :func:`parse_grid` and
        :func:`parse_range` give them, values in the problem file's units (SI); the first
        key varies slowest. None (default): no grid (one point).
    samples : int
        Number of random draws (``--samples``), each combined with every grid point;
        default 0: none (then ``randoms`` must be empty).
    randoms : list of (str, str, (float, float)), optional
        ``(dotted key, distribution, parameters)`` per randomly drawn key, as
        :func:`parse_random` gives them (see :data:`DISTRIBUTIONS`). None (default): none.
    seed : int
        Batch seed (default 0): the draws and every case's own seed derive from it
        (:class:`numpy.random.SeedSequence`).
    max_cases : int
        Largest number of cases allowed (default 1,000,000).

    Raises
    ------
    CableOCPError
        On a key given twice, random keys without ``samples`` (or the reverse), or more
        than ``max_cases`` cases.
    """
    grids = list(grids or [])
    randoms = list(randoms or [])
    keys = [k for k, _ in grids] + [k for k, _, _ in randoms]
    dup = sorted({k for k in keys if keys.count(k) > 1})
    if dup:
        raise CableOCPError(f"{dup[0]}: swept twice; give each key once")
    if randoms and samples < 1:
        raise CableOCPError("--random needs --samples N (N >= 1)")
    if samples and not randoms:
        raise CableOCPError("--samples needs at least one --random KEY=DIST(a,b)")
    n_grid = math.prod(len(v) for _, v in grids) if grids else 1
    total = n_grid * max(samples, 1)
    if total > max_cases:
        raise CableOCPError(f"the batch has {total} cases, more than the limit {max_cases}; "
                            "split it or coarsen the grid")
    points = _snake(grids)
    if randoms:
        rng = np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])
        draws = []
        for _ in range(samples):
            d = {}
            for key, dist, (a, b) in randoms:
                x = (rng.uniform(a, b) if dist == "uniform" else rng.normal(a, b)
                     if dist == "normal" else rng.lognormal(a, b))
                if not math.isfinite(x):  # e.g. lognormal(700, 10) or normal(1e308, 1e308)
                    raise CableOCPError(
                        f"--random {key}={dist}({a:g},{b:g}): a draw is not a finite number "
                        f"({x}); give parameters whose draws fit a float")
                d[key] = float(x)
            draws.append(d)
        # samples sorted along the first random key: neighbours are close (warm starts)
        draws.sort(key=lambda d: tuple(d[k] for k, _, _ in randoms))
        points = [{**p, **d} for p, d in itertools.product(points, draws)]
    seeds = np.random.SeedSequence(seed).spawn(len(points) + 1)[1:]
    return [Case(i, p, int(s.generate_state(1)[0])) for i, (p, s) in
            enumerate(zip(points, seeds, strict=True))]
