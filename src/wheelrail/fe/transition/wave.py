"""Surface-wave speed on the transition model's rail from a clean force pulse.

The start of a transition run is a poor source for a wave-speed measurement: the wheel
settles, bounces and rolls, and late motion at every distance masks the surface pulse
(docs/fe_transition.md). :func:`rail_pulse` strikes the *same* rail and track mesh
(:func:`~wheelrail.fe.transition.model.build_transition_model`: rail head, web and foot,
pads, sleepers, ballast; the wheel left out, its nodes held) with a short vertical force
pulse on a few running-surface nodes and records the velocities of the running-surface
line through the source every step; :func:`pulse_arrivals` picks the arrival of the pulse at
each station (the envelope peak, or the lag of the cross-correlation with the nearest
station) and fits the speed by least squares with its standard error;
:func:`elastic_wave_speeds` gives the P, S and Rayleigh speeds of the material to compare
with (the Rayleigh speed as the exact root of the Rayleigh equation and by Viktorov's
approximation).

The rail head is a guide (about 70 mm wide, 40–50 mm deep), not a half-space: a
surface pulse is a Rayleigh wave only where its wavelength is well below the head's
size, while the mesh needs several elements per wavelength (the reduced-integration
hexahedra of the 4 mm model disperse waves shorter than ≈ 8 elements). The pulse's
central frequency is therefore a parameter, and the benchmark
(``benchmarks/bench_fe_transition_wave.py``) reports the measured speed over
frequency and mesh size.

References
----------
.. [1] K.F. Graff, *Wave Motion in Elastic Solids*, Dover 1991, §6.3 (Rayleigh surface
   waves, the Rayleigh equation), §6.4 (Lamb's problem: the surface response to a
   point load is dominated by the Rayleigh pulse).
.. [2] I.A. Viktorov, *Rayleigh and Lamb Waves*, Plenum 1967, ch. 1
   (c_R / c_s ≈ (0.862 + 1.14 ν) / (1 + ν)).
.. [3] J.D. Achenbach, *Wave Propagation in Elastic Solids*, North-Holland 1973, §5.11
   (Rayleigh waves: the cubic in (c/c_s)²).
.. [4] X. Zhao, Z. Li, "The solution of frictional wheel-rail rolling contact with a 3D
   transient finite element model: validation and error analysis", Wear 271 (2011)
   444–452 (the explicit wheel–track model whose surface waves the transition study
   measures).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ...errors import InputError
from .. import _solid as S
from .._explicit import NCHUNK, advance
from .analysis import surface_stations
from .model import (TransitionCase, _group, build_transition_model,
                               check_surface_line, rail_surface_line)

__all__ = ["RailPulseResult", "elastic_wave_speeds", "rail_pulse", "pulse_arrivals",
           "force_pulse", "pulse_phase", "phase_velocity"]


def elastic_wave_speeds(E: float, nu: float, rho: float) -> dict:
    """Body and surface wave speeds of an isotropic elastic solid [m/s].

    Parameters
    ----------
    E : float
        Young's modulus [Pa].
    nu : float
        Poisson's ratio, 0 ≤ ν < 0.5.
    rho : float
        Density [kg/m³].

    Returns
    -------
    dict
        ``c_p`` = √((λ + 2G)/ρ), ``c_s`` = √(G/ρ), ``c_bar`` = √(E/ρ) (the long-wave speed
        of a bar), ``c_R`` the Rayleigh speed, the root in (0, c_s) of the Rayleigh equation
        written as a cubic in x = (c/c_s)² (Achenbach 1973 §5.11):
        x³ − 8x² + (24 − 16κ²)x − 16(1 − κ²) = 0 with κ² = c_s²/c_p² = (1 − 2ν)/(2(1 − ν)),
        and ``c_R_viktorov`` = c_s (0.862 + 1.14ν)/(1 + ν) (Viktorov 1967).

    Examples
    --------
    Steel, E = 210 GPa, ν = 0.3, ρ = 7850 kg/m³: c_p = 6001, c_s = 3208, c_R = 2975 m/s.
    """
    if not (E > 0 and rho > 0):
        raise InputError(f"E and rho must be positive, got E={E!r}, rho={rho!r}")
    if not 0.0 <= nu < 0.5:
        raise InputError(f"nu must be in [0, 0.5), got {nu!r}")
    G = E / (2.0 * (1.0 + nu))
    lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    c_s = np.sqrt(G / rho)
    c_p = np.sqrt((lam + 2.0 * G) / rho)
    k2 = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))
    roots = np.roots([1.0, -8.0, 24.0 - 16.0 * k2, -16.0 * (1.0 - k2)])
    x = [r.real for r in roots if abs(r.imag) < 1e-12 and 0.0 < r.real < 1.0]
    if len(x) != 1:
        raise InputError(f"no unique Rayleigh root for nu={nu!r}: {roots}")
    return {"c_p": float(c_p), "c_s": float(c_s), "c_bar": float(np.sqrt(E / rho)),
            "c_R": float(c_s * np.sqrt(x[0])),
            "c_R_viktorov": float(c_s * (0.862 + 1.14 * nu) / (1.0 + nu))}


def force_pulse(t, shape: str, frequency: float):
    """Unit force pulse at times ``t`` [s].

    ``"ricker"``: (1 − 2π²f²τ²) exp(−π²f²τ²), τ = t − 1.2/f (peak at 1.2/f, practically zero
    before 0 and after 2.4/f, spectrum peaked at f); ``"half-sine"``: sin(π f t) for
    0 ≤ t ≤ 1/f (duration 1/f, a one-signed blow).
    """
    t = np.asarray(t, float)
    if shape == "ricker":
        a = (np.pi * frequency * (t - 1.2 / frequency)) ** 2
        return np.where(t <= 2.4 / frequency, (1.0 - 2.0 * a) * np.exp(-a), 0.0)
    if shape == "half-sine":
        return np.where((t >= 0) & (t <= 1.0 / frequency), np.sin(np.pi * frequency * t), 0.0)
    raise InputError(f"pulse shape must be 'ricker' or 'half-sine', got {shape!r}")


@dataclass(frozen=True)
class RailPulseResult:
    """Record of :func:`rail_pulse`.

    Attributes
    ----------
    x : ndarray (n,)
        Signed distance [m] of the running-surface line's nodes from the source along x.
    t : ndarray (nt,)
        Times [s] of the records (force pulse starting at t = 0).
    v : ndarray (nt, n, 3)
        Velocities [m/s] of those nodes (x along the rail, y lateral, z vertical).
    force : ndarray (nt,)
        Total applied vertical force [N] (downwards positive).
    info : dict
        ``elements`` (rail and sleepers), ``time_step`` [s], ``steps``, ``cpu_s``,
        ``source_nodes``, ``mesh_size`` [m], ``pulse``, ``frequency`` [Hz], ``fine_band``
        (x range [m] of the fine mesh, relative to the source), ``head_width`` [m], ``at``,
        ``normal`` (3,) the outward surface normal of the line, ``contact_angle`` [deg]
        (its angle from the vertical), ``speeds`` (:func:`elastic_wave_speeds`).
    """

    x: np.ndarray
    t: np.ndarray
    v: np.ndarray
    force: np.ndarray
    info: dict


def rail_pulse(case: TransitionCase, *, model=None, at: str = "tread", pulse: str = "ricker",
               frequency: float = 100e3, force: float = 1e3, duration: float | None = None,
               source_x: float | None = None, every: int = 1) -> RailPulseResult:
    """Strike the rail of a transition case with a vertical force pulse; record the surface.

    The rail head, web, foot, pads, sleepers and ballast of
    :func:`~wheelrail.fe.transition.model.build_transition_model` (the same mesh, masses,
    ties and springs as :func:`~wheelrail.fe.transition.run_transition`) start at rest; the
    wheel's nodes are held and its elements left out. A force ``force`` ×
    :func:`force_pulse` along the inward surface normal at the source point (within a few
    degrees of vertical on the tread) is shared by the surface nodes within one element
    size of it: the rail's surface line at the start contact's lateral position
    (``at="tread"``) or at the rigid flange contact on the gauge corner (``at="flange"``,
    the node whose normal is closest to the rigid flange contact angle), at ``source_x``. The central-difference loop of the engine
    (:func:`~wheelrail.fe._solid.element_forces`, :func:`~wheelrail.fe._explicit.advance`)
    runs with the transition run's step; no damping.

    Parameters
    ----------
    case : TransitionCase
        Its ``mesh_size``, ``travel`` (the fine band of the rail is −3h − 10 mm to travel +
        50 mm) and track define the mesh.
    model : TransitionModel, optional
        Already built for ``case``.
    at : {"tread", "flange"}
        Source and recorded line: the tread contact's or the flange contact's position.
    pulse : {"ricker", "half-sine"}
    frequency : float
        Central frequency [Hz] of the Ricker pulse or inverse duration of the half-sine.
    force : float
        Peak force [N] (linear model: only scales the velocities).
    duration : float, optional
        Recorded time [s]; default: the pulse plus the Rayleigh pulse's travel to the
        nearer end of the fine band, × 1.3.
    source_x : float, optional
        Source position along the rail [m]; default the middle of the fine band.
    every : int
        Record every ``every`` steps.

    Returns
    -------
    RailPulseResult
    """
    if frequency <= 0 or force <= 0:
        raise InputError(f"frequency and force must be positive, got {frequency!r}, {force!r}")
    if every < 1:
        raise InputError(f"every must be >= 1, got {every!r}")
    force_pulse(0.0, pulse, frequency)            # validates the shape
    check_surface_line("at", at)             # before the model is built
    m = model if model is not None else build_transition_model(case)
    h = case.mesh_size
    nw = m.n_wheel
    n = m.n_nodes
    band = m.pose["x_band"]
    xs = 0.5 * (band[0] + band[1]) if source_x is None else float(source_x)
    if not band[0] <= xs <= band[1]:
        raise InputError(f"source_x {xs!r} m outside the fine band {band}")
    # rail and sleeper elements only (the wheel's nodes come first)
    groups = []
    for conn, chunks, ed, mat in m.groups:
        keep = np.all(conn >= nw, axis=1)
        groups.append(_group(conn[keep], m.nodes, mat, n) if not np.all(keep)
                      else (conn, chunks, ed, mat))
    n_el = int(sum(g[0].shape[0] for g in groups))
    dt = np.inf
    for conn, _, ed, mat in groups:
        scale = 1.0
        if mat is case.material:
            scale = np.sqrt(max(1.0, (case.min_element_fraction * h / ed.length.min()) ** 2))
        dt = min(dt, float(ed.length.min()) / mat.wave_speed * scale)
    dt = case.courant * min(dt, m.springs.stable_step(m.mass))
    speeds = elastic_wave_speeds(case.material.E, case.material.nu, case.material.density)
    half = min(xs - band[0], band[1] - xs)
    t_pulse = 2.4 / frequency if pulse == "ricker" else 1.0 / frequency
    if duration is None:
        duration = 1.3 * (t_pulse + half / speeds["c_R"])
    n_steps = int(np.ceil(duration / dt))
    # the surface line through the source at the tread or the flange contact position
    xm = m.nodes[m.master]
    line, n_out = rail_surface_line(m, xs, at)
    x_src = float(m.nodes[line[np.argmin(np.abs(m.nodes[line, 0] - xs))], 0])
    # source: surface nodes within one element size of the source point (surface distance)
    y_l, z_l = m.nodes[line[0], 1], m.nodes[line[0], 2]
    d_src = np.linalg.norm(xm - np.array([x_src, y_l, z_l]), axis=1)
    src = m.master[d_src <= 1.01 * h]
    w_src = 1.0 / src.size
    # masses, ties (rail web to head only), holds
    tie = m.tie_slave >= nw
    t_s, t_m, t_w = m.tie_slave[tie], m.tie_master[tie], m.tie_weight[tie]
    mass_eff = m.mass.copy()
    np.add.at(mass_eff, t_m.ravel(), (t_w * m.mass[t_s, None]).ravel())
    inv_m = 1.0 / mass_eff
    inv_m[:nw] = 0.0
    inv_m[t_s] = 0.0
    u = np.zeros((n, 3))
    v = np.zeros((n, 3))
    acc = np.zeros((n, 3))
    f_int = np.zeros((n, 3))
    f_tmp = np.zeros((n, 3))
    fext = np.zeros((n, 3))
    e_buf = [np.zeros((g[0].shape[0], 2)) for g in groups]
    partial = np.zeros((NCHUNK, 2))
    cmap = np.arange(n, dtype=np.int64)
    m_alpha = np.zeros(n)
    no_beta = np.zeros((1, 3))
    n_rec = n_steps // every
    rec = np.zeros((n_rec, line.size, 3))
    t_rec = np.zeros(n_rec)
    f_rec = np.zeros(n_rec)
    t_cpu = time.process_time()
    for k in range(n_steps):
        t = k * dt
        f_int[:] = 0.0
        for g, (conn, chunks, ed, mat) in enumerate(groups):
            S.element_forces(u, conn, chunks, ed.dNdx, ed.wdet, ed.gamma, ed.khg, mat.lam,
                             mat.shear_modulus, False, np.zeros(6), np.zeros(0), np.zeros(0),
                             np.zeros((0, 1, 14)), np.zeros((0, 1, 14)), f_tmp, e_buf[g])
            f_int += f_tmp
        fext[:] = 0.0
        fk = force * float(force_pulse(t, pulse, frequency))
        fext[src] = -fk * w_src * n_out
        m.springs.forces(u, v, fext)
        fs_t = fext[t_s] - f_int[t_s]
        for col in range(2):
            np.add.at(fext, t_m[:, col], t_w[:, col, None] * fs_t)
        advance(u, v, acc, f_int, no_beta, False, m_alpha, inv_m, cmap, fext, dt, partial)
        u[t_s] = (t_w[:, :, None] * u[t_m]).sum(axis=1)
        v[t_s] = (t_w[:, :, None] * v[t_m]).sum(axis=1)
        u[m.held_xy, :2] = 0.0
        v[m.held_xy, :2] = 0.0
        if (k + 1) % every == 0 and (k + 1) // every <= n_rec:
            j = (k + 1) // every - 1
            # v is the half-step velocity v(t + dt/2)
            rec[j] = v[line]
            t_rec[j] = t + 0.5 * dt
            f_rec[j] = fk
    cpu = time.process_time() - t_cpu
    head = m.meta["rail_rows"][0]
    info = {"elements": n_el, "time_step": dt, "steps": n_steps, "cpu_s": cpu,
            "ns_per_element_step": cpu / (n_steps * n_el) * 1e9, "source_nodes": int(src.size),
            "mesh_size": h, "pulse": pulse, "frequency": float(frequency),
            "fine_band": (band[0] - x_src, band[1] - x_src),
            "head_width": float(np.ptp(head[:, 0])), "speeds": speeds, "at": at,
            "normal": n_out, "contact_angle": float(np.degrees(np.arccos(abs(n_out[2]))))}
    return RailPulseResult(m.nodes[line, 0] - x_src, t_rec, rec, f_rec, info)


def _parabolic_peak(y, i):
    """Sub-sample position of the peak of ``y`` at index ``i`` (parabola through 3 points)."""
    if i <= 0 or i >= y.size - 1:
        return float(i)
    a, b, c = y[i - 1], y[i], y[i + 1]
    den = a - 2.0 * b + c
    return float(i) if den == 0 else float(i + 0.5 * (a - c) / den)


def _fit(d, ta):
    """Least-squares t = t0 + d / c: speed, its standard error, t0, rms residual."""
    A = np.stack([d, np.ones(d.size)], axis=1)
    coef, *_ = np.linalg.lstsq(A, ta, rcond=None)
    res = ta - A @ coef
    dof = max(1, d.size - 2)
    s2 = float(np.sum(res ** 2)) / dof
    se_slope = np.sqrt(s2 / float(np.sum((d - d.mean()) ** 2)))
    slope = float(coef[0])
    if not slope > 0:
        raise InputError("the picked arrival times do not increase with the distance")
    return {"speed": 1.0 / slope, "speed_se": se_slope / slope ** 2, "t0": float(coef[1]),
            "residual": float(np.sqrt(np.mean(res ** 2))), "d": d, "t_arrival": ta}


def pulse_arrivals(rec: RailPulseResult, d_min: float = 0.03, d_max: float = 0.08,
                   component: str = "z", method: str = "envelope", c_min: float | None = None,
                   c_max: float | None = None, side: str = "both",
                   threshold: float = 0.1, peak_fraction: float = 0.5) -> dict:
    """Arrival times of the pulse along the surface line and the fitted speed.

    Parameters
    ----------
    rec : RailPulseResult
    d_min, d_max : float
        Distances [m] from the source used in the fit (beyond the near field, inside the
        fine band and the record).
    component : {"x", "y", "z", "n"}
        Velocity component (``"n"``: along the line's surface normal).
    method : {"envelope", "xcorr", "first"}
        ``"envelope"``: the first local maximum of the trace's envelope (modulus of the
        analytic signal, Hilbert transform) inside the arrival window that reaches
        ``peak_fraction`` of the window's largest (the leading pulse; on the rail head a
        slower guided wave train follows it and can be larger); ``"xcorr"``: the pulse tracked outwards from the
        station nearest ``d_min`` (its envelope pick) by the lag of the cross-correlation
        of each pair of neighbouring stations, both under one Hann window of twice the
        pulse's duration centred at the time tracked so far (lags within half the pulse's
        duration: no cycle skips; the later wave train stays outside the window); ``"first"``: the first time the
        trace exceeds ``threshold`` × the largest amplitude at that station inside the
        window (the first arrival, P-like).
    c_min, c_max : float, optional
        Arrival window d/c_max ≤ t − t_pulse/2 ≤ d/c_min + t_pulse [m/s]; default
        0.5 c_s to 1.05 c_p of the case's material (so the slow flexural motion of the
        whole rail, which follows, is not picked).
    side : {"both", "ahead", "behind"}
        Stations on both sides of the source (by |x|), or only x > 0 / x < 0.
    threshold : float
        Fraction of the station's peak for ``method="first"``.
    peak_fraction : float
        Fraction of the window's largest envelope for ``method="envelope"``/``"xcorr"``.

    Returns
    -------
    dict
        ``speed`` [m/s], ``speed_se`` [m/s] (standard error from the residuals of the
        least-squares line t = t0 + d / c), ``t0`` [s], ``residual`` [s] (rms), ``d`` [m]
        and ``t_arrival`` [s] of the stations used, ``method``, ``component``.
    """
    from scipy.signal import hilbert

    comp = {"x": 0, "y": 1, "z": 2, "n": 3}
    if component not in comp:
        raise InputError(f"component must be 'x', 'y', 'z' or 'n', got {component!r}")
    if method not in ("envelope", "xcorr", "first"):
        raise InputError(f"method must be 'envelope', 'xcorr' or 'first', got {method!r}")
    x = rec.x
    sel = surface_stations(x, d_min, d_max, side)
    sp = rec.info["speeds"]
    c_min = 0.5 * sp["c_s"] if c_min is None else c_min
    c_max = 1.05 * sp["c_p"] if c_max is None else c_max
    f0 = rec.info["frequency"]
    t_pulse = 2.4 / f0 if rec.info["pulse"] == "ricker" else 1.0 / f0
    t = rec.t
    dtr = t[1] - t[0]
    idx = np.flatnonzero(sel)
    d = np.abs(x[idx])
    sig = (rec.v[:, idx] @ rec.info["normal"] if component == "n"
           else rec.v[:, idx, comp[component]])
    env = np.abs(hilbert(sig, axis=0))
    ta = np.full(idx.size, np.nan)
    for j in range(idx.size):
        lo = d[j] / c_max + 0.5 * t_pulse
        hi = d[j] / c_min + t_pulse
        win = np.flatnonzero((t >= lo) & (t <= hi))
        if win.size < 3 or hi > t[-1]:
            continue
        if method == "first":
            peak = np.max(np.abs(sig[win, j]))
            k = win[np.argmax(np.abs(sig[win, j]) >= threshold * peak)]
            # linear interpolation of the threshold crossing
            y0, y1 = np.abs(sig[k - 1, j]), np.abs(sig[k, j])
            frac = 1.0 if y1 == y0 else (threshold * peak - y0) / (y1 - y0)
            ta[j] = t[k - 1] + np.clip(frac, 0.0, 1.0) * dtr
        else:
            # the first local maximum of the envelope above peak_fraction of the window's
            # largest: the leading (Rayleigh) pulse, not the later guided wave train
            e = env[win, j]
            big = e >= peak_fraction * e.max()
            loc = np.flatnonzero(big[1:-1] & (e[1:-1] >= e[:-2]) & (e[1:-1] >= e[2:])) + 1
            k = win[loc[0] if loc.size else int(np.argmax(e))]
            ta[j] = t[0] + _parabolic_peak(env[:, j], k) * dtr
    ok = np.isfinite(ta)
    if ok.sum() < 3:
        raise InputError("the pulse has not reached 3 stations inside the record")
    if method == "xcorr":
        # track the pulse outwards on each side: the lag between neighbouring stations
        # (both traces under the same Hann window, centred at the time tracked so far),
        # starting from the envelope pick of the station nearest the source
        half = int(np.ceil(t_pulse / dtr))
        max_lag = 0.5 * t_pulse
        xs_sel = x[idx]
        for sgn in (1.0, -1.0):
            js = np.flatnonzero(np.sign(xs_sel) == sgn)
            js = js[np.argsort(d[js])]
            js = js[np.isfinite(ta[js])] if js.size else js
            if js.size < 2:
                continue
            tk = ta[js[0]]
            for jp, jn in zip(js[:-1], js[1:]):
                k = int(round((tk - t[0]) / dtr))
                w = np.zeros(t.size)
                a, b = max(0, k - half), min(t.size, k + half + 1)
                w[a:b] = np.hanning(b - a)
                cc = np.correlate(sig[:, jn] * w, sig[:, jp] * w, mode="full")
                lags = (np.arange(cc.size) - (t.size - 1)) * dtr
                cc[np.abs(lags) > max_lag] = -np.inf
                kk = int(np.argmax(cc))
                lag = (_parabolic_peak(np.where(np.isfinite(cc), cc, cc[kk]), kk)
                       - (t.size - 1)) * dtr
                tk = tk + lag
                ta[jn] = tk
    out = _fit(d[ok], ta[ok])
    out.update(method=method, component=component)
    return out


def pulse_phase(rec: RailPulseResult, arrivals: dict) -> dict:
    """Phase lag between the longitudinal and the surface-normal velocity at the pulse.

    For a Rayleigh wave the surface particle moves on an ellipse: the motion along the
    surface and the motion normal to it are a quarter period (90°) apart (Graff 1991,
    §6.3). At each station of ``arrivals`` (from :func:`pulse_arrivals`) the phases of the
    analytic signals of v_x and of the velocity along the line's surface normal (within a
    few degrees of v_z on the tread) are compared at the picked arrival time.

    Returns
    -------
    dict
        ``phase`` [deg] (median over the stations of |φ_x − φ_n| wrapped to 0–180°, v_x
        taken positive away from the source),
        ``iqr`` [deg] (its interquartile range), ``per_station`` [deg].
    """
    from scipy.signal import hilbert

    t = rec.t
    ph = []
    for d, ta in zip(arrivals["d"], arrivals["t_arrival"]):
        for j in np.flatnonzero(np.isclose(np.abs(rec.x), d, rtol=0, atol=1e-9)):
            az = hilbert(rec.v[:, j] @ rec.info["normal"])
            # mirrored behind the source (v_x is odd in x), so both sides compare alike
            ax = hilbert(np.sign(rec.x[j]) * rec.v[:, j, 0])
            k = int(np.clip(np.round((ta - t[0]) / (t[1] - t[0])), 0, t.size - 1))
            dphi = np.angle(ax[k] * np.conj(az[k]))
            ph.append(abs(np.degrees(dphi)))
    ph = np.array(ph)
    if ph.size == 0:
        raise InputError("no station of the arrivals found in the record")
    q1, q3 = np.percentile(ph, [25, 75])
    return {"phase": float(np.median(ph)), "iqr": (float(q1), float(q3)), "per_station": ph}


def _record_arrays(record):
    """(x, t, v, normal, source_shift) of a :class:`RailPulseResult` or ``info["wave"]``."""
    if isinstance(record, RailPulseResult):
        return record.x, record.t, record.v, record.info["normal"], 0.0
    if record is None:
        raise InputError("no wave record: run the case with wave_time > 0")
    x, t = np.asarray(record["x"], float), np.asarray(record["t"], float)
    v = np.asarray(record["v"], float) if "v" in record else None
    if v is None:
        raise InputError("the wave record has no 'v' (three components): rerun with this "
                         "version")
    # the contact moves on during the record: the stations ahead must stay ahead of it
    shift = float(record.get("speed", 0.0)) * float(t[-1] - t[0])
    return x, t, v, np.asarray(record.get("normal", (0.0, 0.0, 1.0)), float), shift


def phase_velocity(record, band: tuple = (40e3, 80e3), d_min: float = 0.02,
                   d_max: float = 0.08, side: str = "ahead", component: str = "z",
                   min_r2: float = 0.9) -> dict:
    """Phase velocity of the surface motion along a rail surface line, from its spectra.

    For a wave travelling along the line the phase of its Fourier component at frequency
    f falls linearly with the distance d travelled, φ(d) = φ₀ − 2πf d / c(f). At each
    frequency of ``band`` the phases of the stations (relative to the nearest station,
    unwrapped outwards along the line; the stations of the fine mesh are one element apart,
    so the phase step is below π for c > 2 f h) are fitted by a straight line in d; its
    slope gives c(f) and its coefficient of determination R² says whether one wave
    dominates at that frequency. This is the spectral-analysis-of-surface-waves idea
    (Nazarian & Stokoe 1984) on an array of stations: it needs no clean, isolated pulse, so
    it measures the waves in the record of a rolling run (``info["wave"]`` of
    :func:`~wheelrail.fe.transition.run_transition`) as well as those of
    :func:`rail_pulse`. Each trace is detrended (linear) and Hann-windowed in time first.

    Parameters
    ----------
    record : RailPulseResult or dict
        A :func:`rail_pulse` record or ``info["wave"]`` (``x`` (n,) [m] from the wheel
        centre at the record's start, ``t`` (nt,) [s], ``v`` (nt, n, 3) [m/s]).
    band : (float, float)
        Frequency band [Hz].
    d_min, d_max : float
        Distances [m] of the stations from the source (for a run: stations ahead are
        counted from where the contact is at the *end* of the record, so they stay ahead).
    side : {"ahead", "behind"}
        Stations at positive (ahead of the source, waves running in +x) or negative x.
    component : {"x", "y", "z", "n"}
        Velocity component (``"n"``: along the line's outward surface normal).
    min_r2 : float
        Frequencies whose linear phase fit has R² below this are left out of the band's
        estimate (several waves of similar size at that frequency).

    Returns
    -------
    dict
        ``speed`` [m/s]: 1 / (the power-weighted mean slowness over the accepted
        frequencies); ``speed_median`` [m/s] and ``speed_iqr`` over them; ``f`` [Hz],
        ``c`` [m/s], ``r2`` per frequency of the band; ``accepted`` (fraction of the band's
        frequencies with R² ≥ ``min_r2``); ``stations``; ``d`` [m] (their distances).

    References
    ----------
    S. Nazarian, K.H. Stokoe, "In situ shear wave velocities from spectral analysis of
    surface waves", Proc. 8th World Conf. on Earthquake Engineering, vol. 3 (1984) 31–38.
    K.F. Graff, *Wave Motion in Elastic Solids*, Dover 1991, §6.3 (Rayleigh waves).
    """
    from scipy.signal import detrend

    if side not in ("ahead", "behind"):
        raise InputError(f"side must be 'ahead' or 'behind', got {side!r}")
    f1, f2 = (float(b) for b in band)
    if not 0 < f1 < f2:
        raise InputError(f"band must be (f1, f2) with 0 < f1 < f2 [Hz], got {band!r}")
    if not 0 <= d_min < d_max:
        raise InputError(f"need 0 <= d_min < d_max, got {d_min!r}, {d_max!r}")
    x, t, v, normal, shift = _record_arrays(record)
    comp = {"x": 0, "y": 1, "z": 2}
    if component == "n":
        trace = v @ normal
    elif component in comp:
        trace = v[:, :, comp[component]]
    else:
        raise InputError(f"component must be 'x', 'y', 'z' or 'n', got {component!r}")
    if side == "ahead":
        d = x - shift
    else:
        d = -x
    sel = np.flatnonzero((d >= d_min) & (d <= d_max))
    if sel.size < 4:
        raise InputError(f"only {sel.size} stations between {d_min} and {d_max} m {side} of "
                         f"the source (need 4)")
    sel = sel[np.argsort(d[sel])]
    dt = float(t[1] - t[0])
    if f2 > 0.5 / dt:
        raise InputError(f"band {band!r} reaches above the Nyquist frequency {0.5 / dt:.0f} Hz")
    y = detrend(trace[:, sel], axis=0) * np.hanning(t.size)[:, None]
    spec = np.fft.rfft(y, axis=0)
    freq = np.fft.rfftfreq(t.size, dt)
    kb = np.flatnonzero((freq >= f1) & (freq <= f2))
    if kb.size < 2:
        raise InputError(f"the record ({t.size} samples of {dt:.3g} s) resolves fewer than 2 "
                         f"frequencies in the band {band!r}")
    ds = d[sel]
    dd = ds - ds[0]
    c = np.full(kb.size, np.nan)
    r2 = np.zeros(kb.size)
    power = np.zeros(kb.size)
    for i, k in enumerate(kb):
        s = spec[k]
        phi = np.unwrap(np.angle(s * np.conj(s[0])))
        coef = np.polyfit(dd, phi, 1)
        res = phi - np.polyval(coef, dd)
        tot = float(np.sum((phi - phi.mean()) ** 2))
        r2[i] = 1.0 - float(np.sum(res ** 2)) / tot if tot > 0 else 0.0
        if coef[0] < 0:
            c[i] = -2.0 * np.pi * freq[k] / coef[0]
        power[i] = float(np.sum(np.abs(s) ** 2))
    ok = (r2 >= min_r2) & np.isfinite(c)
    if not ok.any():
        raise InputError(f"no frequency in the band {band!r} has one dominant wave "
                         f"(largest R² {r2.max():.2f} < {min_r2})")
    slow = np.sum(power[ok] / c[ok]) / np.sum(power[ok])
    q1, q3 = np.percentile(c[ok], [25, 75])
    return {"speed": float(1.0 / slow), "speed_median": float(np.median(c[ok])),
            "speed_iqr": (float(q1), float(q3)), "f": freq[kb], "c": c, "r2": r2,
            "accepted": float(ok.mean()), "stations": int(sel.size), "d": ds}
