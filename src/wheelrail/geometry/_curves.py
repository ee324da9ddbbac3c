"""Pure array kernels for plane curves used by the geometry package (private).

A :class:`PiecewiseCubic` stores the breakpoints and coefficients of a cubic
spline ``z(u)`` and evaluates value, slope and second derivative with a
single ``searchsorted`` (the hot loop of the contact search evaluates rails
at ~10⁵ points per iteration).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline

from ..errors import ProfileError

__all__ = ["PiecewiseCubic", "sample_profile", "rotate", "curvature"]

#: Spacing [m] at which profiles are re-sampled before the geometry splines are built.
SAMPLE_STEP = 5e-5


@dataclass(frozen=True, eq=False)
class PiecewiseCubic:
    """Cubic spline z(u) on breakpoints ``u`` (shape (n,)) with coefficients ``c`` (4, n-1)."""

    u: np.ndarray
    c: np.ndarray

    def __post_init__(self):
        du = np.diff(self.u)
        uniform = bool(np.all(np.abs(du - du[0]) <= 1e-9 * abs(du[0])))
        object.__setattr__(self, "_h", float(du[0]) if uniform else 0.0)

    @classmethod
    def through(cls, u, z, *, uniform_step: float | None = None) -> "PiecewiseCubic":
        """Interpolating not-a-knot cubic spline through (u, z), u strictly increasing.

        With ``uniform_step`` the spline is re-sampled on an equidistant grid
        (then evaluation needs no search).
        """
        u = np.asarray(u, float)
        s = CubicSpline(u, np.asarray(z, float))
        if uniform_step:
            n = max(int(np.ceil((u[-1] - u[0]) / uniform_step)) + 1, 8)
            uu = np.linspace(u[0], u[-1], n)
            s = CubicSpline(uu, s(uu))
        return cls(np.asarray(s.x), np.asarray(s.c))

    @property
    def u_min(self) -> float:
        return float(self.u[0])

    @property
    def u_max(self) -> float:
        return float(self.u[-1])

    def eval(self, x, order: int = 2):
        """Value, first and second derivative at ``x`` (any shape); extrapolates the end cubics.

        Returns
        -------
        f, f1, f2 : ndarray
            ``order`` < 2 returns only the first ``order + 1`` of them.
        """
        x = np.asarray(x, dtype=float)
        if self._h:
            i = np.clip(((x - self.u[0]) * (1.0 / self._h)).astype(np.intp), 0, self.u.size - 2)
        else:
            i = np.clip(np.searchsorted(self.u, x) - 1, 0, self.u.size - 2)
        dx = x - self.u[i]
        c0, c1, c2, c3 = self.c[0, i], self.c[1, i], self.c[2, i], self.c[3, i]
        f = ((c0 * dx + c1) * dx + c2) * dx + c3
        if order == 0:
            return (f,)
        f1 = (3.0 * c0 * dx + 2.0 * c1) * dx + c2
        if order == 1:
            return f, f1
        f2 = 6.0 * c0 * dx + 2.0 * c1
        return f, f1, f2


def sample_profile(profile, step: float = SAMPLE_STEP):
    """Points (y, z) of a profile on an equidistant grid over its whole extent [m].

    ``profile`` is anything with ``y_min``, ``y_max`` and a vectorised
    ``__call__`` (a :class:`wheelrail.profiles.Profile`).
    """
    y0, y1 = float(profile.y_min), float(profile.y_max)
    n = max(int(np.ceil((y1 - y0) / step)) + 1, 8)
    y = np.linspace(y0, y1, n)
    z = np.asarray(profile(y), dtype=float)
    if not np.all(np.isfinite(z)):
        bad = y[~np.isfinite(z)][0]
        raise ProfileError(f"profile {getattr(profile, 'name', '')!r} is not finite at y = {bad!r} m")
    return y, z


def rotate(y, z, angle: float):
    """Rotate points counter-clockwise by ``angle`` [rad] about the origin of the (y, z) plane."""
    c, s = np.cos(angle), np.sin(angle)
    return c * y - s * z, s * y + c * z


def curvature(d1, d2):
    """Signed curvature z''/(1 + z'²)^(3/2) of a graph z(u) [1/m]."""
    return d2 / (1.0 + d1 * d1) ** 1.5
