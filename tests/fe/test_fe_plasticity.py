"""J2 plasticity kernel of the FE engine against closed forms.

References
----------
* Uniaxial tension and pure shear of a homogeneously strained element: the flow curve of
  the hardening law itself. Uniaxial stress: σ = σ_y(p) + X(p), total strain
  ε = σ/E + p; pure (simple) shear: τ = (σ_y(p) + X(p))/√3, γ = τ/G + √3 p (von Mises;
  Lemaitre & Chaboche, *Mechanics of Solid Materials*, 1990, §5.2-5.4); X the uniaxial
  back stress, C p (Prager) or (C/γ)(1 − e^(−γ p)) (Armstrong–Frederick).
  Under proportional loading the radial return is exact for isotropic and Prager
  hardening (tolerance 1e-6, measured ~1e-12); the backward-Euler Armstrong–Frederick
  update is first-order accurate (the order is fitted).
* The consistent tangent (Simo & Hughes 1998, Box 3.2) against central differences of the
  internal forces.
* Bitwise equality of the parallel kernel on 1 and 2 threads.
"""

import numba
import numpy as np
import pytest
import scipy.sparse as sp

from wheelrail.errors import InputError
from wheelrail.fe import J2Plastic, TabulatedHardening, Voce, r900a
from wheelrail.fe import _solid as S
from wheelrail.fe.elements import Hex8
from wheelrail.fe.mesh import _hex_connectivity

L = 1e-2


def _cube():
    ax = np.array([0.0, L])
    X, Y, Z = np.meshgrid(ax, ax, ax, indexing="ij")
    return np.stack([X, Y, Z], -1).reshape(-1, 3), _hex_connectivity((2, 2, 2))


class OneBody:
    """Internal force and tangent of a small mesh through the kernels (committed state)."""

    def __init__(self, nodes, conn, mat, integration="reduced"):
        self.nodes, self.conn, self.mat = nodes, conn, mat
        self.ed = Hex8(integration).precompute(nodes, conn, mat)
        self.chunks = S.element_chunks(conn, nodes.shape[0])
        ng = self.ed.dNdx.shape[1]
        self.committed = np.zeros((conn.shape[0], ng, S.NSTATE))
        self.trial = self.committed.copy()
        self.hp = mat.kernel_parameters()

    def force(self, u):
        f = np.zeros_like(u)
        en = np.zeros((self.conn.shape[0], 2))
        hp, tp, ts = self.hp
        S.element_forces(u, self.conn, self.chunks, self.ed.dNdx, self.ed.wdet,
                         self.ed.gamma, self.ed.khg, self.mat.lam, self.mat.G, True, hp, tp, ts,
                         self.committed, self.trial, f, en)
        return f

    def tangent(self, u):
        ne = self.conn.shape[0]
        r, c, v = np.empty(ne * 576, np.int64), np.empty(ne * 576, np.int64), np.empty(ne * 576)
        hp, tp, ts = self.hp
        S.tangent_triplets(u, self.conn, self.ed.dNdx, self.ed.wdet, self.ed.gamma, self.ed.khg,
                           self.mat.lam, self.mat.G, True, hp, tp, ts, self.committed, r, c, v)
        n = u.size
        return sp.coo_matrix((v, (r, c)), shape=(n, n)).toarray()

    def solve(self, u, fixed, fext=None, tol=1e-14):
        """Newton on the free dofs for prescribed values of u at ``fixed``; commits."""
        free = np.setdiff1d(np.arange(u.size), fixed)
        for _ in range(30):
            r = self.force(u).ravel() - (0 if fext is None else fext.ravel())
            if free.size == 0 or np.max(np.abs(r[free])) <= tol * max(1.0, np.max(np.abs(r))):
                break
            Kt = self.tangent(u)
            du = np.linalg.solve(Kt[np.ix_(free, free)], -r[free])
            uu = u.ravel().copy()
            uu[free] += du
            u = uu.reshape(-1, 3)
        else:
            raise AssertionError("Newton did not converge")
        self.force(u)
        self.committed, self.trial = self.trial, self.committed
        return u

    def stress(self, u):
        out = np.zeros((self.conn.shape[0], 6))
        S.element_stress(u, self.conn, self.ed.dNdx, self.ed.wdet, self.mat.lam, self.mat.G,
                         True, self.committed, out)
        return out


MATERIALS = {
    "voce+prager": J2Plastic(2.1e11, 0.28, 489e6, hardening=Voce(490e6, 36.7, 2e8),
                             kinematic=5e9),
    "table": J2Plastic(2.1e11, 0.28, 489e6,
                       hardening=TabulatedHardening([0, 0.002, 0.01, 0.03], [489e6, 560e6,
                                                                              650e6, 700e6])),
    "perfect": J2Plastic(2.1e11, 0.28, 489e6),
}


def _uniaxial(mat, strains, integration="reduced"):
    nodes, conn = _cube()
    body = OneBody(nodes, conn, mat, integration)
    x0, y0, z0 = (nodes[:, k] < 0.5 * L for k in range(3))
    x1 = ~x0
    fixed = np.concatenate([3 * np.flatnonzero(x0), 3 * np.flatnonzero(x1),
                            3 * np.flatnonzero(y0) + 1, 3 * np.flatnonzero(z0) + 2])
    u = np.zeros_like(nodes)
    out = []
    for e in strains:
        u[x1, 0] = e * L
        u = body.solve(u, fixed)
        sig = body.stress(u)[0]
        p = body.committed[0, :, 6].mean()
        out.append((e, sig, p))
    return out


@pytest.mark.parametrize("integration", ["reduced", "full"])
@pytest.mark.parametrize("name", list(MATERIALS))
def test_uniaxial_tension_follows_the_flow_curve(name, integration):
    mat = MATERIALS[name]
    strains = np.concatenate([np.linspace(0.0005, 0.004, 8), np.linspace(0.005, 0.04, 8)])
    for e, sig, p in _uniaxial(mat, strains, integration):
        s = sig[0]
        if p == 0:
            assert s == pytest.approx(mat.E * e, rel=1e-9)
            continue
        expected = mat.flow_stress(p) + mat.back_stress(p)
        assert s == pytest.approx(expected, rel=1e-6)
        assert e == pytest.approx(s / mat.E + p, rel=1e-6)        # uniaxial plastic strain p
        assert np.max(np.abs(sig[1:])) < 1e-6 * abs(s)             # free lateral faces
    assert p > 0.03


@pytest.mark.parametrize("name", list(MATERIALS))
def test_pure_shear_follows_the_flow_curve(name):
    mat = MATERIALS[name]
    nodes, conn = _cube()
    body = OneBody(nodes, conn, mat)
    fixed = np.arange(24)
    u = np.zeros_like(nodes)
    seen_plastic = False
    for g in np.linspace(0.001, 0.05, 12):
        u[:, 0] = g * nodes[:, 1]                                   # simple shear γ_xy = g
        u = body.solve(u, fixed)
        tau = body.stress(u)[0, 3]
        p = body.committed[0, 0, 6]
        if p == 0:
            assert tau == pytest.approx(mat.G * g, rel=1e-9)
            continue
        seen_plastic = True
        assert tau == pytest.approx((mat.flow_stress(p) + mat.back_stress(p)) / np.sqrt(3),
                                    rel=1e-6)
        assert g == pytest.approx(tau / mat.G + np.sqrt(3) * p, rel=1e-6)
    assert seen_plastic


def test_armstrong_frederick_backward_euler_converges_first_order():
    mat = J2Plastic(2.1e11, 0.28, 489e6, kinematic=2e10, kinematic_recovery=60.0)
    errs = []
    for n in (10, 20, 40):
        e, sig, p = _uniaxial(mat, np.linspace(0.001, 0.03, n))[-1]
        errs.append(abs(sig[0] - mat.flow_stress(p) - mat.back_stress(p)) / sig[0])
    order = np.polyfit(np.log([10, 20, 40]), np.log(errs), 1)[0]
    assert -1.3 < order < -0.8                                      # first order in Δp
    assert errs[-1] < 5e-3                                          # measured 3.0e-3


@pytest.mark.parametrize("integration", ["reduced", "full"])
def test_consistent_tangent_equals_finite_differences(integration):
    rng = np.random.default_rng(4)
    n = 2
    ax = np.linspace(0, L, n + 1)
    X, Y, Z = np.meshgrid(ax, ax, ax, indexing="ij")
    nodes = np.stack([X, Y, Z], -1).reshape(-1, 3)
    nodes += rng.uniform(-1, 1, nodes.shape) * 0.05 * L / n
    conn = _hex_connectivity((n + 1,) * 3)
    mat = J2Plastic(2.1e11, 0.28, 300e6, hardening=Voce(200e6, 30.0), kinematic=3e9)
    body = OneBody(nodes, conn, mat, integration)
    body.committed[..., 6] = 0.01                                  # a hardened, shifted start
    alpha = rng.normal(size=6) * 2e7
    alpha[:3] -= alpha[:3].mean()                                  # back stresses are deviatoric
    body.committed[..., 7:13] = alpha
    u = rng.normal(size=nodes.shape) * 3e-5
    body.force(u)
    assert (body.trial[..., 6] > 0.01).mean() > 0.5                # mostly plastic points
    Kt = body.tangent(u)
    du = rng.normal(size=nodes.shape) * 1e-11
    fd = (body.force(u + du) - body.force(u - du)).ravel() / 2
    np.testing.assert_allclose(Kt @ du.ravel(), fd, atol=1e-6 * np.abs(fd).max())


def test_parallel_kernel_is_bitwise_identical_on_one_and_two_threads():
    rng = np.random.default_rng(5)
    n = 6
    ax = np.linspace(0, L, n + 1)
    X, Y, Z = np.meshgrid(ax, ax, ax, indexing="ij")
    nodes = np.stack([X, Y, Z], -1).reshape(-1, 3)
    conn = _hex_connectivity((n + 1,) * 3)
    body = OneBody(nodes, conn, r900a())
    u = rng.normal(size=nodes.shape) * 2e-5
    default = numba.get_num_threads()
    out = {}
    try:
        for threads in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
            numba.set_num_threads(threads)
            out[threads] = (body.force(u), body.trial.copy())
    finally:
        numba.set_num_threads(default)
    (f1, s1), (f2, s2) = out[1], out[max(out)]
    assert np.array_equal(f1, f2) and np.array_equal(s1, s2)
    assert (s1[..., 6] > 0).any()


@pytest.mark.parametrize("kw, match", [
    (dict(yield_stress=-1.0), "yield_stress"),
    (dict(hardening="steep"), "hardening"),
    (dict(hardening=([0, 0.1], [400e6, 500e6])), "table starts at"),
    (dict(hardening=([0.1, 0.2], [489e6, 500e6])), "start at 0"),
    (dict(kinematic=-1.0), "kinematic"),
])
def test_bad_plastic_input_is_named(kw, match):
    args = dict(E=2.1e11, nu=0.28, yield_stress=489e6)
    args.update(kw)
    with pytest.raises(InputError, match=match):
        J2Plastic(**args)
