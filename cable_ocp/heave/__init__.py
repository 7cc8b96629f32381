"""Heave compensation of a tethered subsea unit (Huang 1992, chapter 6).

Seed: ``/work/shared/seeds/004_7da4a1ee8042db40.txt`` (cited below as *004*), eqs. (6.1)-(6.35).

Modules
-------
sea         wave spectra (6.20), JONSWAP, Pierson-Moskowitz, shaping filters (6.21)-(6.23), fits
plant       state-space blocks (6.1)/(6.5), (6.2), (6.25), delay models (6.13)-(6.14), (6.28)
identify    Gauss-Newton identification of (6.2) and (6.3) (section 6.2.3)
lqr         LQR designs with the delay handled three ways, delay margins, indices (6.16)-(6.18)
stochastic  Lyapunov (6.31) and spectral (6.33)-(6.35) variances, LQG, winch-gain study (6.3.5)
mpc         condensed linear MPC (CasADi ``conic``) and nonlinear MPC (IPOPT), built once
simulate    closed-loop simulation on one seeded wave realisation, metrics
scene       heave TOML schema -> frozen dataclasses
"""
