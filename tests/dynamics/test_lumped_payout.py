"""Pay-out and haul-in of the 3D lumped-mass line (cable_ocp/dynamics/lumped_payout.py):
nodes enter at the winch above 1.5 element lengths and leave below 0.4 (004 7.3 (2); Huang
(1992) ch. 3-4 vary the length in 1D and 2D).

The bookkeeping across an event against its closed forms (mass, momentum, the split's
kinetic-energy drop, the strain energy), the energy balance of a run with pay-out and
haul-in, and the axial and planar models as independent methods on a vertical and a
planar pay-out.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from cable_ocp.dynamics import load_dynamic_scene, simulate
from cable_ocp.dynamics.lumped_payout import PayoutState
from cable_ocp.dynamics.lumped_payout_run import payout_line
from cable_ocp.dynamics.lumped_scene import LumpedSceneModel
from cable_ocp.errors import CableOCPError

PROBLEMS = Path(__file__).resolve().parents[2] / "problems" / "dynamics"

#: Huang's 3.3.5 line (axial, heave and pay-out) shortened: 50 m, 10 elements of 5 m,
#: 1 m/s after a 5 s ramp for 15 s (2 nodes enter), heave 0.5 m at 1.26 rad/s
VERTICAL = {"simulation.duration": 15.0, "simulation.time_step": 0.05,
            "simulation.output_step": 0.25, "simulation.segments": 10,
            "top_motion.payout_speed": 1.0, "top_motion.ramp_time": 5.0}
#: Huang's 4.5.4 (planar: sway of the unit while lowered, 5 m horizontal top motion)
#: shortened: 100 m, 1 m/s for 20 s
PLANAR = {"simulation.duration": 20.0, "simulation.time_step": 0.05,
          "simulation.output_step": 0.5, "top_motion.payout_speed": 1.0,
          "cable.length": 100.0}


def _model(path: Path, overrides: dict) -> LumpedSceneModel:
    scene = load_dynamic_scene(path, {**overrides, "simulation.model": "lumped3d"})
    return LumpedSceneModel(scene)


@pytest.fixture(scope="module")
def moving() -> tuple[LumpedSceneModel, PayoutState]:
    """Huang's 5.7 line hanging at rest with random node velocities (m/s) and a top
    segment of 1.7 element lengths: a state to split."""
    m = _model(PROBLEMS / "huang_5_7.toml", {"simulation.segments": 6,
                                            "top_motion.payout_speed": 1.0})
    line = payout_line(m)
    x0, _ = m.static_positions()
    rng = np.random.default_rng(7)
    st = line.state(0.0, line.lengths_at(m.params.segment_length, 0.0), np.asarray(x0),
                    rng.normal(0.0, 0.3, x0.size))
    # a top segment of 1.7 l_e at the same strain: the free nodes 0.7 chords lower
    chord = np.linalg.norm(st.r[-1] - st.r[-2])
    st.r[:-1, 2] -= 0.7 * chord
    st.lengths[-1] *= 1.7
    return m, st


def test_split_bookkeeping(moving) -> None:
    """A split keeps the mass (to round-off) and the momentum (the winch's share at the
    material's velocity, exactly), its strain energy grows by the closed form of the
    balanced strain step, and the kinetic energy drops by mu l f (1 - f) |v_below -
    v_winch|^2 / 4, f = l_e / l_top."""
    m, st = moving
    line = payout_line(m)
    new = line.split(st)
    assert new.segments == st.segments + 1
    mass0, mass1 = (np.sum(line.node_masses(s.lengths)[:, 0]) for s in (st, new))
    assert abs(mass1 - mass0) <= 1e-14 * mass0  # round-off of a sum of ~10 terms
    p0, p1 = line.momentum(st), line.momentum(new)
    assert np.max(np.abs(p1 - p0)) <= 1e-12 * np.max(np.abs(p0))  # rounding only
    # the strain energy (E at zero velocities) grows by w_t^2 l_e (l_top - l_e) l_top / (8 EA)
    rest0 = PayoutState(st.t, st.lengths, st.r, np.zeros_like(st.v))
    rest1 = PayoutState(new.t, new.lengths, new.r, np.zeros_like(new.v))
    e0, e1 = line.energy_of(rest0), line.energy_of(rest1)
    ltop, le = st.lengths[-1], line.element_length
    w, ea = float(m.params.weight_in_water[-1]), float(m.params.axial_stiffness[-1])
    grow = w**2 * le * (ltop - le) * ltop / (8.0 * ea)  # a vertical line: w_t = w
    # to 1e-6: the smooth no-compression law's departure from Hooke at 27 kN is 1e-13, the
    # cancellation of E ~ 1e4 J to a jump of ~1 J costs ~1e-12
    assert e1 - e0 == pytest.approx(grow, rel=1e-6)
    # the nodes keep their balance: the new node's and the one below's net static force
    # along the line is unchanged (the tension steps by its weight w l_top / 2)
    t0, t1 = line._tensions(rest0), line._tensions(rest1)
    assert t1[-1] - t1[-2] == pytest.approx(0.5 * w * ltop, rel=1e-6)
    # the node below loses the weight w (l_top - l_e) / 2 and the pull above it as much
    assert (t1[-2] - t1[-3]) - (t0[-1] - t0[-2]) == pytest.approx(-0.5 * w * (ltop - le),
                                                                  rel=1e-6)
    # the line's kinetic energy (the winch's share included) drops by the closed form
    mu = float(m.params.mass_per_length[-1])

    def kinetic(s: PayoutState) -> float:
        return 0.5 * float(np.sum(line.node_masses(s.lengths) * s.v**2))

    f = le / ltop
    drop = 0.25 * mu * ltop * f * (1 - f) * float(np.sum((st.v[-2] - st.v[-1]) ** 2))
    assert kinetic(st) - kinetic(new) == pytest.approx(drop, rel=1e-9)
    assert drop > 0


def test_merge_bookkeeping(moving) -> None:
    """A merge keeps the mass (to round-off); the momentum changes only by the leaving
    node's share given to the winch, mu l_below / 2 (v_winch - v_node)."""
    m, st = moving
    line = payout_line(m)
    two = line.split(line.split(st))
    two.lengths[-1] = 0.3 * line.element_length
    new = line.merge(two)
    assert new.segments == two.segments - 1
    mass0, mass1 = (np.sum(line.node_masses(s.lengths)[:, 0]) for s in (two, new))
    assert abs(mass1 - mass0) <= 1e-14 * mass0
    mu = float(m.params.mass_per_length[-1])
    handed = 0.5 * mu * two.lengths[-2] * (two.v[-1] - two.v[-2])
    jump = line.momentum(new) - line.momentum(two)
    assert np.allclose(jump, handed, rtol=1e-9, atol=1e-12 * np.max(np.abs(line.momentum(
        two))))
    with pytest.raises(AssertionError):  # the closed form is not trivially zero
        assert np.allclose(handed, 0.0, atol=1e-6)


def _energy_run(dt: float, path: Path = PROBLEMS / "huang_5_7.toml"):
    """The 5.7 line, 20 m in 8 segments of 2.5 m, with its 3D top motion and a periodic
    pay-out of 3 m (nodes enter and leave), no line added mass and no material damping
    (the energy identity's setting: a mass matrix independent of the direction)."""
    over = {"simulation.segments": 8, "cable.added_mass_coefficient": 0.0,
            "cable.length": 20.0, "top_motion.payout_law": "periodic",
            "top_motion.payout_amplitude": 3.0, "top_motion.payout_frequency": 0.5,
            "top_motion.ramp_time": 4.0}
    m = _model(path, over)
    line = payout_line(m)
    x0, _ = m.static_positions()
    return line.run(np.asarray(x0), 12.0, dt, record_every=int(round(0.5 / dt)),
                    energy=True)


#: a stiffening tension-strain table (N, -) in place of the 5.7 line's EA (1.56e7 N)
TABLE = "tension_strain = [[0.0, 0.0], [20000.0, 0.004], [60000.0, 0.007], [2e5, 0.012]]"


@pytest.mark.parametrize("material", ["hooke", "table"])
def test_energy_balance_with_payout_and_haul_in(material: str, tmp_path: Path) -> None:
    """E(t) - E(0) = the work of the winch (the top segment's tension on the material at the
    winch: the sheave's motion and the pay-out), of gravity, of the drag (a dissipation in
    still water), the energy of the cable paid in and out (its strain and kinetic energy)
    and the events' jumps, through 2 splits and 2 merges: the step keeps the identity
    exactly, so the balance closes to the Newton tolerance (1e-10 of the force scale;
    measured 2e-11 of the work; 7e-12 with a tension-strain table, whose energy the
    table integrates and whose tangent sets the split's strain step)."""
    path = PROBLEMS / "huang_5_7.toml"
    if material == "table":
        text = path.read_text()
        line = next(x for x in text.splitlines() if x.startswith("axial_stiffness"))
        path = tmp_path / "table.toml"
        path.write_text(text.replace(line, TABLE))
    run = _energy_run(0.04, path)
    assert run.status == "solved", run.message
    assert run.splits >= 2 and run.merges >= 2
    e = run.energy
    work = e["gravity"] + e["drag"] + e["winch"] + e["inflow"] + e["events"]
    scale = max(np.max(np.abs(e["winch"])), np.max(np.abs(e["gravity"])))
    assert np.max(np.abs(e["E"] - e["E"][0] - work)) < 1e-8 * scale
    # every term matters at this level: the events' jumps and the inflow are far above it
    assert abs(e["events"][-1]) > 1e-6 * scale and np.max(np.abs(e["inflow"])) > 1e-4 * scale
    assert e["drag"][-1] < 0.0 and np.all(np.diff(e["drag"]) <= 0.0)  # still water
    assert min(np.min(t) for t in run.tensions) > 0.0  # taut: the identity's setting


def test_mass_is_mu_L_through_a_run() -> None:
    """Through a run with splits, the line's mass is mu L(t) + the unit's mass to
    round-off, and every split's momentum jump is at rounding level."""
    m = _model(PROBLEMS / "huang_3_3_5.toml", VERTICAL)
    line = payout_line(m)
    x0, _ = m.static_positions()
    run = line.run(np.asarray(x0), 10.0, 0.05, record_every=10)
    assert run.status == "solved" and run.splits >= 1
    unit = m.params.unit.mass
    mu = float(m.params.mass_per_length[0])
    for st in run.states:
        big_l = line.length(st.t)[0]
        total = float(np.sum(line.node_masses(st.lengths)[:, 2])) - m.params.unit.added_mass[2]
        assert abs(total - (mu * big_l + unit)) <= 1e-13 * (mu * big_l + unit)
    for ev in run.events:
        assert np.max(np.abs(ev["momentum_jump"])) < 1e-9  # N s: rounding of ~1e4 N s


def test_vertical_payout_equals_axial() -> None:
    """A vertical pay-out with heave in 3D is the axial model: the same discrete chain at
    the nodes (docs/dynamics.md), the axial model's moving grid and the 3D model's material
    nodes differing by the discretisation of the pay-out. The unit's height agrees to
    3e-5 m (of a 0.5 m heave): measured 1.5e-5 m, the difference of the two schemes' own
    time-discretisation errors (second order: 8e-7 m at dt = 0.01 s; the axial model moves
    by 1e-6 m from 10 to 40 elements), and the top tension to 0.1 % (measured 11 N of
    55 kN: the unresolved axial waves of the two meshes, dt = 0.05 s against an axial
    period of 2 L / c = 0.06 s)."""
    f = PROBLEMS / "huang_3_3_5.toml"
    ax = simulate(f, overrides=VERTICAL)
    r3 = simulate(f, overrides={**VERTICAL, "simulation.model": "lumped3d"})
    assert ax.status == r3.status == "solved"
    assert r3.diagnostics["payout"]["splits"] == 2
    assert np.allclose(r3.length, ax.length, rtol=0, atol=1e-12)
    assert np.max(np.abs(r3.unit_position[:, 2] - ax.unit_position[:, 2])) < 3e-5
    assert np.max(np.abs(r3.unit_position[:, :2])) < 1e-9  # stays on the axis
    assert np.max(np.abs(r3.top_tension - ax.top_tension)) < 1e-3 * np.max(ax.top_tension)


def test_planar_payout_equals_planar() -> None:
    """A planar pay-out in 3D is the planar model to the discretisation error: the unit's
    sway differs from the planar model's by less than the planar model's own change from
    20 to 40 elements (measured 1.6 mm against 3.7 mm of a 0.77 m sway; 0.15 mm against
    0.53 mm in height), and stays in the plane."""
    f = PROBLEMS / "huang_4_5_4.toml"
    pl20 = simulate(f, overrides={**PLANAR, "simulation.segments": 20})
    pl40 = simulate(f, overrides={**PLANAR, "simulation.segments": 40})
    r3 = simulate(f, overrides={**PLANAR, "simulation.segments": 20,
                                "simulation.model": "lumped3d"})
    assert r3.status == pl20.status == "solved"
    own = np.max(np.abs(pl20.unit_position - pl40.unit_position), axis=0)
    diff = np.max(np.abs(r3.unit_position - pl20.unit_position), axis=0)
    assert diff[0] < own[0] and diff[2] < own[2]
    assert np.max(np.abs(r3.unit_position[:, 1])) < 1e-9


def test_deployment_in_a_turning_current() -> None:
    """The shipped 3D deployment: the unit, lowered from the surface current (towards +x)
    into the turned one (towards +y), drifts towards +y and its depth follows the
    pay-out."""
    f = PROBLEMS / "deployment_lumped3d_turning_current.toml"
    r = simulate(f, overrides={"simulation.duration": 40.0})
    assert r.status == "solved", r.message
    pay = r.diagnostics["payout"]
    assert pay["splits"] == 3 and pay["segments_end"] == 8  # 50 m -> 85 m, 10 m each
    assert r.length[-1] == pytest.approx(85.0, abs=1e-9)
    y = r.unit_position[:, 1]
    assert y[-1] > y[0] + 0.1 and r.unit_position[0, 0] > 0.0
    # the unit goes down with the pay-out, to the line's elongation (< 0.5 m)
    drop = r.unit_position[0, 2] - r.unit_position[-1, 2]
    assert drop == pytest.approx(35.0, abs=0.5)


def test_payout_scene_errors() -> None:
    """The keys are checked and named: element_length only for lumped3d, a pay-out only
    with the midpoint rule, a top segment within the thresholds."""
    f = PROBLEMS / "huang_3_3_5.toml"
    with pytest.raises(CableOCPError, match="simulation.element_length"):
        load_dynamic_scene(f, {"simulation.element_length": 5.0})
    with pytest.raises(CableOCPError, match="simulation.scheme"):
        simulate(f, overrides={**VERTICAL, "simulation.model": "lumped3d",
                               "simulation.scheme": "bdf2"})
    with pytest.raises(CableOCPError, match="simulation.element_length"):
        simulate(f, overrides={**VERTICAL, "simulation.model": "lumped3d",
                               "simulation.element_length": 20.0})
