"""The heave deployment on the 3D lumped-mass line with pay-out
(:class:`cable_ocp.heave.lumped_deploy.LumpedPayoutPlant`).

Independent references:

* the axial plant (:class:`cable_ocp.heave.axial_plant.AxialCablePlant`, Huang (1992)
  ch. 3: the fixed domain y = s / L(t) (3.4)-(3.7), its own discretisation of the pay-out)
  on the same vertical line under the same pay-out and boom-tip heave;
* the closed form of the static vertical line, ``z_b - L - (W L + w L^2 / 2) / EA``;
* the lumped-mass model's static equilibrium in the current at the final length
  (:func:`cable_ocp.dynamics.lumped_scene.lumped_start`: the statics solver refined by
  Newton), for the direction of the unit's offset;
* the pay-out law itself (:func:`cable_ocp.heave.deployment.length_history`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.dynamics.lumped_scene import LumpedSceneModel
from cable_ocp.heave.axial_plant import AxialCablePlant
from cable_ocp.heave.deployment import length_history
from cable_ocp.heave.lumped_deploy import LumpedPayoutPlant
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.scene.heave import load_scene

ROOT = Path(__file__).resolve().parents[2]
DYN = ROOT / "problems" / "dynamics"
# the 6.2.6 line (deployment_6_3_6.toml): unit weight in water W (N), cable w (N/m), EA (N)
W, W_CABLE, EA = 50000.0, 54.0, 1.57706e7


def _vertical(model: str, **over: object):
    """deployment_6_3_6.toml's line at 50 m, 10 m elements, no current."""
    o = {"cable.length": 50.0, "simulation.segments": 5, "simulation.time_step": 0.01,
         "simulation.model": model, **over}
    if model == "lumped3d":
        o["simulation.element_length"] = 10.0
    return load_dynamic_scene(DYN / "deployment_6_3_6.toml").with_overrides(o)


def test_vertical_deployment_equals_axial_plant() -> None:
    """A vertical lumped3d deployment without current is the axial one: 50 -> 60 m at
    1 m/s (10 s ramps, so the 125 t unit stays taut) under a boom-tip heave of 0.1 m at
    0.6 rad/s, 5 sub-steps of 0.01 s per 0.05 s sample, 10 m elements in both (22 s).

    The two discretise the same lumped chain (masses at the nodes, chord tensions, the
    midpoint rule), but the pay-out differently: the axial plant stretches every element
    of its fixed domain (with its advection terms), the lumped3d one lengthens its top
    segment and adds a node there (a split at 15 m). The unit's height agrees to 1e-4 m
    (seen 5e-6 m: the pay-out's discretisation); the top tension to 0.5 % of its swing
    (seen 0.15 %, about 70 N: the same size as with the winch still, where the heights
    agree to 1e-9 m, so it is the evaluation of the output at the end of a step, with
    the material damping at the end velocities, not the dynamics). The unstretched
    length is the pay-out's to round-off, every sample."""
    lum = LumpedPayoutPlant(_vertical("lumped3d"), 0.05, (50.0, 60.0))
    ax = AxialCablePlant(_vertical("axial"), 0.05)
    # the static reference: the closed form (exact for the lumped chain, any mesh)
    lg = np.array([50.0, 53.3, 57.9])
    z_cf = 3000.0 - lg - (W * lg + 0.5 * W_CABLE * lg**2) / EA
    np.testing.assert_allclose(lum.static_unit_height(lg), z_cf, rtol=0, atol=1e-9)
    m, k_n = lum.substeps, 440
    t = np.arange(k_n * m + 1) * lum.dt
    length = length_history(t, 50.0, 60.0, 1.0, 1.0, 10.0)
    top = lum.z_top0 + 0.1 * np.sin(0.6 * t) * np.clip(t / 5.0, 0.0, 1.0) ** 3
    xl, xa = lum.initial_state(), ax.initial_state()
    zl, za, tl, ta, paid = [], [], [], [], []
    for k in range(k_n):
        sl = slice(k * m, k * m + m + 1)
        xl, ol = lum.advance(xl, length[sl], top[sl])
        xa, oa = ax.advance(xa, length[sl], top[sl])
        zl.append(ol["z_unit"])
        za.append(oa["z_unit"])
        tl.append(ol["t_top"])
        ta.append(oa["t_top"])
        paid.append(float(np.sum(xl.lengths)) - length[(k + 1) * m])
        assert ol["residual"] < 1e-6  # every sample converged
    zl, za, tl, ta = (np.concatenate(v) for v in (zl, za, tl, ta))
    assert np.max(np.abs(zl - za)) < 1e-4
    assert np.max(np.abs(tl - ta)) < 5e-3 * np.ptp(ta)
    assert np.max(np.abs(paid)) < 1e-9  # the length follows the pay-out exactly
    assert xl.segments == 6  # a node entered at the winch (the top segment passed 15 m)
    assert lum.segment_counts[-1] == 6
    assert np.max(np.abs(np.array(lum.unit_xy))) < 1e-12  # no current: it stays vertical


def test_unit_offset_turns_with_the_current() -> None:
    """The shipped deployment line (problems/dynamics/deployment_lumped3d.toml: 0.8 m/s
    towards +x at the surface turning to +y at 200 m), lowered 50 -> 90 m at 1.5 m/s
    (10 s ramps) and held 10 s, one 0.05 s step per sample, no heave: the unit's
    horizontal offset turns from its static direction at 50 m (about 14 deg from +x)
    towards the turned current, to within 4 deg of the static direction at 90 m (about
    27 deg, an independent static solve), the remainder the drift still settling after
    the stop (the moving line's drag lags). The length is the pay-out's to round-off and
    nodes entered at the winch (4 -> 7 segments)."""
    sc = load_dynamic_scene(DYN / "deployment_lumped3d.toml").with_overrides(
        {"simulation.time_step": 0.05})
    plant = LumpedPayoutPlant(sc, 0.05, (50.0, 90.0))

    def static_angle(length: float) -> float:
        m = LumpedSceneModel(sc.with_overrides({"cable.length": length}),
                             segments=int(round(length / 12.5)))
        x, info = m.static_positions()
        assert x is not None, info
        return math.degrees(math.atan2(x[1], x[0]))

    a50, a90 = static_angle(50.0), static_angle(90.0)
    assert a90 - a50 > 10.0  # the static offset itself turns (the test can see a turn)
    n = 940
    t = np.arange(n + 1) * 0.05
    length = length_history(t, 50.0, 90.0, 1.5, 0.0, 10.0)
    x = plant.initial_state()
    tops = np.full(2, plant.z_top0)
    for k in range(n):
        x, out = plant.advance(x, length[k:k + 2], tops)
        assert out["residual"] < 1e-6
        assert abs(float(np.sum(x.lengths)) - length[k + 1]) < 1e-9
    xy = np.array(plant.unit_xy)
    ang = np.degrees(np.arctan2(xy[:, 1], xy[:, 0]))
    assert ang[0] == pytest.approx(a50, abs=0.1)  # starts at rest in its static offset
    assert abs(ang[-1] - a90) < 4.0
    assert x.segments == 7 and max(plant.segment_counts) == 7


def test_shipped_deployment_scene_is_lumped3d() -> None:
    """problems/heave/deployment_lumped3d.toml loads (a [deployment] on a lumped3d line is
    accepted) and lowers 50 -> 200 m on 12.5 m elements in a current that turns 90 deg."""
    sc = load_scene(ROOT / "problems" / "heave" / "deployment_lumped3d.toml")
    dyn = load_dynamic_scene(DYN / "deployment_lumped3d.toml")
    assert sc.deployment.final_length == 200.0
    assert dyn.simulation.model == "lumped3d" and dyn.simulation.element_length == 12.5
    assert dyn.length == 50.0


def test_failed_sample_is_taken_again_in_finer_steps() -> None:
    """A sample whose Newton residual exceeds the failure threshold is stepped again with
    2 times the sub-steps (HALVINGS): the unit's height of the finer sample agrees with the
    plain one to 1e-5 m (seen 1e-6 m: the midpoint rule's O(dt^2) on 1 cm of pay-out and
    1 mm of heave per sample) and the length is the same."""
    plant = LumpedPayoutPlant(_vertical("lumped3d"), 0.05, (50.0, 50.5))
    lengths = np.linspace(50.0, 50.01, plant.substeps + 1)
    tops = plant.z_top0 + np.linspace(0.0, 0.001, plant.substeps + 1)
    x1, o1 = plant.advance(plant.initial_state(), lengths, tops)
    real, finer = plant._sample_fn, []

    def failing(n: int, sub: int | None = None):  # the plain sample "fails"
        fn = real(n, sub)
        if sub is None:
            return lambda *a: [math.inf if i == 7 else v for i, v in enumerate(fn(*a))]
        finer.append(sub)
        return fn

    plant._sample_fn = failing
    x2, o2 = plant.advance(plant.initial_state(), lengths, tops)
    assert finer == [2 * plant.substeps]
    assert np.max(np.abs(o1["z_unit"] - o2["z_unit"])) < 1e-5
    assert o2["residual"] < 1e-6
    np.testing.assert_allclose(x2.lengths, x1.lengths, rtol=0, atol=1e-12)
