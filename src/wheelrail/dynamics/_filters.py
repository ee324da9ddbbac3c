"""Signal processing of the running-safety assessment: filters, sliding means, Sperling's Wz.

Plain array functions (public through :mod:`wheelrail.dynamics`):

* :func:`lowpass`, :func:`bandpass` — Butterworth filters (digital, bilinear
  transform with the edge frequencies pre-warped, so the −3 dB points are
  exactly at the given frequencies), applied causally as a measuring chain
  would (started in the steady state of the first sample) or zero-phase
  (forward and backward: the gain squared, no delay);
* :func:`sliding_mean` — mean over a window of distance (not time), exact for
  the piecewise-linear interpolant of the samples;
* :func:`sperling_wz` — Sperling's ride index from the amplitude spectrum of an
  acceleration with Sperling's frequency weighting.

References
----------
.. [1] EN 14363:2016, Railway applications — Testing and simulation for the
   acceptance of running characteristics of railway vehicles (ΣY and Y/Q as
   2 m sliding means of forces low-pass filtered at 20 Hz; car-body
   accelerations band-pass filtered 0.4–10 Hz).
.. [2] E. Sperling, Verfahren zur Beurteilung der Laufeigenschaften von
   Eisenbahnwagen, Organ für die Fortschritte des Eisenbahnwesens 12 (1941)
   176–187; in the form of V.K. Garg, R.V. Dukkipati, *Dynamics of railway
   vehicle systems*, Academic Press 1984, ch. 12 (Wz and the weighting F(f)).
.. [3] S. Butterworth, On the theory of filter amplifiers, Wireless Engineer 7
   (1930) 536–541.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.signal import butter, sosfilt, sosfilt_zi, sosfiltfilt

from ..errors import InputError

__all__ = ["lowpass", "bandpass", "sliding_mean", "sperling_wz", "sperling_weighting"]


def _check_rate(fs, *freqs):
    if not (isinstance(fs, (int, float, np.floating)) and math.isfinite(fs) and fs > 0):
        raise InputError(f"sampling rate fs must be > 0 Hz, got {fs!r}")
    for f in freqs:
        if not (isinstance(f, (int, float, np.floating)) and math.isfinite(f) and 0 < f < fs / 2):
            raise InputError(f"filter frequency {f!r} Hz must lie in (0, fs/2 = {fs / 2:g} Hz)")


def _apply(sos, x, axis, zero_phase):
    x = np.asarray(x, dtype=float)
    if x.shape[axis] < 2:
        raise InputError(f"a signal of at least 2 samples is needed, got {x.shape[axis]}")
    if zero_phase:
        return sosfiltfilt(sos, x, axis=axis)
    xm = np.moveaxis(x, axis, -1)
    zi = sosfilt_zi(sos)                                       # (n_sections, 2)
    zi = zi.reshape((zi.shape[0],) + (1,) * (xm.ndim - 1) + (2,)) * xm[None, ..., :1]
    y, _ = sosfilt(sos, xm, axis=-1, zi=zi)                    # steady state of x[0]
    return np.moveaxis(y, -1, axis)


def lowpass(x, fs: float, cutoff: float, order: int = 4, *, zero_phase: bool = False,
            axis: int = 0) -> np.ndarray:
    """Butterworth low-pass filter.

    Parameters
    ----------
    x : array_like
        Signal sampled at ``fs`` along ``axis``.
    fs : float
        Sampling rate [Hz].
    cutoff : float
        −3 dB frequency [Hz] (< fs/2).
    order : int
        Filter order (gain 1/√(1 + (Ω/Ω_c)^(2·order)), Ω = 2 fs tan(π f/fs)).
    zero_phase : bool
        Filter forward and backward (gain squared, no delay) instead of causally.

    Returns
    -------
    ndarray
        Filtered signal, same shape. A causal filter starts in the steady state of the
        first sample (no start-up transient for a signal that starts constant).
    """
    _check_rate(fs, cutoff)
    if not (isinstance(order, int) and 1 <= order <= 12):
        raise InputError(f"order must be an integer in [1, 12], got {order!r}")
    sos = butter(order, cutoff, btype="lowpass", fs=fs, output="sos")
    return _apply(sos, x, axis, zero_phase)


def bandpass(x, fs: float, low: float, high: float, order: int = 4, *,
             zero_phase: bool = False, axis: int = 0) -> np.ndarray:
    """Butterworth band-pass filter (−3 dB at ``low`` and ``high`` [Hz]).

    ``order`` is that of the low-pass prototype: the band-pass has 2·order poles,
    gain 1/√(1 + ((Ω² − Ω_l Ω_h)/(Ω (Ω_h − Ω_l)))^(2·order)) with
    Ω = 2 fs tan(π f/fs).
    Other parameters as :func:`lowpass`.
    """
    _check_rate(fs, low, high)
    if not low < high:
        raise InputError(f"band-pass: low = {low!r} Hz must be below high = {high!r} Hz")
    if not (isinstance(order, int) and 1 <= order <= 12):
        raise InputError(f"order must be an integer in [1, 12], got {order!r}")
    sos = butter(order, [low, high], btype="bandpass", fs=fs, output="sos")
    return _apply(sos, x, axis, zero_phase)


def _cumulative(x, s):
    """∫ from s[0] of the piecewise-linear interpolant of x (along axis 0)."""
    ds = np.diff(s).reshape((-1,) + (1,) * (x.ndim - 1))
    return np.concatenate([np.zeros((1,) + x.shape[1:]),
                           np.cumsum(0.5 * (x[1:] + x[:-1]) * ds, axis=0)], axis=0)


def _integral_to(q, x, s, F):
    """∫ from s[0] to q of the piecewise-linear interpolant (exact, q inside [s0, s_end])."""
    k = np.clip(np.searchsorted(s, q, side="right") - 1, 0, s.size - 2)
    h = (q - s[k]).reshape((-1,) + (1,) * (x.ndim - 1))
    L = (s[k + 1] - s[k]).reshape(h.shape)
    slope = (x[k + 1] - x[k]) / L
    return F[k] + x[k] * h + 0.5 * slope * h * h


def sliding_mean(values, distance, window: float = 2.0, step: float | None = None):
    """Mean over a sliding window of distance.

    Parameters
    ----------
    values : array_like, shape (n, ...)
        Samples (first axis along the track).
    distance : array_like, shape (n,)
        Distance of each sample [m], strictly increasing (need not be uniform: a
        result in time at a varying speed).
    window : float
        Window length [m] (EN 14363: 2 m).
    step : float or None
        Spacing of the window centres [m] (EN 14363: 0.5 m); None: the mean
        sample spacing.

    Returns
    -------
    centres : ndarray, shape (m,)
        Window centres [m], from distance[0] + window/2 to distance[-1] − window/2
        (complete windows only).
    means : ndarray, shape (m, ...)
        (1/window) ∫ x ds over [c − window/2, c + window/2] of the linear
        interpolant of the samples (exact for piecewise-linear signals).
    """
    x = np.asarray(values, dtype=float)
    s = np.asarray(distance, dtype=float)
    if s.ndim != 1 or x.shape[:1] != s.shape or s.size < 2:
        raise InputError(f"sliding_mean: distance (n,) with n >= 2 and values (n, ...) needed, "
                         f"got shapes {s.shape} and {x.shape}")
    if not (np.all(np.isfinite(s)) and np.all(np.diff(s) > 0)):
        raise InputError("sliding_mean: distance must be finite and strictly increasing")
    if not np.all(np.isfinite(x)):
        raise InputError("sliding_mean: values must be finite")
    if not (isinstance(window, (int, float)) and math.isfinite(window) and window > 0):
        raise InputError(f"sliding_mean: window must be > 0 m, got {window!r}")
    span = s[-1] - s[0]
    if span < window:
        raise InputError(f"sliding_mean: the record covers {span!r} m, less than the window "
                         f"{window!r} m")
    if step is None:
        step = span / (s.size - 1)
    if not (isinstance(step, (int, float, np.floating)) and math.isfinite(step) and step > 0):
        raise InputError(f"sliding_mean: step must be > 0 m, got {step!r}")
    m = int(math.floor((span - window) / step * (1 + 1e-12))) + 1
    c = s[0] + 0.5 * window + step * np.arange(m)
    F = _cumulative(x, s)
    hi = np.minimum(c + 0.5 * window, s[-1])
    lo = np.maximum(c - 0.5 * window, s[0])
    return c, (_integral_to(hi, x, s, F) - _integral_to(lo, x, s, F)) / window


def sperling_weighting(f, direction: str = "vertical") -> np.ndarray:
    """Sperling's frequency weighting F(f) [-] (Garg & Dukkipati 1984, table of ch. 12).

    vertical: 0.325 f² (0.5–5.9 Hz), 400/f² (5.9–20 Hz), 1 (> 20 Hz);
    lateral: 0.8 f² (0.5–5.4 Hz), 650/f² (5.4–26 Hz), 1 (> 26 Hz); f in Hz.
    """
    f = np.asarray(f, dtype=float)
    if direction == "vertical":
        a, f1, b, f2 = 0.325, 5.9, 400.0, 20.0
    elif direction == "lateral":
        a, f1, b, f2 = 0.8, 5.4, 650.0, 26.0
    else:
        raise InputError(f"direction must be 'vertical' or 'lateral', got {direction!r}")
    with np.errstate(divide="ignore"):
        return np.where(f <= f1, a * f * f, np.where(f <= f2, b / np.maximum(f, 1e-300) ** 2, 1.0))


def sperling_wz(acc, fs: float, direction: str = "vertical", band=(0.5, 30.0),
                axis: int = 0):
    """Sperling's ride index Wz of an acceleration record.

    The record (mean removed) is decomposed into its discrete Fourier components
    of amplitude a_i [cm/s²] at the frequencies f_i [Hz] in ``band``; each gives
    Wz_i = 0.896 (a_i³ F(f_i)/f_i)^(1/10) and the record Wz = (Σ Wz_i¹⁰)^(1/10)
    (Sperling 1941; Garg & Dukkipati 1984), i.e. Wz = [Σ a_i³ B_i³]^(1/10) with
    B³ = 0.896¹⁰ F(f)/f.

    Parameters
    ----------
    acc : array_like
        Acceleration [m/s²] sampled at ``fs`` along ``axis``.
    fs : float
        Sampling rate [Hz].
    direction : {"vertical", "lateral"}
        Weighting (:func:`sperling_weighting`).
    band : (float, float)
        Frequency range of the sum [Hz] (Sperling: 0.5–30 Hz; clipped at fs/2).

    Returns
    -------
    float or ndarray
        Wz [-] (2.5: very good ... 4.5: not running-safe).

    Notes
    -----
    The index of a record sums components, so it depends on the frequency
    resolution (record length) when a component falls between DFT bins; a sine of
    a whole number of periods gives exactly 0.896 (a³ F(f)/f)^(1/10).
    """
    a = np.moveaxis(np.asarray(acc, dtype=float), axis, -1)
    n = a.shape[-1]
    if n < 4:
        raise InputError(f"sperling_wz: at least 4 samples needed, got {n}")
    if not (isinstance(fs, (int, float, np.floating)) and math.isfinite(fs) and fs > 0):
        raise InputError(f"sperling_wz: fs must be > 0 Hz, got {fs!r}")
    lo, hi = float(band[0]), min(float(band[1]), fs / 2)
    if not 0 < lo < hi:
        raise InputError(f"sperling_wz: band {band!r} Hz is empty at fs = {fs!r} Hz")
    X = np.fft.rfft(a - a.mean(axis=-1, keepdims=True), axis=-1)
    f = np.fft.rfftfreq(n, 1.0 / fs)
    amp = 2.0 * np.abs(X) / n
    if n % 2 == 0:
        amp[..., -1] *= 0.5                         # the Nyquist bin is not doubled
    m = (f >= lo) & (f <= hi)
    acm = 100.0 * amp[..., m]                        # cm/s²
    terms = 0.896 ** 10 * acm ** 3 * sperling_weighting(f[m], direction) / f[m]
    return np.sum(terms, axis=-1) ** 0.1
