"""Kalker's exact theory, shift problem, against Cattaneo–Mindlin (circular Hertz contact).

Reference: C. Cattaneo (1938), R.D. Mindlin (1949); K.L. Johnson, *Contact
Mechanics* (1985) §7.2, eqs. (7.38)–(7.42), implemented in
:mod:`wheelrail.reference`. For ν = 0 the Cattaneo–Mindlin solution is exact
for the half-space (the Cerruti coupling terms vanish); for ν > 0 it neglects
the small lateral coupling (Johnson §7.2); measured on 30×30 elements the
shift agrees within 0.3 % for both, the stick radius (from the stick area)
within 1.2 %.
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.halfspace import Grid
from wheelrail.tangential.exact import solve_shift
from wheelrail.reference import cattaneo_shift, cattaneo_stick_radius, cattaneo_traction

A = 1e-3       # contact radius [m]
P = 1e3        # normal load [N]
MU = 0.3


def _setup(n, nu):
    mat = wr.Material(2.1e11, nu)
    grid = Grid.from_bounds(-A, A, -A, A, n, n)
    p0 = 1.5 * P / (np.pi * A * A)
    p = p0 * np.sqrt(np.clip(1 - (grid.X**2 + grid.Y**2) / A**2, 0, None))
    p *= P / (p.sum() * grid.element_area)   # discrete load exactly P
    return mat, grid, p


@pytest.mark.parametrize("nu, dtol, ctol", [(0.0, 0.005, 0.025), (0.28, 0.005, 0.025)])
@pytest.mark.parametrize("ratio", [0.3, 0.6, 0.9])
def test_shift_and_stick_radius(nu, dtol, ctol, ratio):
    mat, grid, p = _setup(30, nu)
    Q = ratio * MU * P
    sol = solve_shift(grid, p, mat, MU, force=(Q, 0.0))
    assert sol.converged
    assert sol.Fx == pytest.approx(Q, rel=1e-5)
    assert abs(sol.Fy) < 1e-6 * Q
    # the wheel is shifted against the force acting on it
    delta_ref = cattaneo_shift(A, Q, MU, P, mat)
    assert -sol.creepage[0] == pytest.approx(delta_ref, rel=dtol)
    c_num = np.sqrt(sol.adhesion_area / np.pi)
    assert c_num == pytest.approx(cattaneo_stick_radius(A, Q, MU, P), rel=ctol)


def test_traction_profile_nu0():
    mat, grid, p = _setup(30, 0.0)
    Q = 0.6 * MU * P
    sol = solve_shift(grid, p, mat, MU, force=(Q, 0.0))
    r = np.hypot(grid.X, grid.Y)
    ref = cattaneo_traction(r, A, Q, MU, P)
    inside = p > 0
    err = np.sqrt(np.mean((sol.px[inside] - ref[inside]) ** 2)) / (MU * p.max())
    assert err < 0.03
    # the traction is parallel to the force for ν = 0
    assert np.abs(sol.py).max() < 1e-6 * np.abs(sol.px).max()


def test_shift_converges_first_order():
    """Error of the shift vs Cattaneo–Mindlin decreases with the element size (ν = 0)."""
    h, err = [], []
    for n in (10, 20, 40):
        mat, grid, p = _setup(n, 0.0)
        Q = 0.6 * MU * P
        sol = solve_shift(grid, p, mat, MU, force=(Q, 0.0))
        h.append(grid.dx)
        err.append(abs(-sol.creepage[0] / cattaneo_shift(A, Q, MU, P, mat) - 1))
    order = np.polyfit(np.log(h), np.log(err), 1)[0]
    assert err[-1] < 2e-3
    assert order > 1.0      # measured ≈ 1.9
