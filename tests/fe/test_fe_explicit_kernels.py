"""The fused kernels of the explicit step against the NumPy definitions they replace.

References: :meth:`wheelrail.fe.model.Model.slave_positions`, ``master_positions`` and
:func:`wheelrail.fe.model.nodal_normals` (NumPy: rotation matrix, ``np.gradient``,
``np.cross``); Kalker's sign convention is not involved (kinematics only).
"""

import numpy as np
import pytest
import xarray as xr

from wheelrail.errors import InputError
from numba import njit

from wheelrail.fe._explicit import (
    _update_nodes,
    contact_to_nodes,
    master_kinematics,
    node_groups,
    phase_one_tasks,
    slave_kinematics,
)
from wheelrail.fe._solid import element_chunks
from wheelrail.fe.curves import merge_creep_curves
from wheelrail.fe.model import nodal_normals


def test_slave_and_master_kinematics_match_the_numpy_definitions():
    rng = np.random.default_rng(3)
    n = 40
    u = rng.normal(scale=1e-5, size=(n, 3))
    slave = np.array([3, 7, 11, 30], np.int64)
    ref_s = rng.normal(scale=0.01, size=(4, 3))
    psi, z = 0.37, 0.46
    Q = np.array([[np.cos(psi), 0, np.sin(psi)], [0, 1, 0], [-np.sin(psi), 0, np.cos(psi)]])
    expect = (ref_s + u[slave]) @ Q.T + [0, 0, z]
    xs, dxs = np.empty((4, 3)), np.empty((4, 3))
    prev = rng.normal(size=(4, 3))
    slave_kinematics(ref_s, u, slave, np.cos(psi), np.sin(psi), z, xs, prev, dxs)
    np.testing.assert_allclose(xs, expect, rtol=0, atol=1e-15)
    np.testing.assert_allclose(dxs, expect - prev, rtol=0, atol=1e-15)

    gx, gy = np.meshgrid(np.linspace(0, 0.02, 6), np.linspace(-0.01, 0.01, 5), indexing="ij")
    ref_m = np.stack([gx, gy, -3 * gy ** 2 + 0.5 * gx ** 2], axis=-1)    # curved surface
    master = np.arange(30, dtype=np.int64).reshape(6, 5) + 5
    xm, dxm, nm, fm = (np.empty((6, 5, 3)) for _ in range(4))
    fm[...] = 7.0
    prev = np.zeros((6, 5, 3))
    master_kinematics(ref_m, u, master, 0.004, 1e-4, xm, prev, dxm, nm, fm)
    expect = ref_m + u[master] - [0.004, 1e-4, 0]
    np.testing.assert_allclose(xm, expect, rtol=0, atol=1e-15)
    np.testing.assert_allclose(nm, nodal_normals(expect), rtol=0, atol=1e-14)
    assert np.all(fm == 0)


def test_contact_forces_rotate_into_the_wheel_frame_and_sum():
    rng = np.random.default_rng(5)
    fs = rng.normal(size=(6, 3))
    fm = rng.normal(size=(2, 3, 3))
    pn, slip, energy = rng.random(6), rng.random(6), rng.random(6)
    ft = rng.normal(size=(6, 3))
    psi = -0.2
    Q = np.array([[np.cos(psi), 0, np.sin(psi)], [0, 1, 0], [-np.sin(psi), 0, np.cos(psi)]])
    fcon, sums = np.empty((12, 3)), np.empty(6)
    contact_to_nodes(fs, fm, pn, ft, slip, energy, np.cos(psi), np.sin(psi), fcon, sums)
    np.testing.assert_allclose(fcon[:6], fs @ Q, atol=1e-14)     # Qᵀ f per row
    np.testing.assert_array_equal(fcon[6:], fm.reshape(-1, 3))
    np.testing.assert_allclose(sums, [*fs.sum(0), pn.sum(),
                                      (np.linalg.norm(ft, axis=1) * slip).sum(), energy.sum()])


@pytest.mark.parametrize("ne, nc", [(16, 8), (3, 40), (5, 1), (4, 0)])
def test_phase_one_tasks_take_every_chunk_once_the_contact_in_the_middle(ne, nc):
    t = phase_one_tasks(ne, nc)
    h = (ne + 1) // 2
    assert t.shape == (ne + nc, 2)
    assert t[:h].tolist() == [[0, k] for k in range(h)]                # the first half
    assert t[h:h + nc].tolist() == [[1, j] for j in range(nc)]         # the contact
    assert t[h + nc:].tolist() == [[0, k] for k in range(h, ne)]       # the second half


def _slab_mesh(nx, ny, nz):
    """Hex8 connectivity of an nx × ny × nz block, numbered slab by slab along x."""
    idx = np.arange((nx + 1) * (ny + 1) * (nz + 1)).reshape(nx + 1, ny + 1, nz + 1)
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1),
               (0, 1, 1)]
    conn = np.stack([idx[i + a, j + b, k + c] for a, b, c in corners], axis=-1)
    return conn.reshape(-1, 8), idx.size


@pytest.mark.parametrize("nx, target", [(40, 8), (41, 8), (40, 1), (9, 32)])
def test_node_groups_partition_the_nodes_so_that_odd_chunks_never_share_them(nx, target):
    conn, n = _slab_mesh(nx, 3, 2)
    bounds = element_chunks(conn, n, target)
    gptr, gnodes = node_groups(conn, bounds, n)
    nc = bounds.size - 1
    assert gptr.size - 1 == max(nc // 2, 1)
    assert sorted(gnodes) == list(range(n))                   # every node in exactly one group
    group = np.empty(n, int)
    for g in range(gptr.size - 1):
        assert np.all(np.diff(gnodes[gptr[g]:gptr[g + 1]]) > 0)
        group[gnodes[gptr[g]:gptr[g + 1]]] = g
    odd = range(1, nc, 2)
    for c in odd:           # an odd chunk's nodes are updated by its own task only
        assert np.all(group[np.unique(conn[bounds[c]:bounds[c + 1]])] == (c - 1) // 2)
    for c in odd:           # no odd chunk reads the nodes another odd chunk's task updates
        for c2 in odd:
            if c2 != c:
                read = np.unique(conn[bounds[c2]:bounds[c2 + 1]])
                assert not np.any(group[read] == (c - 1) // 2)


@njit
def _update_all(gptr, gnodes, u, v, f, fb, has_beta, ma, inv_m, mass, cmap, fcon, dt,
                partial):
    for g in range(gptr.size - 1):
        _update_nodes(g, gptr, gnodes, u, v, f, fb, has_beta, ma, inv_m, mass, cmap, fcon,
                      dt, partial)


def test_node_update_is_the_central_difference_step_with_its_work_sums():
    # Belytschko, Liu & Moran (2000) §6.2.1: a = M⁻¹ f, v_{n+1/2} = v_{n-1/2} + Δt a,
    # u_{n+1} = u_n + Δt v_{n+1/2}; v_n = v_{n+1/2} − Δt a / 2
    rng = np.random.default_rng(7)
    n, dt = 30, 1e-3
    u, v, f, fb = (rng.normal(size=(n, 3)) for _ in range(4))
    mass = rng.random(n) + 0.5
    inv_m = 1.0 / mass
    inv_m[[0, 5]] = 0.0                                   # clamped
    ma = 3.0 * mass
    cmap = -np.ones(n, np.int64)
    cmap[[2, 9, 17]] = [0, 1, 2]
    fcon = rng.normal(size=(3, 3))
    fc = np.zeros((n, 3))
    fc[[2, 9, 17]] = fcon
    gptr = np.array([0, 11, 30], np.int64)
    gnodes = rng.permutation(n).astype(np.int64)
    a_ref = (fc - f - ma[:, None] * v - fb) * inv_m[:, None]
    vn_ref = v + dt * a_ref
    u_ref = u + dt * vn_ref
    vk = vn_ref - 0.5 * dt * a_ref
    sums = [np.sum(ma[:, None] * v * v), np.sum(ma[:, None] * v * vn_ref), np.sum(fc * v),
            np.sum(fc * vn_ref), np.sum(fb * v), np.sum(fb * vn_ref), np.sum(mass[:, None] * vk * vk)]
    partial = np.empty((2, 7))
    v0 = v.copy()
    _update_all(gptr, gnodes, u, v, f, fb, True, ma, inv_m, mass, cmap, fcon, dt, partial)
    np.testing.assert_allclose(v, vn_ref, rtol=1e-14)
    np.testing.assert_allclose(u, u_ref, rtol=1e-14)
    assert np.all(f == 0)                                 # left zero for the next assembly
    np.testing.assert_allclose(partial.sum(0), sums, rtol=1e-12)
    assert np.all(v[[0, 5]] == v0[[0, 5]])                # clamped nodes do not move


def _curve(c, F, offset_attrs=None):
    ds = xr.Dataset({"Fx": ("creepage", np.asarray(F, float)),
                     "Fx_std": ("creepage", np.zeros(len(c)))},
                    coords={"creepage": np.asarray(c, float)})
    ds.attrs.update(component="xi", force="Fx", load=8e4, mu=0.2, normal_load=8e4,
                    mesh_size=1e-3, material="m", linear_fraction=0.5, **(offset_attrs or {}))
    return ds.assign_coords(shifted_creepage=("creepage", ds.creepage.values))


def test_merged_creep_points_give_the_line_through_them():
    # two one-point curves on F = -1e7 (c + 2e-5): slope -1e7 N, offset -2e-5
    a = _curve([3.5e-4], [-1e7 * (3.5e-4 + 2e-5)])
    b = _curve([-3.5e-4], [-1e7 * (-3.5e-4 + 2e-5)])
    m = merge_creep_curves([a, b])
    np.testing.assert_allclose(m.creepage, [-3.5e-4, 3.5e-4])
    assert m.attrs["slope"] == pytest.approx(-1e7)
    assert m.attrs["offset"] == pytest.approx(-2e-5)
    np.testing.assert_allclose(m.shifted_creepage, [-3.3e-4, 3.7e-4])
    with pytest.raises(InputError, match="mu"):
        merge_creep_curves([a, _curve([1e-4], [0.0]).assign_attrs(mu=0.3)])
    # a point written before the steady window was stored: NaN there
    c = b.assign(window_start=("creepage", [0.01]))
    m = merge_creep_curves([a, c])
    assert m.attrs["slope"] == pytest.approx(-1e7)
    np.testing.assert_array_equal(m.window_start, [0.01, np.nan])


def test_creep_curve_reports_the_steady_window_of_each_point():
    """Every point of a creep curve carries the steady window of its rolling run (travel
    interval and steps averaged), as the rolling result reports it, and the window follows
    its definition (from the end of the speed ramp plus 4 a, at most the last quarter of
    the travel, to the end)."""
    import wheelrail as wr
    from wheelrail.fe import RollingCase, creep_curve, solve
    from wheelrail.fe.model import build_model
    from wheelrail.fe.rolling import steady_window

    flat = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
    case = RollingCase(wheel=flat, rail=wr.profiles.load("60E1"), radius=0.46, load=7500.0,
                       mu=0.2, creepage=(7e-4, 0.0, 0.0), mesh_size=2e-3, element="reduced",
                       mass_scaling=400, depth=3, half_width=3, half_length=3, travel=0.005)
    ds = creep_curve(case, [7e-4], progress=False)
    r = solve(case, progress=False)
    g = build_model(case).geometry
    lo, hi = steady_window(case, build_model(case))
    assert hi == pytest.approx(g["travel"])
    assert lo == pytest.approx(min(case.ramp * g["travel"] + 4 * g["a"], 0.75 * g["travel"]))
    assert float(ds.window_start[0]) == pytest.approx(lo)
    assert float(ds.window_end[0]) == pytest.approx(hi)
    assert int(ds.steady_steps[0]) == r.steady["n"] > 10
    assert float(ds.Fx[0]) == r.steady["Fx"]
