"""Sea-wave spectra and rational shaping filters (Huang 1992, section 6.3.1, eqs. (6.19)-(6.23)).

Conventions (docs/conventions.md, "Heave compensation"):

* Spectra are **one-sided** in angular frequency: the wave-elevation variance is
  ``m0 = integral_0^inf S(w) dw`` (m^2), and ``S`` is in m^2 s/rad.
* A shaping filter ``H`` driven by white noise of unit one-sided spectral density approximates
  ``S(w) ~ |H(i w)|^2`` (6.19). The output variance is then ``integral_0^inf |H|^2 dw = pi P11``
  where ``P`` solves the Lyapunov equation (6.31) with ``B2 B2^T``, i.e. the white noise has the
  intensity ``pi`` (``E[w(t) w(s)] = pi delta(t - s)``). :data:`WHITE_NOISE_INTENSITY` is that
  factor.
* Bretschneider (6.20) is used in the standard ``omega_m**4`` form (the thesis prints
  ``omega_m**2``, a misprint: only ``omega_m**4`` gives ``m0 = H_1/3**2 / 16`` and matches the
  rational fit (6.21)).
"""

from __future__ import annotations

from dataclasses import dataclass

import control as ct
import numpy as np
from scipy import integrate, optimize

from cable_ocp.errors import CableOCPError
from cable_ocp.heave.stochastic import WHITE_NOISE_INTENSITY, output_variance_lyapunov

__all__ = ["WHITE_NOISE_INTENSITY"]  # defined with the variance convention in ``stochastic``

#: Constants of the thesis' rational approximation (6.21)-(6.22) (Triantafyllou et al. 1983).
THESIS_S0_FACTOR = 1.8861
THESIS_W0_FACTOR = 0.9538
THESIS_SECTION_DAMPING_2ZETA = 1.414


def bretschneider(omega: np.ndarray, hs: float, omega_m: float) -> np.ndarray:
    """Bretschneider spectrum (Huang 1992, eq. (6.20), standard ``omega_m**4`` form).

    Parameters
    ----------
    omega : array_like
        Angular frequency, rad/s (> 0; zero returns 0).
    hs : float
        Significant wave height ``H_1/3``, m.
    omega_m : float
        Modal (peak) frequency, rad/s.

    Returns
    -------
    numpy.ndarray
        One-sided spectral density, m^2 s/rad.
    """
    w = np.asarray(omega, dtype=float)
    out = np.zeros_like(w)
    pos = w > 0
    wp = w[pos]
    out[pos] = 1.25 / 4.0 * hs**2 * omega_m**4 / wp**5 * np.exp(-1.25 * (omega_m / wp) ** 4)
    return out


def modal_frequency_from_zero_crossing(tz: float) -> float:
    """Modal frequency of the two-parameter Pierson-Moskowitz spectrum from ``T_z`` (rad/s).

    The ITTC two-parameter spectrum ``S = 4 pi^3 Hs^2 / (Tz^4 w^5) exp(-16 pi^3 / (Tz^4 w^4))``
    is the Bretschneider form (6.20) with ``1.25 omega_m^4 = 16 pi^3 / Tz^4``.

    Parameters
    ----------
    tz : float
        Mean zero-crossing period, s.
    """
    return float((16.0 * np.pi**3 / 1.25) ** 0.25 / tz)


def jonswap(
    omega: np.ndarray, hs: float, omega_m: float, gamma: float = 3.3
) -> np.ndarray:
    """JONSWAP spectrum with the Bretschneider/PM shape (6.20) times a peak enhancement.

    ``S_J = A_gamma S_B(w) gamma**r``, ``r = exp(-(w - wm)^2 / (2 s^2 wm^2))``, ``s = 0.07``
    below the peak and ``0.09`` above it, and ``A_gamma = 1 - 0.287 ln(gamma)`` (DNV-RP-C205
    normalisation, which keeps ``m0`` close to ``Hs^2/16``).

    Parameters
    ----------
    omega : array_like
        Angular frequency, rad/s.
    hs : float
        Significant wave height, m.
    omega_m : float
        Peak frequency, rad/s.
    gamma : float
        Peak-enhancement factor (1 gives Bretschneider), dimensionless.

    Returns
    -------
    numpy.ndarray
        One-sided spectral density, m^2 s/rad.
    """
    w = np.asarray(omega, dtype=float)
    sig = np.where(w <= omega_m, 0.07, 0.09)
    r = np.exp(-((w - omega_m) ** 2) / (2.0 * sig**2 * omega_m**2))
    return (1.0 - 0.287 * np.log(gamma)) * bretschneider(w, hs, omega_m) * gamma**r


@dataclass(frozen=True)
class SeaSpectrum:
    """A one-sided wave spectrum with its parameters.

    Attributes
    ----------
    kind : str
        ``"bretschneider"``, ``"pierson_moskowitz"`` or ``"jonswap"``.
    hs : float
        Significant wave height, m.
    omega_m : float
        Modal frequency, rad/s.
    gamma : float
        JONSWAP peak enhancement (ignored otherwise).
    """

    kind: str
    hs: float
    omega_m: float
    gamma: float = 3.3

    def __call__(self, omega: np.ndarray) -> np.ndarray:
        """Spectral density at ``omega`` (rad/s), m^2 s/rad."""
        if self.kind in ("bretschneider", "pierson_moskowitz"):
            return bretschneider(omega, self.hs, self.omega_m)
        if self.kind == "jonswap":
            return jonswap(omega, self.hs, self.omega_m, self.gamma)
        raise CableOCPError(
            f'sea.spectrum = {self.kind!r}: valid are "bretschneider", '
            '"pierson_moskowitz", "jonswap"'
        )

    def m0(self) -> float:
        """Zeroth moment (elevation variance), m^2, by adaptive quadrature."""
        wm = self.omega_m
        val, _ = integrate.quad(self, 0.0, 40.0 * wm, points=[0.5 * wm, wm, 2 * wm],
                                limit=400, epsabs=0.0, epsrel=1e-11)
        tail, _ = integrate.quad(self, 40.0 * wm, np.inf, epsabs=0.0, epsrel=1e-10)
        return float(val + tail)


def second_order_sections(omegas: np.ndarray, two_zetas: np.ndarray, gain: float) -> ct.StateSpace:
    """Chain of second-order sections in the controllable form of (6.23).

    Realises ``H(s) = gain * s**(n-1) * prod_{i<n} w_i**2 / prod_i (s**2 + 2 z_i w_i s + w_i**2)``
    exactly as (6.23): state pairs ``(x_{2i-1}, x_{2i})``, noise into the last section, each
    section driven by the velocity state of the next one, output ``gain * x_1``. With three equal
    sections ``w_0`` and ``2 zeta = 1.414`` this is the thesis' ``A_s, B_s, C_s`` and
    ``H = sqrt(S_0) (s/w_0)^2 / (1 + 1.414 s/w_0 + (s/w_0)^2)^3`` (6.22).

    Parameters
    ----------
    omegas : array_like, shape (n,)
        Section natural frequencies, rad/s.
    two_zetas : array_like, shape (n,)
        ``2 zeta_i`` of each section.
    gain : float
        Output gain (``sqrt(S_0)`` in (6.23)), m per state unit.

    Returns
    -------
    control.StateSpace
        Input ``w`` (white noise), output ``eta`` (wave elevation, m), ``2 n`` states.
    """
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    two_zetas = np.atleast_1d(np.asarray(two_zetas, dtype=float))
    n = omegas.size
    A = np.zeros((2 * n, 2 * n))
    for i in range(n):
        w, tz = omegas[i], two_zetas[i]
        A[2 * i, 2 * i + 1] = 1.0
        A[2 * i + 1, 2 * i] = -(w**2)
        A[2 * i + 1, 2 * i + 1] = -tz * w
        if i < n - 1:
            A[2 * i + 1, 2 * i + 3] = w**2
    B = np.zeros((2 * n, 1))
    B[-1, 0] = 1.0
    C = np.zeros((1, 2 * n))
    C[0, 0] = gain
    names = [f"sea{i + 1}" for i in range(2 * n)]
    return ct.ss(A, B, C, 0, inputs=["w"], outputs=["eta"], states=names, name="sea")


def thesis_shaping_filter(hs: float, omega_m: float) -> ct.StateSpace:
    """The thesis' sixth-order shaping filter (Huang 1992, eqs. (6.21)-(6.23)).

    ``S_0 = 1.25/(4 omega_m) Hs^2 1.8861``, ``omega_0 = 0.9538 omega_m``, three sections with
    ``2 zeta = 1.414``; ``|H(i w)|^2 = S_0 (w/w0)^4 / (1 + (w/w0)^4)^3`` (6.21).

    Parameters
    ----------
    hs : float
        Significant wave height, m.
    omega_m : float
        Modal frequency, rad/s.
    """
    if hs <= 0 or omega_m <= 0:
        raise CableOCPError(
            f"sea.significant_wave_height = {hs!r}, sea.modal_frequency = {omega_m!r}: both "
            "must be > 0 (m, rad/s)"
        )
    s0 = 1.25 / (4.0 * omega_m) * hs**2 * THESIS_S0_FACTOR
    w0 = THESIS_W0_FACTOR * omega_m
    return second_order_sections([w0] * 3, [THESIS_SECTION_DAMPING_2ZETA] * 3, np.sqrt(s0))


def filter_spectrum(sys: ct.StateSpace, omega: np.ndarray) -> np.ndarray:
    """``|H(i w)|^2`` of a SISO filter, in output units squared per unit noise spectral density.

    Parameters
    ----------
    sys : control.StateSpace
        The SISO filter.
    omega : numpy.ndarray
        Frequencies, rad/s.
    """
    resp = np.asarray(sys(1j * np.asarray(omega, dtype=float)))
    return np.abs(resp.reshape(-1)) ** 2


@dataclass(frozen=True)
class FilterFit:
    """A shaping filter and how well it reproduces its target spectrum.

    Attributes
    ----------
    filter : control.StateSpace
        The shaping filter (input unit white noise, output elevation, m).
    spectral_error : float
        Relative L2 error ``||S_a - S|| / ||S||`` on ``(0, 6 omega_m]``, dimensionless.
    variance_error : float
        Relative error of the elevation variance ``(m0_a - m0) / m0``, dimensionless.
    omegas, two_zetas, gain : numpy.ndarray, numpy.ndarray, float
        The sections' parameters.
    """

    filter: ct.StateSpace
    spectral_error: float
    variance_error: float
    omegas: np.ndarray
    two_zetas: np.ndarray
    gain: float


def _grid(omega_m: float) -> np.ndarray:
    return np.linspace(0.05 * omega_m, 6.0 * omega_m, 1200)


def fit_quality(sys: ct.StateSpace, spectrum: SeaSpectrum) -> tuple[float, float]:
    """Spectral (relative L2 on a grid) and variance errors of a filter against a spectrum.

    The filter variance is the Lyapunov value ``pi C P C^T`` (see module docstring); the spectrum
    variance is by quadrature.

    Parameters
    ----------
    sys : control.StateSpace
        The shaping filter.
    spectrum : SeaSpectrum
        The sea spectrum it approximates.

    Returns
    -------
    tuple of float
        ``(spectral_error, variance_error)``, both dimensionless.
    """
    w = _grid(spectrum.omega_m)
    s_true = spectrum(w)
    s_fit = filter_spectrum(sys, w)
    spec_err = float(np.linalg.norm(s_fit - s_true) / np.linalg.norm(s_true))
    var_fit = output_variance_lyapunov(sys.A, sys.B, sys.C)
    var_err = float((var_fit - spectrum.m0()) / spectrum.m0())
    return spec_err, var_err


def thesis_fit(spectrum: SeaSpectrum) -> FilterFit:
    """The thesis filter (6.22) for ``spectrum`` with its fit errors."""
    sys = thesis_shaping_filter(spectrum.hs, spectrum.omega_m)
    se, ve = fit_quality(sys, spectrum)
    w0 = THESIS_W0_FACTOR * spectrum.omega_m
    s0 = 1.25 / (4.0 * spectrum.omega_m) * spectrum.hs**2 * THESIS_S0_FACTOR
    return FilterFit(sys, se, ve, np.full(3, w0), np.full(3, THESIS_SECTION_DAMPING_2ZETA),
                     float(np.sqrt(s0)))


def fit_shaping_filter(spectrum: SeaSpectrum, n_sections: int = 3) -> FilterFit:
    """Least-squares rational fit of ``n_sections`` second-order sections (improves on (6.21)).

    The filter has the chain structure of (6.23) (see :func:`second_order_sections`: numerator
    ``s^(n-1)``, ``n`` sections with free ``w_i``, ``2 zeta_i`` and a free gain), so
    ``|H|^2 ~ w^(2n-2)`` at low and ``~ w^(-2n-2)`` at high frequency; ``n = 3`` is the thesis'
    structure. The parameters minimise the squared spectral error on ``(0.05, 6] omega_m`` plus a
    variance-mismatch penalty (weight 1 on the relative variance error), starting from the thesis'
    constants.

    Parameters
    ----------
    spectrum : SeaSpectrum
        Target spectrum.
    n_sections : int
        Number of second-order sections (``[sea] filter_order``), 2..6.

    Returns
    -------
    FilterFit
    """
    if not (isinstance(n_sections, int) and 2 <= n_sections <= 6):
        raise CableOCPError(
            f"sea.filter_order = {n_sections!r}: expected an integer 2..6"
        )
    wm = spectrum.omega_m
    w = _grid(wm)
    s_true = spectrum(w)
    scale = np.linalg.norm(s_true)
    m0 = spectrum.m0()
    jw = 1j * w

    def residual(p: np.ndarray) -> np.ndarray:
        om = np.exp(p[1 : 1 + n_sections])
        tz = np.exp(p[1 + n_sections :])
        h = np.exp(p[0]) * jw ** (n_sections - 1) * np.prod(om[:-1] ** 2)
        for k in range(n_sections):
            h = h / (jw**2 + tz[k] * om[k] * jw + om[k] ** 2)
        s_fit = np.abs(h) ** 2
        sys = _sections_from_params(p, n_sections)
        var = output_variance_lyapunov(sys.A, sys.B, sys.C)
        return np.concatenate([(s_fit - s_true) / scale, [(var - m0) / m0]])

    # Start: the thesis filter's poles, spread a little for n != 3.
    w0 = THESIS_W0_FACTOR * wm
    om0 = w0 * np.exp(np.linspace(-0.15, 0.15, n_sections)) if n_sections != 3 else np.full(3, w0)
    s0 = 1.25 / (4.0 * wm) * spectrum.hs**2 * THESIS_S0_FACTOR
    # Gain so that the peak level is roughly the thesis filter's.
    c0 = np.sqrt(s0) * w0 ** (3 - n_sections)
    p0 = np.concatenate([[np.log(c0)], np.log(om0), np.log(np.full(n_sections, 1.414))])
    sol = optimize.least_squares(residual, p0, method="trf", x_scale="jac", max_nfev=2000)
    sys = _sections_from_params(sol.x, n_sections)
    se, ve = fit_quality(sys, spectrum)
    om = np.exp(sol.x[1 : 1 + n_sections])
    tz = np.exp(sol.x[1 + n_sections :])
    return FilterFit(sys, se, ve, om, tz, float(sys.C[0, 0]))


def _sections_from_params(p: np.ndarray, n: int) -> ct.StateSpace:
    """Section chain from log-parameters ``[log gain, log w_i (n), log 2zeta_i (n)]``."""
    return second_order_sections(np.exp(p[1 : 1 + n]), np.exp(p[1 + n :]), float(np.exp(p[0])))


def make_shaping_filter(spectrum: SeaSpectrum, kind: str = "thesis",
                        n_sections: int = 3) -> FilterFit:
    """Shaping filter selected by ``[sea] shaping_filter`` (``"thesis"`` default, or ``"fit"``).

    The thesis filter (6.21)-(6.23) is tied to the Bretschneider shape; for a JONSWAP sea it still
    uses the Bretschneider constants (its errors are reported against the JONSWAP spectrum).

    Parameters
    ----------
    spectrum : SeaSpectrum
        The sea spectrum.
    kind : {"thesis", "fit"}
        The thesis filter (6.21)-(6.23) or a least-squares fit of second-order sections.
    n_sections : int
        Second-order sections of the ``"fit"`` filter.
    """
    if kind == "thesis":
        return thesis_fit(spectrum)
    if kind == "fit":
        return fit_shaping_filter(spectrum, n_sections)
    raise CableOCPError(f'sea.shaping_filter = {kind!r}: valid are "thesis", "fit"')
