"""Sweep specification: axes, ranges, chunks, TOML reading and its errors."""

import numpy as np
import pytest

from wheelrail.errors import CaseFileError, InputError
from wheelrail.sweeps import SweepSpec, load_sweep

BASE = dict(method="linear", mu=0.3, Fn=1e4, A=1.0, B=1.5)

CASE = """
[sweep]
method = "fastsim"
mu = 0.3
Fn = 10000.0
A = 1.087
B = 1.667
xi = {start = -0.004, stop = 0.004, num = 5}
eta = {start = 1e-4, stop = 1e-2, num = 3, scale = "log"}
phi = [0.0, 0.5, 1.0]
chunk = 7
[sweep.options]
nx = 10
"""


def test_toml_axes_ranges_and_fixed_values():
    s = load_sweep(CASE)
    assert s.dims == ("xi", "eta", "phi") and s.shape == (5, 3, 3) and s.size == 45
    np.testing.assert_allclose(dict(s.axes)["xi"], np.linspace(-0.004, 0.004, 5))
    np.testing.assert_allclose(dict(s.axes)["eta"], [1e-4, 1e-3, 1e-2])
    assert s.fixed["method"] == "fastsim" and s.fixed["mu"] == 0.3
    assert dict(s.options) == {"nx": 10}
    assert s.source_sha256 and len(s.source_sha256) == 64


def test_chunks_tile_the_grid_exactly_once():
    s = load_sweep(CASE)
    cs = s.chunk_shape()
    assert np.prod(cs) <= 7 and cs[-1] == 3          # whole trailing axis, a slab of eta
    seen = np.zeros(s.shape, int)
    for block in s.chunks():
        seen[block] += 1
        cols = s.columns(block)
        assert len(cols["xi"]) == seen[block].size
    assert np.all(seen == 1)


def test_columns_follow_c_order_of_the_block():
    s = SweepSpec.grid(**BASE, xi=[1.0, 2.0], eta=[10.0, 20.0, 30.0])
    cols = s.columns(s.chunks()[0])
    np.testing.assert_array_equal(cols["xi"], [1, 1, 1, 2, 2, 2])
    np.testing.assert_array_equal(cols["eta"], [10, 20, 30, 10, 20, 30])
    np.testing.assert_array_equal(cols["mu"], 0.3)


def test_points_mode_and_method_axis():
    s = SweepSpec.from_points({"xi": [-1e-3, -2e-3], "eta": [0.0, 1e-3]}, **BASE)
    assert s.mode == "points" and s.dims == ("point",) and s.shape == (2,)
    m = SweepSpec.grid(**{**BASE, "method": ["linear", "fastsim"]}, xi=[0.0],
                       options={"fastsim": {"nx": 8}})
    assert m.shape == (2, 1)


def test_spec_hash_identifies_the_sweep():
    a = SweepSpec.grid(**BASE, xi=[0.0, 1e-3])
    assert a.sha256 == SweepSpec.grid(**BASE, xi=[0.0, 1e-3]).sha256
    assert a.sha256 != SweepSpec.grid(**BASE, xi=[0.0, 2e-3]).sha256


@pytest.mark.parametrize("axis, match", [
    ([], r"axis 'xi' has no values"),
    ({"start": 0.0, "stop": 1.0, "num": 0}, r"axis 'xi': num must be an integer >= 1.*got 0"),
    ({"start": 0.0, "stop": 1.0}, r"lacks num"),
    ({"start": 0.0, "stop": 1.0, "num": 3, "scale": "log"}, r"start=0.0"),
    ([0.0, float("nan")], r"non-finite value nan"),
])
def test_bad_axes_are_named(axis, match):
    with pytest.raises(InputError, match=match):
        SweepSpec.grid(**BASE, xi=axis)


@pytest.mark.parametrize("text, match", [
    ("[sweep]\nmu = 0.3\nFn = 1e4\nA = 1.0\nB = 1.0\nxi = []\n",
     r"<string>: \[sweep\] xi: axis 'xi' has no values"),
    ("[sweep]\nmu = 0.3\nFn = 1e4\nA = 1.0\nB = 1.0\nxj = [1.0]\n",
     r"\[sweep\]: unknown key\(s\) 'xj'"),
    ("[sweep]\nmu = 0.3\nFn = 1e4\nA = 1.0\nB = 1.0\nmethod = 'nope'\n",
     r"unknown creep-force method 'nope'"),
    ("[sweep]\nmu = 0.3\nFn = 1e4\nA = 1.0\n", r"give both A, B"),
    ("[sweep]\nmu = 0.3\nFn = 1e4\nA = 1.0\nB = 1.0\nchunk = 0\n", r"chunk: must be an integer"),
    ("[sweep]\nmu = 0.3\nFn = 1e4\nA = 1.0\nB = 1.0\n[sweep.options]\nnx = 3\n"
     "[sweep.x]\n", r"unknown key\(s\) 'x'"),
    ("[sweep]\nmethod = 'fastsim'\nmu = 0.3\nFn = 1e4\nA = 1.0\nB = 1.0\n[sweep.options]\n"
     "elements = 3\n", r"does not accept option\(s\) elements"),
    ("[sweep]\nmu = 0.3\nFn = 1e4\nA = 1.0\nB = 1.0\n[sweep.points]\nxi = [1.0, 2.0]\n"
     "eta = [1.0]\n", r"columns must have one length"),
])
def test_toml_errors_name_file_table_key_and_value(text, match):
    with pytest.raises(CaseFileError, match=match):
        load_sweep(text)


def test_missing_file_is_named(tmp_path):
    with pytest.raises(CaseFileError, match="nope.toml: sweep file not found"):
        load_sweep(tmp_path / "nope.toml")
