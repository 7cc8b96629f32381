"""The vessel's heave of the pay-out schedule (cable_ocp/schedule/sea.py): the seeded sea's
variance against its spectrum, the CasADi form against numpy, the seeds, the fade-in."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from cable_ocp.errors import CableOCPError
from cable_ocp.heave.sea import SeaSpectrum
from cable_ocp.scene.dynamics import load_dynamic_scene
from cable_ocp.schedule.sea import (
    BAND_HIGH,
    UNSEEN_OFFSET,
    fade,
    sea_components,
    vessel_motions,
)

ROOT = Path(__file__).resolve().parents[2]
HUANG = ROOT / "problems" / "dynamics" / "huang_3_3_5.toml"
HS, WM = 2.0, 0.6


def _sea_scene(**sea):
    ov = {"deployment.target_length": 80.0, "deployment.sea.significant_height": HS,
          "deployment.sea.peak_frequency": WM}
    ov.update({f"deployment.sea.{k}": v for k, v in sea.items()})
    return load_dynamic_scene(HUANG, ov)


def test_sea_variance_over_its_period_is_the_component_sum_and_near_m0():
    scene = _sea_scene(fade_in=0.0)
    motion = vessel_motions(scene)[0]
    w, a, dw = sea_components("bretschneider", HS, WM, 64)
    # on the grid w_i = (k0 + i + 1/2) dw every sum and difference of two frequencies is a
    # multiple of dw: over one period 2 pi / dw the mean of z^2 is the component sum
    # exactly; 20000 samples resolve every product (its highest harmonic is far below
    # half the sampling rate), so only round-off is left (1e-12 relative)
    period = 2.0 * math.pi / dw
    t = np.linspace(0.0, period, 20000, endpoint=False)
    var = float(np.mean(motion.heave(t) ** 2))
    comp = float(np.sum(a**2) / 2.0)
    assert var == pytest.approx(comp, rel=1e-12)
    # the component sum is the midpoint rule of the band's energy, whose closed form is
    # (Hs^2/16) (exp(-1.25 (wm/w_hi)^4) - exp(-1.25 (wm/w_lo)^4)) (the cumulative of
    # Bretschneider (6.20)); the rule's error on 64 bins is below 1e-4 relative
    lo, hi = w[0] - dw / 2, w[-1] + dw / 2
    band = HS**2 / 16 * (math.exp(-1.25 * (WM / hi) ** 4) - math.exp(-1.25 * (WM / lo) ** 4))
    assert comp == pytest.approx(band, rel=1e-4)
    # and m0 = Hs^2/16 itself: the band leaves out 1 - exp(-1.25/4^4) = 0.49 % above
    # 4 omega_m (its top is within dw/2 of BAND_HIGH omega_m), so 0.6 % covers it
    m0 = SeaSpectrum("bretschneider", HS, WM).m0()
    assert m0 == pytest.approx(HS**2 / 16, rel=1e-6)
    assert comp == pytest.approx(m0, rel=6e-3)
    assert comp < m0
    assert hi == pytest.approx(BAND_HIGH * WM, abs=dw / 2 + 1e-12)


def test_jonswap_components_hold_its_energy():
    w, a, _ = sea_components("jonswap", HS, WM, 128)
    # the DNV normalisation keeps m0 within a few per cent of Hs^2/16 (cable_ocp.heave.sea);
    # the band and the 128-bin midpoint rule add below 1 %
    m0 = SeaSpectrum("jonswap", HS, WM).m0()
    assert float(np.sum(a**2) / 2) == pytest.approx(m0, rel=1e-2)


def test_sea_heave_and_its_rate_are_the_faded_sum_written_here():
    """heave and heave_rate evaluate the one CasADi law (and its AD): against the sum
    f(t) sum a cos(w t + p) and its derivative written out here in numpy."""
    t = np.linspace(0.0, 80.0, 401)
    motion = vessel_motions(_sea_scene(fade_in=30.0))[0]
    a, w, p = (np.array(v) for v in (motion.amplitudes, motion.frequencies, motion.phases))
    x = np.clip(t / 30.0, 0.0, 1.0)
    f, df = 10 * x**3 - 15 * x**4 + 6 * x**5, (30 * x**2 - 60 * x**3 + 30 * x**4) / 30.0
    arg = w * t[:, None] + p
    z = f * np.sum(a * np.cos(arg), axis=1)
    dz = df * np.sum(a * np.cos(arg), axis=1) - f * np.sum(a * w * np.sin(arg), axis=1)
    # the same arithmetic in another order: round-off only (|z| ~ 1 m, |dz| ~ 1 m/s)
    assert np.max(np.abs(motion.heave(t) - z)) < 1e-12
    assert np.max(np.abs(motion.heave_rate(t) - dz)) < 1e-12
    sym = np.array(motion.casadi_heave().map(len(t))(t.reshape(1, -1))).ravel()
    assert np.array_equal(sym, motion.heave(t))
    assert motion.heave(t.reshape(-1, 1)).shape == (401, 1)


def test_scene_heave_is_its_ramped_sine_and_series_rows():
    scene = load_dynamic_scene(HUANG)
    motion = vessel_motions(scene)[0]
    tm = scene.top_motion
    t = np.array([0.0, 7.0, 15.0, 29.0, 45.0])
    x = np.minimum(t / tm.ramp_time, 1.0)
    r = 10 * x**3 - 15 * x**4 + 6 * x**5
    want = r * tm.heave_amplitude * np.sin(tm.heave_frequency * t)
    assert np.allclose(motion.heave(t), want, rtol=0, atol=1e-14)  # round-off
    rows = motion.series_rows(10.0, 0.5)
    assert len(rows) == 21 and rows[-1][0] == 10.0
    assert all(r[1] == 0.0 and r[2] == 0.0 for r in rows)
    assert rows[4][3] == pytest.approx(float(motion.heave(np.array([2.0]))[0]), abs=1e-15)


def test_heave_rate_is_the_derivative():
    motion = vessel_motions(_sea_scene(fade_in=20.0))[0]
    t = np.linspace(1.0, 60.0, 300)
    h = 1e-5
    fd = (motion.heave(t + h) - motion.heave(t - h)) / (2 * h)
    # central difference: error h^2 z''' / 6 ~ 1e-10 m/s for |z'''| ~ 10 m/s^3
    assert np.max(np.abs(fd - motion.heave_rate(t))) < 1e-8


def test_seeds_design_and_unseen_are_disjoint():
    scene = _sea_scene(seed=7, realisations=3, unseen=4)
    design = vessel_motions(scene)
    unseen = vessel_motions(scene, "unseen")
    assert [m.seed for m in design] == [7, 8, 9]
    assert [m.seed for m in unseen] == [7 + UNSEEN_OFFSET + j for j in range(4)]
    assert not {m.seed for m in design} & {m.seed for m in unseen}
    phases = [m.phases for m in design + unseen]
    assert len(set(phases)) == len(phases)  # different seeds, different phases
    # the same seed gives the same realisation
    assert vessel_motions(scene)[1].phases == design[1].phases


def test_fade_in_is_the_quintic():
    scene = _sea_scene(fade_in=30.0)
    motion = vessel_motions(scene)[0]
    assert motion.heave(np.array([0.0]))[0] == 0.0
    assert motion.heave_rate(np.array([0.0]))[0] == 0.0
    f, df = fade(np.array([0.0, 15.0, 30.0, 40.0]), 30.0)
    assert np.allclose(f, [0.0, 0.5, 1.0, 1.0], rtol=0, atol=1e-15)  # 10/8-15/16+6/32 = 1/2
    assert df[1] == pytest.approx(30 * 0.25 * 0.25 / 30.0, rel=1e-14)
    # after the fade the realisation is the plain sum of harmonics
    t = np.array([31.0, 50.0])
    a, w, p = (np.array(v) for v in (motion.amplitudes, motion.frequencies, motion.phases))
    plain = np.sum(a * np.cos(w * t[:, None] + p), axis=1)
    assert np.allclose(motion.heave(t), plain, rtol=0, atol=1e-14)
    f0, _ = fade(np.array([3.0]), 0.0)
    assert f0[0] == 1.0


def test_errors_name_the_key():
    with pytest.raises(CableOCPError, match=r"deployment\.sea"):
        vessel_motions(load_dynamic_scene(HUANG), "unseen")
    with pytest.raises(CableOCPError, match="horizontal_amplitude"):
        vessel_motions(load_dynamic_scene(HUANG, {"top_motion.horizontal_amplitude": 1.0,
                                                  "top_motion.horizontal_frequency": 0.5}))
    with pytest.raises(CableOCPError, match="which"):
        vessel_motions(load_dynamic_scene(HUANG), "other")
