"""The implicit integrators' Newton-system solvers: SuperLU (``linear_solver="direct"``) and
MKL PARDISO (``"pardiso"``, the optional extra ``wheelrail[pardiso]``).

Both are direct solvers, so an implicit run must give the same numbers with either to
rounding (the Newton iterations stop at the same iterate as long as the residual norms
agree far below the tolerance). The reference is SuperLU (scipy), which shares no code
with MKL.
"""

import sys

import numpy as np
import pytest
import scipy.sparse as sp

import wheelrail as wr
from wheelrail.errors import InputError
from wheelrail.fe import RollingCase, solve
from wheelrail.fe import _newton as nw

FLAT_WHEEL = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
#: a 2 mm mesh, 7.5 kN on 60E1, two implicit steps of 72 µs (tests/reference/test_fe_rolling.py)
IMPLICIT = dict(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46, Fn=7500.0,
                mu=0.2, mesh_size=2e-3, element="reduced", mass_scaling=1.0, depth=3,
                half_width=3, half_length=3, travel=0.0015, creepage=(7e-4, 0.0, 0.0))


def _system(n=400, seed=3):
    """A sparse unsymmetric, diagonally dominant system like a Newton matrix with friction."""
    rng = np.random.default_rng(seed)
    A = sp.random(n, n, density=0.02, random_state=rng, format="csr")
    A = A + sp.diags(np.abs(A).sum(axis=1).A1 + 1.0)
    return A.tocsr(), rng.standard_normal(n)


def test_pardiso_solves_an_unsymmetric_system_like_superlu():
    pytest.importorskip("pypardiso")
    A, b = _system()
    x_ref = sp.linalg.spsolve(A.tocsc(), b)
    solver = nw.make_solver("pardiso")
    x = solver.solve(A, b)
    np.testing.assert_allclose(x, x_ref, rtol=1e-10, atol=1e-12)
    assert (solver.solves, solver.factorizations, solver.fallbacks) == (1, 1, 0)
    # a second, different matrix is factorised afresh, not solved with the old factors
    A2 = A + sp.diags(np.full(A.shape[0], 3.0))
    np.testing.assert_allclose(solver.solve(A2, b), sp.linalg.spsolve(A2.tocsc(), b),
                               rtol=1e-10, atol=1e-12)


def test_pardiso_bad_solution_falls_back_to_superlu(monkeypatch):
    """A PARDISO solution whose residual is not small (perturbed pivots) is replaced by the
    SuperLU one and counted."""
    pytest.importorskip("pypardiso")
    A, b = _system(seed=5)
    solver = nw.make_solver("pardiso")
    monkeypatch.setattr(solver._pardiso, "solve", lambda A, b: np.zeros_like(b) + 1.0)
    x = solver.solve(A, b)
    np.testing.assert_allclose(x, sp.linalg.spsolve(A.tocsc(), b), rtol=1e-10, atol=1e-12)
    assert solver.fallbacks == 1


def test_implicit_hht_same_with_pardiso_and_superlu():
    pytest.importorskip("pypardiso")
    runs = {name: solve(RollingCase(integrator="implicit-hht", linear_solver=name, **IMPLICIT),
                        progress=False) for name in ("direct", "pardiso")}
    d, p = runs["direct"], runs["pardiso"]
    assert p.info["linear_solves"] == d.info["linear_solves"] > 0
    np.testing.assert_allclose(p.u, d.u, rtol=0, atol=1e-9 * np.abs(d.u).max())
    for name in ("Fx", "Fn"):
        np.testing.assert_allclose(p.dataset[name].values, d.dataset[name].values, rtol=1e-7,
                                   atol=1e-6)


def test_pardiso_missing_is_named(monkeypatch):
    monkeypatch.setitem(sys.modules, "pypardiso", None)       # import fails
    with pytest.raises(ImportError, match=r"wheelrail\[pardiso\]"):
        nw.make_solver("pardiso")


def test_unknown_linear_solver_lists_the_choices():
    with pytest.raises(InputError, match="'auto', 'direct', 'reuse' or 'pardiso'.*'mumps'"):
        RollingCase(linear_solver="mumps", **{k: v for k, v in IMPLICIT.items()
                                               if k != "creepage"})


def test_auto_is_pardiso_where_installed_else_superlu(monkeypatch):
    solver = nw.make_solver("auto")
    has = nw.pardiso_available()
    assert isinstance(solver, nw.PardisoSolver) == has
    monkeypatch.setitem(sys.modules, "pypardiso", None)       # not installed
    assert type(nw.make_solver("auto")) is nw.DirectSolver
