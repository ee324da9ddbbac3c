"""Transient rolling: result containers, kernels and bad input (seed 001)."""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.halfspace.influence import influence_kernel
from wheelrail.halfspace.grid import Grid
from wheelrail.transient.rolling import shifted_influence_kernel


@pytest.fixture(scope="module")
def hc():
    return wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.STEEL)


def test_shifted_kernel_by_one_element_is_the_neighbour_offset():
    g = Grid(0.0, 0.0, 1e-3, 2e-3, 5, 4)
    ext = Grid(0.0, 0.0, 1e-3, 2e-3, 6, 4)
    C = influence_kernel(ext, wr.STEEL)
    Ch = shifted_influence_kernel(g, wr.STEEL, 1e-3)
    assert np.allclose(Ch, C[:, :, 2:11, :], rtol=1e-12, atol=1e-30)


def test_dataset_and_fields(hc):
    res = wr.transient_rolling(hc, travel=8e-4, step=2e-4, mu=0.4, Fn=10e3,
                               creepage=(lambda x: -1e-4 - 0.5 * x, 0.0, 0.0), elements=8)
    ds = res.dataset
    for name in ("xi", "eta", "phi", "Fn", "Fx", "Fy", "p_max", "penetration", "n_contact",
                 "n_adhesion", "n_slip"):
        assert ds[name].dims == ("x",)
    assert ds.x.values == pytest.approx([0, 2e-4, 4e-4, 6e-4, 8e-4])
    assert ds.xi.values[2] == pytest.approx(-1e-4 - 0.5 * 4e-4)
    assert np.all(ds.n_adhesion + ds.n_slip == ds.n_contact)
    assert ds.Fn.values == pytest.approx(10e3, rel=1e-6)
    f = res.fields_at(x=6.1e-4)
    assert float(f.x_frame) == pytest.approx(6e-4)
    assert f.px.shape == res.grid.shape
    assert float((f.px * res.grid.element_area).sum()) == pytest.approx(res.Fx[3])


def test_varying_normal_force_solves_every_step(hc):
    F3 = lambda x: 10e3 + 4.5e3 * np.sin(2 * np.pi * x / 2e-3)  # noqa: E731  seed eq. (3.2)
    res = wr.transient_rolling(hc, travel=1e-3, step=2.5e-4, mu=0.4, Fn=F3,
                               Fx=2000.0, elements=8)
    assert res.Fn == pytest.approx([F3(x) for x in res.x], rel=1e-6)
    assert res.Fx[1:] == pytest.approx(2000.0, rel=1e-6)
    # tractions vanish outside the contact and respect the Coulomb bound
    for k in range(len(res.frame_x)):
        out = res.pn[k] == 0
        assert np.all(res.px[k][out] == 0)
        assert np.all(np.hypot(res.px[k], res.py[k]) <= 0.4 * res.pn[k] * (1 + 1e-9) + 1e-9)


@pytest.mark.parametrize("kwargs, match", [
    (dict(step=1e-2), "step = 0.01"),
    (dict(Fn=lambda x: 5e3 - 1e7 * x), "Fn"),
    (dict(friction="regularised", epsilon=0.0), "epsilon must be > 0, got 0.0"),
    (dict(friction="regularised"), "needs epsilon"),
    (dict(friction="tresca"), "tresca"),
    (dict(Fx=5e3), "Fx"),
    (dict(Fx=lambda x: 1000 + 4e6 * x), r"Fx\(x = 0.00025 m\) = 2000.0 N"),
    (dict(Fn=lambda x: 5e3 - 1e7 * x), r"Fn\(x = 0.0005 m\) = 0.0 N"),
    (dict(penetration=lambda x: 1e-5 - 0.02 * x), r"penetration\(x = 0.0005 m\) = 0.0 m"),
    (dict(penetration=1e-5, Fn=1e4), "not both"),
    (dict(scheme="upwind"), "scheme must be"),
])
def test_bad_input_is_named(hc, kwargs, match):
    base = dict(travel=1e-3, step=2.5e-4, mu=0.4, creepage=(-1e-4, 0, 0), elements=6)
    if "Fx" in kwargs:
        base.pop("creepage")
    if callable(kwargs.get("Fx")):
        base["Fn"] = 5e3
    base.update(kwargs)
    with pytest.raises(wr.InputError, match=match):
        wr.transient_rolling(hc, **base)


def test_prescribed_approach_matches_force_control(hc):
    """Normal control by approach: a constant δ gives the load of the normal solver at that
    penetration, and the tangential history equals the force-controlled run at that load."""
    from wheelrail.normal.bem import hertz_grid, solve_normal

    grid, gap = hertz_grid(hc, elements=8)
    delta = 0.9 * float(solve_normal(grid, gap, wr.STEEL, Fn=10e3).penetration)
    Fn = float(solve_normal(grid, gap, wr.STEEL, penetration=delta).pressure.sum()
               * grid.element_area)
    kw = dict(travel=1e-3, step=2.5e-4, mu=0.4, Fx=1500.0, elements=8)
    by_delta = wr.transient_rolling(hc, penetration=delta, **kw)
    by_force = wr.transient_rolling(hc, Fn=Fn, **kw)
    assert by_delta.Fn == pytest.approx(Fn, rel=1e-9)
    assert by_delta.penetration == pytest.approx(delta, rel=1e-12)
    assert by_delta.xi == pytest.approx(by_force.xi, rel=1e-6)
    # a varying approach: the load follows (more approach, more load)
    wavy = wr.transient_rolling(hc, penetration=lambda x: delta * (1 + 0.2 * np.sin(2e3 * np.pi * x)),
                                **kw)
    assert wavy.Fn[1] > Fn > wavy.Fn[3]
