"""hex8 element and material checks: patch test, rigid-body modes, single-element closed forms.

References: the patch test (Irons; Hughes, *The Finite Element Method*, §3.5) — a
linear displacement field must be reproduced exactly, with the constant stress of
Hooke's law σ = λ tr ε I + 2 μ ε, on a distorted mesh.
"""

import numpy as np
import pytest
import scipy.sparse as sp

from wheelrail.fe import _kernels as K
from wheelrail.fe import _solid as S
from wheelrail.fe.elements import Hex8
from wheelrail.fe.materials import LinearElastic
from wheelrail.fe.mesh import Body, _hex_connectivity, check_quality

MAT = LinearElastic(2.1e11, 0.28)


def _block(n=3, distort=0.15, seed=0):
    ax = np.linspace(0.0, 1e-2, n + 1)
    X, Y, Z = np.meshgrid(ax, ax, ax, indexing="ij")
    nodes = np.stack([X, Y, Z], -1).reshape(-1, 3)
    rng = np.random.default_rng(seed)
    inner = np.all((nodes > 0) & (nodes < 1e-2), axis=1)
    nodes[inner] += distort * 1e-2 / n * rng.uniform(-1, 1, (inner.sum(), 3))
    shape = (n + 1, n + 1, n + 1)
    return nodes, _hex_connectivity(shape), inner


def _stiffness(nodes, conn, elem):
    ed = elem.precompute(nodes, conn, MAT)
    m = conn.shape[0] * 576
    r, c, v = np.empty(m, np.int64), np.empty(m, np.int64), np.empty(m)
    K.stiffness_triplets(conn, ed.dNdx, ed.wdet, MAT.lam, MAT.shear_modulus, ed.gamma, ed.khg, r, c, v)
    n = 3 * nodes.shape[0]
    return sp.coo_matrix((v, (r, c)), shape=(n, n)).tocsr(), ed


@pytest.mark.parametrize("integration", ["full", "reduced"])
def test_patch_test_linear_field_exact(integration):
    nodes, conn, inner = _block()
    Kg, ed = _stiffness(nodes, conn, Hex8(integration))
    G = np.array([[1.0, 0.3, -0.2], [0.1, -0.5, 0.4], [0.25, 0.05, 0.7]]) * 1e-4
    exact = nodes @ G.T
    free = np.flatnonzero(np.repeat(inner, 3))
    fixed = np.flatnonzero(~np.repeat(inner, 3))
    u = exact.ravel().copy()
    u[free] = 0.0
    rhs = -Kg[free][:, fixed] @ exact.ravel()[fixed]
    u[free] = sp.linalg.spsolve(Kg[free][:, free].tocsc(), rhs)
    assert np.max(np.abs(u - exact.ravel())) < 1e-12 * np.abs(exact).max() * 1e3
    # constant stress: the von Mises stress of every element equals the closed form
    eps = 0.5 * (G + G.T)
    sig = MAT.lam * np.trace(eps) * np.eye(3) + 2 * MAT.shear_modulus * eps
    dev = sig - np.trace(sig) / 3 * np.eye(3)
    vm_exact = np.sqrt(1.5 * np.sum(dev * dev))
    sig_e = np.empty((conn.shape[0], 6))
    S.element_stress(u.reshape(-1, 3), conn, ed.dNdx, ed.wdet, MAT.lam, MAT.shear_modulus, False,
                     np.zeros((0, 1, 14)), sig_e)
    np.testing.assert_allclose(S.von_mises(sig_e), vm_exact, rtol=1e-9)


@pytest.mark.parametrize("integration", ["full", "reduced"])
def test_single_element_has_six_rigid_modes(integration):
    nodes, conn, _ = _block(n=1, distort=0.0)
    nodes = nodes * np.array([1.0, 2.0, 0.5])          # a brick, not a cube
    Kg, _ = _stiffness(nodes, conn, Hex8(integration))
    ev = np.linalg.eigvalsh(Kg.toarray())
    n_zero = int(np.sum(ev < 1e-8 * ev.max()))
    assert n_zero == 6


def test_uniaxial_stress_single_element_recovers_young_modulus():
    """A cube pulled by a uniform traction σ: strain σ/E axially and -ν σ/E laterally."""
    L = 1e-2
    nodes, conn, _ = _block(n=1, distort=0.0)
    Kg, _ = _stiffness(nodes, conn, Hex8("full"))
    sigma = 1e8
    f = np.zeros((8, 3))
    top = nodes[:, 2] > 0.5 * L
    f[top, 2] = sigma * L * L / 4
    # symmetric supports: z = 0 on the bottom, x = 0 on the x = 0 face, y = 0 on y = 0
    fixed = [3 * i + 2 for i in np.flatnonzero(~top)]
    fixed += [3 * i for i in np.flatnonzero(nodes[:, 0] < 0.5 * L)]
    fixed += [3 * i + 1 for i in np.flatnonzero(nodes[:, 1] < 0.5 * L)]
    free = np.setdiff1d(np.arange(24), fixed)
    u = np.zeros(24)
    u[free] = np.linalg.solve(Kg.toarray()[np.ix_(free, free)], f.ravel()[free])
    u = u.reshape(8, 3)
    assert u[top, 2].mean() / L == pytest.approx(sigma / MAT.E, rel=1e-10)
    far = nodes[:, 0] > 0.5 * L
    assert u[far, 0].mean() / L == pytest.approx(-MAT.nu * sigma / MAT.E, rel=1e-10)


@pytest.mark.parametrize("integration", ["full", "reduced"])
def test_internal_force_equals_stiffness_times_u_and_energy(integration):
    nodes, conn, _ = _block(n=2, distort=0.2, seed=3)
    Kg, ed = _stiffness(nodes, conn, Hex8(integration))
    u = np.random.default_rng(1).normal(size=nodes.shape) * 1e-6
    f = np.zeros_like(u)
    en = np.zeros((conn.shape[0], 2))
    S.element_forces(u, conn, S.element_chunks(conn, nodes.shape[0]), ed.dNdx, ed.wdet, ed.gamma,
                     ed.khg, MAT.lam, MAT.shear_modulus, False, np.zeros(6), np.zeros(0),
                     np.zeros(0), np.zeros((0, 1, 14)), np.zeros((0, 1, 14)), f, en)
    np.testing.assert_allclose(f.ravel(), Kg @ u.ravel(), rtol=1e-9, atol=1e-9 * np.abs(f).max())
    assert en[:, 0].sum() == pytest.approx(0.5 * u.ravel() @ (Kg @ u.ravel()), rel=1e-10)


def test_reduced_hourglass_matches_full_on_a_cube():
    """The calibrated hourglass stiffness gives the cube's hourglass energy of full integration."""
    nodes, conn, _ = _block(n=1, distort=0.0)
    Kf, _ = _stiffness(nodes, conn, Hex8("full"))
    Kr, _ = _stiffness(nodes, conn, Hex8("reduced"))
    ef, er = [], []
    for h in K.HG:
        for comp in range(3):
            v = np.zeros(24)
            v[comp::3] = h / np.linalg.norm(h)
            ef.append(v @ Kf @ v)
            er.append(v @ Kr @ v)
    ef, er = np.array(ef), np.array(er)
    # calibrated on average over the 12 (mode, component) pairs; each within a factor 2
    assert er.mean() == pytest.approx(ef.mean(), rel=0.05)
    assert np.all((er > 0.5 * ef) & (er < 2.0 * ef))


def test_quality_check_rejects_inverted_element():
    nodes, conn, _ = _block(n=1, distort=0.0)
    nodes = nodes.copy()
    nodes[6] = [-0.01, -0.01, -0.01]                   # fold a corner through the element
    body = Body("test", nodes, conn, (2, 2, 2), (None, None, None), np.zeros((1, 1, 4), int),
                np.zeros(0, int))
    from wheelrail.fe.mesh import MeshQualityError
    with pytest.raises(MeshQualityError, match="non-positive Jacobian"):
        check_quality(body)


@pytest.mark.parametrize("plastic", [False, True])
def test_compact_hourglass_data_gives_the_gamma_forces(plastic):
    """The explicit step's compact hourglass data hx = h·x (4 × 3 per element) gives the forces
    and energies of the Flanagan & Belytschko (1981) vectors γ = (h − (h·x) b)/8, their
    eq. (56), to rounding, on distorted elements (elastic and yielding J2 points)."""
    nodes, conn, _ = _block(n=3, distort=0.25, seed=5)
    ed = Hex8("reduced").precompute(nodes, conn, MAT)
    assert ed.hx.shape == (conn.shape[0], 4, 3)
    assert np.abs(ed.hx).max() > 1e-2 * 1e-2 / 3       # distorted: γ ≠ h/8, hx enters
    u = np.random.default_rng(2).normal(size=nodes.shape) * (3e-6 if plastic else 1e-6)
    chunks = S.element_chunks(conn, nodes.shape[0])
    hp = np.array([3e8, 0.0, 0.0, 1e9, 0.0, 0.0])
    out = {}
    for name, hg in (("gamma", ed.gamma), ("hx", ed.hx)):
        st_out = np.zeros((conn.shape[0], 1, 14))
        f, en = np.zeros_like(u), np.zeros((conn.shape[0], 2))
        S.element_forces(u, conn, chunks, ed.dNdx, ed.wdet, hg, ed.khg, MAT.lam,
                         MAT.shear_modulus, plastic, hp, np.zeros(0), np.zeros(0),
                         np.zeros((conn.shape[0], 1, 14)), st_out, f, en)
        out[name] = f, en, st_out
    f0, en0, st0 = out["gamma"]
    f1, en1, st1 = out["hx"]
    assert np.abs(f0).max() > 0
    np.testing.assert_allclose(f1, f0, rtol=0, atol=1e-12 * np.abs(f0).max())
    np.testing.assert_allclose(en1, en0, rtol=1e-12, atol=1e-14 * np.abs(en0).max())
    np.testing.assert_allclose(st1, st0, rtol=0, atol=1e-12 * max(np.abs(st0).max(), 1e-30))
    if plastic:
        assert st0[:, 0, S.P_INDEX].max() > 0          # some points yield
