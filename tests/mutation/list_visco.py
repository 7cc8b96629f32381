"""Mutations of the viscoelastic law in the planar and lumped models (issue 24 item 5):
the midpoint step's closed-form dashpot update, the lumped kernel's strain shift and the
relaxed static start."""

_DY = "tests/dynamics/test_materials_dynamics.py"

MUTATIONS = [
    dict(name="visco-step-relaxes-twice-as-fast", area="physics",
         file="cable_ocp/physics/viscoelastic.py",
         old="a = 0.5 * time_step / self.relaxation_time\n",
         new="a = time_step / self.relaxation_time\n",
         tests=(_DY,),
         description="planar and lumped steps: e_v's midpoint update with dt / tau for "
                     "dt / (2 tau) (the dashpot relaxes twice as fast as tau says)"),
    dict(name="visco-lumped-kernel-shift-dropped", area="dynamics",
         file="cable_ocp/dynamics/lumped_kernel.py",
         old="sls.step_offset(ev0, dt) / k_step)",
         new="0.0 * sls.step_offset(ev0, dt) / k_step)",
         tests=(_DY,),
         description="lumped step: the tension k e without the dashpot strain's offset "
                     "F_0 (a stiff elastic rope that never creeps)"),
    dict(name="visco-planar-start-unrelaxed", area="dynamics",
         file="cable_ocp/dynamics/planar.py",
         old="return np.concatenate([x, np.maximum(eps, 0.0)])",
         new="return np.concatenate([x, 0.0 * eps])",
         tests=(_DY,),
         description="planar: the static start with e_v = 0 instead of the relaxed e_v = e "
                     "(the line is not at rest: the arm pulls EA_d e)"),
]
