"""Normalise the traction fields of the tangential methods to plain arrays (numpy only).

The fields of the package's methods know their own layout: a container with an
``as_arrays()`` method (the exact theory's :class:`wheelrail.results.GapResult` and
:class:`wheelrail.halfspace.TangentialResult`,
FASTSIM's :class:`wheelrail.tangential.fastsim.FastsimFields`) gives its arrays
itself. For other containers (a user's mapping, ``xarray.Dataset`` or object)
:func:`field_arrays` looks up the usual names and guesses the grid orientation.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

__all__ = ["field_arrays"]

_NAMES = {
    "x": ("x", "xc", "X"),
    "y": ("y", "yc", "Y"),
    "px": ("px", "tx", "qx", "px_t", "traction_x"),
    "py": ("py", "ty", "qy", "py_t", "traction_y"),
    "p": ("p", "pn", "pz", "pressure"),
    "adhesion": ("adhesion", "adh", "stick"),
    "slip": ("slip", "sliding", "slip_mask"),
    "state": ("state", "eldiv"),
    "inside": ("inside", "contact", "in_contact", "mask"),
    "dA": ("dA", "cell_area"),
    "dx": ("dx",),
    "dy": ("dy",),
}


def _lookup(fields, names):
    for n in names:
        try:
            if isinstance(fields, Mapping) or hasattr(fields, "data_vars"):
                if n in fields:
                    return fields[n]
                coords = getattr(fields, "coords", None)
                if coords is not None and n in coords:
                    return coords[n]
            elif hasattr(fields, n):
                v = getattr(fields, n)
                if not callable(v):
                    return v
        except (KeyError, TypeError):
            continue
    return None


def _arr(v):
    if v is None:
        return None
    return np.asarray(getattr(v, "values", v))


def field_arrays(fields):
    """Plain arrays of a traction field, on a grid indexed ``[i_x, i_y]``.

    Parameters
    ----------
    fields : mapping, xarray.Dataset or object
        The ``fields`` of a :class:`wheelrail.CreepForcesResult`.

    Returns
    -------
    dict or None
        ``x``, ``y`` (2-D, m), ``px``, ``py`` (2-D, Pa), and where available
        ``p`` (pressure, Pa), ``adhesion`` (bool, True in the adhesion area),
        ``inside`` (bool, True in the contact area) and ``dA`` (element areas,
        m², 2-D);
        ``None`` if no tangential traction is found.
    """
    if fields is None:
        return None
    as_arrays = getattr(fields, "as_arrays", None)
    if callable(as_arrays):  # the fields know their own layout (exact, FASTSIM)
        return as_arrays()
    px, py = _arr(_lookup(fields, _NAMES["px"])), _arr(_lookup(fields, _NAMES["py"]))
    if px is None and py is None:
        return None
    shape = (px if px is not None else py).shape
    if len(shape) != 2:
        return None
    px = np.zeros(shape) if px is None else px.astype(float)
    py = np.zeros(shape) if py is None else py.astype(float)
    x, y = _arr(_lookup(fields, _NAMES["x"])), _arr(_lookup(fields, _NAMES["y"]))
    transpose = False
    if x is None or y is None:
        x, y = np.meshgrid(np.arange(shape[0], dtype=float), np.arange(shape[1], dtype=float),
                           indexing="ij")
    elif x.ndim == 1 and y.ndim == 1:
        if shape == (x.size, y.size):
            x, y = np.meshgrid(x, y, indexing="ij")
        elif shape == (y.size, x.size):
            transpose = True
            x, y = np.meshgrid(x, y, indexing="ij")
        else:
            return None
    elif x.shape == shape and y.shape == shape:
        # want [i_x, i_y]: transpose when y is constant along the rows (strips [i_y, i_x])
        y_const_rows = shape[1] > 1 and np.allclose(y, y[:, :1])
        y_const_cols = shape[0] > 1 and np.allclose(y, y[:1, :])
        if y_const_rows and not y_const_cols:
            transpose = True
            x, y = x.T, y.T
    else:
        return None
    out = {"x": x.astype(float), "y": y.astype(float)}

    def orient(v):
        if v is None:
            return None
        v = np.asarray(v)
        if v.shape != shape:
            return None
        return v.T if transpose else v

    out["px"], out["py"] = orient(px), orient(py)
    out["p"] = orient(_arr(_lookup(fields, _NAMES["p"])))
    if out["p"] is not None:
        out["p"] = out["p"].astype(float)
    inside = orient(_arr(_lookup(fields, _NAMES["inside"])))
    adhesion = orient(_arr(_lookup(fields, _NAMES["adhesion"])))
    slip = orient(_arr(_lookup(fields, _NAMES["slip"])))
    state = orient(_arr(_lookup(fields, _NAMES["state"])))
    if inside is None and out["p"] is not None:
        inside = out["p"] > 0
    if state is not None and np.issubdtype(state.dtype, np.integer):
        # CONTACT's element division: 0 exterior, 1 adhesion, 2 slip
        inside = state > 0 if inside is None else inside
        adhesion = state == 1 if adhesion is None else adhesion
    if adhesion is None and slip is not None:
        slip = slip.astype(bool)
        adhesion = ~slip if inside is None else (inside.astype(bool) & ~slip)
    out["inside"] = None if inside is None else inside.astype(bool)
    out["adhesion"] = None if adhesion is None else adhesion.astype(bool)
    out["dA"] = _cell_area(fields, out, shape, orient)
    return out


def _cell_area(fields, out, shape, orient):
    """Element areas [m²], shape of the grid ``[i_x, i_y]``, or None if unknown."""
    for name in ("dA", "cell_area", "area"):
        v = _lookup(fields, (name,))
        if v is None:
            continue
        v = _arr(v).astype(float)
        if v.shape == shape:
            return orient(v)
        if v.ndim == 0 and name != "area":
            return np.full(out["x"].shape, float(v))
    dx, dy = _arr(_lookup(fields, _NAMES["dx"])), _arr(_lookup(fields, _NAMES["dy"]))
    if dx is not None and dy is not None:
        dx, dy = dx.astype(float), dy.astype(float)
        if dx.ndim == 0 and dy.ndim == 0:
            return np.full(out["x"].shape, float(dx * dy))
        if dx.ndim == 1 and dx.shape == dy.shape and dx.size in shape:
            per = dx * dy  # one value per strip
            axis = 0 if dx.size == shape[0] else 1
            full = np.broadcast_to(per[:, None] if axis == 0 else per[None, :], shape)
            return orient(np.array(full))
    x, y = out["x"], out["y"]
    if x.shape[0] > 1 and x.shape[1] > 1 and np.allclose(x, x[:, :1]) and np.allclose(y, y[:1, :]):
        ddx, ddy = np.diff(x[:, 0]), np.diff(y[0, :])
        if np.allclose(ddx, ddx[0]) and np.allclose(ddy, ddy[0]):
            return np.full(x.shape, abs(ddx[0] * ddy[0]))
    return None
