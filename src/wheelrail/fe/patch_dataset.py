"""Contact-patch outputs per wheel surface node (pressure, shear, stick/slip) as xarray."""

from __future__ import annotations

import numpy as np

__all__ = ["patch_from_contact", "STICK_SLIP_TOLERANCE"]

#: A closed node is reported as slipping when |q| >= (1 - tol) μ p (the return map
#: puts slipping nodes exactly on the cone; the tolerance only absorbs round-off).
STICK_SLIP_TOLERANCE = 1e-6


def patch_from_contact(model, c, psi, dt=None):
    """An :class:`xarray.Dataset` of the wheel surface nodes over (x, y).

    ``x`` is the arc length from the axle's vertical through the contact
    (positive ahead) [m], ``y`` the lateral position [m]. Variables: pressure
    [Pa], shear_x, shear_y, shear [Pa] (traction on the wheel), status (0 open,
    1 stick, 2 slip), gap [m], slip [m] (micro-slip increment of the step) and,
    if ``dt`` is given, slip_velocity [m/s]. Attributes: p_max [Pa], Fn [N],
    a, b [m] (equivalent semi-axes from the second moments of the pressure,
    exact for Hertz's ellipsoidal distribution: ⟨x²⟩ = a²/5), extent_a,
    extent_b [m] (half extents of the loaded nodes), adhesion_fraction.
    """
    import xarray as xr

    wb = model.wheel
    nt, ny, _ = wb.shape
    R = model.geometry["r_c"]
    theta = wb.axes[0]
    x = R * (theta - psi)
    y = wb.axes[1]
    A = model.slave_area
    pn = c["pn"]
    p = (pn / A).reshape(nt, ny)
    ft = c["ft"]
    qx = (ft[:, 0] / A).reshape(nt, ny)
    qy = (ft[:, 1] / A).reshape(nt, ny)
    status = c["status"].reshape(nt, ny)
    ds = xr.Dataset(
        {"pressure": (("x", "y"), p, {"units": "Pa"}),
         "shear_x": (("x", "y"), qx, {"units": "Pa"}),
         "shear_y": (("x", "y"), qy, {"units": "Pa"}),
         "shear": (("x", "y"), np.hypot(qx, qy), {"units": "Pa"}),
         "status": (("x", "y"), status, {"meaning": "0 open, 1 stick, 2 slip"}),
         "gap": (("x", "y"), c["gap"].reshape(nt, ny), {"units": "m"}),
         "slip": (("x", "y"), c["slip"].reshape(nt, ny), {"units": "m"})},
        coords={"x": ("x", x, {"units": "m"}), "y": ("y", y, {"units": "m"})})
    if dt:
        ds["slip_velocity"] = ds["slip"] / dt
        ds["slip_velocity"].attrs["units"] = "m/s"
    F = pn.sum()
    attrs = {"Fn": float(F), "p_max": float(p.max()), "a": 0.0, "b": 0.0, "extent_a": 0.0,
             "extent_b": 0.0, "adhesion_fraction": 0.0, "stick_slip_tolerance": STICK_SLIP_TOLERANCE}
    if F > 0:
        X, Y = np.meshgrid(x, y, indexing="ij")
        f = pn.reshape(nt, ny)
        xc, yc = (f * X).sum() / F, (f * Y).sum() / F
        attrs["a"] = float(np.sqrt(5 * (f * (X - xc) ** 2).sum() / F))
        attrs["b"] = float(np.sqrt(5 * (f * (Y - yc) ** 2).sum() / F))
        on = f > 0
        attrs["extent_a"] = float(0.5 * (X[on].max() - X[on].min()))
        attrs["extent_b"] = float(0.5 * (Y[on].max() - Y[on].min()))
        closed = status > 0
        attrs["adhesion_fraction"] = float((status == 1).sum() / max(closed.sum(), 1))
        attrs["x_centre"], attrs["y_centre"] = float(xc), float(yc)
    ds.attrs.update(attrs)
    return ds
