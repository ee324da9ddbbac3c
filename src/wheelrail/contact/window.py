"""Automatic choice of the potential contact area (the BEM window) from the gap.

The grid solvers (:func:`~wheelrail.normal.bem.solve_normal`,
:func:`~wheelrail.contact.solve_gap`) need a rectangular window that
contains the whole contact area. For an arbitrary undeformed gap h(x, y)
(given as a callable) the window is found as follows:

1. **Minimum of h.** h is sampled on the ``search`` box and the smallest
   sample is refined by zooming; a minimum on the boundary of the box means
   the box does not contain the minimum (``InputError``).
2. **Approach δ.** Prescribed (``penetration``), or, for a prescribed
   ``load``, estimated from Hertz's theory with the principal curvatures of h
   at its minimum (central differences at the scale of the Hertz patch,
   repeated twice so that a non-quadratic gap is probed where it matters).
3. **Rigid interpenetration region** {h < δ}. The elastic contact area lies
   inside it for any gap (convex or not) at the same δ: in contact
   e = h − δ + u_n = 0 and u_n ≥ 0 (positive influence kernel, p ≥ 0), so
   h ≤ δ there. (With dissimilar materials, K ≠ 0, the tangential tractions add
   a normal displacement of either sign, and the contact may leave the region
   slightly; :func:`solve_gap_auto` checks for that.) Its bounding box
   is found by sampling, zooming on the box until the region fills at least
   half of the sampled box in both directions.
4. **Window.** The bounding box, scaled by ``margin`` about its centre and
   clipped to the ``search`` box, is divided into an odd number of elements
   along each side, ``elements`` (made odd) along the longer side and the
   same element size (aspect ≈ 1) along the shorter one (at least 5).

Several separated minima (e.g. tread and flange contact) are covered by
**one** window: the bounding box of all parts of {h < δ}. The elements are
then shared by all patches; :func:`contact_patches` counts and separates the
patches of a solution afterwards.

:func:`solve_gap_auto` chains window → :func:`~wheelrail.contact.solve_gap`
and, when the computed contact touches the window edge (``truncated``; always
possible for a load-controlled non-Hertzian gap, whose δ is only estimated),
moves the touched edges outwards by a quarter of the window size and solves
again (at most ``max_enlarge`` times, the same number of elements each time).

References
----------
.. [1] K.L. Johnson, *Contact Mechanics*, CUP 1985, eqs. (3.64)–(3.66)
   (Hertz estimate of δ for a prescribed load).
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, §5.1 (the potential contact area must contain the true
   contact area; it is usually taken from the rigid interpenetration).
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np

from .._validation import as_float_array, integer, positive
from ..errors import InputError, NoContactError
from ..halfspace.grid import Grid
from ..normal.bem import ContactTruncatedWarning
from ..normal._gap import (_SAMPLES, DEFAULT_SEARCH, _check_search, _evaluate, _minimum,
                            _principal_curvatures, _sample)
from ..normal.hertz import hertz
from .coupled import solve_gap

__all__ = ["DEFAULT_SEARCH", "contact_patches", "potential_contact_grid", "solve_gap_auto"]

_ENLARGE = 0.25         # a touched window edge moves out by this fraction of the window size
_MIN_ELEMENTS = 5       # fewest elements along the shorter side of a window


# --------------------------------------------------------------------------- helpers
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
        load = float(positive("load", load))
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
def potential_contact_grid(gap, *, penetration=None, load=None, materials=None, elements=60,
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
    load : float, optional
        Prescribed normal force [N] > 0; δ is then estimated by Hertz's theory
        from the principal curvatures of h at its minimum (needs ``materials``).
        Exactly one of ``penetration`` and ``load``.
    materials : Material or MaterialPair, optional
        Needed with ``load``.
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
        with the same ``penetration`` or ``load``).

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
    prescribed load the window rests on a Hertz estimate of δ; use
    :func:`solve_gap_auto`, which checks the solution for truncation and
    enlarges the window. Separate minima below δ are covered by one window
    (bounding box of all of them).

    Examples
    --------
    >>> import wheelrail as wr
    >>> from wheelrail.contact import potential_contact_grid
    >>> from wheelrail.normal.bem import solve_normal
    >>> h = lambda x, y: 1.0 * x**2 + 2.0 * y**2
    >>> grid, h0 = potential_contact_grid(h, load=10e3, materials=wr.STEEL, elements=31)
    >>> sol = solve_normal(grid, h0, wr.STEEL, load=10e3)
    >>> sol.truncated, abs(sol.p_max / wr.hertz(10e3, 1.0, 2.0, wr.STEEL).p0 - 1) < 0.03
    (False, True)
    """
    w = _window(gap, penetration, load, materials, elements, margin, search)
    grid = w["grid"]
    return grid, np.array(_evaluate(gap, grid.X, grid.Y))


def contact_patches(solution):
    """Separate the contact area of a solution into connected patches.

    Elements are connected through their edges (4-neighbourhood; diagonal
    neighbours are separate patches, as in :func:`contact_outline`).

    Parameters
    ----------
    solution : NormalSolution or GapSolution
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


def solve_gap_auto(gap, materials, *, load=None, penetration=None, creepage=None, mu=None,
                   elements=60, margin=1.2, search=None, max_enlarge=4, **solve_gap_options):
    """Solve the contact of an arbitrary gap on an automatically chosen window.

    Window from :func:`potential_contact_grid`, then
    :func:`~wheelrail.contact.solve_gap`; while the contact touches the
    window edge (``normal.truncated``), each touched edge is moved out by a
    quarter of the window size (clipped to ``search``; same ``elements`` rule,
    so the elements grow) and the problem is solved again.

    Parameters
    ----------
    gap : callable
        ``gap(x, y) -> h`` [m], vectorised (see :func:`potential_contact_grid`).
    materials : Material or MaterialPair
    load, penetration : float
        Exactly one: normal force [N] or approach δ [m] (same datum as h).
    creepage, mu
        Tangential problem, as in :func:`~wheelrail.contact.solve_gap`.
    elements, margin, search
        First window, as in :func:`potential_contact_grid`.
    max_enlarge : int
        Largest number of enlargements (>= 0).
    **solve_gap_options
        Passed on to :func:`~wheelrail.contact.solve_gap` (``tol``,
        ``shift``, ``force``, ``on_fail``, ...).

    Returns
    -------
    GapSolution
        Its ``grid`` is the final window. ``normal.info`` gains
        ``window_enlargements`` (int), ``contact_patches`` (int, connected
        components of the contact area, :func:`contact_patches`),
        ``patch_loads`` (list of N, decreasing), ``approach_estimate`` (δ used
        for the first window [m]) and ``gap_minimum`` ((x, y, h) [m]).

    Raises
    ------
    InputError, NoContactError
        As :func:`potential_contact_grid` and :func:`solve_gap`.

    Warns
    -----
    ContactTruncatedWarning
        If the contact still touches the window edge after ``max_enlarge``
        enlargements (or the window cannot grow inside ``search``); the
        message gives the final window.

    Examples
    --------
    >>> import wheelrail as wr
    >>> from wheelrail.contact import solve_gap_auto
    >>> sol = solve_gap_auto(lambda x, y: x**2 + 2 * y**2, wr.STEEL, load=10e3, elements=31)
    >>> sol.normal.truncated, sol.normal.info["contact_patches"]
    (False, 1)
    """
    max_enlarge = integer("max_enlarge", max_enlarge, 0)
    w = _window(gap, penetration, load, materials, elements, margin, search)
    grid, search = w["grid"], w["search"]
    enlargements = 0
    while True:
        h0 = np.array(_evaluate(gap, grid.X, grid.Y))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ContactTruncatedWarning)
            sol = solve_gap(grid, h0, materials, load=load, penetration=penetration,
                            creepage=creepage, mu=mu, **solve_gap_options)
        c = sol.normal.contact
        if not sol.normal.truncated or enlargements >= max_enlarge:
            break
        b = list(grid.bounds)
        lx, ly = b[1] - b[0], b[3] - b[2]
        if c[0].any():
            b[0] = max(b[0] - _ENLARGE * lx, search[0])
        if c[-1].any():
            b[1] = min(b[1] + _ENLARGE * lx, search[1])
        if c[:, 0].any():
            b[2] = max(b[2] - _ENLARGE * ly, search[2])
        if c[:, -1].any():
            b[3] = min(b[3] + _ENLARGE * ly, search[3])
        if np.allclose(b, grid.bounds, rtol=0, atol=1e-12 * max(lx, ly)):
            break           # the touched edges are on the search box: cannot grow
        grid = _grid_on(tuple(b), w["elements"])
        enlargements += 1
    if sol.normal.truncated:
        g = sol.grid
        warnings.warn(
            f"the contact still reaches the edge of the window after {enlargements} "
            f"enlargement(s): final window {tuple(round(v, 9) for v in g.bounds)} m, "
            f"{g.nx}x{g.ny} elements of {g.dx:.3g} x {g.dy:.3g} m (search box {search} m); "
            "increase max_enlarge= or search=, the result is truncated",
            ContactTruncatedWarning, stacklevel=2)
    _, loads = contact_patches(sol.normal)
    info = dict(sol.normal.info)
    info.update(window_enlargements=enlargements, contact_patches=int(loads.size),
                patch_loads=[float(v) for v in loads], approach_estimate=w["approach"],
                gap_minimum=w["minimum"])
    return dataclasses.replace(sol, normal=dataclasses.replace(sol.normal, info=info))
