"""The fused kernels of the explicit step against the NumPy definitions they replace.

References: :meth:`wheelrail.fe.model.Model.slave_positions`, ``master_positions`` and
:func:`wheelrail.fe.model.nodal_normals` (NumPy: rotation matrix, ``np.gradient``,
``np.cross``); Kalker's sign convention is not involved (kinematics only).
"""

import numpy as np
import pytest
import xarray as xr

from wheelrail.errors import InputError
from wheelrail.fe._explicit import (
    contact_to_nodes,
    interleaved_tasks,
    master_kinematics,
    slave_kinematics,
)
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


@pytest.mark.parametrize("ne, nc", [(16, 8), (3, 40), (5, 1)])
def test_interleaved_tasks_cover_both_kinds_in_proportion(ne, nc):
    t = interleaved_tasks(ne, nc)
    assert sorted(t[t[:, 0] == 0, 1]) == list(range(ne))
    assert sorted(t[t[:, 0] == 1, 1]) == list(range(nc))
    half = t[: len(t) // 2]
    assert abs((half[:, 0] == 0).sum() - ne / 2) <= 1


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
