"""The identification experiment of Huang (1992), section 6.2.3 run on the cable model.

Huang simulates the unit's response to a random boom-tip motion with his ch. 3 cable model
and fits ``a, b`` of (6.2) (and of (6.3)) by Gauss-Newton. Here the cable model is the model
of the heave scene's ``[unit] cable_scene`` (axial, planar or lumped3d), stepped by the heave
plant (:func:`cable_ocp.heave.cable_models.cable_plant`) with a prescribed top motion at a
fixed length, and the fit is :func:`cable_ocp.heave.identify.identify_unit` (the thesis'
iteration with exact sensitivities).

Excitations (``[identification] excitation``):

* ``"multisine"`` (default): a sum of harmonics of ``2 pi / T_p`` (``T_p`` a third of the
  duration) with equal amplitudes over ``band`` and Schroeder phases (low crest factor),
  scaled to ``amplitude`` RMS, faded in over 10 s. Why the default: it puts the same power
  at every frequency of the band where the design model must be right (the wave band, the
  first axial resonance and the loop's bandwidth) and none outside it; it is periodic and
  deterministic (no leakage, the same record every time); and at the sea's RMS the
  amplitude-dependent drag is linearised at the amplitude the compensator will see.
* ``"chirp"``: a linear sweep from ``band[0]`` to ``band[1]``: the same band, but a lightly
  damped resonance answers a sweep with a transient that depends on the sweep rate.
* ``"step"``: a smooth step (quintic over 0.5 s) of 2 ``amplitude`` at 5 s: its power falls
  as ``1 / omega^2``, so the wave band gets little of it; the fit is dominated by the
  free ringing of the first mode.
* ``"sea"``: the heave scene's own boom-tip motion (another seed), as the thesis did
  (Fig. 6.10).

Defaults: ``amplitude`` the boom tip's RMS in the scene's sea (Lyapunov), ``band``
``[omega_m / 2, max(3 omega_m, 1.5 omega_1)]`` (``omega_m`` the sea's modal frequency,
``omega_1`` the line's first axial natural frequency), ``noise`` (white noise on the recorded
depth, m) the depth sensor's ``[controller] measurement_noise``.

``a`` and ``omega_1``: for a line whose first mode dominates and a unit whose static gain is
1, ``a ~ 1 / omega_1^2`` (``omega_1`` from :meth:`AxialModel.modes`). The low-frequency
expansion of a rod with a tip mass gives instead ``a = (M + mu L / 2) / K`` (K = EA / L);
Rayleigh's ``1 / omega_1^2 ~ (M + mu L / 3) / K``: a fit over a band that contains the
resonance lands near the latter.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from cable_ocp.errors import CableOCPError
from cable_ocp.heave.identify import IdentificationResult, identify_unit
from cable_ocp.numerics.ramp import smoothstep
from cable_ocp.scene.dynamics import DynamicScene
from cable_ocp.scene.heave import HeaveScene

__all__ = ["CableIdentification", "excitation_signal", "identified_json",
           "identify_from_cable", "identify_line", "run_experiment"]

#: fade-in of the multisine, chirp and sea excitations, s
FADE_IN = 10.0


@dataclass(frozen=True)
class CableIdentification:
    """The identification experiment and its fits.

    Attributes
    ----------
    linear, quadratic : IdentificationResult
        Fits of (6.2) (``a`` s^2, ``b`` s) and of (6.3) (``a`` s^2, ``b`` s^2/m).
    excitation : str
        The prescribed top motion (module docstring).
    amplitude : float
        RMS of the top motion over the record, m.
    band : tuple of float or None
        Frequency band of a multisine or chirp, rad/s.
    duration, sample_time, noise : float
        Record length (s), sampling (s), depth-noise std (m).
    omega_1 : float
        First axial natural frequency of the same line (undamped), rad/s.
    length : float
        Unstretched length of the line, m.
    t, x0, z : numpy.ndarray
        Samples (s), top motion (m) and recorded unit heave (m, with noise).
    """

    linear: IdentificationResult
    quadratic: IdentificationResult
    excitation: str
    amplitude: float
    band: tuple | None
    duration: float
    sample_time: float
    noise: float
    omega_1: float
    length: float
    t: np.ndarray
    x0: np.ndarray
    z: np.ndarray


def _fade(t: np.ndarray, t_fade: float) -> np.ndarray:
    return smoothstep(np.clip(t / t_fade, 0.0, 1.0))


def excitation_signal(kind: str, t: np.ndarray, amplitude: float, band: tuple[float, float],
                      sea: np.ndarray | None = None) -> np.ndarray:
    """The prescribed top motion (m) on the times ``t`` (s) (module docstring).

    ``amplitude``: the RMS (m) of the multisine, chirp and sea over the record after the
    fade-in; the step's height is twice it. ``sea``: the boom-tip record for ``"sea"``.

    Parameters
    ----------
    kind : str
        ``[identification] excitation``: multisine, chirp, step or sea.
    t : numpy.ndarray
        Times, s.
    amplitude : float
        RMS of the motion, m.
    band : tuple of float
        Frequency band (low, high), rad/s.
    sea : numpy.ndarray, optional
        The boom-tip record at ``t`` for ``"sea"``, m.
    """
    duration = float(t[-1])
    fade = _fade(t, min(FADE_IN, duration / 4))
    if kind == "multisine":
        w0 = 2.0 * math.pi / (duration / 3.0)
        ks = np.arange(max(1, math.ceil(band[0] / w0 - 1e-9)),
                       math.floor(band[1] / w0 + 1e-9) + 1)
        if ks.size == 0:
            raise CableOCPError(f"identification.band = {list(band)}: holds no harmonic of "
                                f"2 pi / (identification.duration / 3) = {w0:.4g} rad/s; "
                                "widen identification.band (rad/s; default from the sea) or "
                                "lengthen identification.duration (s)")
        kk = np.arange(ks.size)
        phases = -math.pi * kk * (kk + 1) / ks.size  # Schroeder
        x = np.sin(np.outer(t, ks * w0) + phases).sum(axis=1)
    elif kind == "chirp":
        lo, hi = band
        x = np.sin(lo * t + 0.5 * (hi - lo) * t**2 / duration)
    elif kind == "step":
        t_on = min(5.0, duration / 4)
        s = np.clip((t - t_on) / 0.5, 0.0, 1.0)
        return 2.0 * amplitude * smoothstep(s)
    elif kind == "sea":
        if sea is None:
            raise CableOCPError("excitation 'sea' needs the boom-tip record")
        x = np.asarray(sea, dtype=float)
    else:
        raise CableOCPError(f"identification.excitation = {kind!r}: valid are multisine, "
                            "chirp, step, sea")
    x = x * fade
    keep = t >= min(FADE_IN, duration / 4)
    return x * (amplitude / float(np.sqrt(np.mean(x[keep] ** 2))))


def run_experiment(scene: DynamicScene, x0: np.ndarray, sample_time: float
                   ) -> dict[str, np.ndarray]:
    """Move the top of the cable scene's line by ``x0`` (m, samples every ``sample_time``
    s, from rest) at its length; return the unit's heave ``z`` (m, relative to the static
    depth, on the sample grid), the tensions at the unit and the top, and the Newton
    residual (:meth:`AxialCablePlant.run_open_loop`).

    Parameters
    ----------
    scene : DynamicScene
        The cable scene.
    x0 : numpy.ndarray
        The top's motion per sample, m.
    sample_time : float
        Sample time, s.
    """
    from cable_ocp.heave.cable_models import cable_plant

    plant = cable_plant(scene, sample_time)
    m = plant.substeps
    n = x0.size
    t = np.arange(n) * sample_time
    tf = np.arange((n - 1) * m + 1) * (sample_time / m)
    tops = plant.z_top0 + np.interp(tf, t, x0)
    lengths = np.full(tf.size, plant.length0)
    out = plant.run_open_loop(lengths, tops)
    z = out["z_unit"][::m] - float(plant.static_unit_height(plant.length0))
    return {"z": z, "t_unit": out["t_unit"][::m], "t_top": out["t_top"][::m],
            "t_min": out["t_min"], "residual": out["residual"], "plant": plant}


def first_frequency(scene: DynamicScene) -> float:
    """First axial natural frequency of the line, rad/s (undamped, about the static state;
    for a planar or lumped3d scene that of the same line hanging vertically, without the
    current: the axial model's, or, for a lumped3d line of several ``[[cable.segments]]``
    or with ``[[bodies]]``, the lumped-mass model's first vertical mode)."""
    from cable_ocp.dynamics.axial import AxialModel
    from cable_ocp.heave.cable_models import axial_twin, lumped_axial_frequency

    st = scene.statics
    if scene.simulation.model == "lumped3d" and (st.segments or st.bodies):
        return lumped_axial_frequency(scene)
    return float(AxialModel(axial_twin(scene)).modes(1).frequencies[0])


def identify_line(scene: DynamicScene, *, excitation: str, amplitude: float,
                  band: tuple[float, float], duration: float, sample_time: float,
                  noise: float, seed: int, sea: np.ndarray | None = None
                  ) -> CableIdentification:
    """Run the experiment on the line of ``scene`` and fit (6.2) and (6.3).

    The Gauss-Newton starts from the modal estimate ``a = 1 / omega_1^2`` with 5 % of
    critical damping (``b = 0.1 / omega_1``); the fit of (6.3) starts from the linear fit,
    ``b_q = b / (sqrt(8 / pi) sigma_v)`` (equivalent linearisation for a Gaussian velocity of
    std ``sigma_v``, that of the linear fit's response).

    Parameters
    ----------
    scene : DynamicScene
        The cable scene.
    excitation : str
        The top motion (:func:`excitation_signal`).
    amplitude : float
        Its RMS, m.
    band : tuple of float
        Its band (low, high), rad/s.
    duration : float
        Length of the record, s.
    sample_time : float
        Sample time, s.
    noise : float
        Standard deviation of the depth sensor's noise, m.
    seed : int
        Seed of that noise.
    sea : numpy.ndarray, optional
        ``(t, x0)`` rows of a boom-tip record for ``excitation = "sea"`` (s, m).
    """
    n = int(round(duration / sample_time)) + 1
    t = np.arange(n) * sample_time
    x0 = excitation_signal(excitation, t, amplitude, band,
                           None if sea is None else np.interp(t, sea[0], sea[1]))
    run = run_experiment(scene, x0, sample_time)
    rng = np.random.default_rng(seed)
    z = run["z"] + (noise * rng.standard_normal(n) if noise > 0 else 0.0)
    # The experiment starts at rest in the static state: the initial state (the fit's initial
    # condition, z[0]) is known, not measured; a noisy z[0] would start the fitted model with
    # a free oscillation that a lightly damped model keeps over the whole record.
    z[0] = run["z"][0]
    w1 = first_frequency(scene)
    lin = identify_unit(t, x0, z, model="linear", guess=(1.0 / w1**2, 0.1 / w1))
    xm = lin.x_model
    sig_v = float(np.std(np.gradient(xm, t)))
    bq0 = lin.b / (math.sqrt(8.0 / math.pi) * max(sig_v, 1e-9)) if lin.b > 0 else 1e-3
    quad = identify_unit(t, x0, z, model="quadratic", guess=(lin.a, bq0))
    return CableIdentification(linear=lin, quadratic=quad, excitation=excitation,
                               amplitude=float(np.sqrt(np.mean(x0**2))),
                               band=band if excitation in ("multisine", "chirp") else None,
                               duration=float(t[-1]), sample_time=sample_time, noise=noise,
                               omega_1=w1, length=scene.length, t=t, x0=x0, z=z)


def _sea_band_amplitude(sc: HeaveScene) -> tuple[float, float, Any]:
    """(boom-tip RMS (m), the sea's modal frequency (rad/s), the models of the scene)."""
    from cable_ocp.heave.design_loop import build_models
    from cable_ocp.heave.stochastic import output_variance_lyapunov

    # the sea and vessel filters only (the unit and a compensator are not known yet)
    models = build_models(replace(sc, unit=replace(sc.unit, cable_scene=None),
                                  passive_compensator=None))
    p = models.plant
    lo = p.blocks["vessel"].start
    cx0, _ = p.output_row("x0")
    var = output_variance_lyapunov(p.A[lo:, lo:], p.B2[lo:], cx0[lo:])
    return math.sqrt(var), models.spectrum.omega_m, models


def identify_from_cable(scene: HeaveScene, cable_scene: DynamicScene, length: float | None = None
                        ) -> CableIdentification:
    """The experiment of ``[identification]`` on the heave scene's cable scene (module
    docstring), optionally at another unstretched ``length`` (m).

    Parameters
    ----------
    scene : HeaveScene
        The heave scene (``[identification]``).
    cable_scene : DynamicScene
        Its cable scene.
    length : float, optional
        Unstretched length of the experiment, m (default the cable scene's).
    """
    from cable_ocp.heave.design_loop import wave_realisation

    if length is not None and length != cable_scene.length:
        cable_scene = cable_scene.with_overrides({"cable.length": float(length)})
    spec = scene.identification
    amp, wm, models = _sea_band_amplitude(scene)
    amplitude = spec.amplitude if spec.amplitude is not None else amp
    w1 = first_frequency(cable_scene)
    band = spec.band if spec.band is not None else (0.5 * wm, max(3.0 * wm, 1.5 * w1))
    noise = spec.noise if spec.noise is not None else scene.controller.measurement_noise
    h = scene.controller.sample_time
    sea = None
    if spec.excitation == "sea":
        hs = h / scene.simulation.substeps
        ts, xs, _ = wave_realisation(models.plant, spec.duration + h, hs, spec.seed + 17)
        sea = np.vstack([ts, xs])
    return identify_line(cable_scene, excitation=spec.excitation, amplitude=amplitude, band=band,
                         duration=spec.duration, sample_time=h, noise=noise, seed=spec.seed,
                         sea=sea)


def identified_json(ident: CableIdentification) -> dict[str, Any]:
    """The ``"identified"`` JSON object: ``a`` (s^2), ``b`` (s) of (6.2); ``b_quadratic``
    (s^2/m) and ``a_quadratic`` (s^2) of (6.3); fit percentages, standard errors, the
    excitation, and the first axial frequency of the same line for comparison."""
    lin, quad = ident.linear, ident.quadratic
    a_modal = 1.0 / ident.omega_1**2
    return {
        "a": lin.a, "b": lin.b, "b_quadratic": quad.b, "fit_pct": lin.fit_pct,
        "excitation": ident.excitation,
        "a_std": float(lin.std_errors[0]), "b_std": float(lin.std_errors[1]),
        "a_quadratic": quad.a, "a_quadratic_std": float(quad.std_errors[0]),
        "b_quadratic_std": float(quad.std_errors[1]), "fit_pct_quadratic": quad.fit_pct,
        "rms_residual": lin.rms_residual, "rms_residual_quadratic": quad.rms_residual,
        "converged": bool(lin.converged and quad.converged),
        "omega_1": ident.omega_1, "a_modal": a_modal,
        "omega_identified": 1.0 / math.sqrt(lin.a) if lin.a > 0 else None,
        "a_vs_modal_pct": 100.0 * (lin.a / a_modal - 1.0),
        "amplitude_rms": ident.amplitude,
        "band": list(ident.band) if ident.band is not None else None,
        "duration": ident.duration, "sample_time": ident.sample_time, "noise": ident.noise,
        "length": ident.length,
    }
