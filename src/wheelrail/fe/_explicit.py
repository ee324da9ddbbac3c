"""Kernels of the explicit central-difference step (private, numba).

A step has two parallel phases: the element forces (in the parity-ordered chunks of
:func:`wheelrail.fe._solid.element_chunks`) with the contact, and the node update (the
acceleration from the internal, contact and damping forces, the half-step velocity and the
new displacement), fused into the second phase node group by node group
(:func:`node_groups`). Partial sums are taken per task (element chunk, node group) and
added in task order, so that the results do not depend on the thread count; the tasks are
handed out dynamically, so that a slower thread (plastic elements, a busy core) does
fewer of them, even threads from the front of a phase's task range and odd threads from
its back, so that a thread works on the same part of the mesh in every step. :func:`run_steps` runs a block of steps in one parallel region (its
threads wait for each other's phases without sleeping). :func:`advance` is the node update
alone (the transition driver).

The contact bookkeeping of a step (positions of the contact surfaces, their increments
and nodal normals, the contact forces rotated into the body frames, the force and energy
sums) runs in small serial kernels (:func:`slave_kinematics`, :func:`master_kinematics`,
:func:`contact_to_nodes`): a few thousand nodes at most, where a parallel phase would
cost more than it saves, and where NumPy temporaries cost more than the arithmetic.
"""

from __future__ import annotations

import ctypes
import platform
import sys

import numpy as np
from llvmlite import binding as llvm_binding
from llvmlite import ir
from numba import njit, prange
from numba.core import cgutils, types
from numba.extending import intrinsic

from ._kernels import _slave, scatter_to_grid
from ._solid import _element

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


#: Columns of the partial sums of the node update of :func:`run_steps`.
ADV_COLUMNS = ("ma_vo_vo", "ma_vo_vn", "fcon_vo", "fcon_vn", "fbeta_vo", "fbeta_vn", "m_vk_vk")


# ----------------------------------------------------------------------------- synchronisation
def _yield_address():
    """Address of the C function that gives the CPU to another runnable thread
    (``sched_yield``; ``SwitchToThread`` on Windows), or 0."""
    try:
        if sys.platform == "win32":
            fn = ctypes.windll.kernel32.SwitchToThread
        else:
            fn = ctypes.CDLL(None).sched_yield
        return ctypes.cast(fn, ctypes.c_void_p).value or 0
    except (AttributeError, OSError):
        return 0


_YIELD = "wheelrail_fe_yield"
_HAS_YIELD = _yield_address() != 0
if _HAS_YIELD:                       # resolvable by the JIT and by cached kernels
    llvm_binding.add_symbol(_YIELD, _yield_address())
_X86 = platform.machine().lower() in ("x86_64", "amd64", "i386", "i686", "x86")


def _element_pointer(context, builder, sig, args):
    aryty = sig.args[0]
    ary = context.make_array(aryty)(context, builder, args[0])
    return cgutils.get_item_pointer(context, builder, aryty, ary, [args[1]])


@intrinsic
def _atomic_load(typingctx, arr, idx):
    """``arr[idx]`` (int64 array) read atomically (sequentially consistent)."""
    if not (isinstance(arr, types.Array) and arr.dtype == types.int64):
        return None

    def codegen(context, builder, sig, args):
        return builder.load_atomic(_element_pointer(context, builder, sig, args), "seq_cst", 8)

    return types.int64(arr, types.intp), codegen


@intrinsic
def _atomic_store(typingctx, arr, idx, val):
    """``arr[idx] = val`` (int64 array), atomically (sequentially consistent)."""
    if not (isinstance(arr, types.Array) and arr.dtype == types.int64):
        return None

    def codegen(context, builder, sig, args):
        builder.store_atomic(args[2], _element_pointer(context, builder, sig, args), "seq_cst", 8)
        return context.get_dummy_value()

    return types.none(arr, types.intp, types.int64), codegen


@intrinsic
def _atomic_add(typingctx, arr, idx, val):
    """``arr[idx] += val`` (int64 array) atomically; returns the old value."""
    if not (isinstance(arr, types.Array) and arr.dtype == types.int64):
        return None

    def codegen(context, builder, sig, args):
        return builder.atomic_rmw("add", _element_pointer(context, builder, sig, args), args[2],
                                  "seq_cst")

    return types.int64(arr, types.intp, types.int64), codegen


@intrinsic
def _compare_swap(typingctx, arr, idx, old, new):
    """If ``arr[idx] == old``, set it to ``new`` (atomically); True if it did."""
    if not (isinstance(arr, types.Array) and arr.dtype == types.int64):
        return None

    def codegen(context, builder, sig, args):
        res = builder.cmpxchg(_element_pointer(context, builder, sig, args), args[2], args[3],
                              "seq_cst", "seq_cst")
        return builder.extract_value(res, 1)

    return types.boolean(arr, types.intp, types.int64, types.int64), codegen


@intrinsic
def _relax(typingctx, spins):
    """Wait a little: a pause instruction (x86) while ``spins`` < 64, then give the CPU to
    any other runnable thread (``sched_yield``): a waiting thread never sleeps (no wake-up
    latency), and on a busy machine it does not keep a core from the other jobs."""
    def codegen(context, builder, sig, args):
        mod = builder.module
        few = builder.icmp_signed("<", args[0], context.get_constant(types.int64, 64))
        with builder.if_else(few) as (then, otherwise):
            with then:
                if _X86:
                    fn = cgutils.get_or_insert_function(mod, ir.FunctionType(ir.VoidType(), []),
                                                        "llvm.x86.sse2.pause")
                    builder.call(fn, [])
            with otherwise:
                if _HAS_YIELD:
                    fn = cgutils.get_or_insert_function(mod, ir.FunctionType(ir.IntType(32), []),
                                                        _YIELD)
                    builder.call(fn, [])
        return context.get_dummy_value()

    return types.none(types.int64), codegen


#: Slots of the control array of :func:`run_steps` (one cache line apart): the tasks left in
#: the current phase (phase · 2³² + hi · 2¹⁶ + lo: tasks lo ≤ t < hi), the tasks done in it,
#: the phase under way, the current row of the double buffers.
_TAKE, _DONE, _PHASE, _CUR = 0, 8, 16, 24
#: Most tasks of a phase (the task range is packed into 16-bit fields of ``ctl[_TAKE]``).
MAX_TASKS = 0xFFFF


@njit(cache=True, inline="always")
def _open_tasks(p, n):
    """The value of ``ctl[_TAKE]`` that opens phase ``p`` with tasks 0 … n − 1."""
    return (p << 32) | (n << 16)


@njit(cache=True, inline="always")
def _take_task(ctl, p, back):
    """The next task of phase ``p`` from the front of its range (the lowest left) or, if
    ``back``, from the back (the highest left); −1 when there is none left or the phase is
    over (the phase number is part of the word: a thread that comes late never takes a
    task of a later phase). Threads taking from opposite ends meet where the work is
    done; each task is taken exactly once."""
    while True:
        c = _atomic_load(ctl, _TAKE)
        lo = c & 0xFFFF
        hi = (c >> 16) & 0xFFFF
        if (c >> 32) != p or lo >= hi:
            return -1
        if back:
            if _compare_swap(ctl, _TAKE, c, c - 0x10000):
                return hi - 1
        elif _compare_swap(ctl, _TAKE, c, c + 1):
            return lo


@njit(cache=True, inline="always")
def _wait_phase(ctl, p):
    """Wait until the phase under way is past ``p``; returns the new phase."""
    spins = 0
    q = _atomic_load(ctl, _PHASE)
    while q <= p:
        _relax(spins)
        spins += 1
        q = _atomic_load(ctl, _PHASE)
    return q


def node_groups(conn, bounds, n_nodes):
    """Node groups of the node update fused into the odd phase of :func:`run_steps`.

    Returns ``(gptr, gnodes)``: group g holds the nodes ``gnodes[gptr[g]:gptr[g + 1]]``
    (ascending). Group g belongs to the odd element chunk 2g + 1 (:func:`wheelrail.fe._solid.
    element_chunks`): the nodes that chunk touches, and the nodes touched by the even chunk
    2g only (by the last even chunk only: the last group; untouched nodes: group 0). So a
    group's nodes are final once its odd chunk has been assembled, and no other odd chunk
    reads or writes them: the task of chunk 2g + 1 updates them right after its elements.
    With a single chunk there is one group of all nodes. The groups do not depend on the
    number of threads.
    """
    conn = np.asarray(conn)
    bounds = np.asarray(bounds)
    nc = bounds.size - 1
    ng = max(nc // 2, 1)
    cid = np.repeat(np.arange(nc), np.diff(bounds))
    lo = np.full(n_nodes, nc, np.int64)
    hi = np.full(n_nodes, -1, np.int64)
    np.minimum.at(lo, conn.ravel(), np.repeat(cid, conn.shape[1]))
    np.maximum.at(hi, conn.ravel(), np.repeat(cid, conn.shape[1]))
    if nc > 1 and np.any(hi - lo > 1):
        raise ValueError("element chunks share nodes beyond their neighbours")
    odd = np.where(hi % 2 == 1, hi, lo)             # the odd chunk touching the node, if any
    group = np.where(odd % 2 == 1, (odd - 1) // 2, np.minimum(odd // 2, ng - 1))
    group = np.where(hi < 0, 0, group) if nc > 1 else np.zeros(n_nodes, np.int64)
    order = np.lexsort((np.arange(n_nodes), group))
    gptr = np.searchsorted(group[order], np.arange(ng + 1)).astype(np.int64)
    return gptr, order.astype(np.int64)


@njit(cache=True, inline="always")
def _update_nodes(g, gptr, gnodes, u, v, f_int, fd_beta, has_beta, m_alpha, inv_m, mass,
                  cmap, fcon, dt, partial):
    """Central-difference update of the nodes of group ``g`` (in place), ``f_int`` zeroed;
    its partial sums (:data:`ADV_COLUMNS`) into ``partial[g]``."""
    pa = 0.0
    pb = 0.0
    pc = 0.0
    pd = 0.0
    pe = 0.0
    pf = 0.0
    pk = 0.0
    hdt = 0.5 * dt
    for q in range(gptr[g], gptr[g + 1]):
        i = gnodes[q]
        im = inv_m[i]
        ma = m_alpha[i]
        mi = mass[i]
        k = cmap[i]
        for d in range(3):
            vo = v[i, d]
            fx = -f_int[i, d] - ma * vo
            f_int[i, d] = 0.0
            if has_beta:
                fx -= fd_beta[i, d]
            if k >= 0:
                fx += fcon[k, d]
            a = fx * im
            vn = vo + dt * a
            v[i, d] = vn
            u[i, d] += dt * vn
            pa += ma * vo * vo
            pb += ma * vo * vn
            if k >= 0:
                pc += fcon[k, d] * vo
                pd += fcon[k, d] * vn
            if has_beta:
                pe += fd_beta[i, d] * vo
                pf += fd_beta[i, d] * vn
            vk = vn - hdt * a
            pk += mi * vk * vk
    partial[g, 0] = pa
    partial[g, 1] = pb
    partial[g, 2] = pc
    partial[g, 3] = pd
    partial[g, 4] = pe
    partial[g, 5] = pf
    partial[g, 6] = pk


@njit(cache=True, inline="always")
def slave_position(s, n, ref, u, cpsi, spsi, z, xs_prev, xs, dxs):
    """Current position of wheel slave ``s`` (mesh node ``n``): reference ``ref[s]`` plus
    displacement ``u[n]`` [m], rotated by the wheel angle (cos, sin) about the axle and
    lifted by the axle height ``z`` [m]; ``dxs[s]`` is the change since ``xs_prev[s]``."""
    X0 = ref[s, 0] + u[n, 0]
    X1 = ref[s, 1] + u[n, 1]
    X2 = ref[s, 2] + u[n, 2]
    x0 = cpsi * X0 + spsi * X2
    x2 = -spsi * X0 + cpsi * X2 + z
    xs[s, 0] = x0
    xs[s, 1] = X1
    xs[s, 2] = x2
    dxs[s, 0] = x0 - xs_prev[s, 0]
    dxs[s, 1] = X1 - xs_prev[s, 1]
    dxs[s, 2] = x2 - xs_prev[s, 2]


@njit(cache=True)
def slave_kinematics(ref, u, nodes, cpsi, spsi, z, xs, xs_prev, dxs):
    """Global positions of the wheel surface nodes and their increments over the step.

    x = Q(ψ) (X + u) + (0, 0, z) with Q the rotation by ψ about the axle (y) axis.

    Parameters
    ----------
    ref : (ns, 3)
        Reference positions of the slave nodes in the wheel frame [m].
    u : (n, 3)
        Displacements of all nodes (body frames) [m].
    nodes : (ns,) int
        Node numbers of the slaves in ``u``.
    cpsi, spsi : float
        cos ψ, sin ψ of the wheel rotation.
    z : float
        Axle height [m].
    xs, dxs : (ns, 3)
        Output: positions and ``xs − xs_prev`` [m].
    """
    for s in range(ref.shape[0]):
        slave_position(s, nodes[s], ref, u, cpsi, spsi, z, xs_prev, xs, dxs)


@njit(cache=True)
def master_kinematics(ref, u, nodes, shift_x, shift_y, xm, xm_prev, dxm, nm, fm):
    """Global positions, increments and unit nodal normals of the rail surface grid.

    x = X + u − (shift_x, shift_y, 0). The normals are those of
    :func:`wheelrail.fe.model.nodal_normals` (the cross product of the differences along both
    grid axes: central inside, one-sided at the edges). ``fm`` is zeroed (the contact kernel
    accumulates into it).

    Parameters
    ----------
    ref : (nx, ny, 3)
        Reference positions of the master nodes in the rail frame [m].
    u : (n, 3)
        Displacements of all nodes [m].
    nodes : (nx, ny) int
        Node numbers of the master grid in ``u``.
    shift_x, shift_y : float
        Rail travel and lateral drift [m].
    xm, dxm, nm, fm : (nx, ny, 3)
        Output: positions, ``xm − xm_prev``, unit normals, zeros.
    """
    nx, ny = nodes.shape
    for i in range(nx):
        for j in range(ny):
            n = nodes[i, j]
            for d in range(3):
                x = ref[i, j, d] + u[n, d]
                if d == 0:
                    x -= shift_x
                elif d == 1:
                    x -= shift_y
                xm[i, j, d] = x
                dxm[i, j, d] = x - xm_prev[i, j, d]
                fm[i, j, d] = 0.0
    tx = np.empty(3)
    ty = np.empty(3)
    for i in range(nx):
        i0 = max(i - 1, 0)
        i1 = min(i + 1, nx - 1)
        hx = 0.5 if (i > 0 and i < nx - 1) else 1.0
        for j in range(ny):
            j0 = max(j - 1, 0)
            j1 = min(j + 1, ny - 1)
            hy = 0.5 if (j > 0 and j < ny - 1) else 1.0
            for d in range(3):
                tx[d] = (xm[i1, j, d] - xm[i0, j, d]) * hx
                ty[d] = (xm[i, j1, d] - xm[i, j0, d]) * hy
            n0 = tx[1] * ty[2] - tx[2] * ty[1]
            n1 = tx[2] * ty[0] - tx[0] * ty[2]
            n2 = tx[0] * ty[1] - tx[1] * ty[0]
            nn = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
            nm[i, j, 0] = n0 / nn
            nm[i, j, 1] = n1 / nn
            nm[i, j, 2] = n2 / nn


@njit(cache=True)
def contact_to_nodes(fs, fm, pn, ft, slip, energy, cpsi, spsi, fcon, sums):
    """Contact forces into the rows of ``fcon`` and the sums of the step.

    ``fcon`` (ns + nx·ny, 3): the slave forces rotated into the wheel frame (Qᵀ f), then the
    master forces (rail frame = global). ``sums`` (6,): Fx, Fy, Fz (sums of the slave forces,
    global frame) [N], Σ p_n [N], the friction dissipation Σ |f_t| · slip [J] and the penalty
    energy Σ energy [J], each summed in slave order.
    """
    ns = fs.shape[0]
    sx = sy = sz = sn = sf = se = 0.0
    for s in range(ns):
        f0 = fs[s, 0]
        f1 = fs[s, 1]
        f2 = fs[s, 2]
        fcon[s, 0] = cpsi * f0 - spsi * f2
        fcon[s, 1] = f1
        fcon[s, 2] = spsi * f0 + cpsi * f2
        sx += f0
        sy += f1
        sz += f2
        sn += pn[s]
        sf += np.sqrt(ft[s, 0] ** 2 + ft[s, 1] ** 2 + ft[s, 2] ** 2) * slip[s]
        se += energy[s]
    nx, ny = fm.shape[0], fm.shape[1]
    k = ns
    for i in range(nx):
        for j in range(ny):
            for d in range(3):
                fcon[k, d] = fm[i, j, d]
            k += 1
    sums[0] = sx
    sums[1] = sy
    sums[2] = sz
    sums[3] = sn
    sums[4] = sf
    sums[5] = se


def phase_one_tasks(n_element_chunks: int, n_contact_chunks: int) -> np.ndarray:
    """Task table (T, 2) of the first parallel phase of :func:`run_steps`: rows (0, k) for
    the k-th even element chunk and (1, j) for the j-th contact chunk, the contact chunks in
    the middle: (0, 0) … (0, h − 1), (1, 0) … (1, n_c − 1), (0, h) … with h = ⌈n_e / 2⌉.

    One thread takes the tasks from the front of the table and the other from the back
    (:func:`_take_task`), so each works on the same half of the mesh in every step (its
    data stay in its core's caches), and the two meet among the short contact tasks (a few
    tens of µs each, against 50–200 µs for an element chunk): they end the phase within
    about one contact task of each other.
    """
    h = (n_element_chunks + 1) // 2
    kind = np.concatenate([np.zeros(h, np.int64), np.ones(n_contact_chunks, np.int64),
                           np.zeros(n_element_chunks - h, np.int64)])
    idx = np.concatenate([np.arange(h), np.arange(n_contact_chunks),
                          np.arange(h, n_element_chunks)])
    return np.ascontiguousarray(np.stack([kind, idx], axis=1).astype(np.int64))


@njit(cache=True, inline="always")
def _element_chunk(ch, bounds, u, conn, dNdx, wdet, gamma, khg, has_hg, lam, G, plastic, bbar,
                   hp, tp, ts, st_in, st_out, f, energy, echunk, ue, eps, sig, D, bb):
    """Forces of the elements of chunk ``ch`` added to f; their energies (elastic, plastic
    work) summed into ``echunk[ch]`` in element order (the same sums on any thread count)."""
    a0 = 0.0
    a1 = 0.0
    for e in range(bounds[ch], bounds[ch + 1]):
        e_el, e_pl = _element(e, u, conn, dNdx, wdet, gamma, khg, has_hg, lam, G, plastic, bbar,
                              hp, tp, ts, st_in, st_out, f, energy, ue, eps, sig, D, bb)
        a0 += e_el
        a1 += e_pl
    echunk[ch, 0] = a0
    echunk[ch, 1] = a1


@njit(cache=True, inline="always")
def _step_start(k, cur, sx, sy, y_ref, y_ref0, ref_m, u, mnodes, xmb, dxm, nm, fm):
    """The serial start of step k: the lateral drift of the rail grid's y axis, the rail
    surface positions, increments and normals (:func:`master_kinematics`)."""
    lat = sy[k]
    for j in range(y_ref.shape[0]):
        y_ref[j] = y_ref0[j] - lat
    master_kinematics(ref_m, u, mnodes, sx[k], lat, xmb[1 - cur], xmb[cur], dxm, nm, fm)


@njit(cache=True, inline="always")
def _step_end(k, relax, every, n_steps, ax, E, hist, rows, nrow, sx, tt, loads, axle, sums,
              echunk, partial, totals, has_beta, plastic, dt):
    """The serial end of step k: the energy sums in chunk and group order, then the axle's
    vertical motion and the energy bookkeeping (``ax`` = w, vw, e_int0, F_z)."""
    e0 = 0.0
    e1 = 0.0
    for ch in range(echunk.shape[0]):
        e0 += echunk[ch, 0]
        e1 += echunk[ch, 1]
    sums[6] = e0
    sums[7] = e1
    for j in range(totals.shape[0]):
        totals[j] = 0.0
    for g in range(partial.shape[0]):
        for j in range(totals.shape[0]):
            totals[j] += partial[g, j]
    hdt = 0.5 * dt
    w = ax[0]
    vw = ax[1]
    e_int0 = ax[2]
    fcw = sums[2]
    ax[3] = fcw
    if relax:
        aw = (fcw - loads[k] - axle[1] * vw) / axle[0]
        vw += dt * aw
        w += dt * vw
        ax[0] = w
        ax[1] = vw
        return
    load = axle[0]
    M_w = axle[1]
    cv = axle[2]
    e_int = sums[6] + sums[7]
    E[3] += sums[4]
    hist[k, 0] = sx[k]
    hist[k, 1] = sums[0]
    hist[k, 2] = sums[1]
    hist[k, 3] = sums[2]
    hist[k, 4] = sums[3]
    E[6] += hdt * (totals[2] + fcw * vw)
    if has_beta:
        E[4] += hdt * totals[4]
    aw = (fcw - load - cv * vw) / M_w
    vw_new = vw + dt * aw
    E[4] += hdt * (cv * vw * vw + totals[0])
    if k % every == 0 or k == n_steps - 1:
        vwn = vw + hdt * aw
        E[0] = 0.5 * totals[6] + 0.5 * M_w * vwn * vwn
        E[1] = e_int - e_int0
        E[2] = sums[5]
        if plastic:
            E[7] = sums[7]
        r = nrow[0]
        rows[r, 0] = tt[k]
        rows[r, 1] = sx[k]
        for j in range(4):
            rows[r, 2 + j] = sums[j]
        for j in range(8):
            rows[r, 6 + j] = E[j]
        nrow[0] = r + 1
    E[6] += hdt * (totals[3] + fcw * vw_new)
    E[4] += hdt * (cv * vw * vw_new + totals[1])
    if has_beta:
        E[4] += hdt * totals[5]
    dw = dt * vw_new
    vw = vw_new
    w += dw
    E[5] += -load * dw
    ax[0] = w
    ax[1] = vw


@njit(cache=True, parallel=True)
def run_steps(k0, k1, cur, relax, nthr, books, per_step, solid, contact, law, out, nodes, tasks):
    """Steps ``k0`` to ``k1 − 1`` of the explicit loop, with the axle's vertical motion and
    the energy bookkeeping of the rolling step, in one parallel region.

    The arrays come in records (tuples, in this order; each name is described below):

    * ``books`` = ``(every, n_steps, ax, E, hist, rows, nrow, axle)``: the axle and the
      bookkeeping;
    * ``per_step`` = ``(cps, sps, sx, sy, tt, loads)``: the values of each step;
    * ``solid`` = ``(u, conn, bounds, dNdx, wdet, gamma, khg, lam, G, plastic, hp, tp, ts,
      st_in, st_out, f, energy, echunk)``: the bodies' elements;
    * ``contact`` = ``(ref_s, snodes, z_axle, dxs, ref_m, mnodes, dxm, nm, area, kn, cdamp,
      x_ref, y_ref, y_ref0, xsb, xmb, ftb)``: the contact surfaces and their buffers;
    * ``law`` = ``(mu, reach, g0, inv_dt)``: the contact law (:func:`wheelrail.fe._kernels.
      node_to_surface`);
    * ``out`` = ``(cenergy, fs, fm, gap, pn, status, cell, rt, normal, slip, fcon, sums)``:
      the contact's outputs;
    * ``nodes`` = ``(v, fd_beta, has_beta, m_alpha, inv_m, mass, cmap, dt, gptr, gnodes,
      partial, totals)``: the node update.

    A step k has two parallel phases and serial parts between them:

    1. (serial) the lateral drift of the rail grid and :func:`master_kinematics`;
    2. (phase 2(k − k0)) the even element chunks of
       :func:`wheelrail.fe._solid.element_chunks` and the slave chunks of the contact
       (:func:`slave_position` and :func:`wheelrail.fe._kernels.node_to_surface` per slave),
       the tasks ``tasks`` (:func:`phase_one_tasks`);
    3. (serial) the master forces scattered in slave order and :func:`contact_to_nodes`;
    4. (phase 2(k − k0) + 1) per node group g of :func:`node_groups`: the odd element chunk
       2g + 1, then the update of the group's nodes (their forces are final then):
       a = (f_con − f_int − m_α v − f_β) / m; v ← v + Δt a; u ← u + Δt v (a is not stored);
       ``f`` (the internal forces, which must hold zeros on entry) is left zero;
    5. (serial) the sums in chunk and group order, the axle and the bookkeeping.

    The tasks of a phase are handed out dynamically through a word that holds the range of
    the tasks left and the phase number (:func:`_take_task`): even threads take from the
    front of the range, odd threads from its back, so that with two threads each works on
    the same half of the mesh in every step (its element and node data stay in its core's
    caches) and they meet in the middle of the range (in the first phase among the short
    contact tasks, :func:`phase_one_tasks`). The results do not depend on which thread runs a task, because the tasks
    of a phase write disjoint nodes, each node receives its element forces in element
    order, and every sum is taken per task and added in task order. Nothing depends on the
    number of threads. The ``nthr`` threads stay in one parallel region for all the steps:
    a thread that runs out of tasks waits for the next phase spinning, then yielding the CPU
    (:func:`_relax`), instead of falling asleep and waking late; the thread that completes a
    phase's last task runs the serial part after it and then opens the next phase. No
    thread ever waits for a thread that has not taken a task, so the loop also finishes if
    fewer threads than ``nthr`` run it.

    Parameters
    ----------
    k0, k1 : int
        The steps to run.
    relax : bool
        The dynamic relaxation (axle load ``loads[k]``, ``axle`` = (mass, dashpot)) or the
        rolling step (``axle`` = (load, mass, α m + dashpot)).
    every, n_steps : int
        Rolling: a row of ``rows`` every ``every`` steps and at step ``n_steps − 1``.
    ax : (4,)
        w, vw (the axle's vertical displacement [m] and velocity [m/s]), e_int0 (the internal
        energy at the start of rolling [J]) and the last vertical contact force [N]; updated.
    E : (8,)
        Rolling: the energies in the order of the rolling result (kinetic, internal,
        contact, friction, damping, external, contact work, plastic work) [J]; updated.
    hist : (n_steps, 5)
        Rolling: ``hist[k]`` = (travel, Fx, Fy, Fz, Fn).
    rows, nrow : (m, 14), (1,) int
        Rolling: the output rows (time, travel, Fx, Fy, Fz, Fn, the energies), written at
        ``nrow[0]`` (incremented).
    cps, sps, sx, sy, tt, loads : (n_steps,)
        Per step: cos and sin of the wheel angle, rail travel and lateral drift [m], time
        [s], axle load of the relaxation [N].
    axle : (3,)
        See ``relax``.
    y_ref0 : (ny,)
        The rail grid's y axis without drift [m] (``y_ref`` is the drifted copy).
    cur : int
        The row of the double buffers ``xsb``, ``xmb``, ``ftb`` (2, …) (slave positions,
        master positions, tangential forces) that holds the previous values.
    u, conn, bounds, dNdx, wdet, gamma, khg, lam, G, plastic, hp, tp, ts, st_in, st_out, f, energy
        As :func:`wheelrail.fe._solid.element_forces`; ``u`` (n, 3) [m] is read by the
        element and contact tasks before the node update; ``energy`` may be (0, 2): the
        element energies are then only summed per chunk, not stored.
    echunk : (nc, 2)
        Output: elastic energy and plastic work per element chunk.
    tasks : (T, 2) int
        The first phase's tasks (:func:`phase_one_tasks`).
    ref_s, snodes, z_axle, dxs, ref_m, mnodes, dxm, nm, area, kn, mu, x_ref, y_ref, reach, g0, cdamp, inv_dt, cenergy, fs, fm, gap, pn, status, cell, rt, normal, slip
        The contact: as :func:`slave_position`, :func:`master_kinematics` and
        :func:`wheelrail.fe._kernels.node_to_surface` (``z_axle`` + w is the axle height).
    fcon : (nc, 3)
        Output: contact forces [N] in the body frames of the contact nodes.
    sums : (8,)
        Output: Fx, Fy, Fz, Σ p_n, friction dissipation, penalty energy (as
        :func:`contact_to_nodes`), elastic strain energy and plastic work [J] of ``u``.
    v : (n, 3)
        Half-step velocities [m/s] (updated).
    fd_beta : (n, 3)
        Stiffness-proportional damping forces [N] (read only if ``has_beta``).
    m_alpha, inv_m, mass : (n,)
        α m [kg/s], inverse (scaled) lumped masses [1/kg] (0: clamped), masses [kg].
    cmap : (n,) int
        Row of the node in ``fcon`` (contact nodes) or −1.
    dt : float
        Time step [s].
    gptr, gnodes : int arrays
        Node groups of :func:`node_groups`.
    partial : (ngroups, 7), totals : (7,)
        Output: per group and summed in group order, the sums of :data:`ADV_COLUMNS`:
        Σ m_α v_old·v_old, Σ m_α v_old·v_new, Σ f_con·v_old, Σ f_con·v_new, Σ f_β·v_old,
        Σ f_β·v_new and Σ m v_k·v_k with v_k = v_new − Δt a / 2 (twice the kinetic
        energy at the step).
    nthr : int
        ``numba.get_num_threads()``.

    Returns
    -------
    int
        The row of the double buffers holding the last written values.

    Raises
    ------
    RuntimeError
        If a thread left the region before the last phase (a task raised).
    """
    if k1 <= k0:
        return cur
    every, n_steps, ax, E, hist, rows, nrow, axle = books
    cps, sps, sx, sy, tt, loads = per_step
    (u, conn, bounds, dNdx, wdet, gamma, khg, lam, G, plastic, hp, tp, ts, st_in, st_out, f,
     energy, echunk) = solid
    (ref_s, snodes, z_axle, dxs, ref_m, mnodes, dxm, nm, area, kn, cdamp, x_ref, y_ref, y_ref0,
     xsb, xmb, ftb) = contact
    cenergy, fs, fm, gap, pn, status, cell, rt, normal, slip, fcon, sums = out
    v, fd_beta, has_beta, m_alpha, inv_m, mass, cmap, dt, gptr, gnodes, partial, totals = nodes
    ne = conn.shape[0]
    ng = dNdx.shape[1]
    has_hg = gamma.shape[0] == ne
    bbar = plastic and ng > 1
    nc = bounds.shape[0] - 1
    ns = fs.shape[0]
    n_even = (nc + 1) // 2
    n_tasks = tasks.shape[0]
    ncc = n_tasks - n_even
    n_groups = gptr.shape[0] - 1
    if n_tasks < 1 or n_groups < 1:
        raise ValueError("run_steps: no tasks")
    if n_tasks > MAX_TASKS or n_groups > MAX_TASKS:
        raise ValueError("run_steps: more than 65 535 tasks in a phase")
    n_phases = 2 * (k1 - k0)
    ctl = np.zeros(32, np.int64)
    ctl[_CUR] = cur
    ctl[_TAKE] = _open_tasks(0, n_tasks)
    _step_start(k0, cur, sx, sy, y_ref, y_ref0, ref_m, u, mnodes, xmb, dxm, nm, fm)
    for w in prange(nthr):
        ue = np.empty((8, 3))
        eps = np.empty(6)
        sig = np.empty(6)
        D = np.empty((6, 6))
        bb = np.empty((8, 3))
        scratch = (np.empty((4, 3)), np.empty(3), np.empty(3))
        back = w % 2 == 1                # odd threads take from the back of the task ranges
        p = _atomic_load(ctl, _PHASE)
        while p < n_phases:
            k = k0 + p // 2
            old = ctl[_CUR]
            new = 1 - old
            first = p % 2 == 0               # phase 1 (element and contact tasks) or 2
            n_open = n_tasks if first else n_groups
            t = _take_task(ctl, p, back)
            while t >= 0:
                # one call site of the (inlined) element chunk for both phases: a second
                # one doubled the compile time of this function
                if first:
                    ch = 2 * tasks[t, 1] if tasks[t, 0] == 0 else -1
                else:
                    ch = 2 * t + 1 if 2 * t + 1 < nc else -1
                if ch >= 0:
                    _element_chunk(ch, bounds, u, conn, dNdx, wdet, gamma, khg, has_hg, lam, G,
                                   plastic, bbar, hp, tp, ts, st_in, st_out, f, energy, echunk,
                                   ue, eps, sig, D, bb)
                if first:
                    if tasks[t, 0] != 0:
                        j = tasks[t, 1]
                        z = z_axle + ax[0]
                        xs = xsb[new]
                        slaves = (xs, dxs, area, kn, kn, cdamp)
                        master = (xmb[new], nm, dxm, x_ref, y_ref, sx[k])
                        souts = (cenergy, fs, gap, pn, ftb[new], status, cell, rt, normal, slip)
                        for s in range(ns * j // ncc, ns * (j + 1) // ncc):
                            slave_position(s, snodes[s], ref_s, u, cps[k], sps[k], z, xsb[old],
                                           xs, dxs)
                            _slave(s, slaves, master, law, ftb[old], souts, scratch)
                else:
                    _update_nodes(t, gptr, gnodes, u, v, f, fd_beta, has_beta, m_alpha, inv_m,
                                  mass, cmap, fcon, dt, partial)
                if _atomic_add(ctl, _DONE, 1) == n_open - 1:        # the phase's last task
                    if first:
                        scatter_to_grid(status, cell, rt, fs, fm)
                        contact_to_nodes(fs, fm, pn, ftb[new], slip, cenergy, cps[k], sps[k],
                                         fcon, sums)
                        _atomic_store(ctl, _DONE, 0)
                        _atomic_store(ctl, _TAKE, _open_tasks(p + 1, n_groups))
                        _atomic_store(ctl, _PHASE, p + 1)
                    else:
                        _step_end(k, relax, every, n_steps, ax, E, hist, rows, nrow, sx, tt,
                                  loads, axle, sums, echunk, partial, totals, has_beta, plastic,
                                  dt)
                        ctl[_CUR] = new
                        if k + 1 < k1:
                            _step_start(k + 1, new, sx, sy, y_ref, y_ref0, ref_m, u, mnodes,
                                        xmb, dxm, nm, fm)
                        _atomic_store(ctl, _DONE, 0)
                        _atomic_store(ctl, _TAKE, _open_tasks(p + 1, n_tasks))
                        _atomic_store(ctl, _PHASE, p + 1)
                t = _take_task(ctl, p, back)
            p = _wait_phase(ctl, p)
    if ctl[_PHASE] != n_phases:      # a thread left the region early: a task raised
        raise RuntimeError("run_steps: a task of the explicit step raised an exception (a "
                           "division by zero on a degenerate element or contact cell?)")
    return ctl[_CUR]
