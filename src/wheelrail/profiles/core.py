"""The :class:`Profile` — a wheel or rail cross-section z(y) in its own profile frame.

Coordinate convention (kept by every reader, writer and generator)
-------------------------------------------------------------------
A profile is a single-valued curve ``z(y)`` in its own *profile frame*, in
metres:

* ``y`` — lateral, strictly increasing along the stored points;
* ``z`` — vertical, **positive upward** (it is the surface height).

Rail
    ``y`` positive towards the **field side** (outside of the track), origin
    on the centre line of the rail head, ``z = 0`` at the top of the rail. The
    rail surface is the *upper* boundary of the rail body; a crowned head has
    ``z'' < 0``. An *uncanted* rail is described; cant (inclination 1:n
    towards the track centre) is applied with
    ``profile.rotated(np.arctan(1/n))`` — a positive (counter-clockwise)
    rotation in this frame tilts the top of the rail towards negative ``y``
    (the gauge side / track centre), so that the running surface then rises
    towards the field side with slope ``1/n``.

Wheel
    ``y`` positive towards the **field side** (away from the flange), so the
    flange lies at negative ``y``; origin on the tape circle (nominal rolling
    circle; for S1002 70 mm from the back of the flange) with ``z = 0`` there.
    ``z(y)`` is the *lower* boundary of the wheel: the flange tip has the most
    negative ``z``; a conical tread whose radius decreases towards the field
    side has ``z' > 0``.

Profiles read from files (Simpack/MiniProf often use ``z`` downward, mm and
other origins) are converted to this convention by the readers in
:mod:`wheelrail.profiles.io`. A measured contour is often not single-valued
(vertical flange back or rim face, closed contour, overhanging gauge lip);
the readers keep only the part visible from the contact side as z(y) and
raise :class:`~wheelrail.errors.ProfileError` when that would drop more
than half of the points.

Evaluation
----------
``Profile(y)`` evaluates a cubic spline through the points (``smoothing = 0``)
or a smoothing spline (``smoothing > 0``). Outside ``[y_min, y_max]`` the
evaluation returns NaN (no extrapolation); check ``y_min``/``y_max`` or use
``contains(y)``.

References
----------
.. [1] EN 13715:2006+A1:2010, *Railway applications — Wheelsets and bogies —
   Wheels — Tread profile* (S1002).
.. [2] EN 13674-1:2011, *Railway applications — Track — Rail — Part 1* (60E1, 54E1).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np
from scipy.interpolate import CubicSpline, make_smoothing_spline

from ..errors import ProfileError

__all__ = ["Profile", "ProfileWarning", "KINDS", "MIN_POINTS", "MAX_PLAUSIBLE_WIDTH"]

#: Allowed values of :attr:`Profile.kind`.
KINDS = ("wheel", "rail")
#: Minimum number of distinct points of a profile.
MIN_POINTS = 4
#: A profile wider (or higher) than this [m] is taken as a unit error ("looks like mm").
MAX_PLAUSIBLE_WIDTH = 2.0


class ProfileWarning(UserWarning):
    """A profile was repaired on construction (e.g. duplicated points removed)."""


def _as_points(name: str, value) -> np.ndarray:
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ProfileError(f"profile {name} must be numeric, got {value!r:.80}") from exc
    if arr.ndim != 1:
        raise ProfileError(f"profile {name} must be one-dimensional, got shape {arr.shape}")
    return arr


def _clean_points(y: np.ndarray, z: np.ndarray, label: str) -> tuple[np.ndarray, np.ndarray]:
    """Validate points and return them with y strictly increasing (see Profile)."""
    if y.shape != z.shape:
        raise ProfileError(f"{label}: y and z have different lengths ({y.size} and {z.size})")
    bad = ~(np.isfinite(y) & np.isfinite(z))
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        raise ProfileError(f"{label}: point {i} is not finite (y={float(y[i])}, z={float(z[i])})")
    if y.size < MIN_POINTS:
        raise ProfileError(f"{label}: needs at least {MIN_POINTS} points, got {y.size}")
    width = float(np.ptp(y))
    height = float(np.ptp(z))
    if width == 0.0:
        raise ProfileError(f"{label}: zero width (all points have y = {float(y[0]):.9g} m)")
    if width > MAX_PLAUSIBLE_WIDTH or height > MAX_PLAUSIBLE_WIDTH:
        raise ProfileError(
            f"{label}: width {width:.4g} m x height {height:.4g} m is implausible for a wheel or "
            f"rail profile — it looks like mm; divide the coordinates by 1000")
    # exact duplicates of the previous point: remove with a warning
    dup = (np.diff(y) == 0.0) & (np.diff(z) == 0.0)
    if np.any(dup):
        keep = np.concatenate(([True], ~dup))
        warnings.warn(f"{label}: removed {int(dup.sum())} duplicated point(s) "
                      f"(first at index {int(np.flatnonzero(dup)[0]) + 1})", ProfileWarning,
                      stacklevel=4)
        y, z = y[keep], z[keep]
        if y.size < MIN_POINTS:
            raise ProfileError(f"{label}: needs at least {MIN_POINTS} distinct points, "
                               f"got {y.size}")
    dy = np.diff(y)
    if np.all(dy <= 0.0):  # stored in decreasing y: same curve, reverse the order
        y, z, dy = y[::-1], z[::-1], -dy[::-1]
    if np.any(dy > 0.0) and np.any(dy < 0.0):
        sign = np.sign(dy)
        major = 1.0 if np.sum(sign > 0) >= np.sum(sign < 0) else -1.0
        i = int(np.flatnonzero((sign != major) & (sign != 0.0))[0])
        raise ProfileError(
            f"{label}: points are not sorted in y — direction reversal (zig-zag or self-crossing "
            f"contour) at point {i + 1} (y = {float(y[i + 1]):.9g} m after y = {float(y[i]):.9g} "
            f"m); z(y) must be single-valued with y strictly monotone")
    if np.any(dy == 0.0):
        i = int(np.flatnonzero(dy == 0.0)[0])
        raise ProfileError(
            f"{label}: vertical segment between points {i} and {i + 1} (y = {float(y[i]):.9g} m, "
            f"z = {float(z[i]):.9g} and {float(z[i + 1]):.9g} m); z(y) is not single-valued there")
    return y, z


@dataclass(frozen=True, eq=False)
class Profile:
    """Wheel or rail cross-section ``z(y)`` in its profile frame (SI; z up).

    Parameters
    ----------
    y : array_like, shape (n,)
        Lateral coordinates [m], strictly monotone (points given in decreasing
        ``y`` are reversed); n >= 4 distinct points.
    z : array_like, shape (n,)
        Surface height [m], positive upward (see the module docstring for the
        origin and the side conventions of wheels and rails).
    kind : {"rail", "wheel"}
    name : str
        Free label (file name, standard designation).
    smoothing : float
        Smoothing length [m] of a smoothing spline (features shorter than
        about this length are smoothed out; the spline penalty is
        ``lam = smoothing**4 / mean point spacing`` in
        :func:`scipy.interpolate.make_smoothing_spline`). 0 (default): the
        interpolating (not-a-knot) cubic spline through the points.
    meta : mapping
        Metadata (e.g. ``nominal_radius`` [m] of a wheel, ``source`` file,
        ``flange_thickness``); not used in comparisons.

    Raises
    ------
    ProfileError
        NaN/inf, fewer than 4 points, zero width, implausible size (mm
        passed as m), vertical segments or direction reversals in ``y``
        (zig-zags, self-crossing or closed contours), unknown kind.

    Warns
    -----
    ProfileWarning
        Consecutive duplicated points are removed.
    """

    y: np.ndarray
    z: np.ndarray
    kind: str = "rail"
    name: str = ""
    smoothing: float = 0.0
    meta: Mapping[str, Any] = field(default_factory=dict, repr=False)
    _spline: Any = field(init=False, repr=False)

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ProfileError(f"profile kind must be one of {KINDS}, got {self.kind!r}")
        label = f"{self.kind} profile {self.name!r}" if self.name else f"{self.kind} profile"
        try:
            smoothing = float(self.smoothing)
        except (TypeError, ValueError) as exc:
            raise ProfileError(f"{label}: smoothing must be a number, got {self.smoothing!r}") \
                from exc
        if not np.isfinite(smoothing) or smoothing < 0.0:
            raise ProfileError(f"{label}: smoothing must be finite and >= 0, got {smoothing!r}")
        with np.errstate(over="ignore", invalid="ignore"):
            y, z = _clean_points(_as_points("y", self.y), _as_points("z", self.z), label)
        if smoothing > float(y[-1] - y[0]):
            raise ProfileError(f"{label}: smoothing length {smoothing!r} m exceeds the profile "
                               f"width {float(y[-1] - y[0]):.6g} m")
        y.setflags(write=False)
        z.setflags(write=False)
        if smoothing == 0.0:
            spline = CubicSpline(y, z, extrapolate=False)
        else:
            lam = smoothing ** 4 / float(np.mean(np.diff(y)))
            try:
                spline = make_smoothing_spline(y, z, lam=lam)
            except (ValueError, np.linalg.LinAlgError) as exc:
                raise ProfileError(f"{label}: smoothing spline failed ({exc})") from exc
        object.__setattr__(self, "y", y)
        object.__setattr__(self, "z", z)
        object.__setattr__(self, "smoothing", smoothing)
        object.__setattr__(self, "meta", dict(self.meta))
        object.__setattr__(self, "_spline", (spline, spline.derivative(1), spline.derivative(2)))

    # ------------------------------------------------------------------ evaluation
    def _eval(self, which: int, y):
        yy = np.asarray(y, dtype=float)
        out = np.full(yy.shape, np.nan)
        inside = (yy >= self.y[0]) & (yy <= self.y[-1])
        if np.any(inside):
            out[inside] = self._spline[which](yy[inside])
        return float(out) if out.ndim == 0 else out

    def __call__(self, y):
        """Surface height z(y) [m]; NaN outside ``[y_min, y_max]``. Shape of ``y``."""
        return self._eval(0, y)

    def slope(self, y):
        """Slope dz/dy [-]; NaN outside ``[y_min, y_max]``."""
        return self._eval(1, y)

    def curvature(self, y):
        """Signed curvature ``z'' / (1 + z'^2)^(3/2)`` [1/m].

        Positive where the surface is concave seen from above (a valley),
        negative on a crowned rail head (radius R → curvature −1/R). NaN
        outside ``[y_min, y_max]``.
        """
        d1 = self._eval(1, y)
        d2 = self._eval(2, y)
        return d2 / (1.0 + np.square(d1)) ** 1.5

    def contains(self, y):
        """True where ``y`` lies inside ``[y_min, y_max]``."""
        yy = np.asarray(y, dtype=float)
        return (yy >= self.y[0]) & (yy <= self.y[-1])

    # ------------------------------------------------------------------ extent
    @property
    def y_min(self) -> float:
        """Smallest lateral coordinate [m]."""
        return float(self.y[0])

    @property
    def y_max(self) -> float:
        """Largest lateral coordinate [m]."""
        return float(self.y[-1])

    @property
    def width(self) -> float:
        """``y_max - y_min`` [m]."""
        return float(self.y[-1] - self.y[0])

    def __len__(self) -> int:
        return int(self.y.size)

    # ------------------------------------------------------------------ copies
    def _replace(self, y, z, **changes) -> "Profile":
        kw = dict(kind=self.kind, name=self.name, smoothing=self.smoothing, meta=self.meta)
        kw.update(changes)
        return Profile(y, z, **kw)

    def mirrored(self) -> "Profile":
        """Profile mirrored about ``y = 0`` (``y -> -y``), e.g. right ↔ left side."""
        return self._replace(-self.y[::-1], self.z[::-1].copy())

    def shifted(self, dy: float = 0.0, dz: float = 0.0) -> "Profile":
        """Profile translated by ``dy``, ``dz`` [m]."""
        return self._replace(self.y + float(dy), self.z + float(dz))

    def rotated(self, angle: float, about=(0.0, 0.0)) -> "Profile":
        """Profile rotated counter-clockwise by ``angle`` [rad] in the (y, z) plane.

        ``y' = y0 + cos(a)(y - y0) - sin(a)(z - z0)``,
        ``z' = z0 + sin(a)(y - y0) + cos(a)(z - z0)``. The points are rotated
        (not the spline). For a rail, ``rotated(np.arctan(1/40))`` applies an
        inclination of 1:40 towards the track centre (top of rail moves to
        negative ``y``); ``rotated(-np.arctan(1/40))`` removes it.

        Raises
        ------
        ProfileError
            If the rotated points are no longer single-valued in ``y`` (steep
            flanks rotated past vertical); trim the profile first.
        """
        a = float(angle)
        if not np.isfinite(a):
            raise ProfileError(f"rotation angle must be finite, got {angle!r}")
        y0, z0 = (float(v) for v in about)
        c, s = np.cos(a), np.sin(a)
        dy, dz = self.y - y0, self.z - z0
        return self._replace(y0 + c * dy - s * dz, z0 + s * dy + c * dz)

    def resampled(self, n: int | None = None, step: float | None = None) -> "Profile":
        """Profile re-sampled at equidistant ``y`` on ``[y_min, y_max]``.

        Give ``n`` (number of points, >= 4) or ``step`` [m] (not both); by
        default the current number of points. The new points lie on the
        current spline (smoothed if ``smoothing > 0``); the result is an
        interpolating profile (``smoothing = 0``).
        """
        if n is not None and step is not None:
            raise ProfileError("resampled: give n or step, not both")
        if step is not None:
            step = float(step)
            if not np.isfinite(step) or step <= 0.0:
                raise ProfileError(f"resampled: step must be > 0, got {step!r}")
            n = int(np.ceil(self.width / step - 1e-9)) + 1
        if n is None:
            n = len(self)
        n = int(n)
        if n < MIN_POINTS:
            raise ProfileError(f"resampled: needs at least {MIN_POINTS} points, got n={n}")
        yn = np.linspace(self.y[0], self.y[-1], n)
        zn = self._spline[0](yn)
        return self._replace(yn, zn, smoothing=0.0)

    # ------------------------------------------------------------------ comparison
    def __eq__(self, other):
        if not isinstance(other, Profile):
            return NotImplemented
        return (self.kind == other.kind and self.name == other.name
                and self.smoothing == other.smoothing
                and np.array_equal(self.y, other.y) and np.array_equal(self.z, other.z))

    def __hash__(self):
        return hash((self.kind, self.name, self.smoothing, self.y.tobytes(), self.z.tobytes()))

    def __repr__(self):
        return (f"Profile(kind={self.kind!r}, name={self.name!r}, n={len(self)}, "
                f"y=[{self.y_min:.6g}, {self.y_max:.6g}] m, smoothing={self.smoothing:g})")
