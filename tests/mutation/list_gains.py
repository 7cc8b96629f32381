"""Mutations of the thesis' printed gains in closed loop (cable_ocp/heave/regulator.py) and of
the inverse problem of 6.4 (2) (cable_ocp/heave/inverse.py)."""

MUTATIONS = [
    dict(name="gains-taylor-filter-input", area="heave",
         file="cable_ocp/heave/printed.py",
         old="self.w = self.Phi @ self.w + self.Gam * u0",
         new="self.w = self.Phi @ self.w + self.Gam * (-u0)",
         tests=("tests/heave/test_thesis_gains.py",),
         description="printed gains: the Taylor states (6.13) driven by the command's negative"),
    dict(name="gains-decay-extremes", area="heave",
         file="cable_ocp/heave/regulator.py",
         old="return float(np.polyfit(tt[i], np.log(xx[i]), 1)[0])",
         new="return float(np.polyfit(tt[i], np.log(xx[i]), 1)[0]) / 2",
         tests=("tests/heave/test_thesis_gains.py",),
         description="printed gains: the decay rate of the free response halved"),
    dict(name="inverse-beta-frequency", area="heave",
         file="cable_ocp/heave/inverse.py",
         old="beta = _beta(mu * L / M)",
         new="beta = _beta(mu * L / (2 * M))",
         tests=("tests/heave/test_inverse.py",),
         description="inverse: the tip mass doubled in the frequency equation beta tan beta"),
    dict(name="inverse-line-drag-weight", area="heave",
         file="cable_ocp/heave/inverse.py",
         old="cq = body_drag_factor(p.water_density, 1.0, p.unit_drag) + kt * int_phi3",
         new="cq = body_drag_factor(p.water_density, 1.0, p.unit_drag) + kt * int_phi2",
         tests=("tests/heave/test_inverse.py",),
         description="inverse: the line's drag weighted by int phi^2 instead of int phi^3"),
]
