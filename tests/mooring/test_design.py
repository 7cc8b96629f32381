"""Design optimisation through the mooring equilibrium (cable_ocp.mooring.design): the exact
gradients against central differences of full equilibria, and an SLSQP optimum against a
scan; the line's length sensitivity against two line solves."""

from __future__ import annotations

import copy
import tomllib
from dataclasses import replace

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.mooring import solve_system
from cable_ocp.mooring.design import MooringDesign, optimise
from cable_ocp.scene import End
from cable_ocp.scene.system import system_from_dict
from cable_ocp.statics.solver import SolveSession

OUTPUTS = ("offset", "tension", "laid_length", "uplift")


@pytest.fixture(scope="module")
def spar(problems) -> dict:
    with open(problems / "systems" / "spar_3line.toml", "rb") as fh:
        return tomllib.load(fh)


def _held(x) -> End:
    return End(position=tuple(float(v) for v in x), force=(None, None, None))


def test_length_sensitivity_equals_two_solves(spar) -> None:
    """dF/dL, dg/dL and dg/dx of one grounded chain equal central differences of two line
    solves: both are exact for the discretised equations, so they differ by the step's
    truncation (h = 0.01 m on 902 m) and the solves' tolerance, ~1e-6 relative."""
    line = system_from_dict(spar).lines[0].scene
    ses = SolveSession(error_estimate=False)
    sol = ses.solve(line)
    d = sol.length_sensitivity()
    assert sol.grounded_length > 100.0  # the grounded case: the contact's unknown moves too
    h, length = 0.01, line.cable.length

    def at(sc):
        s = ses.solve(sc)
        return np.concatenate([s.force_a, s.force_b]), s.grounded_length

    (fp, gp), (fm, gm) = (at(replace(line, cable=replace(line.cable, length=length + sg * h)))
                          for sg in (1.0, -1.0))
    fd = (fp - fm) / (2 * h)
    assert np.max(np.abs(d["force"] - fd)) < 1e-5 * np.max(np.abs(fd))
    assert d["grounded_length"] == pytest.approx((gp - gm) / (2 * h), rel=1e-5)
    assert np.array_equal(d["end_jacobian"], sol.end_jacobian(), equal_nan=True)
    xb = np.array(line.end_b.position)
    g2 = [at(replace(line, end_b=_held(xb + sg * h * np.array([1.0, 0, 0]))))[1]
          for sg in (1.0, -1.0)]
    assert d["grounded_length_ends"][3] == pytest.approx((g2[0] - g2[1]) / (2 * h), rel=1e-5)
    assert np.isnan(d["grounded_length_ends"][2])  # lifting a grounded anchor: one-sided


def _clump_system(spar: dict) -> dict:
    """The spar with line L1 split by a 2 t clump at 500 m from its anchor."""
    base = solve_system(system_from_dict(spar), stiffness=False)
    sol = base.solutions["L1"]
    pos = sol.position[int(np.argmin(np.abs(sol.s - 500.0)))]
    data = copy.deepcopy(spar)
    data["points"].append({"name": "c1", "kind": "free", "position": pos.tolist(),
                           "mass": 2000.0})
    data["lines"] = [ln for ln in data["lines"] if ln["name"] != "L1"]
    data["lines"] += [{"name": "L1a", "point_a": "a1", "point_b": "c1", "type": "chain",
                       "length": 500.0},
                      {"name": "L1b", "point_a": "c1", "point_b": "f1", "type": "chain",
                       "length": 402.2}]
    return data


def _check(design: MooringDesign, x0: np.ndarray, steps, scales) -> dict[str, float]:
    """Largest error of the exact gradient against central differences of full
    equilibria, per output, each variable's derivative in its natural unit (``scales``:
    m, or m of arc per rad, or kg of chain per m) over the largest of them."""
    pt = design.evaluate(x0)
    fds = {k: [] for k in OUTPUTS}
    for j, h in enumerate(steps):
        xp, xm = x0.copy(), x0.copy()
        xp[j] += h
        xm[j] -= h
        a, b = design.evaluate(xp, gradient=False), design.evaluate(xm, gradient=False)
        for k in OUTPUTS:
            fds[k].append((np.asarray(getattr(a, k)) - np.asarray(getattr(b, k))) / (2 * h))
    errs = {}
    for k in OUTPUTS:
        fd = np.moveaxis(np.array(fds[k]), 0, -1) * scales
        ex = np.asarray(pt.grad[k]) * scales
        errs[k] = float(np.max(np.abs(ex - fd)) / np.max(np.abs(fd)))
    return errs


def test_gradients_equal_central_differences_of_equilibria(spar) -> None:
    """Every output's gradient in every kind of variable (a line's length, two lengths
    tied, an anchor's radius and heading, a clump's mass) equals central differences of
    full equilibria to 2e-5 of the output's largest derivative: both are exact up to the
    differences' truncation and the equilibria's tolerance (1e-8 of the tension: a
    noise ~1e-9 * 2 MN / 0.2 m ~ 1e-2 N/m on derivatives ~1e4 N/m)."""
    design = MooringDesign(system_from_dict(_clump_system(spar)),
                           ["length:L1b", "length:L2,L3", "radius:L2", "heading:L3",
                            "mass:c1"], [1.0e6, 0.0, 0.0])
    x0 = design.values()
    x0[3] += 0.05  # off the symmetric heading, where the offset's derivative vanishes
    errs = _check(design, x0, [0.1, 0.1, 0.1, 1e-4, 10.0],
                  np.array([1.0, 1.0, 1.0, 1.0 / x0[2], 162.0]))
    for k, e in errs.items():
        assert e < 2e-5, (k, errs)
    pt = design.evaluate(x0, gradient=False)
    # each output really depends on the variables: the uplift of the lifted anchors a2,
    # a3, the laid length of the grounded L1a, the clump's line
    assert pt.uplift[1] > 1e4 and pt.laid_length[2] > 50.0  # lines L2, L3, L1a, L1b


def test_slsqp_optimum_equals_the_scan(spar) -> None:
    """Minimum chain mass, the three lengths tied, s.t. offset <= 20 m and SF >= 3.2 under
    1 MN: the optimum is the shortest length of the scan that is feasible, to within the
    scan's spacing (0.05 m), and the safety factor is the active constraint."""
    scene = system_from_dict(spar)
    res = optimise(scene, ["length:L1,L2,L3"], [1.0e6, 0.0, 0.0], max_offset=20.0,
                   min_safety_factor=3.2, bounds=[(880.0, 930.0)])
    assert res.success, res.message
    length = res.x["length:L1,L2,L3"]
    assert abs(res.constraints["safety_factor"].min()) < 1e-6  # active
    assert res.constraints["offset"][0] > 0.05  # inactive
    design = MooringDesign(scene, ["length:L1,L2,L3"], [1.0e6, 0.0, 0.0])

    def feasible(x: float) -> bool:
        pt = design.evaluate([x], gradient=False)
        return bool(pt.offset <= 20.0 and np.nanmin(pt.safety_factor) >= 3.2)

    coarse = [x for x in np.arange(895.0, 912.0, 1.0) if feasible(x)]
    best = coarse[0]
    fine = [x for x in np.arange(best - 1.0, best + 1e-9, 0.05) if feasible(x)]
    assert abs(length - fine[0]) <= 0.05


def test_multi_part_line_length_and_part_length(spar) -> None:
    """On a line of two parts (chain, wire), the line's length (its parts' shares held:
    exact) and one part's length (a central difference of two line solves: the shares are
    built into the line's functions) both give gradients equal to central differences of
    full equilibria, to 2e-5 of the largest derivative (the reasons of the test above;
    the uplift is left out: every anchor is grounded here, it is 0 to rounding)."""
    data = copy.deepcopy(spar)
    data["line_types"]["wire"] = {"diameter": 0.09, "mass_per_length": 40.0, "mbl": 6e6,
                                  "axial_stiffness": 6e8, "normal_drag": 1.2}
    line = data["lines"][0]
    del line["type"], line["length"]
    line["parts"] = [{"type": "chain", "length": 400.0}, {"type": "wire", "length": 502.2}]
    data["lines"][1]["parts"] = [{"type": "chain", "length": 450.0},
                                 {"type": "wire", "length": 452.2}]
    data["lines"][1].pop("type")
    data["lines"][1].pop("length")
    design = MooringDesign(system_from_dict(data), ["length:L1", "length:L2/1"],
                           [1.0e6, 0.0, 0.0])
    errs = _check(design, design.values(), [0.1, 0.1], np.ones(2))
    for k in ("offset", "tension", "laid_length"):
        assert errs[k] < 2e-5, (k, errs)
    pt = design.evaluate(design.values(), gradient=False)
    assert pt.mass == pytest.approx(400 * 162 + 502.2 * 40 + 450 * 162 + 452.2 * 40
                                    + 902.2 * 162, rel=1e-12)
    with pytest.raises(CableOCPError, match="already set"):
        MooringDesign(system_from_dict(data), ["length:L1", "length:L1/0"], [1e6, 0, 0])
