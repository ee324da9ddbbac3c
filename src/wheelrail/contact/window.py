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
import warnings

import numpy as np

from .._validation import integer
from ..normal._gap import (
    DEFAULT_SEARCH,
    _enlarged_bounds,
    _evaluate,
    _grid_on,
    _window,
    contact_patches,
    potential_contact_grid,
)
from ..normal.bem import ContactTruncatedWarning
from ..tangential.exact import solve_gap

__all__ = ["DEFAULT_SEARCH", "contact_patches", "potential_contact_grid", "solve_gap_auto"]



# --------------------------------------------------------------------------- helpers
def solve_gap_auto(gap, materials, *, Fn=None, penetration=None, creepage=None, mu=None,
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
    Fn, penetration : float
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
    GapResult
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
    >>> sol = solve_gap_auto(lambda x, y: x**2 + 2 * y**2, wr.STEEL, Fn=10e3, elements=31)
    >>> sol.normal.truncated, sol.normal.info["contact_patches"]
    (False, 1)
    """
    max_enlarge = integer("max_enlarge", max_enlarge, 0)
    w = _window(gap, penetration, Fn, materials, elements, margin, search)
    grid, search = w["grid"], w["search"]
    enlargements = 0
    while True:
        h0 = np.array(_evaluate(gap, grid.X, grid.Y))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ContactTruncatedWarning)
            sol = solve_gap(grid, h0, materials, Fn=Fn, penetration=penetration,
                            creepage=creepage, mu=mu, **solve_gap_options)
        c = sol.normal.contact
        if not sol.normal.truncated or enlargements >= max_enlarge:
            break
        b = _enlarged_bounds(grid, c, search)
        if b is None:
            break
        grid = _grid_on(b, w["elements"])
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
