"""Modal analysis of the lumped-mass model (Huang (1992) ch. 5) against closed forms.

* the exact dispersion relation of the discrete chain, omega = 2 sqrt(T / (m l))
  |sin(k l / 2)| (transverse) and 2 sqrt(EA / (m l)) |sin(k l / 2)| (axial), which Huang's
  (5.16) approximates;
* a hanging cable with a tip mass: transverse modes against the Bessel-function closed form,
  itself checked first against the hanging-chain (J0 zeros) and pendulum limits;
* the axial modes of a vertical line against the axial model of the same scene.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from closed_forms import hanging_cable_frequencies
from scipy.special import jn_zeros

from cable_ocp.dynamics import modes
from cable_ocp.dynamics.lumped import LumpedMassModel
from cable_ocp.dynamics.lumped_params import UnitParams, uniform_params


# --------------------------------------------------------------------------------------
# closed form: transverse modes of a hanging inextensible cable with a tip mass
# --------------------------------------------------------------------------------------
def test_closed_form_hanging_chain_limit() -> None:
    """Without a tip mass the closed form gives the hanging chain, omega_n = (j_0,n / 2)
    sqrt(g / L) (j_0,n the zeros of J0). Tolerance 1e-7: the tip is 1e-10 of the cable's
    weight, not exactly zero (Y0 is singular there)."""
    length, mu, g = 100.0, 2.0, 9.81
    om = hanging_cable_frequencies(length, mu * g, mu, 1e-10 * mu * g * length,
                                   1e-10 * mu * length, 4)
    exact = jn_zeros(0, 4) / 2.0 * math.sqrt(g / length)
    np.testing.assert_allclose(om, exact, rtol=1e-7)


def test_closed_form_pendulum_limit() -> None:
    """With a tip mass 1000 times the cable's the first frequency is the pendulum's
    sqrt(g / L) up to the cable's own share, O(mu L / M) = 1e-3 (tolerance 2e-4 on the
    ratio: the Rayleigh quotient below gives the first correction), and the Rayleigh
    quotient with the pendulum's straight shape, omega^2 = (W + w L / 2) / (L (M + mu L /
    3)), is exact to second order in mu L / M = 1e-3 (tolerance 1e-6)."""
    length, mu, g = 100.0, 2.0, 9.81
    big_m = 1000.0 * mu * length
    om = hanging_cable_frequencies(length, mu * g, mu, big_m * g, big_m, 1)[0]
    assert om / math.sqrt(g / length) == pytest.approx(1.0, abs=2e-4)
    rayleigh = math.sqrt((big_m * g + mu * g * length / 2.0)
                         / (length * (big_m + mu * length / 3.0)))
    assert om / rayleigh == pytest.approx(1.0, abs=1e-6)


# --------------------------------------------------------------------------------------
# the discrete chain: exact dispersion relation (Huang's (5.16) is an approximation)
# --------------------------------------------------------------------------------------
def _taut_chain(n: int, length: float = 10.0, ea: float = 1.0e6, mu: float = 1.0,
                tension: float = 100.0) -> tuple[LumpedMassModel, np.ndarray, float]:
    """A string fixed at both ends under uniform tension, no gravity, in air."""
    eps = tension / ea
    p = uniform_params(length, n, axial_stiffness=ea, diameter=0.01, mass_per_length=mu,
                       weight_in_water=0.0, top_position=[0.0, 0.0, length * (1.0 + eps)],
                       end_a_position=[0.0, 0.0, 0.0], water_density=0.0, gravity=0.0)
    m = LumpedMassModel(p)
    ls = length / n * (1.0 + eps)
    x = np.zeros((n - 1, 3))
    x[:, 2] = np.arange(1, n) * ls
    return m, x.reshape(-1), ls


def test_discrete_chain_dispersion_and_cutoff() -> None:
    """Eigenfrequencies of the linearised taut chain equal the exact discrete chain,
    omega_n = 2 sqrt(T / (m l_s)) sin(n pi / (2 N)) transversally (m = mu l the node mass,
    l_s the stretched spacing; each twice, in x and y) and 2 sqrt(EA / (m l))
    sin(n pi / (2 N)) axially, to 1e-9 relative (the linearisation is exact for this
    chain; the tolerance covers the eigensolver's rounding). The high-frequency cut-off
    is 2 sqrt(T / (m l)) (k l = pi); Huang's (5.16), omega = sqrt(l T / m) k sqrt(1 -
    l^2 k^2 / 12), puts it at sqrt(3 T / (l m)) (k l = sqrt 6), 13 % low, and it agrees
    with the exact relation only to O((k l)^4)."""
    n, length, ea, mu, tension = 20, 10.0, 1.0e6, 1.0, 100.0
    m, x, ls = _taut_chain(n, length, ea, mu, tension)
    om, shapes, _ = m.modes(x)
    node_m = mu * length / n
    k = np.arange(1, n)
    # the model's tension: the smooth no-compression law adds delta_T^2 / (4 T) = 2.5e-7 N
    t_model = float(np.asarray(m.tensions(x, 0.0)[0]).ravel()[0])
    assert t_model == pytest.approx(tension, rel=1e-8)
    trans = 2.0 * np.sqrt(t_model / (node_m * ls)) * np.sin(k * np.pi / (2 * n))
    # and its slope EA (1 + u / sqrt(u^2 + delta_T^2)) / 2, u = EA eps: 1 - 2.5e-9 here
    dd = m.params.slack_smoothing
    slope = ea * 0.5 * (1.0 + tension / math.sqrt(tension**2 + dd**2))
    axial = 2.0 * np.sqrt(slope / (node_m * length / n)) * np.sin(k * np.pi / (2 * n))
    z_share = np.array([np.sum(s[:, 2] ** 2) / np.sum(s**2) for s in shapes])
    got_t = om[z_share < 1e-6]
    got_a = om[z_share > 1.0 - 1e-6]
    np.testing.assert_allclose(got_t, np.repeat(trans, 2), rtol=1e-9)
    np.testing.assert_allclose(got_a, axial, rtol=1e-9)
    # the cut-off: exact 2 sqrt(T/(m l)) (k l -> pi) against Huang's sqrt(3 T / (l m))
    c = math.sqrt(tension * ls / node_m)  # wave speed sqrt(T / mu_s) in node units
    kk = np.linspace(1e-3, math.sqrt(6.0), 400) / ls
    huang = c * kk * np.sqrt(1.0 - ls**2 * kk**2 / 12.0)
    exact = 2.0 * math.sqrt(tension / (node_m * ls)) * np.abs(np.sin(kk * ls / 2.0))
    assert huang.max() / (2.0 * math.sqrt(tension / (node_m * ls))) == pytest.approx(
        math.sqrt(3.0) / 2.0, rel=1e-6)
    # second-order agreement: sqrt(1 - x^2/12) against sin(x/2) / (x/2) differ by
    # x^4 (1/1152 + 1/1920) = x^4 / 720 at small x = k l
    small = (kk * ls > 0.05) & (kk * ls < 0.3)
    gap = np.abs(huang[small] / exact[small] - 1.0) / (kk[small] * ls) ** 4 * 720.0
    np.testing.assert_allclose(gap, 1.0, atol=0.02)


# --------------------------------------------------------------------------------------
# hanging cable with a tip mass, in water: transverse (pendulum) modes
# --------------------------------------------------------------------------------------
def _hanging(n: int) -> tuple[LumpedMassModel, np.ndarray]:
    """300 m cable with a unit in water (Huang's 5.7 particulars, EA raised to 1e11 N so
    that the stretch, < 4e-7, stays far below the discretisation error), vertical, no
    current."""
    rho, d, mu, g = 1025.0, 0.047, 5.4, 9.81
    area = math.pi * d * d / 4.0
    unit = UnitParams(mass=3000.0, added_mass=3000.0, weight_in_water=25870.4)
    p = uniform_params(300.0, n, axial_stiffness=1.0e11, diameter=d, mass_per_length=mu,
                       weight_in_water=(mu - rho * area) * g, top_position=[0, 0, 1000.0],
                       added_mass_coefficient=1.0, unit=unit, water_density=rho)
    m = LumpedMassModel(p)
    xg = np.zeros((n, 3))
    xg[:, 2] = 700.0 + p.node_arc_length[:-1]
    x, info = m.static_equilibrium(xg.reshape(-1))
    assert info["converged"]
    return m, x


def _transverse(m: LumpedMassModel, x: np.ndarray, count: int) -> np.ndarray:
    """The x-direction modes: on a vertical line the x degrees of freedom decouple from y
    and z in K and M exactly, so the x-x blocks are solved alone (the axial stiffness
    EA / l = 3e10 N/m would otherwise set the condition number of the full problem)."""
    from scipy.linalg import eigh

    k, mm = m.linearize(x)
    assert np.abs(k[0::3, 2::3]).max() <= 1e-9 * np.abs(k[0::3, 0::3]).max()
    assert np.abs(mm[0::3, 1::3]).max() == 0.0
    lam = eigh(k[0::3, 0::3], mm[0::3, 0::3], eigvals_only=True, subset_by_index=[0, count - 1])
    return np.sqrt(lam)


def test_hanging_cable_with_tip_mass_against_bessel() -> None:
    """Transverse modes of the lumped model in water (normal added mass rho pi d^2 / 4 per
    metre, the unit's 3000 kg) against the Bessel closed form with mu_t = mu + m_a,
    M_t = M + M_a, weights in water. The lumped chain converges as O(1/N^2): the error
    must fall by 3.5..4.5 per doubling of N, and at N = 80 be below 1e-3 relative on
    the first four modes (the closed form is exact: an inextensible continuum)."""
    rho, d, mu, g = 1025.0, 0.047, 5.4, 9.81
    area = math.pi * d * d / 4.0
    w = (mu - rho * area) * g
    exact = hanging_cable_frequencies(300.0, w, mu + rho * area, 25870.4, 6000.0, 4)
    errs = []
    for n in (20, 40, 80):
        m, x = _hanging(n)
        got = _transverse(m, x, 4)
        errs.append(np.abs(got / exact - 1.0))
    errs = np.array(errs)
    assert np.all(errs[-1] < 1e-3)
    ratio = errs[:-1] / errs[1:]
    assert np.all((ratio > 3.5) & (ratio < 4.5)), ratio


def test_modes_api_shapes_and_vertical_axial_modes_equal_axial_model(problems) -> None:
    """Through :func:`cable_ocp.dynamics.modes`: frequencies ascending, one shape row per
    node from end_a to end_b with the fixed top row zero and max |component| = 1. The
    vertical line's axial (z) modes equal the axial model's modes of the same scene: the
    vertical lumped-mass chain is the same discrete system (tolerance 1e-8 relative:
    the 3D tangent stiffness carries the smooth slack switch, 1 - 1e-12 here)."""
    f = problems / "dynamics" / "vertical_in_air.toml"
    res = modes(f, 60, overrides={"simulation.model": "lumped3d"})
    assert res.status == "solved"
    assert np.all(np.diff(res.frequencies) >= 0)
    assert res.shapes.shape == (60, 21, 3)
    np.testing.assert_array_equal(res.shapes[:, -1, :], 0.0)
    np.testing.assert_allclose(np.max(np.abs(res.shapes), axis=(1, 2)), 1.0)
    z_share = np.array([np.sum(s[:, 2] ** 2) / np.sum(s**2) for s in res.shapes])
    axial_3d = res.frequencies[z_share > 1.0 - 1e-9]
    ax = modes(f, axial_3d.size)
    np.testing.assert_allclose(axial_3d, ax.frequencies, rtol=1e-8)


# --------------------------------------------------------------------------------------
# the deployment chart of a segmented line (issue 21, item 9)
# --------------------------------------------------------------------------------------
#: two segments in air, end_a's below (EA 1e6 N, 1 kg/m) and the top one (2e6 N, 2 kg/m),
#: 30 m each, a 100 kg unit; 6 lumped segments, shared by length
_TWO_SEGMENTS = """
[environment]
water_depth = 500.0
water_density = 1.225

[[cable.segments]]
length = 30.0
diameter = 0.01
weight_in_water = 9.81
axial_stiffness = 1.0e6
mass_per_length = 1.0
added_mass_coefficient = 0.0

[[cable.segments]]
length = 30.0
diameter = 0.02
weight_in_water = 19.62
axial_stiffness = 2.0e6
mass_per_length = 2.0
added_mass_coefficient = 0.0

[unit]
mass = 100.0
weight_in_water = 981.0

[end_b]
position = [0.0, 0.0, 200.0]

[simulation]
model = "lumped3d"
duration = 1.0
time_step = 0.01
segments = 6
"""


def _vertical_chain_frequencies(parts: list[tuple[int, float, float, float, float]],
                                unit_mass: float, unit_weight: float) -> np.ndarray:
    """Every natural frequency (rad/s, ascending) of a vertical lumped chain hanging from a
    fixed top, written out here: ``parts`` from end_a up, each (lumped segments, length m,
    EA N, mu kg/m, w N/m). Node masses: half of each adjacent segment's plus the unit's
    at node 0 (in air: no added mass); static tensions T_j = W_unit + the weights of the
    nodes 0..j (half segments); stretched lengths s_j = l_j (1 + T_j / EA_j). Transverse
    springs T_j / s_j (the x and y chains, alike), axial springs EA_j / l_j."""
    from scipy.linalg import eigh

    ell = np.concatenate([np.full(n, length / n) for n, length, *_ in parts])
    ea, mu, w = (np.concatenate([np.full(part[0], part[i]) for part in parts])
                 for i in (2, 3, 4))
    n = ell.size
    mass = np.zeros(n + 1)
    mass[:-1] += 0.5 * mu * ell
    mass[1:] += 0.5 * mu * ell
    mass[0] += unit_mass
    wn = np.zeros(n + 1)
    wn[:-1] += 0.5 * w * ell
    wn[1:] += 0.5 * w * ell
    wn[0] += unit_weight
    tens = np.cumsum(wn)[:-1]
    stretched = ell * (1.0 + tens / ea)

    def chain(k: np.ndarray) -> np.ndarray:  # springs j between nodes j, j + 1; top fixed
        kmat = np.diag(k + np.append(0.0, k[:-1])) - np.diag(k[:-1], 1) - np.diag(k[:-1], -1)
        return eigh(kmat, np.diag(mass[:-1]), eigvals_only=True)

    lam_x = chain(tens / stretched)
    return np.sqrt(np.sort(np.concatenate([lam_x, lam_x, chain(ea / ell)])))


def test_the_deployment_chart_of_a_segmented_line_pays_out_the_top_segment(
        tmp_path, capsys) -> None:
    """``modes(scene, count, lengths)`` on a line of two [[cable.segments]] changes the top
    segment (end_b's, where pay-out happens) and leaves end_a's: at 60 m (the scene's own
    length) the chart's row is the plain modes of the scene (the same computation) and the
    chain of 3 + 3 lumped segments; at 90 m it is the chain of 30 m of the lower cable in 2
    lumped segments and 60 m of the upper one in 4 (the shares by length), written out
    here (:func:`_vertical_chain_frequencies`), all 18 frequencies to 1e-9 relative (the
    static Newton's tolerance, 1e-9 of the force scale, bounds the tensions; the smooth
    no-compression law changes them by delta_T^2 / (4 T), 1e-11 of T; seen 2e-11). Paying
    out the lower segment instead (60 m below, 30 m on top) moves them by up to 15 %. The
    CLI's ``--lengths 60:90:2`` gives the same lengths (exactly) and frequencies; a length
    not longer than the segments below the top one (30 m) is refused."""
    from cable_ocp.cli import main
    from cable_ocp.errors import CableOCPError
    from cable_ocp.scene.dynamics import load_dynamic_scene

    f = tmp_path / "two.toml"
    f.write_text(_TWO_SEGMENTS)
    scene = load_dynamic_scene(f)
    chart = modes(scene, 18, lengths=[60.0, 90.0])
    assert chart.status == "solved", chart.message
    np.testing.assert_array_equal(chart.lengths, [60.0, 90.0])
    assert chart.frequencies.shape == (2, 18)
    np.testing.assert_allclose(chart.frequencies[0], modes(scene, 18).frequencies,
                               rtol=1e-12)
    lower, upper = (1.0e6, 1.0, 9.81), (2.0e6, 2.0, 19.62)
    at60 = _vertical_chain_frequencies([(3, 30.0, *lower), (3, 30.0, *upper)], 100.0, 981.0)
    at90 = _vertical_chain_frequencies([(2, 30.0, *lower), (4, 60.0, *upper)], 100.0, 981.0)
    np.testing.assert_allclose(chart.frequencies[0], at60, rtol=1e-9)
    np.testing.assert_allclose(chart.frequencies[1], at90, rtol=1e-9)
    wrong = _vertical_chain_frequencies([(4, 60.0, *lower), (2, 30.0, *upper)], 100.0, 981.0)
    assert np.max(np.abs(wrong / at90 - 1.0)) > 0.1
    assert main(["modes", str(f), "--count", "18", "--lengths", "60:90:2", "--json", "-",
                 "--quiet"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["lengths"] == [60.0, 90.0]
    np.testing.assert_allclose(d["frequencies_rad_s"], chart.frequencies, rtol=1e-12)
    with pytest.raises(CableOCPError, match="not longer than the segments below"):
        modes(scene, 18, lengths=[30.0])
