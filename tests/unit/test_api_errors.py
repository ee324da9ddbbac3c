"""Bad input to the public entry functions gives a clear error naming the value.

Every registered creep-force law goes through the same validation in
``wheelrail.api.creep_forces``; these checks run for each of them.
"""

import numpy as np
import pytest

import wheelrail as wr

C = wr.hertz(7500.0, 1.0869565, 1.6666667, wr.STEEL)
OPTS = {"fastsim": {"nx": 6, "ny": 6}, "exact": {"elements": 8}}


@pytest.mark.parametrize("method", list(wr.tangential_methods()))
@pytest.mark.parametrize("creepage, mu, match", [
    ((np.nan, 0.0, 0.0), 0.3, "creepage must be finite"),
    ((0.0, np.inf, 0.0), 0.3, "creepage must be finite"),
    ((1e-3, 0.0), 0.3, "shape"),
    ((1e-3, 0.0, 0.0), 0.0, "mu must be > 0, got 0.0"),
    ((1e-3, 0.0, 0.0), -0.2, "mu must be > 0, got -0.2"),
    ((1e-3, 0.0, 0.0), np.nan, "mu must be finite"),
])
def test_bad_creepage_and_friction(method, creepage, mu, match):
    with pytest.raises(wr.InputError, match=match):
        wr.creep_forces(C, creepage, mu, method=method, **OPTS.get(method, {}))


def test_unknown_method_and_option_are_named():
    with pytest.raises(wr.InputError, match="unknown creep-force method 'fastsimm'"):
        wr.creep_forces(C, (0, 0, 0), 0.3, method="fastsimm")
    with pytest.raises(wr.InputError, match="does not accept option.*nxx"):
        wr.creep_forces(C, (0, 0, 0), 0.3, method="fastsim", nxx=4)


def test_contact_must_be_a_hertz_contact():
    with pytest.raises(wr.InputError, match="HertzContact"):
        wr.creep_forces({"a": 1.0}, (0, 0, 0), 0.3)


@pytest.mark.parametrize("kwargs, match", [
    (dict(a=8e-3, b=-4e-3, Fn=1e4), "b must be > 0"),
    (dict(a=8e-3, b=4e-3, Fn=0.0), "Fn must be > 0, got 0.0"),
    (dict(a=1e-3, b=1e7, Fn=1e4), "a/b"),
])
def test_semiaxes_out_of_range(kwargs, match):
    with pytest.raises(wr.InputError, match=match):
        wr.hertz_from_semiaxes(material=wr.STEEL, **kwargs)


def test_material_out_of_range():
    with pytest.raises(wr.InputError, match="nu must lie in"):
        wr.Material(2.1e11, 0.5)
    with pytest.raises(wr.InputError, match="E must be > 0"):
        wr.Material(-1.0, 0.3)
