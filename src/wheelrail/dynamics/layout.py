"""Track layout for the time integration: curves with cant and transitions, irregularities.

A :class:`TrackLayout` is a cross-section (:class:`wheelrail.Track`: rail
profiles, gauge, inclination) laid along a line: tangent track, circular
:class:`Curve` s entered and left through clothoid transitions (curvature and
cant linear in the distance s along the track), and irregularities of the rails
(:class:`~wheelrail.dynamics.TrackIrregularity`: alignment, level, cross level,
gauge; or a lateral alignment :class:`Irregularity` of both rails). The
equations of motion are written in a frame that follows the track centre line
(see :mod:`wheelrail.dynamics.model`); the layout gives, at every s, the
curvature κ [1/m] (positive in a curve to the right), the cant angle φ [rad]
(positive with the right rail higher; a curve to the right raises the left
rail, φ < 0) and the lateral and vertical displacement of each rail [m] with
their derivatives along s.

References
----------
.. [1] S. Iwnicki (ed.), *Handbook of railway vehicle dynamics*, CRC 2006,
   ch. 7 (track geometry: transitions, cant, irregularities).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..geometry import Track
from ._motion import layout_at, rail_offsets
from .irregularity import TrackIrregularity

__all__ = ["Curve", "Irregularity", "TrackLayout", "as_layout"]


@dataclass(frozen=True)
class Curve:
    """A circular curve with clothoid transitions (frozen, SI).

    Parameters
    ----------
    radius : float
        Radius of the circular part [m], > 0.
    start : float
        Distance along the track where the entry transition begins [m].
    length : float
        Length of the circular part [m] (``inf``: the curve never ends).
    transition : float
        Length of each transition [m] (0: curvature and cant jump).
    cant : float
        Superelevation of the outer rail over the inner one [m] (≥ 0).
    direction : {"right", "left"}
        Side to which the track turns (looking forward).
    """

    radius: float
    start: float = 0.0
    length: float = math.inf
    transition: float = 0.0
    cant: float = 0.0
    direction: str = "right"

    def __post_init__(self):
        for name, lo, open_lo, inf_ok in (("radius", 0.0, True, False),
                                          ("start", -math.inf, False, False),
                                          ("length", 0.0, False, True),
                                          ("transition", 0.0, False, False),
                                          ("cant", 0.0, False, False)):
            try:
                v = float(getattr(self, name))
            except (TypeError, ValueError):
                raise InputError(f"Curve: {name} must be a number, got "
                                 f"{getattr(self, name)!r}") from None
            if math.isnan(v) or (math.isinf(v) and not inf_ok) or (v <= lo if open_lo else v < lo):
                raise InputError(f"Curve: {name} must be {'>' if open_lo else '>='} {lo:g} "
                                 f"and finite, got {getattr(self, name)!r}")
            object.__setattr__(self, name, v)
        if self.direction not in ("right", "left"):
            raise InputError(f"Curve: direction must be 'right' or 'left', got "
                             f"{self.direction!r}")
        if self.cant > 0.3:
            raise InputError(f"Curve: cant = {self.cant!r} m is implausible (a height in m, "
                             "e.g. 0.15)")

    @property
    def sign(self) -> float:
        return 1.0 if self.direction == "right" else -1.0

    def knots(self):
        """(s, κ, cant height with the sign of the cant angle) at the breakpoints."""
        k = self.sign / self.radius
        h = -self.sign * self.cant           # a curve to the right raises the left rail
        s0, t, L = self.start, self.transition, self.length
        pts = [(s0, 0.0, 0.0), (s0 + t, k, h)]
        if math.isfinite(L):
            pts += [(s0 + t + L, k, h), (s0 + 2 * t + L, 0.0, 0.0)]
        return pts


@dataclass(frozen=True)
class Irregularity:
    """Lateral alignment of both rails along the track (frozen, SI).

    Samples ``lateral`` [m] (positive to the right) at the distances ``s`` [m]
    (uniformly spaced), interpolated by cubic Hermite splines with Catmull–Rom
    slopes (continuous slope, so the rails' lateral velocity V dy/ds is
    continuous); zero outside.
    """

    s: np.ndarray
    lateral: np.ndarray

    def __post_init__(self):
        s = np.asarray(self.s, dtype=float)
        y = np.asarray(self.lateral, dtype=float)
        if s.ndim != 1 or s.shape != y.shape or s.size < 4:
            raise InputError(f"Irregularity: s and lateral must be 1-D of equal length >= 4, got "
                             f"shapes {s.shape} and {y.shape}")
        if not (np.all(np.isfinite(s)) and np.all(np.isfinite(y))):
            raise InputError("Irregularity: s and lateral must be finite")
        ds = np.diff(s)
        if not (np.all(ds > 0) and np.allclose(ds, ds[0], rtol=1e-6, atol=0)):
            raise InputError("Irregularity: s must be increasing and uniformly spaced")
        if np.max(np.abs(y)) > 0.05:
            raise InputError(f"Irregularity: lateral = {np.max(np.abs(y))!r} m is implausible "
                             "(metres expected, e.g. 0.003)")
        object.__setattr__(self, "s", s)
        object.__setattr__(self, "lateral", y)

    @classmethod
    def sine(cls, amplitude: float, wavelength: float, start: float = 0.0, cycles: float = 1.0,
             step: float = 0.05) -> Irregularity:
        """A sine of ``amplitude`` [m] and ``wavelength`` [m] over ``cycles`` periods from
        ``start`` [m] (a smooth 1 − cos ramp of amplitude is not added: it starts with zero
        value and non-zero slope, as a single lateral kink of the alignment)."""
        if not (wavelength > 0 and cycles > 0 and step > 0):
            raise InputError(f"Irregularity.sine: wavelength, cycles and step must be > 0, got "
                             f"{wavelength!r}, {cycles!r}, {step!r}")
        n = int(math.ceil(cycles * wavelength / step)) + 1
        s = start + np.arange(n) * step
        y = amplitude * np.sin(2 * np.pi * (s - start) / wavelength)
        y[s > start + cycles * wavelength] = 0.0
        return cls(s, y)

    @classmethod
    def bump(cls, amplitude: float, length: float, start: float = 0.0,
             step: float = 0.05) -> Irregularity:
        """A lateral kink of the alignment: ½ A (1 − cos 2π (s − start)/length) over one
        ``length`` [m] (zero value and slope at both ends)."""
        if not (length > 0 and step > 0):
            raise InputError(f"Irregularity.bump: length and step must be > 0, got {length!r}, "
                             f"{step!r}")
        n = int(math.ceil(length / step)) + 1
        s = start + np.arange(n) * step
        y = 0.5 * amplitude * (1.0 - np.cos(2 * np.pi * (s - start) / length))
        return cls(s, y)


@dataclass(frozen=True, eq=False)
class TrackLayout:
    """A track cross-section laid along a line with curves and an irregularity (frozen).

    Parameters
    ----------
    track : Track
        The cross-section (:class:`wheelrail.Track`).
    curves : sequence of Curve
        Non-overlapping curves (tangent track elsewhere).
    irregularity : TrackIrregularity or Irregularity or None
        Irregularities of the rails: alignment, level, cross level and gauge
        (:class:`~wheelrail.dynamics.TrackIrregularity`), or the lateral
        alignment of both rails only (:class:`Irregularity`).
    cant_base : float
        Distance between the rails' running circles used to turn cant heights
        into angles [m] (1.5 m for standard gauge).
    """

    track: object
    curves: tuple = ()
    irregularity: Irregularity | None = None
    cant_base: float = 1.5

    def __post_init__(self):
        if not isinstance(self.track, Track):
            raise InputError(f"track must be a wheelrail.Track, got {type(self.track).__name__}")
        curves = tuple(self.curves)
        for c in curves:
            if not isinstance(c, Curve):
                raise InputError(f"curves must be wheelrail.dynamics.Curve objects, got "
                                 f"{type(c).__name__}")
        curves = tuple(sorted(curves, key=lambda c: c.start))
        for a, b in zip(curves, curves[1:]):
            end = a.start + 2 * a.transition + a.length
            if not end <= b.start:
                raise InputError(f"curves overlap: one ends at s = {end!r} m, the next starts at "
                                 f"{b.start!r} m")
        object.__setattr__(self, "curves", curves)
        if self.irregularity is not None and not isinstance(self.irregularity,
                                                            (Irregularity, TrackIrregularity)):
            raise InputError(f"irregularity must be a wheelrail.dynamics.TrackIrregularity or "
                             f"Irregularity, got {type(self.irregularity).__name__}")
        if not self.cant_base > 0:
            raise InputError(f"cant_base must be > 0 m, got {self.cant_base!r}")
        s, k, h = [-1e9], [0.0], [0.0]
        for c in curves:
            for p in c.knots():
                s.append(p[0])
                k.append(p[1])
                h.append(p[2])
        s.append(1e12)
        k.append(k[-1])
        h.append(h[-1])
        s = np.array(s)
        order = np.argsort(s, kind="stable")
        s, k, h = s[order], np.array(k)[order], np.array(h)[order]
        # equal knots (no transition): nudge so that s stays strictly increasing
        for i in range(1, s.size):
            if s[i] <= s[i - 1]:
                s[i] = s[i - 1] + 1e-9
        phi = np.arcsin(np.clip(h / self.cant_base, -1.0, 1.0))
        head = np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * np.diff(s))])
        irr = self.irregularity
        if isinstance(irr, TrackIrregularity):
            ir = irr.kernel_arrays()
        elif irr is not None:           # lateral alignment only
            samples = np.zeros((4, irr.s.size))
            samples[0] = irr.lateral
            ir = (float(irr.s[0]), float(irr.s[1] - irr.s[0]), samples)
        else:
            ir = (0.0, 1.0, np.zeros((4, 4)))
        object.__setattr__(self, "_arrays", (s, k, phi, head, *ir))

    @property
    def arrays(self) -> tuple:
        """(knots s, κ, cant angle, heading, irregularity s0, ds, samples (4, n)) for the
        kernels (samples: alignment, level, cross level, gauge)."""
        return self._arrays

    def at(self, s):
        """κ [1/m], cant angle [rad], alignment irregularity [m] and its slope at ``s`` [m]."""
        out = np.array([layout_at(float(v), *self._arrays) for v in np.atleast_1d(s)])
        return out[:, 0], out[:, 1], out[:, 2], out[:, 3]

    def rails(self, s) -> np.ndarray:
        """Irregular offsets of the rails at ``s`` [m] as the equations of motion see them.

        Returns
        -------
        ndarray, shape (n, 2, 4)
            Per side (left, right): lateral offset [m], its d/ds, vertical offset [m],
            its d/ds (zero without an irregularity).
        """
        _, _, _, _, s0, ds, iy = self._arrays
        out = np.empty((np.atleast_1d(s).size, 2, 4))
        for k, v in enumerate(np.atleast_1d(s)):
            rail_offsets(float(v), s0, ds, iy, out[k])
        return out


def as_layout(track) -> TrackLayout:
    """A :class:`TrackLayout` from a layout or a bare :class:`wheelrail.Track` (tangent)."""
    if isinstance(track, TrackLayout):
        return track
    if isinstance(track, Track):
        return TrackLayout(track)
    raise InputError(f"track must be a wheelrail.Track or a wheelrail.dynamics.TrackLayout, got "
                     f"{type(track).__name__}")
