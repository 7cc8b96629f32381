"""Heave compensation of a tethered subsea unit (Huang 1992, chapter 6).

Huang, S. (1992), *Analysis and control of marine cable systems*, PhD thesis, University of
Strathclyde, chapter 6, eqs. (6.1)-(6.35).

In a few lines::

    import cable_ocp.heave as hv
    sc = hv.load_scene("problems/heave/ex_6_3_6.toml")
    res = hv.compare(sc, ("passive", "lqr", "mpc"))      # closed loop on one seeded sea
    res                                                    # a short summary; res.plot()
    print(res.metrics["mpc"].heave_rms)

    models = hv.build_models(sc)                           # spectrum, filter, plant (6.28)
    mpc = hv.LinearMPC(models.plant, sc.winch.delay, hv.settings_from_scene(sc))
    step = mpc.step(x)                 # x: the plant's state; the MPC keeps the delay buffer

Modules
-------
sea         wave spectra (6.20), JONSWAP, Pierson-Moskowitz, shaping filters (6.21)-(6.23), fits
plant       state-space blocks (6.1)/(6.5), (6.2), (6.25), delay models (6.13)-(6.14), (6.28)
discrete    exact sampled-data models: ZOH with an input delay, cost and noise discretisation
identify    Gauss-Newton identification of (6.2) and (6.3) (section 6.2.3)
lqr         LQR designs with the delay handled three ways, delay margins, indices (6.16)-(6.18)
printed     the thesis' printed gains G3, G5 (6.2.4-6.2.6) as controllers of a heave scene
regulator   the thesis' printed gains G3, G5 (6.2.4-6.2.6) in the closed loop, Figs. 6.14-6.17
inverse     the inverse problem of 6.4 (2): cable and unit parameters from an identified a, b
stochastic  Lyapunov (6.31) and spectral (6.33)-(6.35) variances, LQG, winch-gain study (6.3.5)
mpc         condensed linear MPC (CasADi ``conic``) and nonlinear MPC (IPOPT), built once
mpc_daqp    the DAQP backend of the linear MPC
mpc_drive   the winch motor's torque and power limits of the linear MPC
drive       the winch drive along a run: line tension, motor torque and power
design_loop closed-loop comparison on one seeded wave realisation (the design model)
identify_cable  the identification experiment (6.2.3) on a cable scene's line
axial_plant     the axial line as the plant, stepped one control sample per call
cable_models    the planar and 3D lumped-mass lines as the plant; cable_plant(): the plant by
                the scene's model
design      design scene, design table (gains, Kalman gains, sampled model over lengths)
estimators  the observation, the full-state estimator and the one Kalman filter
controllers the controller interface: passive, state feedback (LQR, LQG, scheduled), MPC
delay       the delay line of the winch command (plant side and prediction side)
loop_plants the plants of the closed loop: the design model with its winch, a line under the
            winch (the cable or the design model)
closed_loop the closed loop: any plant with any controller
metrics     the results and metrics of a comparison
deployment  lowering the unit through resonance, with gain scheduling
lumped_deploy   the 3D lumped-mass line with pay-out as a deployment's plant
cable_compare   :func:`compare` for every scene: on the design model, or on the cable
(the scene schema lives in :mod:`cable_ocp.scene.heave`)
"""

from cable_ocp.heave.cable_compare import compare
from cable_ocp.heave.design_loop import build_models
from cable_ocp.heave.lqr import LQRDesign, design_lqr, regulator_plant
from cable_ocp.heave.metrics import Comparison, Metrics
from cable_ocp.heave.mpc import LinearMPC, MPCSettings, MPCStep, settings_from_scene
from cable_ocp.heave.plant import HeavePlant, assemble_plant
from cable_ocp.scene.heave import HeaveScene, load_scene, scene_from_dict

#: the closed loop of each controller, under the verb of :func:`cable_ocp.dynamics.simulate`:
#: ``simulate(scene, controllers)`` is :func:`compare` itself (one function, two names)
simulate = compare

__all__ = [
    "Comparison",
    "HeavePlant",
    "HeaveScene",
    "LQRDesign",
    "LinearMPC",
    "MPCSettings",
    "MPCStep",
    "Metrics",
    "assemble_plant",
    "build_models",
    "compare",
    "design_lqr",
    "load_scene",
    "regulator_plant",
    "scene_from_dict",
    "settings_from_scene",
    "simulate",
]
