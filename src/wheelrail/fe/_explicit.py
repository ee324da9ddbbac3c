"""Node-level kernel of the explicit central-difference step (private, numba, parallel).

One parallel region per step for everything done node by node: the acceleration from
the internal, contact and damping forces, the half-step velocity and the new
displacement, and the partial sums of the damping work. Partial sums are taken over a
fixed number of node chunks (independent of the number of threads) and added in chunk
order, so that the results do not depend on the thread count.
"""

from __future__ import annotations

from numba import njit, prange

#: Node chunks of the partial sums (fixed: results independent of the threads).
NCHUNK = 128


@njit(cache=True, parallel=True)
def advance(u, v, acc, f_int, fd_beta, has_beta, m_alpha, inv_m, cmap, fcon, dt, partial):
    """Central-difference update of all nodes (in place).

    acc = (f_con − f_int − m_α v − f_β) / m;  v ← v + Δt acc;  u ← u + Δt v.

    Parameters
    ----------
    u, v, acc : (n, 3)
        Displacements [m], half-step velocities [m/s] (updated), accelerations (output).
    f_int, fd_beta : (n, 3)
        Internal forces and stiffness-proportional damping forces [N] (``fd_beta`` read
        only if ``has_beta``).
    m_alpha : (n,)
        Mass-proportional damping α m [kg/s] of each node.
    inv_m : (n,)
        Inverse (scaled) lumped masses [1/kg], 0 for clamped nodes.
    cmap : (n,) int
        Row of the node in ``fcon`` (contact nodes) or −1.
    fcon : (nc, 3)
        Contact forces [N] in the body frames of the contact nodes.
    dt : float
    partial : (NCHUNK, 2)
        Output: Σ m_α v_old·v_old and Σ m_α v_old·v_new per chunk (damping work).
    """
    n = u.shape[0]
    for ch in prange(NCHUNK):
        pa = 0.0
        pb = 0.0
        for i in range(n * ch // NCHUNK, n * (ch + 1) // NCHUNK):
            im = inv_m[i]
            ma = m_alpha[i]
            k = cmap[i]
            for d in range(3):
                vo = v[i, d]
                fx = -f_int[i, d] - ma * vo
                if has_beta:
                    fx -= fd_beta[i, d]
                if k >= 0:
                    fx += fcon[k, d]
                a = fx * im
                acc[i, d] = a
                vn = vo + dt * a
                v[i, d] = vn
                u[i, d] += dt * vn
                pa += ma * vo * vo
                pb += ma * vo * vn
        partial[ch, 0] = pa
        partial[ch, 1] = pb


def chunk_sum(partial, col):
    """The sum of a column of partial sums in chunk order (deterministic)."""
    total = 0.0
    for x in partial[:, col]:
        total += float(x)
    return total
