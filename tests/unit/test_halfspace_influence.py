"""Influence coefficients of the elastic half-space and the FFT operator.

References: Johnson, *Contact Mechanics* (1985) §3.2, §3.3; Love (1929);
seed 001 (Baeza et al.) eqs. (2.14)–(2.18).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError
from wheelrail.materials import as_material_pair
from wheelrail.halfspace import (ConvolutionOperator, Grid, InfluenceOperator, influence_kernel,
                                 point_influence, rectangle_influence)

STEEL = wr.Material(2.1e11, 0.28)
# dissimilar pair: K != 0, exercises the coupling blocks
DISSIMILAR = wr.MaterialPair(wr.Material(2.1e11, 0.28), wr.Material(0.9e11, 0.35))


def test_grid_geometry():
    g = Grid.from_bounds(-2e-3, 2e-3, -1e-3, 3e-3, nx=8, ny=5)
    assert g.dx == pytest.approx(0.5e-3) and g.dy == pytest.approx(0.8e-3)
    assert g.x[0] == pytest.approx(-1.75e-3) and g.y[-1] == pytest.approx(2.6e-3)
    assert g.X.shape == g.Y.shape == (8, 5)
    assert np.all(g.X[:, 0] == g.x) and np.all(g.Y[0] == g.y)
    assert g.element_area == pytest.approx(0.4e-6)
    assert g.bounds == pytest.approx((-2e-3, 2e-3, -1e-3, 3e-3))
    with pytest.raises(InputError, match="dx"):
        Grid(0.0, 0.0, -1.0, 1.0, 3, 3)
    with pytest.raises(InputError, match="nx"):
        Grid(0.0, 0.0, 1.0, 1.0, 0, 3)
    with pytest.raises(InputError, match="xmax"):
        Grid.from_bounds(1.0, 0.0, 0.0, 1.0, 3, 3)


@pytest.mark.parametrize("materials", [STEEL, DISSIMILAR], ids=["identical", "dissimilar"])
def test_fft_operator_equals_dense_sum(materials):
    g = Grid.from_bounds(-1e-3, 1.2e-3, -0.7e-3, 0.9e-3, nx=9, ny=6)
    op = InfluenceOperator(g, materials)
    p = np.random.default_rng(1).normal(size=(3, 9, 6)) * 1e8
    u = op.apply(p)
    D = np.block([[op.dense_matrix(i, j) for j in range(3)] for i in range(3)])
    ref = (D @ p.ravel()).reshape(3, 9, 6)
    assert np.max(np.abs(u - ref)) <= 1e-12 * np.max(np.abs(ref))
    # the same from single blocks
    for i in range(3):
        acc = sum(op.apply_block(i, j, p[j]) for j in range(3))
        assert np.max(np.abs(acc - ref[i])) <= 1e-12 * np.max(np.abs(ref))
    ut = op.apply_tangential(p[0], p[1])
    ref_t = sum(op.dense_matrix(0, j) @ p[j].ravel() for j in range(2)).reshape(9, 6)
    assert np.max(np.abs(ut[0] - ref_t)) <= 1e-12 * np.max(np.abs(ref_t))


def test_dense_sum_by_definition():
    """ConvolutionOperator against the literal double sum of the kernel layout."""
    rng = np.random.default_rng(2)
    nx, ny = 5, 4
    k = rng.normal(size=(2 * nx - 1, 2 * ny - 1))
    f = rng.normal(size=(nx, ny))
    ref = np.zeros((nx, ny))
    for a in range(nx):
        for b in range(ny):
            for c in range(nx):
                for d in range(ny):
                    ref[a, b] += k[a - c + nx - 1, b - d + ny - 1] * f[c, d]
    op = ConvolutionOperator(k)
    assert np.allclose(op(f), ref, rtol=0, atol=1e-12 * np.abs(ref).max())
    assert np.allclose(op.dense() @ f.ravel(), ref.ravel(), rtol=0, atol=1e-12 * np.abs(ref).max())
    with pytest.raises(InputError):
        ConvolutionOperator(np.ones((4, 3)))


def test_kernel_symmetry_and_reciprocity():
    g = Grid(0.0, 0.0, 1e-4, 0.6e-4, 6, 5)
    k = influence_kernel(g, DISSIMILAR)
    assert k.shape == (3, 3, 11, 9)
    flipped = k[:, :, ::-1, ::-1]
    tol = 1e-13 * np.abs(k).max()
    # reciprocity (Betti): A_ij(offset) = A_ji(-offset)
    assert np.allclose(k, np.swapaxes(flipped, 0, 1), rtol=0, atol=tol)
    for i in range(3):
        assert np.allclose(k[i, i], k[i, i, ::-1, :], rtol=0, atol=tol)
        assert np.allclose(k[i, i], k[i, i, :, ::-1], rtol=0, atol=tol)
    assert np.allclose(k[0, 1], -k[0, 1, ::-1, :], rtol=0, atol=tol)
    assert np.allclose(k[0, 2], -k[0, 2, ::-1, :], rtol=0, atol=tol)
    assert np.allclose(k[0, 2], -k[2, 0], rtol=0, atol=tol)
    assert np.abs(k[0, 2]).max() > 1e3 * tol   # the coupling is really there
    # the whole 3N x 3N matrix is symmetric
    op = InfluenceOperator(g, DISSIMILAR)
    D = np.block([[op.dense_matrix(i, j) for j in range(3)] for i in range(3)])
    assert np.allclose(D, D.T, rtol=0, atol=1e-14 * np.abs(D).max())
    # positive definite (elastic energy)
    assert np.linalg.eigvalsh(D).min() > 0
    # identical materials: no coupling
    ks = influence_kernel(g, STEEL)
    assert np.all(ks[0, 2] == 0) and np.all(ks[2, 1] == 0)
    # signs: pressure opens the gap, shear drags the surfaces along itself
    c = (g.nx - 1, g.ny - 1)
    assert ks[2, 2][c] > 0 and ks[0, 0][c] > 0 and ks[1, 1][c] > 0


def test_point_load_matches_boussinesq_cerruti_textbook():
    """Two identical bodies: twice Johnson's single-body surface values (§3.2)."""
    E, nu = STEEL.E, STEEL.nu
    pair = wr.MaterialPair.same(STEEL)
    x, y = 3e-3, -4e-3
    r = 5e-3
    A = point_influence(x, y, pair.G, pair.nu, pair.K)
    uz = (1 - nu**2) / (np.pi * E * r)                                    # Boussinesq
    ux = (1 + nu) / (2 * np.pi * E * r) * (2 * (1 - nu) + 2 * nu * x**2 / r**2)  # Cerruti
    uy = (1 + nu) / (2 * np.pi * E * r) * 2 * nu * x * y / r**2
    assert A[2, 2] == pytest.approx(2 * uz, rel=1e-14)
    assert A[0, 0] == pytest.approx(2 * ux, rel=1e-14)
    assert A[1, 0] == pytest.approx(2 * uy, rel=1e-14)


def test_coupling_sign_from_single_body_fields():
    """K-coupling from the two bodies' Boussinesq radial/Cerruti normal displacements."""
    w, rl = DISSIMILAR.wheel, DISSIMILAR.rail
    x, y = 2e-3, 1e-3
    r2 = x * x + y * y
    A = point_influence(x, y, DISSIMILAR.G, DISSIMILAR.nu, DISSIMILAR.K)
    # unit pressure: each surface moves radially towards the load by (1-2v)/(4 pi G r)
    ux = -(1 - 2 * w.nu) / (4 * np.pi * w.G) * x / r2 + (1 - 2 * rl.nu) / (4 * np.pi * rl.G) * x / r2
    assert A[0, 2] == pytest.approx(ux, rel=1e-12)
    assert A[2, 0] == pytest.approx(-ux, rel=1e-12)


def test_far_field_tends_to_point_load():
    pair = DISSIMILAR
    hx, hy = 1e-4, 0.7e-4
    for dist in (50.0, 400.0):
        x, y = dist * hx * 0.8, dist * hx * 0.6
        R = rectangle_influence(x, y, hx, hy, pair.G, pair.nu, pair.K)
        P = point_influence(x, y, pair.G, pair.nu, pair.K) * (4 * hx * hy)
        err = np.max(np.abs(R - P)) / np.max(np.abs(P))
        assert err < 2.0 / dist**2   # O((h/r)^2) correction
        assert err < 1e-3


def _love_centre(a, b):
    """∫∫ 1/r over the rectangle [-a,a]x[-b,b] seen from its centre (Love 1929; Johnson §3.3)."""
    return 4 * (a * np.arcsinh(b / a) + b * np.arcsinh(a / b))


def test_uniform_pressure_on_large_patch():
    """Centre and corner displacement of a uniformly loaded rectangle (Johnson §3.3)."""
    pair = wr.MaterialPair.same(STEEL)
    a, b = 2e-3, 3e-3
    g = Grid.from_bounds(-a, a, -b, b, 41, 61)   # odd: an element at the centre
    op = InfluenceOperator(g, pair)
    p = 1e8
    u = op.apply_normal(np.full(g.shape, p))
    single = (1 - STEEL.nu**2) / (np.pi * STEEL.E)   # one body
    w_centre = 2 * single * p * _love_centre(a, b)
    assert u[20, 30] == pytest.approx(w_centre, rel=1e-12)
    # square: the corner deflects half as much as the centre (Johnson 3.3)
    gs = Grid.from_bounds(0.0, 2 * a, 0.0, 2 * a, 1, 1)
    corner = rectangle_influence(a, a, a, a, pair.G, pair.nu)[2, 2]
    centre = rectangle_influence(0.0, 0.0, a, a, pair.G, pair.nu)[2, 2]
    assert corner == pytest.approx(0.5 * centre, rel=1e-13)
    assert centre == pytest.approx(2 * single * 8 * a * np.log(1 + np.sqrt(2)), rel=1e-13)
    assert gs.size == 1


def _seed_L(x1, x2, b1, b2):
    """L1, L2, L3 of seed 001, eqs. (2.14)–(2.16), written out in log form."""
    s = np.sqrt
    L1 = ((x2 + b2) * np.log((x1 + b1 + s((x2 + b2)**2 + (x1 + b1)**2))
                             / (x1 - b1 + s((x2 + b2)**2 + (x1 - b1)**2)))
          + (x2 - b2) * np.log((x1 - b1 + s((x2 - b2)**2 + (x1 - b1)**2))
                               / (x1 + b1 + s((x2 - b2)**2 + (x1 + b1)**2))))
    L2 = ((x1 + b1) * np.log((x2 + b2 + s((x2 + b2)**2 + (x1 + b1)**2))
                             / (x2 - b2 + s((x2 - b2)**2 + (x1 + b1)**2)))
          + (x1 - b1) * np.log((x2 - b2 + s((x2 - b2)**2 + (x1 - b1)**2))
                               / (x2 + b2 + s((x2 + b2)**2 + (x1 - b1)**2))))
    L3 = (s((x2 + b2)**2 + (x1 - b1)**2) - s((x2 + b2)**2 + (x1 + b1)**2)
          - s((x2 - b2)**2 + (x1 - b1)**2) + s((x2 - b2)**2 + (x1 + b1)**2))
    return L1, L2, L3


def test_tangential_rectangle_matches_seed_equations():
    """u1, u2 of seed 001 eqs. (2.17)-(2.18) (one body) x 2 for identical bodies."""
    E, nu = STEEL.E, STEEL.nu
    pair = wr.MaterialPair.same(STEEL)
    b1, b2 = 0.5e-3, 0.3e-3
    pts = np.array([[0.1e-3, 0.05e-3], [1.3e-3, 0.7e-3], [-2.0e-3, 0.9e-3], [0.7e-3, -1.1e-3]])
    A = rectangle_influence(pts[:, 0], pts[:, 1], b1, b2, pair.G, pair.nu)
    L1, L2, L3 = _seed_L(pts[:, 0], pts[:, 1], b1, b2)
    u1 = (1 + nu) / (np.pi * E) * (L1 + (1 - nu) * L2)
    u2 = (1 + nu) / (np.pi * E) * nu * L3
    assert np.allclose(A[0, 0], 2 * u1, rtol=1e-12, atol=0)
    assert np.allclose(A[1, 0], 2 * u2, rtol=1e-12, atol=0)


def test_operator_input_errors():
    g = Grid(0.0, 0.0, 1e-4, 1e-4, 4, 4)
    op = InfluenceOperator(g, STEEL)
    with pytest.raises(InputError, match="shape"):
        op.apply(np.zeros((3, 4, 5)))
    with pytest.raises(InputError, match="block"):
        op.apply_block(3, 0, np.zeros((4, 4)))
    assert np.all(op.apply_block(0, 2, np.ones((4, 4))) == 0)


@pytest.mark.parametrize("materials", [STEEL, DISSIMILAR], ids=["identical", "dissimilar"])
def test_kernel_equals_pointwise_rectangle_formula(materials):
    """The edge-lattice evaluation of influence_kernel equals rectangle_influence per offset."""
    pair = as_material_pair(materials)
    g = Grid(0.0, 0.0, 1e-4, 0.7e-4, 7, 4)
    k = influence_kernel(g, pair)
    ox = (np.arange(13) - 6) * g.dx
    oy = (np.arange(7) - 3) * g.dy
    ref = rectangle_influence(ox[:, None], oy[None, :], 0.5 * g.dx, 0.5 * g.dy,
                              pair.G, pair.nu, pair.K)
    assert np.allclose(k, ref, rtol=0, atol=1e-12 * np.abs(ref).max())


@pytest.mark.parametrize("module", ["wheelrail.normal.bem", "wheelrail.halfspace", "wheelrail.contact"])
def test_bem_halfspace_contact_import_in_any_order(module):
    """The kernel package, the BEM method and the contact drivers import in any order."""
    import subprocess
    import sys

    code = (f"import {module}; from wheelrail.normal.bem import solve_normal; "
            "from wheelrail.tangential.exact import solve_gap; from wheelrail.halfspace import Grid")
    subprocess.run([sys.executable, "-c", code], check=True)
