"""Parallel numba kernels of the solid elements: elastic and J2 elasto-plastic (private).

Array in, array out. Small strain in each body's frame; strains and stresses in
Voigt order (xx, yy, zz, xy, yz, xz) with engineering shear strains.

Parallel and deterministic
--------------------------
The elements are split into contiguous chunks (:func:`element_chunks`) such that
chunks of the same parity share no node; the even chunks are processed in parallel,
then the odd ones, each chunk scattering its element forces into the nodal vector
in element order. No two threads write to the same node at the same time, and every
node receives its contributions in the same order whatever the number of threads:
results are bitwise identical on 1 and 2 threads. Energies are written per element
and summed afterwards in element order. Two parallel regions per evaluation (few
barriers: the step of an explicit run is short, and a shared machine punishes every
barrier).

Plastic state
-------------
Per integration point, ``NSTATE`` = 14 numbers: the plastic strain (6, engineering
shear), the equivalent plastic strain p (1), the back stress α (6, tensor
components) and the plastic work density w_p = ∫ σ : dε_p (1) [J/m³]. Kernels
read the state of the last converged step (``st_in``) and write the state that
belongs to the displacement ``u`` (``st_out``): one backward-Euler (radial return)
step from ``st_in``; the integrators commit ``st_out`` when the step is accepted.

Hardening parameters ``hp`` = (σ0, Q, b, H, C, γ): isotropic σ_y(p) = σ0 + Q (1 −
exp(−b p)) + H p (Voce plus linear), or, if ``tp`` is not empty, the piecewise
linear table σ_y(tp) = ts (constant beyond its last point); kinematic
dα = (2/3) C dε_p − γ α dp (Prager for γ = 0, Armstrong–Frederick for γ > 0).

References
----------
.. [1] J.C. Simo, T.J.R. Hughes, *Computational Inelasticity*, Springer 1998, §3.3,
   Box 3.2 (radial return, consistent elastoplastic tangent moduli).
.. [2] P.J. Armstrong, C.O. Frederick, "A mathematical representation of the
   multiaxial Bauschinger effect", CEGB report RD/B/N731 (1966); backward-Euler
   return of the Armstrong–Frederick rule as in J.L. Chaboche, G. Cailletaud,
   "Integration methods for complex plastic constitutive equations", Comput.
   Methods Appl. Mech. Engrg 133 (1996) 125-155.
.. [3] T.J.R. Hughes, "Generalization of selective integration procedures to
   anisotropic and nonlinear media", Int. J. Numer. Meth. Engng 15 (1980)
   1413-1418 (B-bar: the mean dilatation of the fully integrated element).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

NSTATE = 14
#: index of the equivalent plastic strain and of the plastic work density in a state row
P_INDEX = 6
WP_INDEX = 13


# ----------------------------------------------------------------------------- chunks
def element_chunks(conn, n_nodes, target: int = 32):
    """Contiguous element chunks for the two-phase parallel scatter.

    Returns ``bounds`` (nc + 1,): chunk c is elements bounds[c]:bounds[c + 1]. Every node is
    touched by at most two consecutive chunks, so the even chunks share no node (phase 1,
    in parallel), nor do the odd ones (phase 2). On a structured mesh numbered slab by slab
    this holds when a chunk is longer than a slab; the number of chunks is halved from
    ``target`` until it holds (1 chunk: serial). The chunks do not depend on the number of
    threads, so neither do the sums.
    """
    conn = np.asarray(conn)
    ne = conn.shape[0]
    nc = int(target)
    while nc > 1:
        bounds = np.linspace(0, ne, nc + 1).round().astype(np.int64)
        cid = np.repeat(np.arange(nc), np.diff(bounds))
        lo = np.full(n_nodes, nc, np.int64)
        hi = np.full(n_nodes, -1, np.int64)
        np.minimum.at(lo, conn.ravel(), np.repeat(cid, 8))
        np.maximum.at(hi, conn.ravel(), np.repeat(cid, 8))
        used = hi >= 0
        if np.all(hi[used] - lo[used] <= 1):
            return bounds
        nc //= 2
    return np.array([0, ne], np.int64)


# ----------------------------------------------------------------------------- J2 point law
@njit(cache=True, inline="always")
def yield_stress(p, hp, tp, ts):
    """Isotropic yield stress σ_y(p) [Pa] and its slope dσ_y/dp [Pa]."""
    n = tp.shape[0]
    if n > 0:
        if p >= tp[n - 1]:
            return ts[n - 1], 0.0
        k = np.searchsorted(tp, p, side="right") - 1
        if k < 0:
            k = 0
        slope = (ts[k + 1] - ts[k]) / (tp[k + 1] - tp[k])
        return ts[k] + slope * (p - tp[k]), slope
    ex = np.exp(-hp[2] * p)
    return hp[0] + hp[1] * (1.0 - ex) + hp[3] * p, hp[1] * hp[2] * ex + hp[3]


@njit(cache=True)
def return_map(eps, st_in, st_out, lam, G, hp, tp, ts, sig, D, tangent):
    """One radial-return step of J2 plasticity at a point.

    Parameters
    ----------
    eps : (6,) total strain (engineering shear).
    st_in, st_out : (NSTATE,) state of the last converged step / the new state.
    sig : (6,) output stress [Pa].
    D : (6, 6) output consistent tangent (filled if ``tangent``).

    Returns
    -------
    float
        The equivalent plastic strain increment Δp (0 for an elastic step).
    """
    K = lam + 2.0 * G / 3.0
    e0 = eps[0] - st_in[0]
    e1 = eps[1] - st_in[1]
    e2 = eps[2] - st_in[2]
    tr = e0 + e1 + e2
    pm = K * tr
    s0 = 2.0 * G * (e0 - tr / 3.0)
    s1 = 2.0 * G * (e1 - tr / 3.0)
    s2 = 2.0 * G * (e2 - tr / 3.0)
    s3 = G * (eps[3] - st_in[3])
    s4 = G * (eps[4] - st_in[4])
    s5 = G * (eps[5] - st_in[5])
    a0, a1, a2, a3, a4, a5 = st_in[7], st_in[8], st_in[9], st_in[10], st_in[11], st_in[12]
    x0, x1, x2, x3, x4, x5 = s0 - a0, s1 - a1, s2 - a2, s3 - a3, s4 - a4, s5 - a5
    q_tr = np.sqrt(1.5 * (x0 * x0 + x1 * x1 + x2 * x2 + 2.0 * (x3 * x3 + x4 * x4 + x5 * x5)))
    p_n = st_in[6]
    if p_n == 0.0 and tp.shape[0] == 0:
        sy = hp[0]                       # virgin point: no exp (most points of a run)
    else:
        sy, h = yield_stress(p_n, hp, tp, ts)
    if q_tr <= sy * (1.0 + 1e-12):
        # elastic: the state is unchanged (nothing to write when updated in place, as the
        # explicit step does: a plastic run's points are mostly elastic)
        if st_out.ctypes.data != st_in.ctypes.data:
            for k in range(NSTATE):
                st_out[k] = st_in[k]
        sig[0] = s0 + pm
        sig[1] = s1 + pm
        sig[2] = s2 + pm
        sig[3] = s3
        sig[4] = s4
        sig[5] = s5
        if tangent:
            for i in range(6):
                for j in range(6):
                    D[i, j] = 0.0
            for i in range(3):
                for j in range(3):
                    D[i, j] = lam
                D[i, i] = lam + 2.0 * G
                D[3 + i, 3 + i] = G
        return 0.0
    C = hp[4]
    gk = hp[5]
    # scalar equation r(dp) = |s_tr - alpha_n / (1 + gk dp)|_eq - (3G + C/(1 + gk dp)) dp
    #                         - sigma_y(p_n + dp) = 0; r(0) > 0, r decreasing
    lo = 0.0
    hi = q_tr / (3.0 * G)
    dp = 0.0
    for it in range(60):
        den = 1.0 / (1.0 + gk * dp)
        y0 = s0 - a0 * den
        y1 = s1 - a1 * den
        y2 = s2 - a2 * den
        y3 = s3 - a3 * den
        y4 = s4 - a4 * den
        y5 = s5 - a5 * den
        qt = np.sqrt(1.5 * (y0 * y0 + y1 * y1 + y2 * y2 + 2.0 * (y3 * y3 + y4 * y4 + y5 * y5)))
        sy, h = yield_stress(p_n + dp, hp, tp, ts)
        r = qt - (3.0 * G + C * den) * dp - sy
        # d qt / d dp = 1.5 (y : alpha_n) gk den^2 / qt
        ya = y0 * a0 + y1 * a1 + y2 * a2 + 2.0 * (y3 * a3 + y4 * a4 + y5 * a5)
        dqt = 1.5 * ya * gk * den * den / qt if qt > 0 else 0.0
        dr = dqt - 3.0 * G - C * den + C * gk * dp * den * den - h
        if r > 0:
            lo = dp
        else:
            hi = dp
        if abs(r) <= 1e-13 * sy:
            break
        step = -r / dr if dr < 0 else 0.5 * (hi - lo)
        new = dp + step
        if not (lo < new < hi):
            new = 0.5 * (lo + hi)
        dp = new
    den = 1.0 / (1.0 + gk * dp)
    y0 = s0 - a0 * den
    y1 = s1 - a1 * den
    y2 = s2 - a2 * den
    y3 = s3 - a3 * den
    y4 = s4 - a4 * den
    y5 = s5 - a5 * den
    qt = np.sqrt(1.5 * (y0 * y0 + y1 * y1 + y2 * y2 + 2.0 * (y3 * y3 + y4 * y4 + y5 * y5)))
    c = 1.5 / qt                       # flow direction n = 1.5 y / qt (tensor components)
    n0, n1, n2, n3, n4, n5 = c * y0, c * y1, c * y2, c * y3, c * y4, c * y5
    s0 -= 2.0 * G * dp * n0
    s1 -= 2.0 * G * dp * n1
    s2 -= 2.0 * G * dp * n2
    s3 -= 2.0 * G * dp * n3
    s4 -= 2.0 * G * dp * n4
    s5 -= 2.0 * G * dp * n5
    sig[0] = s0 + pm
    sig[1] = s1 + pm
    sig[2] = s2 + pm
    sig[3] = s3
    sig[4] = s4
    sig[5] = s5
    st_out[0] = st_in[0] + dp * n0
    st_out[1] = st_in[1] + dp * n1
    st_out[2] = st_in[2] + dp * n2
    st_out[3] = st_in[3] + 2.0 * dp * n3
    st_out[4] = st_in[4] + 2.0 * dp * n4
    st_out[5] = st_in[5] + 2.0 * dp * n5
    st_out[6] = p_n + dp
    ck = 2.0 / 3.0 * C * dp
    st_out[7] = (a0 + ck * n0) * den
    st_out[8] = (a1 + ck * n1) * den
    st_out[9] = (a2 + ck * n2) * den
    st_out[10] = (a3 + ck * n3) * den
    st_out[11] = (a4 + ck * n4) * den
    st_out[12] = (a5 + ck * n5) * den
    st_out[13] = st_in[13] + dp * (sig[0] * n0 + sig[1] * n1 + sig[2] * n2
                                   + 2.0 * (sig[3] * n3 + sig[4] * n4 + sig[5] * n5))
    if tangent:
        # D = K 1x1 + 2G theta I_dev - 2G theta_bar N x N (Simo & Hughes Box 3.2; exact for
        # Prager kinematic hardening, the Armstrong-Frederick term enters through C/(1+gk dp))
        theta = 1.0 - 3.0 * G * dp / q_tr
        sy, h = yield_stress(p_n + dp, hp, tp, ts)
        theta_b = 1.0 / (1.0 + (h + C * den) / (3.0 * G)) - (1.0 - theta)
        nf = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2 + 2.0 * (n3 * n3 + n4 * n4 + n5 * n5))
        N = (n0 / nf, n1 / nf, n2 / nf, n3 / nf, n4 / nf, n5 / nf)
        for i in range(6):
            for j in range(6):
                D[i, j] = -2.0 * G * theta_b * N[i] * N[j]
        for i in range(3):
            for j in range(3):
                D[i, j] += K - 2.0 * G * theta / 3.0
            D[i, i] += 2.0 * G * theta
            D[3 + i, 3 + i] += G * theta
    return dp


# ----------------------------------------------------------------------------- element kernels
@njit(cache=True, inline="always")
def _gather(u, conn, e, ue):
    for a in range(8):
        n = conn[e, a]
        ue[a, 0] = u[n, 0]
        ue[a, 1] = u[n, 1]
        ue[a, 2] = u[n, 2]


@njit(cache=True, inline="always")
def _mean_gradient(dNdx, wdet, e, bb):
    """B-bar: the element's mean shape-function gradient (1/V) ∫ ∇N dV."""
    ng = dNdx.shape[1]
    vol = 0.0
    for g in range(ng):
        vol += wdet[e, g]
    for a in range(8):
        for k in range(3):
            acc = 0.0
            for g in range(ng):
                acc += wdet[e, g] * dNdx[e, g, a, k]
            bb[a, k] = acc / vol


@njit(cache=True, inline="always")
def _strain(dNdx, e, g, ue, eps):
    exx = eyy = ezz = gxy = gyz = gxz = 0.0
    for a in range(8):
        bx = dNdx[e, g, a, 0]
        by = dNdx[e, g, a, 1]
        bz = dNdx[e, g, a, 2]
        exx += bx * ue[a, 0]
        eyy += by * ue[a, 1]
        ezz += bz * ue[a, 2]
        gxy += by * ue[a, 0] + bx * ue[a, 1]
        gyz += bz * ue[a, 1] + by * ue[a, 2]
        gxz += bz * ue[a, 0] + bx * ue[a, 2]
    eps[0] = exx
    eps[1] = eyy
    eps[2] = ezz
    eps[3] = gxy
    eps[4] = gyz
    eps[5] = gxz


@njit(cache=True, inline="always")
def _point_stress(eps, e, g, lam, G, plastic, bbar, theta_bar, hp, tp, ts, st_in, st_out, sig,
                  D, tangent):
    """Stress at one point (B-bar dilatation if ``bbar``); returns the elastic energy density."""
    if bbar:
        corr = (theta_bar - eps[0] - eps[1] - eps[2]) / 3.0
        eps[0] += corr
        eps[1] += corr
        eps[2] += corr
    if plastic:
        return_map(eps, st_in[e, g], st_out[e, g], lam, G, hp, tp, ts, sig, D, tangent)
        pe = st_out[e, g]
        return 0.5 * (sig[0] * (eps[0] - pe[0]) + sig[1] * (eps[1] - pe[1])
                      + sig[2] * (eps[2] - pe[2]) + sig[3] * (eps[3] - pe[3])
                      + sig[4] * (eps[4] - pe[4]) + sig[5] * (eps[5] - pe[5]))
    tr = lam * (eps[0] + eps[1] + eps[2])
    sig[0] = tr + 2.0 * G * eps[0]
    sig[1] = tr + 2.0 * G * eps[1]
    sig[2] = tr + 2.0 * G * eps[2]
    sig[3] = G * eps[3]
    sig[4] = G * eps[4]
    sig[5] = G * eps[5]
    if tangent:
        for i in range(6):
            for j in range(6):
                D[i, j] = 0.0
        for i in range(3):
            for j in range(3):
                D[i, j] = lam
            D[i, i] = lam + 2.0 * G
            D[3 + i, 3 + i] = G
    return 0.5 * (sig[0] * eps[0] + sig[1] * eps[1] + sig[2] * eps[2] + sig[3] * eps[3]
                  + sig[4] * eps[4] + sig[5] * eps[5])


@njit(cache=True, inline="always")
def _elastic_one_point(e, ue, conn, dNdx, wdet, gamma, khg, has_hg, lam, G, f):
    """The one-point elastic element (the explicit fast path): forces added to f; returns
    the energies (elastic, plastic = 0) [J]."""
    exx = eyy = ezz = gxy = gyz = gxz = 0.0
    for a in range(8):
        bx = dNdx[e, 0, a, 0]
        by = dNdx[e, 0, a, 1]
        bz = dNdx[e, 0, a, 2]
        exx += bx * ue[a, 0]
        eyy += by * ue[a, 1]
        ezz += bz * ue[a, 2]
        gxy += by * ue[a, 0] + bx * ue[a, 1]
        gyz += bz * ue[a, 1] + by * ue[a, 2]
        gxz += bz * ue[a, 0] + bx * ue[a, 2]
    w = wdet[e, 0]
    tr = lam * (exx + eyy + ezz)
    sxx = w * (tr + 2.0 * G * exx)
    syy = w * (tr + 2.0 * G * eyy)
    szz = w * (tr + 2.0 * G * ezz)
    sxy = w * G * gxy
    syz = w * G * gyz
    sxz = w * G * gxz
    en = 0.5 * (sxx * exx + syy * eyy + szz * ezz + sxy * gxy + syz * gyz + sxz * gxz)
    for a in range(8):
        bx = dNdx[e, 0, a, 0]
        by = dNdx[e, 0, a, 1]
        bz = dNdx[e, 0, a, 2]
        n = conn[e, a]
        f[n, 0] += bx * sxx + by * sxy + bz * sxz
        f[n, 1] += bx * sxy + by * syy + bz * syz
        f[n, 2] += bx * sxz + by * syz + bz * szz
    if has_hg:
        en += _hourglass(e, ue, conn, gamma, khg, f)
    return en, 0.0


@njit(cache=True, inline="always")
def _gradient(e, ue, dNdx, W):
    """Displacement gradient W[i, j] = Σ_a u_ai ∂N_a/∂x_j (i, j < 3) at the element's first point."""
    h00 = h01 = h02 = h10 = h11 = h12 = h20 = h21 = h22 = 0.0
    for a in range(8):
        bx = dNdx[e, 0, a, 0]
        by = dNdx[e, 0, a, 1]
        bz = dNdx[e, 0, a, 2]
        ux = ue[a, 0]
        uy = ue[a, 1]
        uz = ue[a, 2]
        h00 += ux * bx
        h01 += ux * by
        h02 += ux * bz
        h10 += uy * bx
        h11 += uy * by
        h12 += uy * bz
        h20 += uz * bx
        h21 += uz * by
        h22 += uz * bz
    W[0, 0] = h00
    W[0, 1] = h01
    W[0, 2] = h02
    W[1, 0] = h10
    W[1, 1] = h11
    W[1, 2] = h12
    W[2, 0] = h20
    W[2, 1] = h21
    W[2, 2] = h22


@njit(cache=True, inline="always")
def _hourglass_hx(e, ue, hx, khg, W, hf):
    """Flanagan-Belytschko hourglass forces from the compact element data hx = h·x (ne, 4, 3).

    With γ_m = (h_m − Σ_j hx_mj b_j)/8 (h_m the base vectors :data:`_kernels.HG`, b the
    gradients) the hourglass strain of mode m, component i, is q_mi = γ_m · u_i =
    (h_m · u_i − Σ_j hx_mj H_ij)/8 with H the displacement gradient W[:3, :3], and the
    nodal force k γ_ma q_mi = (k/8) h_ma q_mi − Σ_j b_aj R_ij with R_ij = (k/8) Σ_m q_mi
    hx_mj. Writes the first part to hf (8, 3) and R to W[3:6, :3]; returns the energy
    ½ k Σ q². The caller adds −b R to its stress term: the γ vectors (256 bytes per
    element) are not read.
    """
    k = khg[e]
    c = 0.125
    ck = c * k
    en = 0.0
    x00, x01, x02 = hx[e, 0, 0], hx[e, 0, 1], hx[e, 0, 2]
    x10, x11, x12 = hx[e, 1, 0], hx[e, 1, 1], hx[e, 1, 2]
    x20, x21, x22 = hx[e, 2, 0], hx[e, 2, 1], hx[e, 2, 2]
    x30, x31, x32 = hx[e, 3, 0], hx[e, 3, 1], hx[e, 3, 2]
    for i in range(3):
        h0 = W[i, 0]
        h1 = W[i, 1]
        h2 = W[i, 2]
        u0, u1, u2, u3 = ue[0, i], ue[1, i], ue[2, i], ue[3, i]
        u4, u5, u6, u7 = ue[4, i], ue[5, i], ue[6, i], ue[7, i]
        # h_m . u_i (rows of HG)
        s0 = (u0 + u1) - (u2 + u3) - (u4 + u5) + (u6 + u7)
        s1 = (u0 - u1) - (u2 - u3) - (u4 - u5) + (u6 - u7)
        s2 = (u0 - u1) + (u2 - u3) + (u4 - u5) + (u6 - u7)
        s3 = -(u0 - u1) - (u2 - u3) + (u4 - u5) + (u6 - u7)
        q0 = c * (s0 - (x00 * h0 + x01 * h1 + x02 * h2))
        q1 = c * (s1 - (x10 * h0 + x11 * h1 + x12 * h2))
        q2 = c * (s2 - (x20 * h0 + x21 * h1 + x22 * h2))
        q3 = c * (s3 - (x30 * h0 + x31 * h1 + x32 * h2))
        en += 0.5 * k * (q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
        q0 *= ck
        q1 *= ck
        q2 *= ck
        q3 *= ck
        # (k/8) sum_m h_ma q_m (columns of HG)
        hf[0, i] = (q0 + q1) + (q2 - q3)
        hf[1, i] = (q0 - q1) - (q2 - q3)
        hf[2, i] = -(q0 + q1) + (q2 - q3)
        hf[3, i] = -(q0 - q1) - (q2 - q3)
        hf[4, i] = -(q0 + q1) + (q2 + q3)
        hf[5, i] = -(q0 - q1) - (q2 + q3)
        hf[6, i] = (q0 + q1) + (q2 + q3)
        hf[7, i] = (q0 - q1) - (q2 + q3)
        W[3 + i, 0] = q0 * x00 + q1 * x10 + q2 * x20 + q3 * x30
        W[3 + i, 1] = q0 * x01 + q1 * x11 + q2 * x21 + q3 * x31
        W[3 + i, 2] = q0 * x02 + q1 * x12 + q2 * x22 + q3 * x32
    return en


@njit(cache=True, inline="always")
def _scatter_one_point(e, conn, dNdx, sxx, syy, szz, sxy, syz, sxz, W, hf, f):
    """Add the one-point element's nodal forces to ``f``: the weighted stress minus the
    hourglass stress correction (rows 3-5 of ``W``, :func:`_hourglass_hx`) on the mean
    gradients, plus the sign-only hourglass forces ``hf``; one scatter per node."""
    p00 = sxx - W[3, 0]
    p01 = sxy - W[3, 1]
    p02 = sxz - W[3, 2]
    p10 = sxy - W[4, 0]
    p11 = syy - W[4, 1]
    p12 = syz - W[4, 2]
    p20 = sxz - W[5, 0]
    p21 = syz - W[5, 1]
    p22 = szz - W[5, 2]
    for a in range(8):
        bx = dNdx[e, 0, a, 0]
        by = dNdx[e, 0, a, 1]
        bz = dNdx[e, 0, a, 2]
        n = conn[e, a]
        f[n, 0] += bx * p00 + by * p01 + bz * p02 + hf[a, 0]
        f[n, 1] += bx * p10 + by * p11 + bz * p12 + hf[a, 1]
        f[n, 2] += bx * p20 + by * p21 + bz * p22 + hf[a, 2]


@njit(cache=True, inline="always")
def _elastic_one_point_hx(e, ue, conn, dNdx, wdet, hx, khg, lam, G, f, W, hf):
    """:func:`_elastic_one_point` with the compact hourglass data (:func:`_hourglass_hx`):
    one scatter per node. W (≥ 6, ≥ 3) and hf (8, 3) are scratch. Returns the energies."""
    _gradient(e, ue, dNdx, W)
    exx = W[0, 0]
    eyy = W[1, 1]
    ezz = W[2, 2]
    gxy = W[0, 1] + W[1, 0]
    gyz = W[1, 2] + W[2, 1]
    gxz = W[0, 2] + W[2, 0]
    w = wdet[e, 0]
    tr = lam * (exx + eyy + ezz)
    sxx = w * (tr + 2.0 * G * exx)
    syy = w * (tr + 2.0 * G * eyy)
    szz = w * (tr + 2.0 * G * ezz)
    sxy = w * G * gxy
    syz = w * G * gyz
    sxz = w * G * gxz
    en = 0.5 * (sxx * exx + syy * eyy + szz * ezz + sxy * gxy + syz * gyz + sxz * gxz)
    en += _hourglass_hx(e, ue, hx, khg, W, hf)
    _scatter_one_point(e, conn, dNdx, sxx, syy, szz, sxy, syz, sxz, W, hf, f)
    return en, 0.0


@njit(cache=True, inline="always")
def _plastic_one_point_hx(e, ue, conn, dNdx, wdet, hx, khg, lam, G, hp, tp, ts, st_in, st_out,
                          f, eps, sig, W, hf):
    """The one-point J2 element with the compact hourglass data (:func:`_hourglass_hx`): the
    strain from the displacement gradient, the return map, one scatter per node."""
    _gradient(e, ue, dNdx, W)
    eps[0] = W[0, 0]
    eps[1] = W[1, 1]
    eps[2] = W[2, 2]
    eps[3] = W[0, 1] + W[1, 0]
    eps[4] = W[1, 2] + W[2, 1]
    eps[5] = W[0, 2] + W[2, 0]
    w = wdet[e, 0]
    return_map(eps, st_in[e, 0], st_out[e, 0], lam, G, hp, tp, ts, sig, W, False)
    pe = st_out[e, 0]
    e_el = 0.5 * w * (sig[0] * (eps[0] - pe[0]) + sig[1] * (eps[1] - pe[1])
                      + sig[2] * (eps[2] - pe[2]) + sig[3] * (eps[3] - pe[3])
                      + sig[4] * (eps[4] - pe[4]) + sig[5] * (eps[5] - pe[5]))
    e_pl = w * pe[WP_INDEX]
    e_el += _hourglass_hx(e, ue, hx, khg, W, hf)
    sxx, syy, szz = w * sig[0], w * sig[1], w * sig[2]
    sxy, syz, sxz = w * sig[3], w * sig[4], w * sig[5]
    _scatter_one_point(e, conn, dNdx, sxx, syy, szz, sxy, syz, sxz, W, hf, f)
    return e_el, e_pl


@njit(cache=True, parallel=True)
def element_forces(u, conn, bounds, dNdx, wdet, gamma, khg, lam, G, plastic, hp, tp, ts,
                   st_in, st_out, f, energy):
    """f = ∫ B̄ᵀσ dV (+ elastic hourglass forces), elastic or J2 elasto-plastic.

    u, f : (nn, 3) (f is overwritten); conn : (ne, 8) node numbers into u; bounds :
    (nc + 1,) contiguous element chunks of :func:`element_chunks` (no node shared by two
    chunks of the same parity); dNdx : (ne, ng, 8, 3); wdet : (ne, ng); gamma : (ne, 4, 8)
    hourglass vectors γ, or their compact form (ne, 4, 3) h·x (:attr:`ElementData.hx`, one
    point only; the same forces to rounding, a third of the bytes), or (0, 4, 8); khg : (ne,); st_in, st_out : (ne, ng, NSTATE) (ignored if not
    ``plastic``); energy : (ne, 2) output, elastic strain energy (hourglass included) and
    plastic work of each element [J]. B-bar (mean dilatation) for plastic, fully
    integrated elements.
    """
    ne = conn.shape[0]
    ng = dNdx.shape[1]
    has_hg = gamma.shape[0] == ne
    bbar = plastic and ng > 1
    nc = bounds.shape[0] - 1
    f[:, :] = 0.0
    for parity in range(2):
        for cc in prange((nc - parity + 1) // 2):
            ch = 2 * cc + parity
            ue = np.empty((8, 3))
            eps = np.empty(6)
            sig = np.empty(6)
            D = np.empty((6, 6))
            bb = np.empty((8, 3))
            for e in range(bounds[ch], bounds[ch + 1]):
                _element(e, u, conn, dNdx, wdet, gamma, khg, has_hg, lam, G, plastic, bbar, hp,
                         tp, ts, st_in, st_out, f, energy, ue, eps, sig, D, bb)


@njit(cache=True, inline="always")
def _element(e, u, conn, dNdx, wdet, gamma, khg, has_hg, lam, G, plastic, bbar, hp, tp, ts,
             st_in, st_out, f, energy, ue, eps, sig, D, bb):
    """Forces of element e added to f (its nodes); returns its energies (elastic strain
    energy with the hourglass part, plastic work) [J] and writes them to energy[e] unless
    ``energy`` is empty (the explicit step sums them per chunk without storing them)."""
    ng = dNdx.shape[1]
    compact = has_hg and gamma.shape[2] == 3
    _gather(u, conn, e, ue)
    if compact:                       # one point, hourglass data h.x
        if plastic:
            e_el, e_pl = _plastic_one_point_hx(e, ue, conn, dNdx, wdet, gamma, khg, lam, G, hp,
                                               tp, ts, st_in, st_out, f, eps, sig, D, bb)
        else:
            e_el, e_pl = _elastic_one_point_hx(e, ue, conn, dNdx, wdet, gamma, khg, lam, G, f, D,
                                               bb)
    elif ng == 1 and not plastic:
        e_el, e_pl = _elastic_one_point(e, ue, conn, dNdx, wdet, gamma, khg, has_hg, lam, G, f)
    else:
        e_el, e_pl = _element_points(e, ue, conn, dNdx, wdet, gamma, khg, has_hg, lam, G,
                                     plastic, bbar, hp, tp, ts, st_in, st_out, f, eps, sig, D, bb)
    if energy.shape[0] > 0:
        energy[e, 0] = e_el
        energy[e, 1] = e_pl
    return e_el, e_pl


@njit(cache=True, inline="always")
def _element_points(e, ue, conn, dNdx, wdet, gamma, khg, has_hg, lam, G, plastic, bbar, hp, tp,
                    ts, st_in, st_out, f, eps, sig, D, bb):
    """The general element of :func:`_element` (any integration rule, B-bar, γ hourglass)."""
    ng = dNdx.shape[1]
    theta_bar = 0.0
    if bbar:
        _mean_gradient(dNdx, wdet, e, bb)
        for a in range(8):
            theta_bar += bb[a, 0] * ue[a, 0] + bb[a, 1] * ue[a, 1] + bb[a, 2] * ue[a, 2]
    e_el = 0.0
    e_pl = 0.0
    for g in range(ng):
        _strain(dNdx, e, g, ue, eps)
        w = wdet[e, g]
        e_el += w * _point_stress(eps, e, g, lam, G, plastic, bbar, theta_bar, hp,
                                  tp, ts, st_in, st_out, sig, D, False)
        if plastic:
            e_pl += w * st_out[e, g, 13]
        sxx, syy, szz, sxy, syz, sxz = sig[0], sig[1], sig[2], sig[3], sig[4], sig[5]
        pm3 = (sxx + syy + szz) / 3.0
        for a in range(8):
            bx = dNdx[e, g, a, 0]
            by = dNdx[e, g, a, 1]
            bz = dNdx[e, g, a, 2]
            fx = bx * sxx + by * sxy + bz * sxz
            fy = bx * sxy + by * syy + bz * syz
            fz = bx * sxz + by * syz + bz * szz
            if bbar:
                fx += (bb[a, 0] - bx) * pm3
                fy += (bb[a, 1] - by) * pm3
                fz += (bb[a, 2] - bz) * pm3
            n = conn[e, a]
            f[n, 0] += w * fx
            f[n, 1] += w * fy
            f[n, 2] += w * fz
    if has_hg:
        e_el += _hourglass(e, ue, conn, gamma, khg, f)
    return e_el, e_pl


@njit(cache=True, inline="always")
def _hourglass(e, ue, conn, gamma, khg, f):
    k = khg[e]
    en = 0.0
    for m in range(4):
        q0 = q1 = q2 = 0.0
        for a in range(8):
            gm = gamma[e, m, a]
            q0 += gm * ue[a, 0]
            q1 += gm * ue[a, 1]
            q2 += gm * ue[a, 2]
        en += 0.5 * k * (q0 * q0 + q1 * q1 + q2 * q2)
        for a in range(8):
            gm = k * gamma[e, m, a]
            n = conn[e, a]
            f[n, 0] += gm * q0
            f[n, 1] += gm * q1
            f[n, 2] += gm * q2
    return en


@njit(cache=True, parallel=True)
def tangent_triplets(u, conn, dNdx, wdet, gamma, khg, lam, G, plastic, hp, tp, ts, st_in,
                     rows, cols, vals):
    """Element tangent stiffness ∫ B̄ᵀ D B̄ dV (+ hourglass) as COO triplets, 576 per element.

    D is the consistent elasto-plastic tangent of the return map from ``st_in`` at the
    strains of ``u`` (the elastic D where the point is elastic, or if not ``plastic``).
    """
    ne = conn.shape[0]
    ng = dNdx.shape[1]
    has_hg = gamma.shape[0] == ne
    bbar = plastic and ng > 1
    for e in prange(ne):
        ue = np.empty((8, 3))
        eps = np.empty(6)
        sig = np.empty(6)
        D = np.empty((6, 6))
        bb = np.empty((8, 3))
        B = np.zeros((6, 24))
        DB = np.empty((6, 24))
        ke = np.zeros((24, 24))
        st_a = np.empty((1, ng, st_in.shape[2]))
        st_b = np.empty((1, ng, st_in.shape[2]))
        _gather(u, conn, e, ue)
        theta_bar = 0.0
        if bbar:
            _mean_gradient(dNdx, wdet, e, bb)
            for a in range(8):
                theta_bar += bb[a, 0] * ue[a, 0] + bb[a, 1] * ue[a, 1] + bb[a, 2] * ue[a, 2]
        for g in range(ng):
            _strain(dNdx, e, g, ue, eps)
            if plastic:
                for k in range(st_in.shape[2]):
                    st_a[0, g, k] = st_in[e, g, k]
                _point_stress(eps, 0, g, lam, G, True, bbar, theta_bar, hp, tp, ts, st_a,
                              st_b, sig, D, True)
            else:
                _point_stress(eps, e, g, lam, G, False, False, 0.0, hp, tp, ts, st_in, st_in,
                              sig, D, True)
            for a in range(8):
                bx = dNdx[e, g, a, 0]
                by = dNdx[e, g, a, 1]
                bz = dNdx[e, g, a, 2]
                c0 = 3 * a
                B[0, c0] = bx
                B[1, c0 + 1] = by
                B[2, c0 + 2] = bz
                B[3, c0] = by
                B[3, c0 + 1] = bx
                B[4, c0 + 1] = bz
                B[4, c0 + 2] = by
                B[5, c0] = bz
                B[5, c0 + 2] = bx
                if bbar:
                    for i in range(3):
                        B[i, c0] = (bb[a, 0] - bx) / 3.0
                        B[i, c0 + 1] = (bb[a, 1] - by) / 3.0
                        B[i, c0 + 2] = (bb[a, 2] - bz) / 3.0
                    B[0, c0] += bx
                    B[1, c0 + 1] += by
                    B[2, c0 + 2] += bz
            w = wdet[e, g]
            for i in range(6):
                for j in range(24):
                    acc = 0.0
                    for k in range(6):
                        acc += D[i, k] * B[k, j]
                    DB[i, j] = acc
            for i in range(24):
                for j in range(24):
                    acc = 0.0
                    for k in range(6):
                        acc += B[k, i] * DB[k, j]
                    ke[i, j] += w * acc
        if has_hg:
            kk = khg[e]
            for m in range(4):
                for a in range(8):
                    for b in range(8):
                        v = kk * gamma[e, m, a] * gamma[e, m, b]
                        for i in range(3):
                            ke[3 * a + i, 3 * b + i] += v
        base = e * 576
        c = 0
        for a in range(8):
            for i in range(3):
                for b in range(8):
                    for j in range(3):
                        rows[base + c] = 3 * conn[e, a] + i
                        cols[base + c] = 3 * conn[e, b] + j
                        vals[base + c] = ke[3 * a + i, 3 * b + j]
                        c += 1


@njit(cache=True, parallel=True)
def element_stress(u, conn, dNdx, wdet, lam, G, plastic, st, out):
    """Mean stress (ne, 6) [Pa] over the integration points, σ = C:(ε − ε_p) with the
    plastic strain of the state ``st`` (committed: the state that belongs to ``u``)."""
    ne = conn.shape[0]
    ng = dNdx.shape[1]
    bbar = plastic and ng > 1
    for e in prange(ne):
        ue = np.empty((8, 3))
        eps = np.empty(6)
        bb = np.empty((8, 3))
        _gather(u, conn, e, ue)
        theta_bar = 0.0
        if bbar:
            _mean_gradient(dNdx, wdet, e, bb)
            for a in range(8):
                theta_bar += bb[a, 0] * ue[a, 0] + bb[a, 1] * ue[a, 1] + bb[a, 2] * ue[a, 2]
        for k in range(6):
            out[e, k] = 0.0
        for g in range(ng):
            _strain(dNdx, e, g, ue, eps)
            if bbar:
                corr = (theta_bar - eps[0] - eps[1] - eps[2]) / 3.0
                eps[0] += corr
                eps[1] += corr
                eps[2] += corr
            if plastic:
                for k in range(6):
                    eps[k] -= st[e, g, k]
            tr = lam * (eps[0] + eps[1] + eps[2])
            out[e, 0] += (tr + 2.0 * G * eps[0]) / ng
            out[e, 1] += (tr + 2.0 * G * eps[1]) / ng
            out[e, 2] += (tr + 2.0 * G * eps[2]) / ng
            out[e, 3] += G * eps[3] / ng
            out[e, 4] += G * eps[4] / ng
            out[e, 5] += G * eps[5] / ng


def von_mises(stress):
    """Von Mises stress [Pa] of Voigt stresses (..., 6)."""
    s = np.asarray(stress)
    return np.sqrt(0.5 * ((s[..., 0] - s[..., 1]) ** 2 + (s[..., 1] - s[..., 2]) ** 2
                          + (s[..., 2] - s[..., 0]) ** 2)
                   + 3.0 * (s[..., 3] ** 2 + s[..., 4] ** 2 + s[..., 5] ** 2))
