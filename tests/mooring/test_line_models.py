"""The spar's equilibrium with the catenary line model (auto) and with the collocation."""

from __future__ import annotations

import numpy as np

from cable_ocp.mooring import solve_system
from cable_ocp.scene.system import system_from_dict
from tests.mooring.test_equilibrium import spar_dict


def test_spar_catenary_equals_collocation() -> None:
    res = {}
    for model in ("auto", "collocation"):
        data = spar_dict()
        data.setdefault("system", {})["line_model"] = model
        res[model] = solve_system(system_from_dict(data))
        assert res[model].status == "solved"
    a, c = res["auto"], res["collocation"]
    assert set(a.diagnostics["line_models"].values()) == {"catenary"}
    assert set(c.diagnostics["line_models"].values()) == {"collocation"}
    # both solve the same equations: the pose to the equilibrium's tolerance
    assert np.max(np.abs(np.subtract(a.body()["position"], c.body()["position"]))) < 1e-6
    for ln in a.lines:
        other = c.line(ln["name"])
        for key in ("tension_a", "tension_b"):
            assert abs(ln[key] / other[key] - 1.0) < 1e-7  # the collocation's accuracy
    ka, kc = a.stiffness(), c.stiffness()
    assert np.max(np.abs(ka - kc)) <= 1e-6 * np.max(np.abs(kc))
