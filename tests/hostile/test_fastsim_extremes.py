"""FASTSIM at the ends of the float range: finite forces within the Coulomb bound.

Found by the case-file property test (test_casefile_hostile.py): a spin of 3.2e294 1/m
overflowed the rigid-slip rate to inf (nan forces), and E = 5.9e155 Pa made the
flexibilities (~1e-158 m/Pa) underflow when squared in the slip-direction rule
(ZeroDivisionError). Full sliding is the physical limit of both: |F_t| = mu Fn.
"""
import math
import warnings

import numpy as np
import pytest

import wheelrail as wr


@pytest.fixture(autouse=True)
def _no_plausibility_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", wr.plausibility.PlausibilityWarning)
        yield


@pytest.mark.parametrize("fields", [False, True])
@pytest.mark.parametrize("creepage", [(-7e-4, 0.0, 3.2e294), (0.0, 0.0, 1e308),
                                      (1e300, -1e300, 0.0), (-1e-3, 1e-3, 1e200)])
def test_astronomical_creepages_slide_fully(creepage, fields):
    c = wr.hertz(7500.0, 1.0869565, 1.6666667, wr.STEEL)
    r = wr.creep_forces(c, creepage, 0.2, method="fastsim", fields=fields)
    for v in (r.Fx, r.Fy, r.Mz):
        assert math.isfinite(v)
    assert math.hypot(r.Fx, r.Fy) <= 0.2 * c.Fn * (1 + 1e-9)
    if creepage[2] == 0.0:                 # pure translation: full sliding against it
        assert math.hypot(r.Fx, r.Fy) == pytest.approx(0.2 * c.Fn, rel=1e-6)
        assert np.sign(r.Fx) == -np.sign(creepage[0])


@pytest.mark.parametrize("E", [5.9e155, 1e-150])
def test_extreme_stiffness_gives_finite_forces(E):
    with wr.plausibility.disabled():
        c = wr.hertz(7500.0, 1.0869565, 1.6666667, wr.Material(E, 0.28))
        r = wr.creep_forces(c, (-1e-3, 5e-4, 0.5), 0.2, method="fastsim")
    assert all(math.isfinite(v) for v in (r.Fx, r.Fy, r.Mz))
    assert math.hypot(r.Fx, r.Fy) <= 0.2 * c.Fn * (1 + 1e-9)
