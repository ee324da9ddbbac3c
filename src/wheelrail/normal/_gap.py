"""Potential contact area (the BEM window) from an arbitrary gap; patches of a solution.

Shared by the boundary-element normal method and the coupled driver
:func:`wheelrail.contact.solve_gap_auto`; the method is described in
:mod:`wheelrail.contact.window`.

``h(x, y)`` is an undeformed gap given as a vectorised callable [m]
(contact-plane axes, :mod:`wheelrail.conventions`).
"""

from __future__ import annotations

import math

import numpy as np

from .._validation import as_float_array, integer, positive
from ..errors import InputError, NoContactError
from ..halfspace.grid import Grid
from ..hertzian import hertz

#: Default search box (xmin, xmax, ymin, ymax) [m]: ±20 mm around the origin, i.e. the
#: default ±20 mm lateral window of :func:`wheelrail.geometry.separation` around the rigid
#: contact point, and ±20 mm along the rolling direction (twice the largest wheel–rail
#: semi-axes met in practice).
DEFAULT_SEARCH = (-0.02, 0.02, -0.02, 0.02)

_SAMPLES = 161          # samples per side of the search / zoom boxes
_ENLARGE = 0.25         # a touched window edge moves out by this fraction of the window size
_MIN_ELEMENTS = 5       # fewest elements along the shorter side of a window


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


def _hertz_penetration(gap, load, materials, xm, ym, spacing):
    """Hertz estimate of δ for ``load`` from the curvatures of h at its minimum."""

    hx, hy = spacing
    for _ in range(3):
        c = _principal_curvatures(gap, xm, ym, hx, hy)
        if not c[1] > 0:
            raise InputError(
                f"the gap has no positive curvature at its minimum (x, y) = ({xm!r}, {ym!r}) m "
                f"(principal curvatures {c.tolist()} 1/m): δ cannot be estimated from the load; "
                "give penetration= instead")
        c = np.maximum(c, 1e-3 * c[1])      # flat direction: bounded, the enlargement loop fixes it
        hc = hertz(load, c[0], c[1], materials)
        hx = hy = 0.5 * math.sqrt(float(hc.a) * float(hc.b))
    return float(hc.penetration)


def _rigid_box(gap, delta, search, xm, ym):
    """Bounding box (xmin, xmax, ymin, ymax) of {h < δ} inside the search box."""
    box = search
    for _ in range(12):
        x, y, H = _sample(gap, box)
        sx, sy = x[1] - x[0], y[1] - y[0]
        mask = H < delta
        if not mask.any():      # region finer than the lattice: zoom on the minimum
            box = (max(xm - 2 * sx, search[0]), min(xm + 2 * sx, search[1]),
                   max(ym - 2 * sy, search[2]), min(ym + 2 * sy, search[3]))
            continue
        rows, cols = np.nonzero(mask.any(axis=1))[0], np.nonzero(mask.any(axis=0))[0]
        i0, i1, j0, j1 = rows[0], rows[-1], cols[0], cols[-1]
        edges = {"xmin": (i0 == 0, box[0] <= search[0]),
                 "xmax": (i1 == x.size - 1, box[1] >= search[1]),
                 "ymin": (j0 == 0, box[2] <= search[2]),
                 "ymax": (j1 == y.size - 1, box[3] >= search[3])}
        hit = [k for k, (touch, outer) in edges.items() if touch and outer]
        if hit:
            raise InputError(
                f"the region where the gap is below the approach δ = {delta!r} m reaches the "
                f"{'/'.join(hit)} edge of the search box {search} m: the contact may extend "
                "beyond it; enlarge search=")
        new = [max(x[i0] - sx, search[0]), min(x[i1] + sx, search[1]),
               max(y[j0] - sy, search[2]), min(y[j1] + sy, search[3])]
        grow = False      # region touches an inner zoom edge: push that edge out
        if i0 == 0:
            new[0], grow = max(box[0] - 0.25 * (box[1] - box[0]), search[0]), True
        if i1 == x.size - 1:
            new[1], grow = min(box[1] + 0.25 * (box[1] - box[0]), search[1]), True
        if j0 == 0:
            new[2], grow = max(box[2] - 0.25 * (box[3] - box[2]), search[2]), True
        if j1 == y.size - 1:
            new[3], grow = min(box[3] + 0.25 * (box[3] - box[2]), search[3]), True
        filled = (new[1] - new[0] >= 0.5 * (box[1] - box[0])
                  and new[3] - new[2] >= 0.5 * (box[3] - box[2]))
        box = tuple(new)
        if filled and not grow:
            return box
    return box


def _grid_on(bounds, elements) -> Grid:
    """Grid on ``bounds``: odd element counts, ``elements`` (made odd) along the longer side."""
    lx, ly = bounds[1] - bounds[0], bounds[3] - bounds[2]
    n_long = elements + 1 - elements % 2
    d = max(lx, ly) / n_long

    def odd(length):
        n = max(round(length / d), _MIN_ELEMENTS)
        return n + 1 - n % 2

    nx, ny = (n_long, odd(ly)) if lx >= ly else (odd(lx), n_long)
    return Grid.from_bounds(*bounds, nx=nx, ny=ny)


def _scaled(box, margin, search):
    cx, cy = 0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3])
    hx, hy = 0.5 * margin * (box[1] - box[0]), 0.5 * margin * (box[3] - box[2])
    return (max(cx - hx, search[0]), min(cx + hx, search[1]),
            max(cy - hy, search[2]), min(cy + hy, search[3]))


def _window(gap, penetration, load, materials, elements, margin, search):
    """Shared front end: checks, δ, rigid box, first window. Returns a dict."""
    if not callable(gap):
        raise InputError(f"gap must be a callable h(x, y) -> gap [m], got {type(gap).__name__}")
    if (load is None) == (penetration is None):
        raise InputError("give exactly one of load= and penetration= "
                         f"(got load={load!r}, penetration={penetration!r})")
    elements = integer("elements", elements, 3)
    margin = float(positive("margin", margin))
    search = _check_search(search)
    xm, ym, hmin, spacing = _minimum(gap, search)
    if load is not None:
        load = float(positive("Fn", load))
        if materials is None:
            raise InputError("materials= is needed to estimate the approach from load=")
        delta = _hertz_penetration(gap, load, materials, xm, ym, spacing)
        delta_ref = hmin + delta
    else:
        delta = delta_ref = float(as_float_array("penetration", penetration))
        if not hmin < delta:
            raise NoContactError(
                f"no contact: the gap is >= the penetration everywhere in the search box "
                f"{search} m (minimum gap {hmin!r} m at (x, y) = ({xm!r}, {ym!r}) m, "
                f"penetration {delta!r} m)")
    box = _rigid_box(gap, delta_ref, search, xm, ym)
    bounds = _scaled(box, margin, search)
    grid = _grid_on(bounds, elements)
    return {"grid": grid, "search": search, "rigid_box": box, "minimum": (xm, ym, hmin),
            "approach": delta_ref, "elements": elements}


# --------------------------------------------------------------------------- public
def potential_contact_grid(gap, *, penetration=None, Fn=None, materials=None, elements=60,
                           margin=1.2, search=None):
    """Grid (potential contact area) and gap array chosen from an arbitrary gap function.

    Parameters
    ----------
    gap : callable
        ``gap(x, y) -> h`` [m], the undeformed separation of the surfaces,
        vectorised over arrays of equal shape (x rolling direction, y lateral,
        m). E.g. an analytic function, or an interpolant of
        :func:`wheelrail.geometry.undeformed_distance` data
        (``scipy.interpolate.RegularGridInterpolator`` wrapped as
        ``lambda x, y: f(np.stack([x, y], -1))``). Only evaluated inside ``search``.
    penetration : float, optional
        Prescribed approach δ [m], same datum as ``h`` (contact where h < δ).
    Fn : float, optional
        Prescribed normal force [N] > 0; δ is then estimated by Hertz's theory
        from the principal curvatures of h at its minimum (needs ``materials``).
        Exactly one of ``penetration`` and ``Fn``.
    materials : Material or MaterialPair, optional
        Needed with ``Fn``.
    elements : int
        Elements along the longer side of the window (made odd), >= 3; the
        element size is the same along the shorter side (aspect ≈ 1, odd count,
        at least 5).
    margin : float
        Window half-size / half-size of the bounding box of {h < δ}, > 0
        (values < 1 give a window smaller than the rigid region).
    search : (xmin, xmax, ymin, ymax), optional
        Box [m] where the minimum and the contact are looked for, and to which
        the window is clipped. Default :data:`DEFAULT_SEARCH` (±20 mm around
        the origin, e.g. the contact point of
        :func:`wheelrail.geometry.separation`).

    Returns
    -------
    grid : Grid
    gap : ndarray, shape (nx, ny)
        h at the element centres [m] (for :func:`solve_normal` / :func:`solve_gap`
        with the same ``penetration`` or ``Fn``).

    Raises
    ------
    InputError
        Bad arguments; the minimum of h lies on the boundary of ``search``; the
        region {h < δ} reaches the boundary of ``search``.
    NoContactError
        With ``penetration``: h ≥ δ in the whole search box.

    Notes
    -----
    For a prescribed penetration and ``margin >= 1`` the window contains
    {h < δ}, hence the elastic contact (u_n ≥ 0 in e = h − δ + u_n; exact for
    quasi-identical materials, see the module notes for K ≠ 0). For a
    prescribed Fn the window rests on a Hertz estimate of δ; use
    :func:`solve_gap_auto`, which checks the solution for truncation and
    enlarges the window. Separate minima below δ are covered by one window
    (bounding box of all of them).

    Examples
    --------
    >>> import wheelrail as wr
    >>> from wheelrail.contact import potential_contact_grid
    >>> from wheelrail.normal.bem import solve_normal
    >>> h = lambda x, y: 1.0 * x**2 + 2.0 * y**2
    >>> grid, h0 = potential_contact_grid(h, Fn=10e3, materials=wr.STEEL, elements=31)
    >>> sol = solve_normal(grid, h0, wr.STEEL, Fn=10e3)
    >>> sol.truncated, abs(sol.p_max / wr.hertz(10e3, 1.0, 2.0, wr.STEEL).p0 - 1) < 0.03
    (False, True)
    """
    w = _window(gap, penetration, Fn, materials, elements, margin, search)
    grid = w["grid"]
    return grid, np.array(_evaluate(gap, grid.X, grid.Y))


def contact_patches(solution):
    """Separate the contact area of a solution into connected patches.

    Elements are connected through their edges (4-neighbourhood; diagonal
    neighbours are separate patches, as in :func:`contact_outline`).

    Parameters
    ----------
    solution : NormalResult or GapResult
        Anything with ``grid``, ``contact`` (nx, ny) bool and ``pressure`` (nx, ny) [Pa].

    Returns
    -------
    labels : ndarray of int, shape (nx, ny)
        0 outside the contact, k = 1..n on patch k; patches numbered by
        decreasing normal force.
    loads : ndarray, shape (n,)
        Normal force of each patch [N] (``len(loads)`` is the number of patches).
    """
    from scipy import ndimage

    contact = np.asarray(solution.contact, dtype=bool)
    p = np.asarray(solution.pressure, dtype=float)
    raw, n = ndimage.label(contact)
    if n == 0:
        return np.zeros(contact.shape, dtype=int), np.zeros(0)
    loads = ndimage.sum_labels(p, raw, index=np.arange(1, n + 1)) * solution.grid.element_area
    order = np.argsort(-loads, kind="stable")
    relabel = np.zeros(n + 1, dtype=int)
    relabel[order + 1] = np.arange(1, n + 1)
    return relabel[raw], np.asarray(loads)[order]


def _enlarged_bounds(grid, contact, search):
    """Window bounds with each edge that the ``contact`` mask touches moved out by
    ``_ENLARGE`` of the window size (clipped to ``search``); ``None`` if nothing can move."""
    b = list(grid.bounds)
    lx, ly = b[1] - b[0], b[3] - b[2]
    if contact[0].any():
        b[0] = max(b[0] - _ENLARGE * lx, search[0])
    if contact[-1].any():
        b[1] = min(b[1] + _ENLARGE * lx, search[1])
    if contact[:, 0].any():
        b[2] = max(b[2] - _ENLARGE * ly, search[2])
    if contact[:, -1].any():
        b[3] = min(b[3] + _ENLARGE * ly, search[3])
    if np.allclose(b, grid.bounds, rtol=0, atol=1e-12 * max(lx, ly)):
        return None             # the touched edges are on the search box: cannot grow
    return tuple(b)
