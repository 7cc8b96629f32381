"""Nonlinear cable materials in the statics and the scene (issue 24 item 5).

The law T = T(e) of Huang (1992) 3.4 (004 (12.4): EA depending on the tension) given as
``[cable] tension_strain``: the table's interpolants (cable_ocp.physics.elasticity), its
validation, and the statics of a vertical hanging line against the closed form of the
elongation integral, stretched length = int_0^L (1 + e(T(s))) ds with T = W + w s.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import quad

from cable_ocp.errors import CableOCPError
from cable_ocp.physics.elasticity import TensionStrainTable
from cable_ocp.physics.viscoelastic import StandardLinearSolid
from cable_ocp.scene import scene_from_dict
from cable_ocp.statics.solver import solve

EA0, B = 1.0e6, 2.0e-9  # the law e(T) = T / EA0 + B T^2 (N, 1/N^2): 12 % stiffer at 0
W, WPL, L, TOP = 2000.0, 50.0, 200.0, 400.0  # unit load N, weight N/m, length m, top z m


def law(t):
    """The analytic law sampled into the table, e(T) (-)."""
    return t / EA0 + B * t**2


def rows(n=25):
    ts = np.linspace(0.0, 1.2 * (W + WPL * L), n)
    return [[float(t), float(law(t))] for t in ts]


def hanging(table, method="collocation"):
    return dict(environment=dict(water_depth=500.0, water_density=1025.0),
                cable=dict(length=L, diameter=0.02, weight_in_water=WPL, tension_strain=table),
                end_a=dict(position=["free", "free", "free"], force=[0.0, 0.0, -W]),
                end_b=dict(position=[0.0, 0.0, TOP]), solver=dict(method=method))


def test_pchip_both_ways_through_rows_monotone_c1_casadi():
    tab = TensionStrainTable(tuple(r[0] for r in rows(8)), tuple(r[1] for r in rows(8)))
    e = np.array(tab.strain)
    assert np.allclose(tab.tension_of(e), tab.tension, rtol=1e-14, atol=1e-9)  # through rows
    assert np.allclose(tab.strain_of(np.array(tab.tension)), e, rtol=1e-14, atol=1e-18)
    fine = np.linspace(-0.01, 1.5 * e[-1], 4001)  # past both ends
    assert np.all(np.diff(tab.tension_of(fine)) > 0)  # monotone, extensions included
    # C1 at the last row: the extension's slope is the cubic's end slope (1e-9 relative:
    # the difference quotient over 1e-9 of the strain)
    h = 1e-9 * e[-1]
    left = (tab.tension_of(e[-1]) - tab.tension_of(e[-1] - h)) / h
    right = (tab.tension_of(e[-1] + h) - tab.tension_of(e[-1])) / h
    assert right == pytest.approx(left, rel=1e-5)
    x = ca.SX.sym("x")  # the CasADi form is the same function with its exact derivative
    f = ca.Function("f", [x], [tab.tension_of(x), ca.jacobian(tab.tension_of(x), x)])
    for v in (-0.001, 0.3 * e[-1], e[3], 1.2 * e[-1]):
        val, der = f(v)
        assert float(val) == pytest.approx(tab.tension_of(v), rel=1e-12, abs=1e-9)
        assert float(der) == pytest.approx(tab.tangent(v), rel=1e-9)
    # the model's exact inverse of u(e) agrees with the statics' e(T) at the rows
    assert np.allclose(tab.invert(np.array(tab.tension)), e, rtol=1e-10, atol=1e-15)
    # and past the last row, where both continue by the same straight line (1e-12: the
    # bisection's round-off)
    big = np.array([1.1, 2.0]) * tab.tension[-1]
    assert np.allclose(tab.strain_of(big), tab.invert(big), rtol=1e-12)
    assert np.all(np.diff(tab.strain_of(np.linspace(0.0, 2.0 * tab.tension[-1], 4001))) > 0)


def test_table_energy_is_the_integral_of_the_tension():
    tab = TensionStrainTable(tuple(r[0] for r in rows(8)), tuple(r[1] for r in rows(8)))
    for e in (-0.001, 0.0, 0.3 * tab.strain[-1], tab.strain[4], 1.3 * tab.strain[-1]):
        knots = [k for k in tab.strain if 0.0 < k < e]  # the cubic's pieces, integrated each
        ref = quad(lambda x: tab.tension_of(x), 0.0, e, epsabs=1e-13, limit=200,
                   points=knots or None)[0]
        assert tab.energy(e) == pytest.approx(ref, rel=1e-11, abs=1e-13)  # quad's accuracy
    x = ca.SX.sym("x")
    f = ca.Function("f", [x], [ca.jacobian(tab.energy(x), x)])
    assert float(f(0.7 * tab.strain[-1])) == pytest.approx(tab.tension_of(0.7 * tab.strain[-1]),
                                                           rel=1e-12)


def test_linear_table_is_hooke():
    tab = TensionStrainTable((0.0, 1e4, 5e4), (0.0, 0.01, 0.05))
    e = np.linspace(-0.02, 0.1, 50)
    assert np.allclose(tab.tension_of(e), 1e6 * e, rtol=1e-12, atol=1e-8)  # PCHIP is exact
    assert np.allclose(tab.strain_of(1e6 * e), e, rtol=1e-12, atol=1e-16)  # on a line


def test_relaxation_and_creep_closed_forms_solve_the_law():
    """The closed forms of StandardLinearSolid solve its own ODE (independent RK45)."""
    from scipy.integrate import solve_ivp
    sls = StandardLinearSolid(1e5, 2.5e5, 3.0)
    e0 = 0.01  # relaxation: e held at e0, e_v(0) = 0
    sol = solve_ivp(lambda t, y: [sls.internal_rate(e0, y[0])], (0, 10), [0.0],
                    rtol=1e-10, atol=1e-14, dense_output=True)
    t = np.linspace(0, 10, 21)
    assert np.allclose(sls.tension(e0, sol.sol(t)[0]), sls.relaxation(t, e0), rtol=1e-7)
    t0 = 1000.0  # creep: T held at t0 -> e = (t0 + (EA_d - EA_s) e_v) / EA_d
    ed, es = sls.dynamic_stiffness, sls.static_stiffness

    def strain(ev):
        return (t0 + (ed - es) * ev) / ed

    sol = solve_ivp(lambda t, y: [sls.internal_rate(strain(y[0]), y[0])], (0, 20), [0.0],
                    rtol=1e-10, atol=1e-14, dense_output=True)
    t = np.linspace(0, 20, 21)
    assert np.allclose(strain(sol.sol(t)[0]), sls.creep(t, t0), rtol=1e-7)  # RK45 at 1e-10


@pytest.mark.parametrize("method", ["collocation", "multiple_shooting"])
def test_vertical_hanging_line_elongation_integral(method):
    table = rows()
    sol = solve(scene_from_dict(hanging(table, method)))
    assert sol.status == "solved"
    stretched = TOP - float(sol.position[0, 2])
    tab = TensionStrainTable(tuple(r[0] for r in table), tuple(r[1] for r in table))
    # the elongation integral of the interpolated law (adaptive quadrature): to the
    # discretisation error, 1e-5 m on 224 m (the shooting's fixed RK steps cross the table's
    # rows, where the cubic's third derivative jumps: 1.9e-6 m seen; collocation 2e-7 m)
    integral = L + quad(lambda s: tab.strain_of(W + WPL * s), 0.0, L, epsabs=1e-12,
                        limit=200)[0]
    assert stretched == pytest.approx(integral, abs=1e-5)
    # the analytic law: int (a T + b T^2) ds in closed form; the table interpolates it to
    # the PCHIP error, bounded here by its largest strain error on the range times L
    exact = L + (W * L + 0.5 * WPL * L**2) / EA0 + B * ((W + WPL * L)**3 - W**3) / (3 * WPL)
    tt = np.linspace(W, W + WPL * L, 2001)
    bound = L * float(np.max(np.abs(tab.strain_of(tt) - law(tt))))
    assert abs(stretched - exact) <= bound + 1e-5
    # and the nonlinear part matters: the linear law alone is 3.3 m short
    assert stretched - (L + (W * L + 0.5 * WPL * L**2) / EA0) > 3.0
    # the top tension is W + w L whatever the law (statics of a vertical line)
    assert float(np.linalg.norm(sol.tension_vector[-1])) == pytest.approx(W + WPL * L,
                                                                           rel=1e-8)


def test_tension_beyond_the_table_is_a_warning():
    short = [r for r in rows() if r[0] < 0.8 * (W + WPL * L)]  # 12 kN top, table to 9.6 kN
    sol = solve(scene_from_dict(hanging(short)))
    assert sol.status == "solved"
    assert any("above the last row of cable.tension_strain" in w
               for w in sol.diagnostics.get("warnings", []))
    full = solve(scene_from_dict(hanging(rows())))
    assert not any("tension_strain" in w for w in full.diagnostics.get("warnings", []))


def test_linear_table_statics_equals_axial_stiffness():
    lin = hanging([[0.0, 0.0], [1e4, 0.01], [5e4, 0.05]])
    a = solve(scene_from_dict(lin))
    d = hanging(None)
    d["cable"].pop("tension_strain")
    d["cable"]["axial_stiffness"] = 1e6
    b = solve(scene_from_dict(d))
    assert np.allclose(a.position, b.position, atol=1e-8)  # same equations, solver round-off


@pytest.mark.parametrize("value, words", [
    ([[0, 0]], "at least two rows"),
    ([[1, 0], [2, 0.1]], "first row must be [0, 0]"),
    ([[0, 0], [10, 0.01], [5, 0.02]], "not monotonic"),
    ([[0, 0], [10, 0.01], [20, 0.01]], "not monotonic"),
    ([[0, 0], [10, 2.0]], "tension_strain[1][1]"),
    ([[0, 0], [10]], "row 1"),
    ("steel", "pairs"),
])
def test_table_validation_names_the_key(value, words):
    with pytest.raises(CableOCPError) as err:
        scene_from_dict(hanging(value))
    assert words in str(err.value) and "cable.tension_strain" in str(err.value)


def test_table_refusals():
    d = hanging(rows())
    d["cable"]["axial_stiffness"] = 1e6
    with pytest.raises(CableOCPError, match="either axial_stiffness"):
        scene_from_dict(d)
    d = hanging(rows(), method="catenary")
    with pytest.raises(CableOCPError, match="collocation"):
        scene_from_dict(d)
    d = hanging(rows())
    d["environment"]["seabed"] = {"friction": 0.0}
    with pytest.raises(CableOCPError, match="seabed"):
        scene_from_dict(d)


def test_viscoelastic_statics_is_the_static_modulus():
    d = hanging(None)
    d["cable"].pop("tension_strain")
    d["cable"]["axial_stiffness"] = 1e6
    a = solve(scene_from_dict(d))
    d["cable"]["viscoelastic"] = {"dynamic_stiffness": 3e6, "relaxation_time": 5.0}
    b = solve(scene_from_dict(d))
    assert np.allclose(a.position, b.position, atol=1e-10)  # the same equations
    for bad, words in (({"dynamic_stiffness": 5e5, "relaxation_time": 5.0},
                        "dynamic_stiffness"),
                       ({"dynamic_stiffness": 3e6}, "relaxation_time"),
                       ({"dynamic_stiffness": 3e6, "relaxation_time": 5.0, "eta": 1},
                        "eta")):
        d["cable"]["viscoelastic"] = bad
        with pytest.raises(CableOCPError, match=words):
            scene_from_dict(d)
