"""Analyses of a one- to two-point contact transition run (waves, onset, equilibrium).

:func:`wave_speed` measures the speed of the surface wave that the start of the contact
(a step load on the rail surface) sends along the rail head: the arrival time of the
largest vertical velocity at each node of the rail's surface line through the contact is
fitted against its distance. For a step point load on an elastic half-space the surface
response is dominated by the Rayleigh pulse (Lamb's problem), so the fitted speed should be
the Rayleigh wave speed of steel, c_R ≈ 0.927 c_s ≈ 2.97 km/s for E = 210 GPa, ν = 0.3,
ρ = 7850 kg/m³ (Viktorov's approximation c_R/c_s = (0.862 + 1.14 ν)/(1 + ν)).

References
----------
.. [1] K.F. Graff, *Wave Motion in Elastic Solids*, Dover 1991, §6.4 (Lamb's problem,
   Rayleigh pulse), §6.3 eq. (6.3.21) (Rayleigh wave speed).
.. [2] I.A. Viktorov, *Rayleigh and Lamb Waves*, Plenum 1967, ch. 1 (c_R/c_s).
"""

from __future__ import annotations

import numpy as np

from ...errors import InputError
from .model import flange_contact_offset, rigid_pose

__all__ = ["wave_speed", "rayleigh_speed", "settled_vertical_balance", "onset_travel",
           "surface_stations", "climb_load", "shear_direction", "slip_direction"]


def rayleigh_speed(E: float, nu: float, rho: float) -> float:
    """Rayleigh wave speed [m/s] (Viktorov's approximation, within 0.5 % for 0 ≤ ν ≤ 0.5)."""
    cs = np.sqrt(E / (2.0 * (1.0 + nu)) / rho)
    return float(cs * (0.862 + 1.14 * nu) / (1.0 + nu))


def surface_stations(x, d_min, d_max, side="both"):
    """Mask of the surface stations at distances ``d_min`` ≤ |x| ≤ ``d_max`` [m] from the
    source, on ``side`` "ahead" (x > 0), "behind" (x < 0) or "both"; at least three."""
    sel = (np.abs(x) >= d_min) & (np.abs(x) <= d_max)
    if side == "ahead":
        sel &= x > 0
    elif side == "behind":
        sel &= x < 0
    elif side != "both":
        raise InputError(f"side must be 'both', 'ahead' or 'behind', got {side!r}")
    if sel.sum() < 3:
        raise InputError(f"fewer than 3 surface nodes between {d_min} and {d_max} m")
    return sel


def wave_speed(wave: dict, d_min: float = 0.015, d_max: float = 0.1,
               side: str = "ahead") -> dict:
    """Surface wave speed [m/s] from the rail surface velocities of a run.

    The start of a run is not a clean impulse (the wheel settles and bounces; 1.5–1.9 km/s
    on the 4 mm runs): for a clean measurement on the same rail mesh see
    :func:`wheelrail.fe.transition.wave.rail_pulse` and
    :func:`~wheelrail.fe.transition.wave.pulse_arrivals`.

    Parameters
    ----------
    wave : dict
        ``info["wave"]`` of :func:`~wheelrail.fe.transition.run_transition` (``x`` (n,)
        node distances along the rail from the start contact [m], ``t`` (nt,) times [s],
        ``vz`` (nt, n) vertical velocities [m/s]); needs ``wave_time`` > 0 in the case.
    d_min, d_max : float
        Distances [m] used in the fit (beyond the contact patch, inside the recorded time).
    side : {"both", "ahead", "behind"}

    Returns
    -------
    dict
        ``speed`` [m/s] (inverse of the least-squares slope of the arrival time against the
        distance), ``d`` and ``t_arrival`` of the fitted nodes, ``t0`` the intercept [s],
        ``residual`` (rms of the fit [s]).
    """
    if wave is None:
        raise InputError("no wave record: run the case with wave_time > 0")
    x = np.asarray(wave["x"])
    t = np.asarray(wave["t"])
    vz = np.asarray(wave["vz"])
    sel = surface_stations(x, d_min, d_max, side)
    d = np.abs(x[sel])
    ta = t[np.argmax(np.abs(vz[:, sel]), axis=0)]
    # the largest velocity must arrive before the end of the record
    ok = ta < t[-1] - 2 * (t[1] - t[0])
    if ok.sum() < 3:
        raise InputError("the wave has not passed the fitted nodes within the record")
    # arrival time against distance (the distances are exact, the picked times noisy)
    A = np.stack([d[ok], np.ones(ok.sum())], axis=1)
    coef, *_ = np.linalg.lstsq(A, ta[ok], rcond=None)
    res = ta[ok] - A @ coef
    if not coef[0] > 0:
        raise InputError("the picked arrival times do not increase with distance")
    return {"speed": float(1.0 / coef[0]), "d": d[ok], "t_arrival": ta[ok],
            "t0": float(coef[1]), "residual": float(np.sqrt(np.mean(res ** 2)))}


def settled_vertical_balance(result, s_from: float, s_to: float) -> dict:
    """Mean vertical contact force against the wheel load over a travel window [m].

    Returns ``{"Fz": mean Σ Fz [N], "std": its standard deviation, "load": Q [N],
    "error": Fz / Q − 1}``.
    """
    h = result.history
    s = h["travel"].values
    sel = (s >= s_from) & (s <= s_to)
    if not np.any(sel):
        raise InputError(f"no outputs between {s_from} and {s_to} m of travel")
    fz = h["Fz_total"].values[sel]
    q = result.info["load"]
    return {"Fz": float(fz.mean()), "std": float(fz.std()), "load": float(q),
            "error": float(fz.mean() / q - 1.0)}


def climb_load(case, travel, wheel_mass: float, dy: float = 1e-4,
               smooth: float = 5e-4) -> dict:
    """Vertical contact force beyond the wheel load that the rigid climb of the axle along
    its prescribed lateral path needs (the transition runs' kinematics).

    The axle moves laterally at V sin α (its heading is yawed by α), so its rigid height
    z(y) over the rail — the height of the wheel profile's origin where the unyawed wheel
    touches the rail (:func:`~wheelrail.fe.transition.model.rigid_pose`) — changes at
    ż = V sin α z′(y) and z̈ = (V sin α)² z″(y). The unsprung mass M_u (the half-axle and
    the wheel) then needs M_u z̈ more contact force, and the primary suspension pushes
    with k (z − z(y₀)) + c ż more while the sprung mass (≈ 2 Hz) has not moved. By the
    envelope theorem z′ is the common slope of the profiles at the contact (tan of the
    contact angle), so z″ grows where the contact climbs the flange root, and the jump of
    the rigid contact onto the flange root is a kink of z (a short peak of z″; the elastic
    run spreads it).

    Parameters
    ----------
    case : TransitionCase
    travel : array_like
        Travel s [m] along the heading from the start (lateral offset y₀ = y_f − the
        flange clearance; y_f from
        :func:`~wheelrail.fe.transition.model.flange_contact_offset`).
    wheel_mass : float
        Mass of the (FE) wheel [kg]; the unsprung mass is it plus
        ``case.suspension.axle_mass``.
    dy : float
        Sampling of the lateral offset [m].
    smooth : float
        Width [m] of the moving average of z′ before it is differentiated (z′ is
        piecewise constant on the profiles' stations).

    Returns
    -------
    dict
        Arrays over ``travel``: ``y`` lateral offset [m], ``z`` rigid height [m], ``dz``
        z′ [-], ``d2z`` z″ [1/m], ``inertia`` M_u (V sin α)² z″ [N], ``suspension``
        k (z − z(y₀)) + c V sin α z′ [N], ``total`` their sum [N].
    """
    s = np.atleast_1d(np.asarray(travel, float))
    if not np.all(np.isfinite(s)) or np.any(s < 0):
        raise InputError(f"travel must be finite and >= 0 [m], got {travel!r}")
    if not (dy > 0 and smooth >= dy):
        raise InputError(f"need dy > 0 and smooth >= dy, got dy={dy!r}, smooth={smooth!r}")
    sa = np.sin(case.angle_of_attack)
    y0 = flange_contact_offset(case) - case.flange_clearance
    y = y0 + s * sa
    pad = smooth + 3 * dy
    grid = np.arange(y.min() - pad, y.max() + pad + dy, dy)
    z = np.array([rigid_pose(case, g)["z_off"] for g in grid])
    dz = np.gradient(z, grid)
    n = max(1, int(round(smooth / dy)))
    dz_s = np.convolve(dz, np.ones(n) / n, mode="same")
    d2z = np.gradient(dz_s, grid)
    vy = case.speed * sa
    susp = case.suspension
    mu = susp.axle_mass + float(wheel_mass)
    zi, dzi, d2zi = (np.interp(y, grid, a) for a in (z, dz, d2z))
    inertia = mu * vy ** 2 * d2zi
    spring = susp.stiffness * (zi - np.interp(y0, grid, z)) + susp.damping * vy * dzi
    return {"y": y, "z": zi, "dz": dzi, "d2z": d2zi, "inertia": inertia,
            "suspension": spring, "total": inertia + spring}


def onset_travel(patches, min_force: float = 1000.0, persist: int = 3) -> float:
    """Travel [m] at which the flange patch (patch 2) first carries more than ``min_force``
    [N] for ``persist`` consecutive outputs (NaN if never)."""
    fn = patches["Fn"].sel(patch=2).values
    on = fn > min_force
    run = np.convolve(on.astype(int), np.ones(persist, int), mode="valid") == persist
    k = np.flatnonzero(run)
    return float(patches["travel"].values[k[0]]) if k.size else float("nan")


def shear_direction(fields, patch: int = 1):
    """Direction of the surface shear stress of a patch over time, three ways of averaging.

    The orientation angle θ of the shear stress on the rail is measured from the negative
    longitudinal axis (0: the traction of a driven wheel), positive towards the patch's
    lateral tangent pointing to +y (the field side of the gauge corner), per node from the
    recorded surface fields. A patch under spin carries a shear whose direction turns across
    the patch, so the patch's "θ" depends on how it is averaged:

    * ``mean_stress``: the angle of the area-weighted mean shear stress (the direction of
      the patch's tangential force; ``theta`` of the patch histories, with its sign);
    * ``mean_angle``: the area-weighted mean of the nodes' signed θ;
    * ``mean_abs_angle``: the area-weighted mean of the nodes' |θ|.

    Parameters
    ----------
    fields : xarray.Dataset
        ``TransitionResult.contact_fields`` (dims time, row, col; ``traction_x/y/z`` [Pa] on
        the rail, ``area`` [m²], ``patch`` labels).
    patch : int
        1 tread, 2 flange, 3 other.

    Returns
    -------
    xarray.Dataset
        ``mean_stress``, ``mean_angle``, ``mean_abs_angle`` [deg] and ``n_nodes`` over
        ``time`` (with ``travel``); NaN where the patch is not in contact.

    References
    ----------
    The orientation angle as defined in the explicit-FE transition study of Zhao & Li's
    group (S1002 on UIC 54E1, the angle between the surface shear stress and the negative
    longitudinal axis; patch values averaged over its elements).
    """
    w, tx, ty, tz = _patch_weights(fields, patch, "traction")
    sel = w > 0
    # the tangential traction's part across the rail lies along ±(the lateral tangent);
    # its sign is that of its y component
    th = np.degrees(np.arctan2(np.sign(ty) * np.hypot(ty, tz), -tx))
    _, _, angle, n_nodes, mean = _patch_means(w, tx, ty, tz)
    out = {"mean_stress": angle,
           "mean_angle": mean(np.where(sel, th, 0.0)),
           "mean_abs_angle": mean(np.where(sel, np.abs(th), 0.0)),
           "n_nodes": n_nodes}
    return _over_time(fields, out, dict.fromkeys(("mean_stress", "mean_angle",
                                                  "mean_abs_angle"), "deg"))


def _patch_weights(fields, patch, kind):
    """Area weights of ``patch``'s nodes (0 elsewhere) and the ``kind``_x/_y/_z fields."""
    if patch not in (1, 2, 3):
        raise InputError(f"patch must be 1, 2 or 3, got {patch!r}")
    names = [f"{kind}_{c}" for c in "xyz"]
    for name in names + ["area", "patch"]:
        if name not in fields:
            raise InputError(f"fields has no {name!r}: pass TransitionResult.contact_fields")
    w = np.where(fields["patch"].values == patch, fields["area"].values, 0.0)
    return (w, *(fields[n].values for n in names))


def _patch_means(w, vx, vy, vz):
    """Over time, NaN where the patch is out of contact: the area-weighted mean vector's
    parts along the rail and across it (along the lateral tangent, signed by y), its angle
    against the negative longitudinal axis [deg], the patch's node count, and a function
    giving the area-weighted mean of a (time, row, col) array."""
    ws = w.sum(axis=(1, 2))
    has = ws > 0
    den = np.where(has, ws, 1.0)

    def mean(v):
        return np.where(has, (w * v).sum(axis=(1, 2)) / den, np.nan)

    mx, my, mz = mean(vx), mean(vy), mean(vz)
    ml = np.sign(my) * np.hypot(my, mz)
    return mx, ml, np.degrees(np.arctan2(ml, -mx)), (w > 0).sum(axis=(1, 2)), mean


def _over_time(fields, out, units):
    import xarray as xr

    ds = xr.Dataset({k: ("time", v) for k, v in out.items()},
                    coords={"time": fields["time"].values,
                            "travel": ("time", fields["travel"].values)})
    for k, u in units.items():
        ds[k].attrs["units"] = u
    return ds


def slip_direction(fields, patch: int = 1):
    """The mean micro-slip of a patch over time: its components along and across the rail
    and its direction, measured like the shear direction θ.

    In a sliding patch the shear on the rail points along the wheel's micro-slip (Coulomb),
    so the slip direction is what turns θ: a patch in full slip under a longitudinal slip
    s_long and a lateral slip s_lat has θ ≈ atan(|s_lat| / |s_long|), whatever its load.

    Parameters
    ----------
    fields : xarray.Dataset
        ``TransitionResult.contact_fields`` (dims time, row, col; ``slip_x/y/z`` [m/s]: the
        wheel's tangential velocity relative to the rail, global components; ``area`` [m²];
        ``patch`` labels).
    patch : int
        1 tread, 2 flange, 3 other.

    Returns
    -------
    xarray.Dataset
        Over ``time`` (with ``travel``), NaN where the patch is not in contact:
        ``slip_long`` [m/s], the area-weighted mean slip along the rail (x; negative for
        the slip of a driven wheel); ``slip_lat`` [m/s], its part across the rail, along the
        patch's lateral tangent, signed by its y component; ``angle`` [deg],
        atan2(slip_lat, −slip_long), the angle against the negative longitudinal axis as
        θ of :func:`shear_direction`; ``n_nodes``.

    References
    ----------
    The orientation angle as defined in the explicit-FE transition study of Zhao & Li's
    group (angle against the negative longitudinal axis); Coulomb's law of sliding
    friction, K.L. Johnson, *Contact Mechanics*, CUP 1985, §8.1.
    """
    w, sx, sy, sz = _patch_weights(fields, patch, "slip")
    mx, ml, angle, n_nodes, _ = _patch_means(w, sx, sy, sz)
    out = {"slip_long": mx, "slip_lat": ml, "angle": angle, "n_nodes": n_nodes}
    return _over_time(fields, out, {"slip_long": "m/s", "slip_lat": "m/s", "angle": "deg"})
