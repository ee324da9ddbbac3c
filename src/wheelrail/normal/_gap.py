"""Gap helpers shared by the normal methods and the window driver (pure functions).

``h(x, y)`` is an undeformed gap given as a vectorised callable [m]
(contact-plane axes, :mod:`wheelrail.conventions`).
"""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array
from ..errors import InputError

#: Default search box (xmin, xmax, ymin, ymax) [m]: ±20 mm around the origin, i.e. the
#: default ±20 mm lateral window of :func:`wheelrail.geometry.separation` around the rigid
#: contact point, and ±20 mm along the rolling direction (twice the largest wheel–rail
#: semi-axes met in practice).
DEFAULT_SEARCH = (-0.02, 0.02, -0.02, 0.02)

_SAMPLES = 161          # samples per side of the search / zoom boxes


def _evaluate(gap, X, Y) -> np.ndarray:
    """h(X, Y) as a finite float array of the shape of X (InputError otherwise)."""
    val = as_float_array("gap(x, y)", gap(X, Y))
    try:
        return np.broadcast_to(val, np.shape(X))
    except ValueError:
        raise InputError(f"gap(x, y) must return an array of the shape of x {np.shape(X)} "
                         f"(vectorised callable), got shape {val.shape}") from None


def _check_search(search):
    if search is None:
        search = DEFAULT_SEARCH
    box = as_float_array("search", search)
    if box.shape != (4,):
        raise InputError(f"search must be (xmin, xmax, ymin, ymax) [m], got {search!r}")
    xmin, xmax, ymin, ymax = (float(v) for v in box)
    if not (xmax > xmin and ymax > ymin):
        raise InputError(f"search must have xmax > xmin and ymax > ymin, got {search!r}")
    return (xmin, xmax, ymin, ymax)


def _sample(gap, box, n=_SAMPLES):
    """Samples of h on an n × n lattice covering ``box`` (edges included)."""
    x = np.linspace(box[0], box[1], n)
    y = np.linspace(box[2], box[3], n)
    X, Y = np.meshgrid(x, y, indexing="ij")
    return x, y, _evaluate(gap, X, Y)


def _minimum(gap, search):
    """(x, y, h) at the minimum of h in the search box, refined by zooming."""
    x, y, H = _sample(gap, search)
    i, j = np.unravel_index(np.argmin(H), H.shape)
    if i in (0, x.size - 1) or j in (0, y.size - 1):
        raise InputError(
            f"the smallest gap in the search box {search} m lies on its boundary, at "
            f"(x, y) = ({x[i]!r}, {y[j]!r}) m with h = {H[i, j]!r} m: the box does not "
            "contain the minimum of the gap; move or enlarge search=")
    xm, ym, hm = x[i], y[j], H[i, j]
    sx, sy = x[1] - x[0], y[1] - y[0]
    for _ in range(4):       # zoom ×10 per step on ±2 lattice spacings
        box = (max(xm - 2 * sx, search[0]), min(xm + 2 * sx, search[1]),
               max(ym - 2 * sy, search[2]), min(ym + 2 * sy, search[3]))
        xz, yz, Hz = _sample(gap, box, 41)
        k, m = np.unravel_index(np.argmin(Hz), Hz.shape)
        if Hz[k, m] < hm:
            xm, ym, hm = xz[k], yz[m], Hz[k, m]
        sx, sy = sx / 10, sy / 10
    return float(xm), float(ym), float(hm), (x[1] - x[0], y[1] - y[0])


def _principal_curvatures(gap, xm, ym, hx, hy):
    """Principal curvatures c1 ≤ c2 [1/m] of h at (xm, ym): h ≈ h_min + c1 u² + c2 v².

    Central differences with steps ``hx``, ``hy`` [m].
    """
    pts_x = xm + hx * np.array([0, 1, -1, 0, 0, 1, 1, -1, -1])
    pts_y = ym + hy * np.array([0, 0, 0, 1, -1, 1, -1, 1, -1])
    h = _evaluate(gap, pts_x, pts_y)
    hxx = (h[1] + h[2] - 2 * h[0]) / hx**2
    hyy = (h[3] + h[4] - 2 * h[0]) / hy**2
    hxy = (h[5] - h[6] - h[7] + h[8]) / (4 * hx * hy)
    return np.linalg.eigvalsh(0.5 * np.array([[hxx, hxy], [hxy, hyy]]))


