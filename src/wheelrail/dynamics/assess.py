"""Running-safety, track-loading and ride assessment of a simulation (EN 14363 quantities).

:func:`assess` post-processes a :class:`~wheelrail.dynamics.SimulationResult`
into an :class:`xarray.Dataset` per wheelset (axle) and wheel:

* **track shift force** ΣY = −(F_y,left + F_y,right), the lateral force of the
  wheelset on the track (F_y the track-frame lateral forces on the wheels,
  ``wheel_Fy``), low-pass filtered at 20 Hz, then averaged over a sliding window
  of 2 m of distance (window centres every 0.5 m); its largest magnitude
  against Prud'homme's limit (ΣY)_lim = α (10 kN + P0/3), P0 the static axle
  load [kN], α = 1 (0.85 for freight wagons). EN 14363 writes the same limit
  as α (10 + 2 Q0/3) with the static wheel load Q0 = P0/2;
* **derailment quotient** (Y/Q)_2m of each wheel: Y (``lateral_force``, the
  wheel's force on the rail towards the field side) and Q (``vertical_load``)
  low-pass filtered at 20 Hz, their ratio averaged over 2 m sliding windows;
  its largest value against 0.8 (EN 14363's limit for curve radii R ≥ 250 m);
  samples where the filtered Q ≤ 0 (a lifted wheel) enter as 0 and are counted
  in the attribute ``wheel_lift_samples`` (see ``Q_min``);
* the largest filtered Y and Q of each wheel;
* the wear number Tγ of each wheel (``wear_number``): mean and largest;
* **car-body accelerations**, when the result has a car body (states
  ``body.vy``/``body.vz``, or dataset variables ``body_vy``/``body_vz`` or
  ``body_ay``/``body_az``): lateral (in the track plane, with the uncompensated
  part g sin φ + V² κ cos φ) and vertical, band-pass filtered 0.4–10 Hz
  (EN 14363), their r.m.s. and largest values, and Sperling's ride index Wz
  of each (:func:`~wheelrail.dynamics.sperling_wz`, on the unfiltered
  acceleration). Without a car body these are left out (attribute
  ``car_body``).

Filters: Butterworth of order 4 (:func:`~wheelrail.dynamics.lowpass`,
:func:`~wheelrail.dynamics.bandpass`), applied causally from the steady state of
the first sample; EN 14363 prescribes the cut-off frequencies (≥ 20 Hz for the
forces, 0.4–10 Hz for the body), not the characteristic, and evaluates
percentiles (0.15 %, 99.85 %) of the sliding means of measured runs; a
simulation is assessed here by its extreme values (the stricter reading).

References
----------
.. [1] EN 14363:2016, Railway applications — Testing and simulation for the
   acceptance of running characteristics of railway vehicles — Running
   behaviour and stationary tests (ΣY, Y/Q, Q, car-body accelerations;
   filtering and 2 m sliding means).
.. [2] M.A. Prud'homme, La résistance de la voie aux efforts transversaux
   exercés par le matériel roulant, Revue Générale des Chemins de Fer, 1967
   (the limit 10 + P/3 kN).
.. [3] E. Sperling, Organ für die Fortschritte des Eisenbahnwesens 12 (1941)
   176–187 (Wz).
.. [4] T.G. Pearce, N.D. Sherratt, Wear 144 (1991) 343–351 (Tγ).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from ..errors import InputError
from ._filters import bandpass, lowpass, sliding_mean, sperling_wz

__all__ = ["assess"]

_G = 9.80665


def _uniform(t, *arrays):
    """Resample onto a uniform time grid when the output times are not uniform."""
    dt = np.diff(t)
    if dt.size == 0 or not np.all(dt > 0):
        raise InputError("assess: the result's times must increase (at least 2 outputs)")
    h = float(np.median(dt))
    if np.allclose(dt, h, rtol=1e-6, atol=1e-12):
        return t, h, arrays
    tu = t[0] + h * np.arange(int(math.floor((t[-1] - t[0]) / h * (1 + 1e-12))) + 1)
    out = []
    for a in arrays:
        flat = a.reshape(a.shape[0], -1)
        r = np.stack([np.interp(tu, t, flat[:, k]) for k in range(flat.shape[1])], axis=1)
        out.append(r.reshape((tu.size,) + a.shape[1:]))
    return tu, h, tuple(out)


def _body_channels(result, ds):
    """(vy, vz) or (ay, az) of the car body if the result has one, else None."""
    names = tuple(getattr(result, "names", ()) or ())
    for pre in ("body", "carbody", "car_body"):
        if f"{pre}_ay" in ds and f"{pre}_az" in ds:
            return "acc", np.asarray(ds[f"{pre}_ay"]), np.asarray(ds[f"{pre}_az"])
        if f"{pre}_vy" in ds and f"{pre}_vz" in ds:
            return "vel", np.asarray(ds[f"{pre}_vy"]), np.asarray(ds[f"{pre}_vz"])
        if f"{pre}.vy" in names and f"{pre}.vz" in names:
            X = np.asarray(result.states)
            return "vel", X[:, names.index(f"{pre}.vy")], X[:, names.index(f"{pre}.vz")]
    return None


def assess(result, *, cutoff: float = 20.0, window: float = 2.0, step: float = 0.5,
           alpha: float = 1.0, axle_load=None, yq_limit: float = 0.8,
           body_band=(0.4, 10.0), order: int = 4) -> xr.Dataset:
    """EN 14363 running-safety and track-loading quantities, ride index and wear number.

    Parameters
    ----------
    result : SimulationResult or xarray.Dataset
        A :func:`~wheelrail.dynamics.simulate` result (or its ``.dataset``).
    cutoff : float
        Low-pass cut-off of the wheel forces [Hz] (EN 14363: 20 Hz). Skipped
        (attribute ``force_filter``) when the output rate is too low for it.
    window, step : float
        Sliding-mean window and spacing of its centres [m] (2 m, 0.5 m).
    alpha : float
        Factor of Prud'homme's limit (1; 0.85 for freight wagons).
    axle_load : float, array_like or None
        Static axle load P0 per wheelset [N] (default: the model's
        ``axle_load``, else the mean of Q_left + Q_right over the run).
    yq_limit : float
        Limit of (Y/Q)_2m (0.8 for R ≥ 250 m).
    body_band : (float, float)
        Band-pass of the car-body accelerations [Hz] (0.4–10 Hz).
    order : int
        Butterworth order of the filters.

    Returns
    -------
    xarray.Dataset
        Dimensions ``wheelset``, ``side`` and ``distance`` (window centres [m]).
        Variables: ``sum_Y_2m`` (distance, wheelset) [N], ``sum_Y_2m_max``,
        ``sum_Y_limit`` (wheelset) [N], ``sum_Y_ok``; ``Y_over_Q_2m`` (distance,
        wheelset, side), ``Y_over_Q_2m_max`` (wheelset, side), ``Y_over_Q_limit``,
        ``Y_over_Q_ok``; ``Y_max``, ``Q_max``, ``Q_min`` (wheelset, side) [N];
        ``wear_number_mean``, ``wear_number_max`` (wheelset, side) [N]; with a car
        body ``body_lateral_acc_rms``, ``body_vertical_acc_rms``,
        ``body_lateral_acc_max``, ``body_vertical_acc_max`` [m/s²] and
        ``sperling_lateral``, ``sperling_vertical`` [-].

    Examples
    --------
    >>> table = wr.dynamics.assess(result)                # doctest: +SKIP
    >>> float(table["sum_Y_2m_max"][0] / table["sum_Y_limit"][0])  # doctest: +SKIP
    """
    ds = result if isinstance(result, xr.Dataset) else getattr(result, "dataset", None)
    if not isinstance(ds, xr.Dataset):
        raise InputError(f"assess: a SimulationResult or its dataset is needed, got "
                         f"{type(result).__name__}")
    for v in ("wheel_Fy", "lateral_force", "vertical_load", "position", "speed"):
        if v not in ds:
            raise InputError(f"assess: the result has no {v!r}")
    t = np.asarray(ds["time"], dtype=float)
    pos = np.asarray(ds["position"], dtype=float)
    V = np.asarray(ds["speed"], dtype=float)
    Fy = np.asarray(ds["wheel_Fy"], dtype=float)
    Y = np.asarray(ds["lateral_force"], dtype=float)
    Q = np.asarray(ds["vertical_load"], dtype=float)
    Tg = np.asarray(ds["wear_number"], dtype=float) if "wear_number" in ds else None
    if t.size < 4:
        raise InputError(f"assess: at least 4 outputs needed, got {t.size}")
    body = _body_channels(result, ds)
    series = [pos, V, Fy, Y, Q]
    if Tg is not None:
        series.append(Tg)
    if body is not None:
        series += [body[1], body[2]]
    tu, h, arrs = _uniform(t, *series)
    pos, V, Fy, Y, Q = arrs[:5]
    k = 5
    if Tg is not None:
        Tg = arrs[k]
        k += 1
    if body is not None:
        body = (body[0], arrs[k], arrs[k + 1])
    fs = 1.0 / h
    nw = Fy.shape[1]
    attrs = {"standard": "EN 14363:2016 (ΣY after Prud'homme, Y/Q, Q; car-body "
                         "accelerations), Sperling's Wz, wear number Tγ",
             "window_m": float(window), "step_m": float(step), "alpha": float(alpha),
             "sampling_rate_Hz": fs}
    if cutoff is not None and cutoff < fs / 2:
        filt = lambda x: lowpass(x, fs, cutoff, order)                      # noqa: E731
        attrs["force_filter"] = f"Butterworth low-pass {cutoff:g} Hz, order {order}, causal"
    else:
        filt = lambda x: x                                                  # noqa: E731
        attrs["force_filter"] = (f"none (output rate {fs:g} Hz does not resolve "
                                 f"{cutoff!r} Hz)")
    if np.any(np.diff(pos) <= 0):
        raise InputError("assess: the position must increase along the run (speed > 0)")
    # static axle load
    if axle_load is None:
        model = getattr(result, "model", None)
        P0 = getattr(model, "axle_load", None) if model is not None else None
        if P0 is None:
            P0 = np.mean(Q[:, :, 0] + Q[:, :, 1], axis=0)
            attrs["axle_load_source"] = "mean of Q_left + Q_right of each wheelset over the run"
        else:
            attrs["axle_load_source"] = "model.axle_load"
    else:
        P0 = axle_load
        attrs["axle_load_source"] = "given"
    P0 = np.broadcast_to(np.asarray(P0, dtype=float), (nw,)).copy()
    if not np.all(np.isfinite(P0) & (P0 > 0)):
        raise InputError(f"assess: axle_load must be > 0 N, got {P0!r}")
    # ΣY: lateral force of the wheelset on the track, +y to the right
    sumY = filt(-(Fy[:, :, 0] + Fy[:, :, 1]))
    c, sumY2 = sliding_mean(sumY, pos, window, step)
    Yf, Qf = filt(Y), filt(Q)
    with np.errstate(divide="ignore", invalid="ignore"):
        yq = np.where(Qf > 0, Yf / np.where(Qf > 0, Qf, 1.0), 0.0)
    # a lifted wheel (Q <= 0) has no quotient: counted, and taken as 0 in the mean
    attrs["wheel_lift_samples"] = int(np.count_nonzero(Qf <= 0))
    _, yq2 = sliding_mean(yq, pos, window, step)
    limit = alpha * (10e3 + P0 / 3.0)
    sY_max = np.max(np.abs(sumY2), axis=0)
    yq_max = np.max(yq2, axis=0)
    data = {
        "sum_Y_2m": (("distance", "wheelset"), sumY2, {"units": "N", "description":
                     "track shift force, 20 Hz low-pass, 2 m sliding mean"}),
        "sum_Y_2m_max": ("wheelset", sY_max, {"units": "N"}),
        "sum_Y_limit": ("wheelset", limit, {"units": "N", "description":
                        "Prud'homme: alpha (10 kN + P0/3)"}),
        "sum_Y_ok": ("wheelset", sY_max <= limit),
        "axle_load": ("wheelset", P0, {"units": "N", "description": "static axle load P0"}),
        "Y_over_Q_2m": (("distance", "wheelset", "side"), yq2, {"units": "1", "description":
                        "Y/Q of 20 Hz low-pass Y and Q, 2 m sliding mean"}),
        "Y_over_Q_2m_max": (("wheelset", "side"), yq_max, {"units": "1"}),
        "Y_over_Q_limit": ((), float(yq_limit), {"units": "1"}),
        "Y_over_Q_ok": (("wheelset", "side"), yq_max <= yq_limit),
        "Y_max": (("wheelset", "side"), np.max(np.abs(Yf), axis=0), {"units": "N"}),
        "Q_max": (("wheelset", "side"), np.max(Qf, axis=0), {"units": "N"}),
        "Q_min": (("wheelset", "side"), np.min(Qf, axis=0), {"units": "N"}),
    }
    if Tg is not None:
        data["wear_number_mean"] = (("wheelset", "side"), Tg.mean(axis=0), {"units": "N"})
        data["wear_number_max"] = (("wheelset", "side"), Tg.max(axis=0), {"units": "N"})
    if body is None:
        attrs["car_body"] = "not in the result (no body states): car-body quantities left out"
    else:
        kind, by, bz = body
        if kind == "vel":
            ay = np.gradient(by, h)
            az = np.gradient(bz, h)
            layout = getattr(result, "layout", None)
            if layout is not None:
                kap, phi, _, _ = layout.at(pos)
                ay = ay + _G * np.sin(phi) + V * V * kap * np.cos(phi)
        else:
            ay, az = by, bz
        lo, hi = body_band
        if hi < fs / 2:
            fay = bandpass(ay, fs, lo, hi, order)
            faz = bandpass(az, fs, lo, hi, order)
            attrs["body_filter"] = f"Butterworth band-pass {lo:g}-{hi:g} Hz, order {order}"
        else:
            fay, faz = ay - ay.mean(), az - az.mean()
            attrs["body_filter"] = f"none (output rate {fs:g} Hz)"
        data["body_lateral_acc_rms"] = ((), float(np.sqrt(np.mean(fay ** 2))), {"units": "m/s2"})
        data["body_vertical_acc_rms"] = ((), float(np.sqrt(np.mean(faz ** 2))),
                                         {"units": "m/s2"})
        data["body_lateral_acc_max"] = ((), float(np.max(np.abs(fay))), {"units": "m/s2"})
        data["body_vertical_acc_max"] = ((), float(np.max(np.abs(faz))), {"units": "m/s2"})
        data["sperling_lateral"] = ((), float(sperling_wz(ay, fs, "lateral")), {"units": "1"})
        data["sperling_vertical"] = ((), float(sperling_wz(az, fs, "vertical")), {"units": "1"})
        attrs["car_body"] = "assessed"
    coords = {"wheelset": np.arange(nw), "side": ["left", "right"], "distance": c}
    return xr.Dataset(data, coords=coords, attrs=attrs)
