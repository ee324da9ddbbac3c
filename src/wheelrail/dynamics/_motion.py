"""Compiled equations of motion of the wheelset and bogie models and the fixed-step integrator.

The state layout and parameter vector are those of
:class:`wheelrail.dynamics.model.Assembly`. The equations (derived with
virtual work in the track-following frame; small angles in the suspension,
the contact forces with their exact lever arms, see
:mod:`wheelrail.dynamics._fastcontact`):

wheelset i (coordinates y, z, θ, ψ relative to the local track frame at s_i)::

    m ÿ  = Q_y + m a_y                a_y = −g sin φ − V² κ cos φ
    m z̈  = Q_z + m a_z                a_z = −g cos φ + V² κ sin φ
    Ix θ̈ = Q_θ + Iy Ω (ψ̇ + V κ)      (gyroscopic roll moment)
    Iz ψ̈ = Q_ψ − Iy Ω θ̇ − Iz (V² κ' + V̇ κ)
    Iy Ω̇ = Q_Ω                        (spin free; else Ω = V/r0)

with Q the contact and suspension forces and the carried mass's apparent
gravity (wheelset model), κ the track curvature, φ the cant angle. A
primary spring set on side σ (lateral position σ b) deflects by
d = (−σ b Δψ, Δy, Δz + σ b Δθ) relative to the frame point above it (frame
pose at the wheelset's position x_i, curvature offsets included) and acts
with F = −K d − C ḋ (− preload vertically). The frame (bogie) has the same
equations with the secondary suspension to the car body, which follows the
track centre line, and the body's apparent gravity acting on it. Rails: per
side and direction m v̇ = F_r − k1 (u − w) − c1 (v − ẇ), ẇ = (k1 (u − w) +
c1 v − k2 w)/(c1 + c2).

References
----------
.. [1] A.H. Wickens, *Fundamentals of rail vehicle dynamics*, 2003, ch. 2–4.
.. [2] J. Piotrowski, H. Chollet, VSD 43 (2005) 455–483, §2.2, §2.3.3.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._fastcontact import wheel_contact
from ._motion_common import (_G_BODY, _G_FM, _G_FRAME, _G_G, _G_NWS, _G_OF, _G_OR, _G_OX,
                             _G_R0, _G_RAILS, _G_RELAX, _G_SEC, _G_SPIN, _G_VEHICLE, _WP_B,
                             _WP_CARRIED_M, _WP_CX, _WP_CY, _WP_CZ, _WP_IX, _WP_IY, _WP_IZ,
                             _WP_KX, _WP_KY, _WP_KZ, _WP_M, _WP_PRELOAD, _WP_X, rail_rates)
from ._relaxation import relax_derivative, relax_gains
from ._speed import profile_at
from ._vehicle_motion import vehicle_derivative
from .model import NGP, NWP

__all__ = ["layout_at", "heading_at", "wheel_inputs", "derivative", "rhs_fast", "run_fixed",
           "relax_gains", "relax_derivative", "relax_decay", "relax_stage", "N_IN"]

#: Per-wheel contact inputs of :func:`wheel_inputs`.
IN_FIELDS = ("y", "zc", "roll", "yaw", "V", "omega", "vy", "vz", "yaw_rate", "roll_rate")
N_IN = len(IN_FIELDS)


# --------------------------------------------------------------------------- layout
@njit(cache=True)
def _hermite(u, j, row, iy):
    """Catmull–Rom cubic Hermite value and d/du of ``iy[row]`` at ``u`` in [j, j + 1)."""
    n = iy.shape[1]
    tt = u - j
    y0 = iy[row, j]
    y1 = iy[row, j + 1]
    m0 = 0.5 * (y1 - (iy[row, j - 1] if j > 0 else 0.0))
    m1 = 0.5 * ((iy[row, j + 2] if j + 2 < n else 0.0) - y0)
    t2 = tt * tt
    t3 = t2 * tt
    y = (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + tt) * m0 + (-2 * t3 + 3 * t2) * y1 \
        + (t3 - t2) * m1
    dy = ((6 * t2 - 6 * tt) * y0 + (3 * t2 - 4 * tt + 1) * m0 + (-6 * t2 + 6 * tt) * y1
          + (3 * t2 - 2 * tt) * m1)
    return y, dy


@njit(cache=True)
def layout_at(s, ks, kk, kp, kh, is0, ids, iy):
    """κ [1/m], cant angle φ [rad], alignment irregularity [m] and its slope d/ds at ``s``.

    ``iy`` (4, n): irregularity samples (alignment, level, cross level, gauge) from
    ``is0`` with spacing ``ids`` (:meth:`wheelrail.dynamics.TrackIrregularity.kernel_arrays`).
    """
    i = np.searchsorted(ks, s) - 1
    if i < 0:
        i = 0
    if i > ks.shape[0] - 2:
        i = ks.shape[0] - 2
    t = (s - ks[i]) / (ks[i + 1] - ks[i])
    kappa = kk[i] + t * (kk[i + 1] - kk[i])
    phi = kp[i] + t * (kp[i + 1] - kp[i])
    n = iy.shape[1]
    u = (s - is0) / ids
    j = int(math.floor(u))
    if j < 0 or j >= n - 1:
        return kappa, phi, 0.0, 0.0
    y, dy = _hermite(u, j, 0, iy)
    return kappa, phi, y, dy / ids


@njit(cache=True)
def rail_offsets(s, is0, ids, iy, out):
    """Irregular offsets of the rails at ``s``: ``out`` (2, 4) per side (left, right) the
    lateral offset [m] (to the right), its d/ds, the vertical offset [m] (up), its d/ds.

    Left rail: alignment − gauge/2, level − cross level/2; right rail: alignment +
    gauge/2, level + cross level/2 (:mod:`wheelrail.dynamics.irregularity`).
    """
    out[:] = 0.0
    n = iy.shape[1]
    u = (s - is0) / ids
    j = int(math.floor(u))
    if j < 0 or j >= n - 1:
        return
    a, da = _hermite(u, j, 0, iy)
    v, dv = _hermite(u, j, 1, iy)
    c, dc = _hermite(u, j, 2, iy)
    g, dg = _hermite(u, j, 3, iy)
    for side in range(2):
        sg = -0.5 if side == 0 else 0.5
        out[side, 0] = a + sg * g
        out[side, 1] = (da + sg * dg) / ids
        out[side, 2] = v + sg * c
        out[side, 3] = (dv + sg * dc) / ids


@njit(cache=True)
def heading_at(s, ks, kk, kh):
    """Heading of the track [rad] (∫κ ds) and dκ/ds at ``s``."""
    i = np.searchsorted(ks, s) - 1
    if i < 0:
        i = 0
    if i > ks.shape[0] - 2:
        i = ks.shape[0] - 2
    d = s - ks[i]
    slope = (kk[i + 1] - kk[i]) / (ks[i + 1] - ks[i])
    return kh[i] + kk[i] * d + 0.5 * slope * d * d, slope


@njit(cache=True)
def _offset(s0, x, ks, kk, kh):
    """Lateral offset of the centre line at s0 + x from the tangent at s0 [m] (Simpson)."""
    h0, _ = heading_at(s0, ks, kk, kh)
    hm, _ = heading_at(s0 + 0.5 * x, ks, kk, kh)
    h1, _ = heading_at(s0 + x, ks, kk, kh)
    return x / 6.0 * (4.0 * (hm - h0) + (h1 - h0))


# --------------------------------------------------------------------------- kinematics
@njit(cache=True)
def wheel_inputs(t, x, P, L, V, s_ref, W):
    """Pose and velocities of every wheel relative to its rail (W: (n_ws, 2, N_IN))."""
    ks, kk, kp, kh, is0, ids, iy = L
    nw = int(P[_G_NWS])
    rails = P[_G_RAILS] > 0
    r0 = P[_G_R0]
    orl = int(P[_G_OR])
    ro = np.empty((2, 4))
    for i in range(nw):
        b = 9 * i
        xi = P[NGP + NWP * i + _WP_X]
        si = s_ref + xi
        kappa, phi, _, _ = layout_at(si, ks, kk, kp, kh, is0, ids, iy)
        rail_offsets(si, is0, ids, iy, ro)
        om = x[b + 8] if P[_G_SPIN] > 0 else V / r0
        for side in range(2):
            ul = 0.0
            vl = 0.0
            uv = 0.0
            vv = 0.0
            if rails:
                rb = orl + 12 * i + 6 * side
                ul = x[rb + 1]
                vl = x[rb + 2]
                uv = x[rb + 4]
                vv = x[rb + 5]
            w = W[i, side]
            w[0] = x[b] - ro[side, 0] - ul
            w[1] = r0 + x[b + 1] - ro[side, 2] - uv
            w[2] = x[b + 2]
            w[3] = x[b + 3]
            w[4] = V
            w[5] = om
            w[6] = x[b + 4] - V * ro[side, 1] - vl
            w[7] = x[b + 5] - V * ro[side, 3] - vv
            w[8] = x[b + 7] + V * kappa
            w[9] = x[b + 6]


@njit(cache=True)
def derivative(t, x, P, L, V, aV, s_ref, Qn, Qt, amean, dx):
    """State derivative ``dx`` from the contact's generalised forces (see the module docstring).

    ``Qn``, ``Qt``: (n_ws, 2, 5) normal and tangential generalised forces of each
    wheel (y, z, roll, yaw, spin) — with creep relaxation, ``Qt`` are the relaxed
    forces (the relaxation states); their own rates are :func:`relax_derivative`'s.
    ``amean`` is not used here (kept for the signature).
    """
    ks, kk, kp, kh, is0, ids, iy = L
    if P[_G_VEHICLE] > 0:      # car body on bogies or wheelsets (_vehicle_motion)
        vehicle_derivative(t, x, P, ks, kk, kp, kh, V, aV, s_ref, Qn, Qt, amean, dx)
        return
    nw = int(P[_G_NWS])
    frame = P[_G_FRAME] > 0
    rails = P[_G_RAILS] > 0
    g = P[_G_G]
    r0 = P[_G_R0]
    of = int(P[_G_OF])
    orl = int(P[_G_OR])
    dx[:] = 0.0
    # frame pose (zero for the wheelset model: the reference follows the track)
    kf, phf, _, _ = layout_at(s_ref, ks, kk, kp, kh, is0, ids, iy)
    hf, dkf = heading_at(s_ref, ks, kk, kh)
    yf = zf = thf = chf = psf = 0.0
    vyf = vzf = wthf = wchf = wpsf = 0.0
    if frame:
        yf, zf, thf, chf, psf = x[of], x[of + 1], x[of + 2], x[of + 3], x[of + 4]
        vyf, vzf, wthf, wchf, wpsf = x[of + 5], x[of + 6], x[of + 7], x[of + 8], x[of + 9]
    Qf = np.zeros(5)            # frame: y, z, roll, pitch, yaw
    for i in range(nw):
        b = 9 * i
        pb = NGP + NWP * i
        m = P[pb + _WP_M]
        Ix = P[pb + _WP_IX]
        Iy = P[pb + _WP_IY]
        Iz = P[pb + _WP_IZ]
        kx, ky, kz = P[pb + _WP_KX], P[pb + _WP_KY], P[pb + _WP_KZ]
        cx, cy, cz = P[pb + _WP_CX], P[pb + _WP_CY], P[pb + _WP_CZ]
        bs = P[pb + _WP_B]
        xi = P[pb + _WP_X]
        pre = P[pb + _WP_PRELOAD]
        mc = P[pb + _WP_CARRIED_M]
        si = s_ref + xi
        kappa, phi, _, _ = layout_at(si, ks, kk, kp, kh, is0, ids, iy)
        hi, dki = heading_at(si, ks, kk, kh)
        cph, sph = math.cos(phi), math.sin(phi)
        ay = -g * sph - V * V * kappa * cph
        az = -g * cph + V * V * kappa * sph
        y, z, th, ps = x[b], x[b + 1], x[b + 2], x[b + 3]
        vy, vz, wth, wps = x[b + 4], x[b + 5], x[b + 6], x[b + 7]
        om = x[b + 8] if P[_G_SPIN] > 0 else V / r0
        Q = np.zeros(5)
        for side in range(2):
            for k in range(5):
                Q[k] += Qn[i, side, k] + Qt[i, side, k]
        Q[0] += mc * ay
        Q[1] += mc * az
        # primary suspension to the frame point above the axle
        Yc = 0.0
        dh = 0.0
        ddh = 0.0
        dphi = 0.0
        if frame:
            Yc = _offset(s_ref, xi, ks, kk, kh)
            dh = hi - hf
            ddh = V * (kappa - kf)
            dphi = phi - phf
        dy_ = y + Yc - (yf + xi * psf)
        dvy = vy - (vyf + xi * wpsf)
        for side in range(2):
            sg = -1.0 if side == 0 else 1.0
            d_x = -sg * bs * (ps + dh - psf)
            v_x = -sg * bs * (wps + ddh - wpsf)
            d_z = z + sg * bs * (th + dphi) - (zf + sg * bs * thf + xi * chf)
            v_z = vz + sg * bs * wth - (vzf + sg * bs * wthf + xi * wchf)
            Fx = -kx * d_x - cx * v_x
            Fy = -ky * dy_ - cy * dvy
            Fz = -kz * d_z - cz * v_z - pre
            Q[0] += Fy
            Q[1] += Fz
            Q[2] += sg * bs * Fz
            Q[3] += -sg * bs * Fx
            # reactions on the frame (virtual work: F . dd/dq_frame)
            Qf[0] += -Fy
            Qf[4] += -xi * Fy + sg * bs * Fx
            Qf[1] += -Fz
            Qf[2] += -sg * bs * Fz
            Qf[3] += -xi * Fz
        dx[b] = vy
        dx[b + 1] = vz
        dx[b + 2] = wth
        dx[b + 3] = wps
        dx[b + 4] = Q[0] / m + ay
        dx[b + 5] = Q[1] / m + az
        dx[b + 6] = (Q[2] + Iy * om * (wps + V * kappa)) / Ix
        dx[b + 7] = (Q[3] - Iy * om * wth) / Iz - (V * V * dki + aV * kappa)
        dx[b + 8] = Q[4] / Iy if P[_G_SPIN] > 0 else aV / r0
        # rails under this wheelset
        if rails:
            rail_rates(i, orl, P, x, Qn, Qt, dx)
    if frame:
        mf = P[_G_FM]
        Ifx, Ify, Ifz = P[_G_FM + 1], P[_G_FM + 2], P[_G_FM + 3]
        skx, sky, skz = P[_G_SEC], P[_G_SEC + 1], P[_G_SEC + 2]
        scx, scy, scz = P[_G_SEC + 3], P[_G_SEC + 4], P[_G_SEC + 5]
        b2 = P[_G_SEC + 6]
        mb = P[_G_BODY]
        cph, sph = math.cos(phf), math.sin(phf)
        ay = -g * sph - V * V * kf * cph
        az = -g * cph + V * V * kf * sph
        for side in range(2):
            sg = -1.0 if side == 0 else 1.0
            Fx = -skx * (-sg * b2 * psf) - scx * (-sg * b2 * wpsf)
            Fy = -sky * yf - scy * vyf
            Fz = -skz * (zf + sg * b2 * thf) - scz * (vzf + sg * b2 * wthf)
            Qf[0] += Fy
            Qf[1] += Fz
            Qf[2] += sg * b2 * Fz
            Qf[4] += -sg * b2 * Fx
        dx[of] = vyf
        dx[of + 1] = vzf
        dx[of + 2] = wthf
        dx[of + 3] = wchf
        dx[of + 4] = wpsf
        dx[of + 5] = Qf[0] / mf + ay * (mf + mb) / mf
        dx[of + 6] = Qf[1] / mf + az * (mf + mb) / mf
        dx[of + 7] = Qf[2] / Ifx
        dx[of + 8] = Qf[3] / Ify
        dx[of + 9] = Qf[4] / Ifz - (V * V * dkf + aV * kf)


# --------------------------------------------------------------------------- creep relaxation
@njit(cache=True)
def _steady_forces(OW, F):
    """The steady creep forces Q_t of every wheel from the contact outputs, F (n_ws·10,)."""
    nw = OW.shape[0]
    for i in range(nw):
        for side in range(2):
            for c in range(5):
                F[10 * i + 5 * side + c] = OW[i, side, 6 + c]


@njit(cache=True)
def relax_decay(P, V, OW, h, E):
    """exp(−k h) of every relaxation state (k from the contact outputs ``OW``), E (n_ws·10,)."""
    nw = OW.shape[0]
    am = np.empty((nw, 2))
    for i in range(nw):
        for side in range(2):
            am[i, side] = OW[i, side, 17]
    k = np.empty((nw, 2))
    relax_gains(P, V, am, k)
    for i in range(nw):
        for side in range(2):
            for c in range(5):
                E[10 * i + 5 * side + c] = math.exp(-k[i, side] * h)


@njit(cache=True)
def relax_stage(xt, x, F, E, ox):
    """The relaxation states of a stage or step end, exact for the steady force F held
    over the interval: q = F + (q0 − F) exp(−k h) (``E`` = exp(−k h))."""
    for j in range(F.shape[0]):
        xt[ox + j] = F[j] + (x[ox + j] - F[j]) * E[j]


@njit(cache=True)
def _split(OW, Qn, Qt, amean, relax, x, ox):
    nw = OW.shape[0]
    for i in range(nw):
        for side in range(2):
            for k in range(5):
                Qn[i, side, k] = OW[i, side, 1 + k]
                Qt[i, side, k] = OW[i, side, 6 + k]
            amean[i, side] = OW[i, side, 17]


@njit(cache=True)
def rhs_fast(t, x, P, L, SP, vmin, geo_l, geo_r, meth, mu, OP, OW, dx):
    """State derivative with the compiled contact of every wheel (see ``wheel_contact``).

    ``SP`` (5, n) is the run's speed profile (:func:`~wheelrail.dynamics._speed.profile_at`:
    speed V, dV/dt and position of the reference at ``t``), the speed floored at
    ``vmin`` in the kinematics. ``OP`` (n_ws, 2, KMAX, fields) and ``OW`` (n_ws, 2,
    fields) receive the contact outputs. Returns the total number of patches.
    """
    V, aV, s_ref = profile_at(SP, t)
    V = max(V, vmin)
    nw = int(P[_G_NWS])
    W = np.empty((nw, 2, N_IN))
    wheel_inputs(t, x, P, L, V, s_ref, W)
    total = 0
    for i in range(nw):
        for side in range(2):
            w = W[i, side]
            geo = geo_l if side == 0 else geo_r
            sg, pg, p1g, lo, hi, wu, winv, wc, ru, rinv, rc, r0, e_tape, sig, off, zt, ang = geo
            (mp, hz_lam, hz_la, hz_lb, hz_lp, hz_ld, kx, c11, c22, c23, c33, fs_t, fs_half, fs_peak,
             fs_cells, fs_factor, rs_i0, rs_i1, rs_w, tk_values, tk_x0, tk_dx, tk_n, tk_cubic, tk_cx0,
             tk_cdx, tk_cn, tk_coef) = meth
            total += wheel_contact(sg, pg, p1g, lo, hi, wu, winv, wc, ru, rinv, rc, r0, e_tape,
                                   sig, off, zt, ang, w[0], w[1], w[2], w[3], w[4], w[5], w[6],
                                   w[7], w[8], w[9], mu, mp, hz_lam, hz_la, hz_lb, hz_lp, hz_ld,
                                   kx, c11, c22, c23, c33, fs_t, fs_half, fs_peak, fs_cells,
                                   fs_factor, rs_i0, rs_i1, rs_w, tk_values, tk_x0, tk_dx, tk_n, tk_cubic,
                                   tk_cx0, tk_cdx, tk_cn, tk_coef, OP[i, side],
                                   OW[i, side])
    Qn = np.empty((nw, 2, 5))
    Qt = np.empty((nw, 2, 5))
    amean = np.empty((nw, 2))
    ox = int(P[_G_OX])
    _split(OW, Qn, Qt, amean, P[_G_RELAX] > 0, x, ox)
    if P[_G_RELAX] > 0:
        Qr = np.empty((nw, 2, 5))
        for i in range(nw):
            for side in range(2):
                for k in range(5):
                    Qr[i, side, k] = x[ox + 10 * i + 5 * side + k]
        derivative(t, x, P, L, V, aV, s_ref, Qn, Qr, amean, dx)
        relax_derivative(x, P, V, Qt, amean, dx)
    else:
        derivative(t, x, P, L, V, aV, s_ref, Qn, Qt, amean, dx)
    return total


@njit(cache=True)
def _signature(OW, sig):
    """Number of patches of every wheel (the contact configuration)."""
    nw = OW.shape[0]
    changed = False
    for i in range(nw):
        for side in range(2):
            v = int(OW[i, side, 0])
            if v != sig[2 * i + side]:
                changed = True
            sig[2 * i + side] = v
    return changed


@njit(cache=True)
def run_fixed(x0, t0, dt, nsteps, every, P, L, SP, vmin, geo_l, geo_r, meth, mu,
              scheme, max_halvings, T_out, X_out, OP_out, OW_out, events):
    """Fixed-step explicit integration with the compiled contact (real-time path).

    ``scheme`` 4: classical Runge–Kutta; 2: Heun. The creep-relaxation states (a
    stiff first-order lag, time constant L/V, often shorter than the step) are not
    stepped by the scheme: each stage and the step end take the exact solution of
    dq/dt = k (F − q) for the steady force F of the stage before held over the
    interval, q = F + (q0 − F) exp(−k h), and the step end the scheme's weighted
    mean of the stages' F (k from the step's start). Stable at any k h, exact for a
    constant F (step response exp(−V t/L)), and the same fixed point as without
    relaxation. A step across which the contact
    configuration (number of patches of a wheel) changes is redone in halves, down
    to ``dt / 2**max_halvings``, so that no step of more than that size straddles a
    contact jump (the configuration is checked at every step end; this costs no extra
    contact evaluation, the end state's is the next step's first stage). Every
    ``every`` steps the state and the contact outputs are written to the ``*_out``
    arrays. ``events`` (k, 3) receives (t, wheel index 2 i + side, new patch count)
    of each configuration change.

    Returns (outputs written, events written, contact evaluations, rejected steps).
    """
    n = x0.shape[0]
    nw = int(P[_G_NWS])
    KM = OP_out.shape[3]
    NF = OP_out.shape[4]
    NWF = OW_out.shape[3]
    x = x0.copy()
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    xt = np.empty(n)
    xn = np.empty(n)
    OP = np.zeros((nw, 2, KM, NF))
    OW = np.zeros((nw, 2, NWF))
    OPn = np.zeros((nw, 2, KM, NF))
    OWn = np.zeros((nw, 2, NWF))
    kn = np.empty(n)
    sig = np.zeros(2 * nw, np.int64)
    sign = np.zeros(2 * nw, np.int64)
    relax = P[_G_RELAX] > 0
    ox = int(P[_G_OX])
    nr = 10 * nw
    F1 = np.empty(nr)
    F2 = np.empty(nr)
    F3 = np.empty(nr)
    F4 = np.empty(nr)
    Eh = np.empty(nr)
    Ef = np.empty(nr)
    t = t0
    rhs_fast(t, x, P, L, SP, vmin, geo_l, geo_r, meth, mu, OP, OW, k1)
    nev = 1
    _signature(OW, sig)
    nout = 0
    ne = 0
    rejected = 0
    for step in range(nsteps):
        if step % every == 0 and nout < T_out.shape[0]:
            T_out[nout] = t
            X_out[nout] = x
            OP_out[nout] = OP
            OW_out[nout] = OW
            nout += 1
        t_end = t0 + (step + 1) * dt
        h = dt
        while t < t_end - 1e-12 * dt:
            hh = min(h, t_end - t)
            # one step from (t, x) with slope k1; the relaxation states by the exact
            # exponential update over each stage (stiff: time constant L/V)
            if relax:
                Vt = max(profile_at(SP, t)[0], vmin)
                relax_decay(P, Vt, OW, 0.5 * hh, Eh)
                relax_decay(P, Vt, OW, hh, Ef)
                _steady_forces(OW, F1)
            if scheme == 4:
                for j in range(n):
                    xt[j] = x[j] + 0.5 * hh * k1[j]
                if relax:
                    relax_stage(xt, x, F1, Eh, ox)
                rhs_fast(t + 0.5 * hh, xt, P, L, SP, vmin, geo_l, geo_r, meth, mu, OPn,
                         OWn, k2)
                if relax:
                    _steady_forces(OWn, F2)
                for j in range(n):
                    xt[j] = x[j] + 0.5 * hh * k2[j]
                if relax:
                    relax_stage(xt, x, F2, Eh, ox)
                rhs_fast(t + 0.5 * hh, xt, P, L, SP, vmin, geo_l, geo_r, meth, mu, OPn,
                         OWn, k3)
                if relax:
                    _steady_forces(OWn, F3)
                for j in range(n):
                    xt[j] = x[j] + hh * k3[j]
                if relax:
                    relax_stage(xt, x, F3, Ef, ox)
                rhs_fast(t + hh, xt, P, L, SP, vmin, geo_l, geo_r, meth, mu, OPn, OWn,
                         k4)
                for j in range(n):
                    xn[j] = x[j] + hh / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
                if relax:
                    _steady_forces(OWn, F4)
                    for j in range(nr):
                        F1[j] = (F1[j] + 2.0 * F2[j] + 2.0 * F3[j] + F4[j]) / 6.0
                    relax_stage(xn, x, F1, Ef, ox)
                nev += 3
            else:
                for j in range(n):
                    xt[j] = x[j] + hh * k1[j]
                if relax:
                    relax_stage(xt, x, F1, Ef, ox)
                rhs_fast(t + hh, xt, P, L, SP, vmin, geo_l, geo_r, meth, mu, OPn, OWn,
                         k2)
                for j in range(n):
                    xn[j] = x[j] + 0.5 * hh * (k1[j] + k2[j])
                if relax:
                    _steady_forces(OWn, F2)
                    for j in range(nr):
                        F1[j] = 0.5 * (F1[j] + F2[j])
                    relax_stage(xn, x, F1, Ef, ox)
                nev += 1
            rhs_fast(t + hh, xn, P, L, SP, vmin, geo_l, geo_r, meth, mu, OPn, OWn, kn)
            nev += 1
            for j in range(2 * nw):
                sign[j] = sig[j]
            changed = _signature(OWn, sign)
            if changed and hh > dt / 2.0 ** max_halvings * (1 + 1e-9):
                h = 0.5 * hh          # the configuration changes inside: halve the step
                rejected += 1
                continue
            t = t + hh
            for j in range(n):
                x[j] = xn[j]
                k1[j] = kn[j]
            OP[:] = OPn
            OW[:] = OWn
            if changed:
                for j in range(2 * nw):
                    if sign[j] != sig[j] and ne < events.shape[0]:
                        events[ne, 0] = t
                        events[ne, 1] = j
                        events[ne, 2] = sign[j]
                        ne += 1
                    sig[j] = sign[j]
                h = dt / 2.0 ** max_halvings        # leave the jump with small steps
            else:
                h = min(2.0 * hh, dt)
        if not np.all(np.isfinite(x)):
            break
    if nout < T_out.shape[0]:
        T_out[nout] = t
        X_out[nout] = x
        OP_out[nout] = OP
        OW_out[nout] = OW
        nout += 1
    return nout, ne, nev, rejected
