"""Track irregularities in alignment, level, cross level and gauge.

A :class:`TrackIrregularity` holds four channels sampled at uniformly spaced
distances s along the track, in the coordinates of the dynamics (x forward, y
to the right, z up; :mod:`wheelrail.dynamics.model`):

* ``alignment`` a(s) — lateral position of the track centre line, positive to
  the right [m];
* ``level`` v(s) — vertical position of the track centre line, positive up [m];
* ``cross_level`` c(s) — height of the right rail over the left rail [m]
  (positive: right rail higher, the sign of a positive cant angle in
  :class:`~wheelrail.dynamics.TrackLayout`); the cant of the layout is not
  included;
* ``gauge`` g(s) — deviation of the gauge from nominal, positive when the rails
  are farther apart [m].

The rails move with them (each rail translates; the small rotation of a rail
by the cross level, c/1.5 m ≈ 3 mrad for 5 mm, is not applied to its
profile)::

    left rail   lateral a − g/2   vertical v − c/2
    right rail  lateral a + g/2   vertical v + c/2

Between samples each channel is interpolated by cubic Hermite splines with
Catmull–Rom slopes (continuous slope, so the rails' velocities V d/ds are
continuous), and is zero outside the sampled range — exactly as the compiled
equations of motion evaluate it.

Irregularities are read from measured files (:meth:`TrackIrregularity.from_file`)
or generated from a standard spectrum (:meth:`TrackIrregularity.from_psd`,
ERRI B176 low/high level, FRA classes 1–6, see
:mod:`wheelrail.dynamics._spectra`).

References
----------
.. [1] S. Iwnicki (ed.), *Handbook of railway vehicle dynamics*, CRC 2006,
   ch. 7 (track geometry and irregularities; generation from spectra by sums of
   harmonics with random phases).
.. [2] EN 13848-1:2019, Railway applications — Track — Track geometry quality —
   Part 1: Characterisation of track geometry (alignment, longitudinal level,
   cross level, track gauge).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ._spectra import CHANNELS, track_spectrum

__all__ = ["TrackIrregularity", "hermite"]

#: Largest plausible irregularity [m] (a value in mm given as metres is refused).
_PLAUSIBLE = 0.5


def hermite(s, s0, ds, samples):
    """Catmull–Rom cubic Hermite interpolation of uniformly spaced samples, zero outside.

    Parameters
    ----------
    s : array_like
        Distances [m].
    s0, ds : float
        First sample's distance and the spacing [m].
    samples : ndarray, shape (..., n)
        Sampled values (last axis along s).

    Returns
    -------
    value, slope : ndarray, shape (..., *s.shape)
        Interpolated values and their derivative d/ds (zero outside [s0, s0 + (n−1) ds)).
    """
    s = np.asarray(s, dtype=float)
    y = np.asarray(samples, dtype=float)
    n = y.shape[-1]
    u = (s - s0) / ds
    j = np.floor(u).astype(np.int64)
    inside = (j >= 0) & (j < n - 1)
    jj = np.clip(j, 0, n - 2)
    t = np.where(inside, u - jj, 0.0)
    pad = np.concatenate([np.zeros(y.shape[:-1] + (1,)), y, np.zeros(y.shape[:-1] + (2,))],
                         axis=-1)           # pad[k + 1] = y[k]; y[-1] = y[n] = y[n + 1] = 0
    ym1, y0, y1, y2 = (pad[..., jj + k] for k in (0, 1, 2, 3))
    m0 = 0.5 * (y1 - ym1)
    m1 = 0.5 * (y2 - y0)
    t2, t3 = t * t, t * t * t
    val = (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * y1 \
        + (t3 - t2) * m1
    der = ((6 * t2 - 6 * t) * y0 + (3 * t2 - 4 * t + 1) * m0 + (-6 * t2 + 6 * t) * y1
           + (3 * t2 - 2 * t) * m1) / ds
    return np.where(inside, val, 0.0), np.where(inside, der, 0.0)


@dataclass(frozen=True, eq=False)
class TrackIrregularity:
    """Irregularities of a track in four channels (frozen, SI; sign conventions: module docstring).

    Parameters
    ----------
    distance : ndarray, shape (n,)
        Distances along the track [m], increasing and uniformly spaced, n ≥ 4.
    alignment, level, cross_level, gauge : ndarray, shape (n,) or None
        The channels [m] (None: zero).

    Examples
    --------
    >>> import numpy as np
    >>> import wheelrail as wr
    >>> s = np.arange(0.0, 100.0, 0.25)
    >>> irr = wr.dynamics.TrackIrregularity(s, level=0.002 * np.sin(2 * np.pi * s / 20))
    >>> irr.rails(5.0)[..., 1].round(6).tolist()        # left, right vertical [m]
    [0.002, 0.002]
    """

    distance: np.ndarray
    alignment: np.ndarray | None = None
    level: np.ndarray | None = None
    cross_level: np.ndarray | None = None
    gauge: np.ndarray | None = None

    def __post_init__(self):
        try:
            s = np.asarray(self.distance, dtype=float)
        except (TypeError, ValueError):
            raise InputError("TrackIrregularity: distance must be an array of numbers") from None
        if s.ndim != 1 or s.size < 4:
            raise InputError(f"TrackIrregularity: distance must be 1-D with at least 4 samples, "
                             f"got shape {s.shape}")
        if not np.all(np.isfinite(s)):
            raise InputError("TrackIrregularity: distance must be finite")
        d = np.diff(s)
        if not np.all(d > 0):
            k = int(np.argmin(d > 0))
            raise InputError(f"TrackIrregularity: distance must increase; sample {k + 1} "
                             f"({s[k + 1]!r} m) follows {s[k]!r} m")
        if not np.allclose(d, d[0], rtol=1e-6, atol=0.0):
            k = int(np.argmax(~np.isclose(d, d[0], rtol=1e-6, atol=0.0)))
            raise InputError(f"TrackIrregularity: distance must be uniformly spaced (spacing "
                             f"{d[0]!r} m, but {d[k]!r} m between samples {k} and {k + 1}); "
                             "resample first (e.g. numpy.interp)")
        object.__setattr__(self, "distance", s)
        for name in CHANNELS:
            v = getattr(self, name)
            if v is None:
                arr = np.zeros_like(s)
            else:
                try:
                    arr = np.asarray(v, dtype=float)
                except (TypeError, ValueError):
                    raise InputError(f"TrackIrregularity: {name} must be an array of numbers"
                                     ) from None
                if arr.shape != s.shape:
                    raise InputError(f"TrackIrregularity: {name} has shape {arr.shape}, distance "
                                     f"{s.shape}")
                if not np.all(np.isfinite(arr)):
                    raise InputError(f"TrackIrregularity: {name} must be finite")
                big = float(np.max(np.abs(arr)))
                if big > _PLAUSIBLE:
                    raise InputError(f"TrackIrregularity: {name} reaches {big!r} m, implausible "
                                     "(metres expected, e.g. 0.003; from_file converts mm)")
            arr = arr.copy()
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    # ------------------------------------------------------------------ access
    @property
    def step(self) -> float:
        """Sample spacing [m]."""
        return float(self.distance[1] - self.distance[0])

    @property
    def samples(self) -> np.ndarray:
        """The channels as one array, shape (4, n), rows in the order of ``CHANNELS``."""
        return np.stack([getattr(self, c) for c in CHANNELS])

    def kernel_arrays(self) -> tuple:
        """(s0, ds, samples (4, n) C-contiguous) for the compiled equations of motion."""
        return float(self.distance[0]), self.step, np.ascontiguousarray(self.samples)

    def at(self, s) -> dict:
        """All channels interpolated at ``s`` [m].

        Returns
        -------
        dict
            ``{"alignment", "level", "cross_level", "gauge"}`` → ndarray of the shape of
            ``s`` [m] (zero outside the sampled range).
        """
        val, _ = hermite(s, self.distance[0], self.step, self.samples)
        return {c: val[k] for k, c in enumerate(CHANNELS)}

    def rails(self, s, slope: bool = False):
        """Lateral and vertical offsets of the left and right rails at ``s`` [m].

        Returns
        -------
        ndarray, shape (*s.shape, 2, 2)
            ``[..., side, direction]``: side 0 left, 1 right; direction 0 lateral
            (positive to the right), 1 vertical (positive up) [m]. With
            ``slope=True`` a pair (offsets, d/ds of the offsets).
        """
        val, der = hermite(s, self.distance[0], self.step, self.samples)
        out = []
        for a, v, c, g in (val, der):
            r = np.stack([np.stack([a - 0.5 * g, v - 0.5 * c], axis=-1),
                          np.stack([a + 0.5 * g, v + 0.5 * c], axis=-1)], axis=-2)
            out.append(r)
        return (out[0], out[1]) if slope else out[0]

    # ------------------------------------------------------------------ files
    @classmethod
    def from_file(cls, path, units: str = "mm") -> TrackIrregularity:
        """Read a measured irregularity file.

        Format: text, one sample per line, five columns separated by commas,
        semicolons, tabs or spaces — distance [m], alignment, level, cross
        level, gauge [mm] (or [m] with ``units="m"``), with the sign
        conventions of the module docstring. Lines starting with ``#`` and
        blank lines are skipped; the first other line may be a header (any
        non-numeric text). Distances must increase with a uniform spacing.

        Raises
        ------
        InputError
            Naming the file and line of the first bad line.
        """
        if units not in ("mm", "m"):
            raise InputError(f"from_file: units must be 'mm' or 'm', got {units!r}")
        scale = 1e-3 if units == "mm" else 1.0
        path = os.fspath(path)
        try:
            with open(path, encoding="utf-8") as fh:
                lines = fh.read().splitlines()
        except OSError as exc:
            raise InputError(f"cannot read irregularity file {path!r}: {exc.strerror}") from None
        except UnicodeDecodeError:
            raise InputError(f"{path}: not a text file") from None
        rows, where = [], []
        header_seen = False
        for no, raw in enumerate(lines, start=1):
            text = raw.strip()
            if not text or text.startswith("#"):
                continue
            parts = [p for p in text.replace(",", " ").replace(";", " ").split() if p]
            try:
                vals = [float(p) for p in parts]
            except ValueError:
                if not rows and not header_seen:
                    header_seen = True          # a header line
                    continue
                raise InputError(f"{path}, line {no}: non-numeric value in {text!r}") from None
            if len(vals) != 5:
                raise InputError(f"{path}, line {no}: expected 5 columns (distance, alignment, "
                                 f"level, cross level, gauge), got {len(vals)}")
            if not all(math.isfinite(v) for v in vals):
                raise InputError(f"{path}, line {no}: non-finite value in {text!r}")
            rows.append(vals)
            where.append(no)
        if len(rows) < 4:
            raise InputError(f"{path}: at least 4 data lines needed, found {len(rows)}")
        a = np.array(rows)
        d = np.diff(a[:, 0])
        bad = np.flatnonzero(d <= 0)
        if bad.size:
            k = int(bad[0]) + 1
            raise InputError(f"{path}, line {where[k]}: distance {a[k, 0]!r} m does not increase "
                             f"(previous {a[k - 1, 0]!r} m)")
        off = np.flatnonzero(~np.isclose(d, d[0], rtol=1e-4, atol=1e-9))
        if off.size:
            k = int(off[0]) + 1
            raise InputError(f"{path}, line {where[k]}: spacing {d[k - 1]!r} m differs from "
                             f"{d[0]!r} m (uniform spacing needed; resample the file)")
        big = np.abs(a[:, 1:]) * scale > _PLAUSIBLE
        if np.any(big):
            k = int(np.flatnonzero(big.any(axis=1))[0])
            raise InputError(f"{path}, line {where[k]}: irregularity {a[k, 1:].tolist()} "
                             f"{units} is implausible (over {_PLAUSIBLE * 1e3:g} mm)")
        s = a[0, 0] + d[0] * np.arange(a.shape[0])      # exact uniform grid
        if np.max(np.abs(s - a[:, 0])) > 1e-3 * d[0]:
            raise InputError(f"{path}: distances drift from a uniform grid")
        return cls(s, *(a[:, 1 + k] * scale for k in range(4)))

    def to_file(self, path, units: str = "mm") -> None:
        """Write the format read by :meth:`from_file` (a header line, distance in m)."""
        if units not in ("mm", "m"):
            raise InputError(f"to_file: units must be 'mm' or 'm', got {units!r}")
        scale = 1e3 if units == "mm" else 1.0
        data = np.column_stack([self.distance] + [getattr(self, c) * scale for c in CHANNELS])
        header = (f"distance_m, alignment_{units}, level_{units}, cross_level_{units}, "
                  f"gauge_{units}")
        np.savetxt(os.fspath(path), data, delimiter=", ", header=header, comments="",
                   fmt="%.10g")

    # ------------------------------------------------------------------ spectra
    @classmethod
    def from_psd(cls, spectrum, length: float, seed=None, *, step: float | None = None,
                 start: float = 0.0, ramp: float = 10.0, channels=CHANNELS,
                 band=None) -> TrackIrregularity:
        """Generate irregularities from a standard spectrum, reproducibly from ``seed``.

        Each channel is a sum of harmonics Σ √(2 S(Ω_k) ΔΩ) cos(Ω_k s + φ_k) on the
        wavenumber grid Ω_k = k ΔΩ of the FFT of the generated length, for the Ω_k in
        the spectrum's wavelength band, with phases φ_k uniform in [0, 2π) drawn from
        :func:`numpy.random.default_rng` (``seed``), independently for each channel
        (evaluated by an inverse FFT). Its one-sided PSD is then S(Ω) over the band
        (variance ∫ S dΩ). The gauge channel uses the spectrum's own gauge PSD
        (:mod:`~wheelrail.dynamics._spectra`) with its own phases.

        Parameters
        ----------
        spectrum : str or TrackSpectrum
            ``"erri-low"``, ``"erri-high"``, ``"fra-1"`` … ``"fra-6"`` or a configured
            :class:`~wheelrail.dynamics.TrackSpectrum`.
        length : float
            Length of the irregular track [m].
        seed : int, numpy.random.Generator or None
            Seed of the phases (the same seed gives the same track).
        step : float or None
            Sample spacing [m] (default: λ_min/8, at most 0.25 m).
        start : float
            Distance where the irregular stretch begins [m].
        ramp : float
            Length [m] of a ½(1 − cos) fade-in and fade-out at both ends (the
            irregularity starts from zero without a jump; 0: none).
        channels : sequence of str
            Channels to generate (the others are zero).
        band : (float, float) or None
            Wavelength band [m] (default: the spectrum's).

        References
        ----------
        .. [1] M. Shinozuka, C.-M. Jan, Digital simulation of random processes and
           its applications, J. Sound Vib. 25 (1972) 111–128 (sum of harmonics
           with random phases).
        """
        spec = track_spectrum(spectrum, band)
        if not (isinstance(length, (int, float)) and math.isfinite(length) and length > 0):
            raise InputError(f"from_psd: length must be > 0 m, got {length!r}")
        lmin, lmax = spec.band
        if step is None:
            step = min(0.25, lmin / 8.0)
        if not (isinstance(step, (int, float)) and math.isfinite(step) and step > 0):
            raise InputError(f"from_psd: step must be > 0 m, got {step!r}")
        if step > lmin / 2.0:
            raise InputError(f"from_psd: step = {step!r} m cannot represent the shortest "
                             f"wavelength {lmin!r} m (step <= λ_min/2 needed)")
        if not (isinstance(ramp, (int, float)) and 0 <= ramp and 2 * ramp <= length):
            raise InputError(f"from_psd: ramp must be in [0, length/2] m, got {ramp!r}")
        bad = [c for c in channels if c not in CHANNELS]
        if bad:
            raise InputError(f"from_psd: unknown channels {bad}; channels: {', '.join(CHANNELS)}")
        rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
        n = int(math.ceil(length / step)) + 1
        # generate over at least twice the longest wavelength (the grid then holds it)
        nfft = max(n, int(math.ceil(2.0 * lmax / step)))
        nfft += nfft % 2
        dw = 2.0 * math.pi / (nfft * step)
        w = dw * np.arange(nfft // 2 + 1)
        wlo, whi = spec.omega_band
        inband = (w >= wlo * (1 - 1e-12)) & (w <= whi * (1 + 1e-12)) & (w > 0)
        s = float(start) + step * np.arange(n)
        x = np.arange(n) * step
        taper = np.ones(n)
        if ramp > 0:
            r = x < ramp
            taper[r] = 0.5 * (1 - np.cos(np.pi * x[r] / ramp))
            e = x > x[-1] - ramp
            taper[e] = 0.5 * (1 - np.cos(np.pi * (x[-1] - x[e]) / ramp))
        out = {}
        for c in CHANNELS:
            phases = rng.uniform(0.0, 2.0 * np.pi, w.size)      # drawn for every channel
            if c not in channels:
                continue
            amp = np.zeros_like(w)
            amp[inband] = np.sqrt(2.0 * spec.psd(c, w[inband]) * dw)
            # x(s) = Σ amp cos(Ω s + φ) = Re Σ amp e^{iφ} e^{iΩs}: irfft scaled by nfft/2
            coef = amp * np.exp(1j * phases) * (nfft / 2.0)
            series = np.fft.irfft(coef, nfft)[:n]
            out[c] = series * taper
        return cls(s, **out)
