"""Onset of yield under a Hertz contact: FE indentation against the half-space solution.

Reference: the stresses on the axis of a Hertzian elliptic pressure, integrated here from
Boussinesq's point-load solution (Johnson, *Contact Mechanics*, CUP 1985, eqs. 3.21 and
3.60-3.66); the quadrature reproduces Johnson's values for the sphere (§6.2: ν = 0.3,
largest von Mises stress 0.62 p0 at z = 0.48 a, first yield at p0 = 1.60 Y). For the case
of Toumi, Chollet & Yin (2016) at its Table-3 load (a/b = 1.334, ν = 0.28): 0.6275 p0 at
z = 0.54 b, first yield at p0 = 1.59 Y.

FE (2 mm mesh, one-point elements, bodies 3 semi-axes deep and wide): largest element von
Mises stress 0.641 p0 (+2.2 %) at the element centre 3.0 mm = 0.60 b deep (1.5 mm mesh:
0.630 p0, +0.4 %, at 0.43 b). With the J2 material at p0 = 1.75 Y the plastic strain
appears below the surface, at the depth of the largest von Mises stress, and none at it.
"""

import numpy as np
import pytest

from wheelrail.fe import J2Plastic, indent, seed000_case


def axis_stresses(z, a, b, nu, n=64):
    """(σx, σy, σz) / p0 at depth z > 0 on the axis of the pressure p0 √(1 − x²/a² − y²/b²)."""
    gx, gw = np.polynomial.legendre.leggauss(n)
    phi, wphi = 0.25 * np.pi * (gx + 1), 0.25 * np.pi * gw      # ρ' = sin φ (edge √ singularity)
    th, wth = np.pi * (gx + 1), np.pi * gw
    R, TH = np.meshgrid(np.sin(phi), th, indexing="ij")
    W = np.outer(wphi * np.cos(phi), wth)
    P = np.sqrt(np.clip(1 - R ** 2, 0, None)) * a * b * R * W   # point loads
    x, y = -a * R * np.cos(TH), -b * R * np.sin(TH)               # field point relative to them
    r2 = x * x + y * y
    rho = np.sqrt(r2 + z * z)
    c = P / (2 * np.pi)
    sz = -3 * c * z ** 3 / rho ** 5
    sx = c * ((1 - 2 * nu) / r2 * ((1 - z / rho) * (x * x - y * y) / r2 + z * y * y / rho ** 3)
              - 3 * z * x * x / rho ** 5)
    sy = c * ((1 - 2 * nu) / r2 * ((1 - z / rho) * (y * y - x * x) / r2 + z * x * x / rho ** 3)
              - 3 * z * y * y / rho ** 5)
    return sx.sum(), sy.sum(), sz.sum()


def max_von_mises_on_axis(a, b, nu):
    """(largest von Mises stress / p0, its depth) on the axis (principal axes there)."""
    zs = np.linspace(0.05, 1.5, 291) * min(a, b)
    vm = [np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2))
          for sx, sy, sz in (axis_stresses(z, a, b, nu) for z in zs)]
    k = int(np.argmax(vm))
    return vm[k], zs[k]


def test_reference_reproduces_johnson_for_the_sphere():
    vm, z = max_von_mises_on_axis(1.0, 1.0, 0.3)
    assert vm == pytest.approx(0.62, abs=0.005)          # Johnson 1985, §6.2
    assert z == pytest.approx(0.48, abs=0.01)
    assert 1 / vm == pytest.approx(1.60, abs=0.02)


def test_yield_onset_under_the_seed_hertz_contact():
    case = seed000_case(mesh_size=2e-3, element="reduced", depth=3, half_width=3, half_length=3)
    r = indent(case)
    hz = r.hertz
    vm_ref, z_ref = max_von_mises_on_axis(float(hz.a), float(hz.b), 0.28)
    assert 1 / vm_ref == pytest.approx(1.59, abs=0.01)   # first yield at p0 = 1.59 Y
    _, vm_r = r.model.von_mises(r.u)
    rail = r.model.rail
    shape = tuple(len(ax) - 1 for ax in rail.axes)
    vm = vm_r.reshape(shape)
    depth = 0.5 * (rail.axes[2][1:] + rail.axes[2][:-1])
    k = np.unravel_index(np.argmax(vm), shape)
    assert vm.max() / hz.p0 == pytest.approx(vm_ref, rel=0.04)      # measured +2.2 %
    assert abs(depth[k[2]] - z_ref) <= case.mesh_size                 # within one element
    # J2 material above the onset (p0 = 1.75 Y): plastic flow below the surface, where the
    # von Mises stress is largest
    plastic = indent(case.replace(material=J2Plastic(2.1e11, 0.28, float(hz.p0) / 1.75)),
                     increments=1)
    pe = plastic.fields.rail_equivalent_plastic_strain
    assert float(pe.max()) > 1e-4
    assert float(pe.isel(depth=0).max()) == 0.0
    kp = np.unravel_index(int(np.argmax(pe.values)), pe.shape)
    assert kp[2] == k[2]
