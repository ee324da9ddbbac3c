"""Convergence of the exact (half-space) steady-rolling solver with and without spin, and
the placement of the spin's rigid slip inside an element.

No closed form exists for partial slip with spin, so the references are Richardson
extrapolations of grid sequences (20, 40, 80 elements across the contact), with the
observed order fitted by np.polyfit on log h / log |F(h) − F(h/2)|.

The rigid slip φ·x of the spin is evaluated a sixth of an element upstream of the
element centre (as Vollebregt's CONTACT does, FACPHI = 1/6; see
:mod:`wheelrail.tangential.exact`). The element-centre placement is reproduced on the
same grid by adding η = −φ·dx/6 (the shift of φ·x is a uniform lateral creepage). Measured
(Hertz a/b = 1.59, steel, μ = 0.3, BEM pressure, Fy of pure spin φ = 3 /m):

* centre: −1002.0, −1016.6, −1023.3 N at 40, 80, 160 elements (first order, limit about
  −1030 N): |Fy| 2.7 % low at 40 elements;
* a sixth upstream: −1031.0, −1031.0, −1030.5 N: within 0.1 % at 40 elements;
* the midpoint of the backward difference (half an element): 5.7 % high at 40.

Without spin nothing changes: η = 1e-3 converges at order 0.8 with |Fy| 1.4 % high at 40
elements.
"""

import numpy as np
import pytest

import wheelrail as wr

MU = 0.3
HC = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)


def _fy(n, creepage):
    return wr.creep_forces(HC, creepage, MU, method="exact", elements=n).Fy


def test_pure_spin_within_half_a_percent_at_40_elements():
    phi = 3.0
    # the element-centre placement, first-order Richardson limit from 40 and 80 elements
    centre = {n: _fy(n, (0.0, -phi * (2 * float(HC.a) / n) / 6.0, phi)) for n in (40, 80)}
    limit = 2.0 * centre[80] - centre[40]
    new40 = _fy(40, (0.0, 0.0, phi))
    err_new = abs(new40 / limit - 1)
    err_centre = abs(centre[40] / limit - 1)
    assert err_new < 0.005, (new40, limit)          # the target: within 0.5 % at 40 elements
    assert err_centre > 5 * err_new, (centre, new40, limit)
    # the same limit: the refined grids agree to the first-order remainder
    assert _fy(80, (0.0, 0.0, phi)) == pytest.approx(limit, rel=0.003)


@pytest.mark.parametrize("creepage", [(0.0, 1e-3, 0.0), (1e-3, 5e-4, 1.0)])
def test_first_order_without_and_with_combined_spin(creepage):
    ns = (20, 40, 80)
    F = np.array([_fy(n, creepage) for n in ns])
    d = np.abs(np.diff(F))
    h = 1.0 / np.array(ns[:-1], dtype=float)
    order = np.polyfit(np.log(h), np.log(d), 1)[0]
    limit = F[-1] + (F[-1] - F[-2]) / (2.0**order - 1.0)
    assert (F[1] - F[0]) * (F[2] - F[1]) > 0, F         # monotone
    assert 0.7 < order < 2.5, (F, order)
    assert abs(F[1] / limit - 1) < 0.02, (F, limit)
