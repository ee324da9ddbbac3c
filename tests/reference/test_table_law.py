"""Table-interpolating creep-force law (issue 10) against the exact solver it tabulates.

References: the exact solver (:mod:`wheelrail.tangential.exact`, Kalker 1990 ch. 5) at points
*not* in the table; Kalker's creep coefficient C11 (Kalker 1990, Table E.3: C11 = 4.12 for
a/b = 1, nu = 0.25) for the small-creepage slope; the full-slip limit |F| = mu Fn.
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError
from wheelrail.tangential import table as T
from wheelrail.sweeps.tables import build_table, table_nodes
from wheelrail.tangential.linear import kalker_coefficients

STEEL = wr.Material(2.1e11, 0.28)


def _exact(c, creep, mu, elements=16):
    return wr.creep_forces(c, creep, mu, method="exact", elements=elements, on_fail="status",
                           progress=False)


def test_symmetries_the_table_relies_on():
    """F(-xi, eta, phi) = (-Fx, Fy, Mz) and F(xi, -eta, -phi) = (Fx, -Fy, -Mz) (K = 0)."""
    c = wr.hertz(1e4, 1.0, 1.7, STEEL)
    xi, eta, phi = -6e-4, 4e-4, 0.6
    f = _exact(c, (xi, eta, phi), 0.3)
    g = _exact(c, (-xi, eta, phi), 0.3)
    h = _exact(c, (xi, -eta, -phi), 0.3)
    scale = 0.3 * 1e4
    assert abs(f.Fx) > 0.1 * scale and abs(f.Fy) > 0.1 * scale
    np.testing.assert_allclose([g.Fx, g.Fy], [-f.Fx, f.Fy], atol=2e-3 * scale)
    np.testing.assert_allclose([h.Fx, h.Fy], [f.Fx, -f.Fy], atol=2e-3 * scale)
    np.testing.assert_allclose([g.Mz, h.Mz], [f.Mz, -f.Mz], atol=2e-3 * scale * 5e-3)


def test_similarity_the_table_relies_on():
    """Equal a/b, nu and scaled creepages give equal F/(mu Fn) for other loads, mu, E, size."""
    out = []
    for load, mu, E, scale in ((1e4, 0.3, 2.1e11, 1.0), (2e3, 0.15, 1.0e11, 3.0)):
        m = wr.Material(E, 0.28)
        c = wr.hertz(load, 1.0 / scale, 1.6 / scale, m)
        cc = float(np.sqrt(c.a * c.b))
        unit = 3 * mu * load / (m.G * cc**2)
        r = _exact(c, (0.4 * unit, -0.3 * unit, 0.5 * unit / cc), mu)
        out.append([r.Fx / (mu * load), r.Fy / (mu * load), r.Mz / (mu * load * cc)])
    np.testing.assert_allclose(out[0], out[1], atol=2e-3)


def test_generator_reproduces_its_nodes(tmp_path):
    """A tiny table built by the package's generator returns the exact solver at its nodes."""
    grid = {"r": [0.0, 0.3, 1.0], "theta": [0.0, 0.5 * np.pi], "s": [-0.2, 0.2],
            "log_ab": np.log([0.8, 1.25]), "nu": [0.25, 0.30]}
    path = build_table(tmp_path / "t.npz", elements=10, workers=1, progress=False, grid=grid)
    data = T.load_table(path)
    assert data.meta["elements"] == 10 and data.values.shape == (3, 2, 2, 2, 2, 3)
    nodes = table_nodes({k: np.asarray(v, float) for k, v in grid.items()})
    i = 13  # some node: reproduce it through creep_forces(method="table", table=path)
    m = wr.Material(2.1e11, nodes["nu"][i])
    c = wr.hertz_from_semiaxes(nodes["a"][i], nodes["b"][i], 1e4, m)
    creep = (nodes["xi"][i], nodes["eta"][i], nodes["phi"][i])
    t = wr.creep_forces(c, creep, 0.3, method="table", table=str(path))
    e = _exact(c, creep, 0.3, elements=10)
    np.testing.assert_allclose([t.Fx, t.Fy], [e.Fx, e.Fy], atol=1e-5 * 3e3)
    assert (tmp_path / "t.npz").exists() and not (tmp_path / "t.npz.zarr").exists()


# ---------------------------------------------------------------- the shipped table
def _random_points(n, seed):
    """Contacts and creepages spread over the shipped table's domain."""
    rng = np.random.default_rng(seed)
    ab = np.exp(rng.uniform(np.log(0.2), np.log(5.0), n))
    nu = rng.uniform(0.25, 0.30, n)
    load = rng.uniform(2e3, 2e4, n)
    mu = rng.uniform(0.1, 0.5, n)
    rho = rng.uniform(0.0, 3.0, n) ** 2
    th = rng.uniform(-np.pi, np.pi, n)
    ph = rng.uniform(-4.0, 4.0, n) * rng.uniform(0.0, 1.0, n)
    return ab, nu, load, mu, rho, th, ph


def _physical(ab, nu, load, mu, rho, th, ph):
    m = wr.Material(2.1e11, nu)
    c = wr.hertz_from_semiaxes(4e-3 * np.sqrt(ab), 4e-3 / np.sqrt(ab), load, m)
    cc = np.sqrt(c.a * c.b)
    C11, C22, C23, _ = kalker_coefficients(ab, nu)
    unit = 3 * mu * load / m.G
    ell = np.hypot(cc * C23, c.b * C11)  # the table's spin length (module docstring)
    creep = (rho * np.cos(th) * unit / (cc**2 * C11),
             (rho * np.sin(th) - ph * cc * C23 / ell) * unit / (cc**2 * C22),
             ph * unit / (cc**2 * ell))
    return c, creep, cc


def test_shipped_table_against_exact_off_the_nodes():
    """Max error on random points not in the table (exact solver at the table's elements)."""
    errs = []
    for p in zip(*_random_points(25, seed=7)):
        c, creep, cc = _physical(*p)
        mu, load = p[3], p[2]
        t = wr.creep_forces(c, creep, mu, method="table")
        e = _exact(c, creep, mu, elements=T.load_table().meta["elements"])
        errs.append([abs(t.Fx - e.Fx) / (mu * load), abs(t.Fy - e.Fy) / (mu * load),
                     abs(t.Mz - e.Mz) / (mu * load * cc)])
    errs = np.array(errs)
    assert errs[:, :2].max() < 0.02, errs.max(0)
    assert errs[:, 2].max() < 0.02, errs.max(0)


def test_small_creepage_slope_is_kalkers_c11():
    """Fx = -G c^2 C11 xi for xi -> 0; Kalker 1990 Table E.3: C11 = 4.12 at a/b = 1, nu = 0.25."""
    m = wr.Material(2.1e11, 0.25)
    c = wr.hertz_from_semiaxes(5e-3, 5e-3, 1e4, m)
    xi = -1e-6
    r = wr.creep_forces(c, (xi, 0.0, 0.0), 0.3, method="table")
    C11 = r.Fx / (-m.G * c.a * c.b * xi)
    assert C11 == pytest.approx(4.12, rel=0.04)


def test_full_slip_limit_and_batch_shapes():
    c = wr.hertz(np.array([1e4, 1e4, 5e3]), 1.0, 1.6, STEEL)
    creep = np.array([[-0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.3, -0.4, 0.0]])
    r = wr.creep_forces(c, creep, 0.3, method="table")
    assert r.Fx.shape == (3,)
    np.testing.assert_allclose(np.hypot(r.Fx, r.Fy), 0.3 * c.Fn, rtol=1e-3)
    assert r.Fx[0] > 0 and r.Fy[1] < 0 and r.Fx[2] < 0 and r.Fy[2] > 0  # opposite to creepage


def test_outside_the_domain_raises_or_falls_back():
    c = wr.hertz(1e4, 1.0, 40.0, STEEL)  # a/b far above 5
    with pytest.raises(InputError, match=r"a/b = [0-9.]+ at point 0 \(table domain: 0.2 <= a/b"):
        wr.creep_forces(c, (-1e-3, 0.0, 0.0), 0.3, method="table")
    r = wr.creep_forces(c, (-1e-3, 0.0, 0.0), 0.3, method="table", outside="fastsim")
    f = wr.creep_forces(c, (-1e-3, 0.0, 0.0), 0.3, method="fastsim")
    assert r.Fx == pytest.approx(f.Fx) and r.info["outside"] is True
    c2 = wr.hertz(1e4, 1.0, 1.6, STEEL)
    with pytest.raises(InputError, match=r"scaled spin phi_hat = [0-9.]+"):
        wr.creep_forces(c2, (0.0, 0.0, 200.0), 0.3, method="table")
    soft = wr.MaterialPair(wr.Material(2.1e11, 0.28), wr.Material(0.7e11, 0.28))
    c3 = wr.hertz(1e4, 1.0, 1.6, soft)
    with pytest.raises(InputError, match=r"difference parameter K"):
        wr.creep_forces(c3, (-1e-3, 0.0, 0.0), 0.3, method="table")
    with pytest.raises(InputError, match="outside must be"):
        wr.creep_forces(c2, (-1e-3, 0.0, 0.0), 0.3, method="table", outside="clamp")
