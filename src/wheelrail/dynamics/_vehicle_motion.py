"""Compiled equations of motion of the whole vehicle (:class:`~wheelrail.dynamics.VehicleModel`).

State layout and parameters: :class:`wheelrail.dynamics.vehicle.VehicleAssembly`.
Every body (car body at s, frame j at s + x_j, wheelset i at s + x_i) moves
relative to the track-following frame at its own position; in it

    m ÿ  = Q_y + m a_y                a_y = −g sin φ − V² κ cos φ
    m z̈  = Q_z + m a_z                a_z = −g cos φ + V² κ sin φ
    Ix θ̈ = Q_θ   (+ Iy Ω (ψ̇ + V κ) for a wheelset)
    Iy χ̈ = Q_χ   (frames and car body)
    Iz ψ̈ = Q_ψ − Iz (V² κ' + V̇ κ)   (− Iy Ω θ̇ for a wheelset)
    Iy Ω̇ = Q_Ω   (wheelset, spin free)

(the wheelset's equations are those of :mod:`wheelrail.dynamics._motion`). A
suspension element between a point p_c of a child body (wheelset or frame)
and p_p of its parent (frame or car body) deflects by the relative
displacement d = δ_c(p_c) − δ_p(p_p) of the two points,

    δ(p) = (−p_y ψ − p_z χ,  y + p_x ψ − p_z θ,  z + p_y θ + p_x χ),

the child's pose taken with the lateral offset of its centre line from the
parent's tangent (Simpson's rule on the heading), the heading and the cant
differences added; its force F on the child acts on the child's coordinates
(y, z, θ, χ, ψ) as (F_y, F_z, −p_z F_y + p_y F_z, −p_z F_x + p_x F_z,
−p_y F_x + p_x F_y) and the opposite on the parent's (virtual work).
Elements: spring–damper sets (F = −K d − C ḋ, the vertical preload P carrying
the weight above; its lever arm turns with the body it acts on, adding the
moments −p_z θ P and −p_z χ P — the overturning of a weight carried below its
centre of mass; the same terms of the lateral and longitudinal forces are of
second order and left out), rotational yaw springs and the anti-roll bar (moments on
the relative yaw and roll), yaw dampers (Maxwell: F = −k (d_x − u),
u̇ = k (d_x − u)/c) and lateral bump stops (F_y = −f(d_y), f the odd
piecewise-linear table).

References
----------
.. [1] A.H. Wickens, *Fundamentals of rail vehicle dynamics*, 2003, ch. 2–6.
.. [2] S. Iwnicki (ed.), *Handbook of railway vehicle dynamics*, CRC 2006, ch. 5.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._motion_common import (_G_G, _G_NWS, _G_OF, _G_OR, _G_R0, _G_RAILS, _G_RELAX, _G_SPIN,
                             _WP_B, _WP_CX, _WP_CY, _WP_CZ, _WP_IX, _WP_IY, _WP_IZ, _WP_KX,
                             _WP_KY, _WP_KZ, _WP_M, _WP_PRELOAD, _WP_X, rail_rates)
from ._relaxation import relax_derivative
from .model import NGP, NWP

__all__ = ["vehicle_derivative", "VP", "NVP", "BUMP_MAX"]

#: Largest number of points of a bump-stop table.
BUMP_MAX = 24
#: Vehicle parameters after the wheelset blocks (see
#: :class:`wheelrail.dynamics.vehicle.VehicleAssembly`; defined here, beside the kernel, so
#: that a change of the layout recompiles it).
VP = {n: i for i, n in enumerate((
    "n_frames", "body_m", "body_Ix", "body_Iy", "body_Iz", "body_h", "frame_h", "prim_h",
    "fm0", "fIx0", "fIy0", "fIz0", "fm1", "fIx1", "fIy1", "fIz1", "xf0", "xf1",
    "s_kx", "s_ky", "s_kz", "s_cx", "s_cy", "s_cz", "s_b", "s_h", "s_kpsi", "s_arb", "s_pre",
    "yd", "yd_c", "yd_k", "yd_b", "bs_n",
    "par0", "par1", "par2", "par3", "xr0", "xr1", "xr2", "xr3",
    "off_body", "off_yd")
    + tuple(f"bs_d{k}" for k in range(BUMP_MAX)) + tuple(f"bs_f{k}" for k in range(BUMP_MAX)))}
NVP = len(VP)

_V_NF = VP["n_frames"]
_V_BODY = VP["body_m"]
_V_BH = VP["body_h"]
_V_FH = VP["frame_h"]
_V_PH = VP["prim_h"]
_V_FM = VP["fm0"]
_V_XF = VP["xf0"]
_V_SEC = VP["s_kx"]
_V_YD = VP["yd"]
_V_BSN = VP["bs_n"]
_V_BSD = VP["bs_d0"]
_V_BSF = VP["bs_f0"]
_V_PAR = VP["par0"]
_V_XR = VP["xr0"]
_V_OB = VP["off_body"]
_V_OYD = VP["off_yd"]


@njit(cache=True)
def _track(s, ks, kk, kp, kh):
    """κ, dκ/ds, φ, dφ/ds and heading ∫κ ds at s (piecewise-linear κ and φ)."""
    i = np.searchsorted(ks, s) - 1
    if i < 0:
        i = 0
    if i > ks.shape[0] - 2:
        i = ks.shape[0] - 2
    L = ks[i + 1] - ks[i]
    d = s - ks[i]
    t = d / L
    dk = (kk[i + 1] - kk[i]) / L
    kappa = kk[i] + t * (kk[i + 1] - kk[i])
    dphi = (kp[i + 1] - kp[i]) / L
    phi = kp[i] + t * (kp[i + 1] - kp[i])
    return kappa, dk, phi, dphi, kh[i] + kk[i] * d + 0.5 * dk * d * d


@njit(cache=True)
def _heading(s, ks, kk, kp, kh):
    return _track(s, ks, kk, kp, kh)[4]


@njit(cache=True)
def _frame_offsets(sp, x, V, ks, kk, kp, kh, off, doff):
    """Offsets of the track frame at sp + x from that at sp: lateral offset of the centre
    line from the tangent (Simpson), heading and cant differences (``off``), their rates
    at speed V (``doff``)."""
    kap0, _, ph0, dph0, h0 = _track(sp, ks, kk, kp, kh)
    kap1, _, ph1, dph1, h1 = _track(sp + x, ks, kk, kp, kh)
    hm = _heading(sp + 0.5 * x, ks, kk, kp, kh)
    off[0] = x / 6.0 * (4.0 * (hm - h0) + (h1 - h0))
    off[1] = h1 - h0
    off[2] = ph1 - ph0
    doff[0] = V * (h1 - h0 - x * kap0)
    doff[1] = V * (kap1 - kap0)
    doff[2] = V * (dph1 - dph0)


@njit(cache=True)
def _delta(q, p, out):
    """Small displacement of the point p of a body with pose q = (y, z, θ, χ, ψ)."""
    out[0] = -p[1] * q[4] - p[2] * q[3]
    out[1] = q[0] + p[0] * q[4] - p[2] * q[2]
    out[2] = q[1] + p[1] * q[2] + p[0] * q[3]


@njit(cache=True)
def _apply(F, p, sgn, Q):
    """Add sgn × the generalised force of the force F at the point p to Q (y, z, θ, χ, ψ)."""
    Q[0] += sgn * F[1]
    Q[1] += sgn * F[2]
    Q[2] += sgn * (-p[2] * F[1] + p[1] * F[2])
    Q[3] += sgn * (-p[2] * F[0] + p[0] * F[2])
    Q[4] += sgn * (-p[1] * F[0] + p[0] * F[1])


@njit(cache=True)
def _pendulum(Fz, pz, q, Q):
    """Roll and pitch moments of a vertical force Fz at height pz of a body rolled and
    pitched by q[2], q[3] (its lever arm turned with the body: the weights' overturning)."""
    Q[2] -= pz * q[2] * Fz
    Q[3] -= pz * q[3] * Fz


@njit(cache=True)
def _relative(qc, vc, pc, qp, vp, pp, d, v):
    """Relative displacement and velocity of the child's point pc and the parent's pp."""
    a = np.empty(3)
    b = np.empty(3)
    _delta(qc, pc, a)
    _delta(qp, pp, b)
    for k in range(3):
        d[k] = a[k] - b[k]
    _delta(vc, pc, a)
    _delta(vp, pp, b)
    for k in range(3):
        v[k] = a[k] - b[k]


@njit(cache=True)
def _bump(P, vb, d):
    """Bump-stop force (odd piecewise-linear table, last slope beyond) at deflection d;
    ``vb`` the start of the vehicle parameters in P."""
    n = int(P[vb + _V_BSN])
    xs = P[vb + _V_BSD:vb + _V_BSD + n]
    fs = P[vb + _V_BSF:vb + _V_BSF + n]
    a = abs(d)
    if n < 2 or a <= xs[0]:
        return 0.0
    last = n - 1
    if a >= xs[last]:
        f = fs[last] + (fs[last] - fs[last - 1]) / (xs[last] - xs[last - 1]) * (a - xs[last])
    else:
        k = np.searchsorted(xs, a) - 1
        f = fs[k] + (a - xs[k]) / (xs[k + 1] - xs[k]) * (fs[k + 1] - fs[k])
    return f if d > 0 else -f


@njit(cache=True)
def vehicle_derivative(t, x, P, ks, kk, kp, kh, V, aV, s_ref, Qn, Qt, amean, dx):
    """State derivative ``dx`` of the vehicle from the wheels' generalised contact forces
    ``Qn``, ``Qt`` (n_ws, 2, 5: y, z, roll, yaw, spin) and patch semi-axes ``amean``
    (module docstring; arguments as :func:`wheelrail.dynamics._motion.derivative` with the
    layout's curvature, cant and heading arrays)."""
    nw = int(P[_G_NWS])
    rails = P[_G_RAILS] > 0
    relax = P[_G_RELAX] > 0
    spin_free = P[_G_SPIN] > 0
    g = P[_G_G]
    r0 = P[_G_R0]
    of = int(P[_G_OF])
    orl = int(P[_G_OR])
    vb = NGP + NWP * nw
    nf = int(P[vb + _V_NF])
    ob = int(P[vb + _V_OB])
    oyd = int(P[vb + _V_OYD])
    dx[:] = 0.0
    hb = P[vb + _V_BH]
    hf = P[vb + _V_FH]
    hp = P[vb + _V_PH]
    # poses (y, z, roll, pitch, yaw) and rates of frames (0, 1) and car body (nf)
    nb = nf + 1
    q = np.zeros((nb, 5))
    qd = np.zeros((nb, 5))
    Qb = np.zeros((nb, 5))
    starts = np.empty(nb, np.int64)
    for j in range(nf):
        starts[j] = of + 10 * j
    starts[nf] = ob
    for j in range(nb):
        o = starts[j]
        for k in range(5):
            q[j, k] = x[o + k]
            qd[j, k] = x[o + 5 + k]
    xpos = np.zeros(nb)          # positions relative to the car body's centre
    for j in range(nf):
        xpos[j] = P[vb + _V_XF + j]
    heights = np.empty(nb)
    for j in range(nf):
        heights[j] = hf
    heights[nf] = hb
    off = np.empty(3)
    doff = np.empty(3)
    d = np.empty(3)
    v = np.empty(3)
    F = np.empty(3)
    pc = np.empty(3)
    pp = np.empty(3)
    qc = np.empty(5)
    vc = np.empty(5)
    # ---------------------------------------------------------------- wheelsets
    for i in range(nw):
        b = 9 * i
        pb = NGP + NWP * i
        m, Ix, Iy, Iz = P[pb + _WP_M], P[pb + _WP_IX], P[pb + _WP_IY], P[pb + _WP_IZ]
        kx, ky, kz = P[pb + _WP_KX], P[pb + _WP_KY], P[pb + _WP_KZ]
        cx, cy, cz = P[pb + _WP_CX], P[pb + _WP_CY], P[pb + _WP_CZ]
        bs = P[pb + _WP_B]
        xi = P[pb + _WP_X]
        pre = P[pb + _WP_PRELOAD]
        par = int(P[vb + _V_PAR + i])
        jp = par if par >= 0 else nf
        xr = P[vb + _V_XR + i]
        si = s_ref + xi
        kappa, dki, phi, _, _ = _track(si, ks, kk, kp, kh)
        cph, sph = math.cos(phi), math.sin(phi)
        ay = -g * sph - V * V * kappa * cph
        az = -g * cph + V * V * kappa * sph
        om = x[b + 8] if spin_free else V / r0
        Q = np.zeros(5)            # y, z, roll, yaw, spin (contact order)
        for side in range(2):
            for k in range(5):
                Q[k] += Qn[i, side, k] + Qt[i, side, k]
        _frame_offsets(s_ref + xpos[jp], xr, V, ks, kk, kp, kh, off, doff)
        qc[0] = x[b] + off[0]
        qc[1] = x[b + 1]
        qc[2] = x[b + 2] + off[2]
        qc[3] = 0.0
        qc[4] = x[b + 3] + off[1]
        vc[0] = x[b + 4] + doff[0]
        vc[1] = x[b + 5]
        vc[2] = x[b + 6] + doff[2]
        vc[3] = 0.0
        vc[4] = x[b + 7] + doff[1]
        Qw = np.zeros(5)           # y, z, roll, pitch, yaw
        for side in range(2):
            sg = -1.0 if side == 0 else 1.0
            pc[0] = 0.0
            pc[1] = sg * bs
            pc[2] = hp - r0
            pp[0] = xr
            pp[1] = sg * bs
            pp[2] = hp - heights[jp]
            _relative(qc, vc, pc, q[jp], qd[jp], pp, d, v)
            F[0] = -kx * d[0] - cx * v[0]
            F[1] = -ky * d[1] - cy * v[1]
            F[2] = -kz * d[2] - cz * v[2] - pre
            _apply(F, pc, 1.0, Qw)
            _apply(F, pp, -1.0, Qb[jp])
            _pendulum(pre, pp[2], q[jp], Qb[jp])
        Q[0] += Qw[0]
        Q[1] += Qw[1]
        Q[2] += Qw[2]
        Q[3] += Qw[4]              # the axle bearings take no moment about the axle
        dx[b] = x[b + 4]
        dx[b + 1] = x[b + 5]
        dx[b + 2] = x[b + 6]
        dx[b + 3] = x[b + 7]
        dx[b + 4] = Q[0] / m + ay
        dx[b + 5] = Q[1] / m + az
        dx[b + 6] = (Q[2] + Iy * om * (x[b + 7] + V * kappa)) / Ix
        dx[b + 7] = (Q[3] - Iy * om * x[b + 6]) / Iz - (V * V * dki + aV * kappa)
        dx[b + 8] = Q[4] / Iy if spin_free else aV / r0
        if rails:
            rail_rates(i, orl, P, x, Qn, Qt, dx)
    if relax:
        relax_derivative(x, P, V, Qt, amean, dx)
    # ---------------------------------------------------------------- secondary suspension
    if nf > 0:
        sv = vb + _V_SEC
        skx, sky, skz = P[sv], P[sv + 1], P[sv + 2]
        scx, scy, scz = P[sv + 3], P[sv + 4], P[sv + 5]
        b2, h2, kpsi, karb, spre = P[sv + 6], P[sv + 7], P[sv + 8], P[sv + 9], P[sv + 10]
        has_yd = P[vb + _V_YD] > 0
        ydc, ydk, ydb = P[vb + _V_YD + 1], P[vb + _V_YD + 2], P[vb + _V_YD + 3]
        for j in range(nf):
            _frame_offsets(s_ref, xpos[j], V, ks, kk, kp, kh, off, doff)
            for k in range(5):
                qc[k] = q[j, k]
                vc[k] = qd[j, k]
            qc[0] += off[0]
            qc[2] += off[2]
            qc[4] += off[1]
            vc[0] += doff[0]
            vc[2] += doff[2]
            vc[4] += doff[1]
            Qc = Qb[j]
            Qp = Qb[nf]
            for side in range(2):
                sg = -1.0 if side == 0 else 1.0
                pc[0] = 0.0
                pc[1] = sg * b2
                pc[2] = h2 - hf
                pp[0] = xpos[j]
                pp[1] = sg * b2
                pp[2] = h2 - hb
                _relative(qc, vc, pc, q[nf], qd[nf], pp, d, v)
                F[0] = -skx * d[0] - scx * v[0]
                F[1] = -sky * d[1] - scy * v[1]
                F[2] = -skz * d[2] - scz * v[2] - spre
                _apply(F, pc, 1.0, Qc)
                _apply(F, pp, -1.0, Qp)
                _pendulum(-spre, pc[2], q[j], Qc)
                _pendulum(spre, pp[2], q[nf], Qp)
                if has_yd:
                    pc[1] = sg * ydb
                    pp[1] = sg * ydb
                    _relative(qc, vc, pc, q[nf], qd[nf], pp, d, v)
                    k = oyd + 2 * j + side
                    fx = ydk * (d[0] - x[k])
                    dx[k] = fx / ydc
                    F[0] = -fx
                    F[1] = 0.0
                    F[2] = 0.0
                    _apply(F, pc, 1.0, Qc)
                    _apply(F, pp, -1.0, Qp)
            # rotational yaw springs of both sides, anti-roll bar
            My = -2.0 * kpsi * (qc[4] - q[nf, 4])
            Mr = -karb * (qc[2] - q[nf, 2])
            Qc[4] += My
            Qp[4] -= My
            Qc[2] += Mr
            Qp[2] -= Mr
            # lateral bump stop at the secondary height
            if P[vb + _V_BSN] > 0:
                pc[0] = 0.0
                pc[1] = 0.0
                pc[2] = h2 - hf
                pp[0] = xpos[j]
                pp[1] = 0.0
                pp[2] = h2 - hb
                _relative(qc, vc, pc, q[nf], qd[nf], pp, d, v)
                F[0] = 0.0
                F[1] = -_bump(P, vb, d[1])
                F[2] = 0.0
                _apply(F, pc, 1.0, Qc)
                _apply(F, pp, -1.0, Qp)
    # ---------------------------------------------------------------- frames and car body
    for j in range(nb):
        o = starts[j]
        if j < nf:
            mj = P[vb + _V_FM + 4 * j]
            Ixj, Iyj, Izj = P[vb + _V_FM + 4 * j + 1], P[vb + _V_FM + 4 * j + 2], \
                P[vb + _V_FM + 4 * j + 3]
        else:
            mj = P[vb + _V_BODY]
            Ixj, Iyj, Izj = P[vb + _V_BODY + 1], P[vb + _V_BODY + 2], P[vb + _V_BODY + 3]
        kappa, dkj, phi, _, _ = _track(s_ref + xpos[j], ks, kk, kp, kh)
        cph, sph = math.cos(phi), math.sin(phi)
        ay = -g * sph - V * V * kappa * cph
        az = -g * cph + V * V * kappa * sph
        for k in range(5):
            dx[o + k] = qd[j, k]
        dx[o + 5] = Qb[j, 0] / mj + ay
        dx[o + 6] = Qb[j, 1] / mj + az
        dx[o + 7] = Qb[j, 2] / Ixj
        dx[o + 8] = Qb[j, 3] / Iyj
        dx[o + 9] = Qb[j, 4] / Izj - (V * V * dkj + aV * kappa)
