"""wheelrail.prescribed.solve_creepages: creepages for prescribed forces."""

import pytest

import wheelrail as wr
from wheelrail.errors import InputError

HC = wr.hertz(1e4, A=1.0, B=2.0, material=wr.STEEL)


@pytest.mark.parametrize("method", ["linear", "fastsim", "exact"])
def test_prescribed_fx(method):
    opts = {"elements": 16} if method == "exact" else {}
    r = wr.solve_creepages(HC, 0.3, Fx=1200.0, method=method, **opts)
    assert r.Fx == pytest.approx(1200.0, abs=1e-5 * 0.3 * 1e4)
    assert r.info["xi"] < 0          # braking-type force on the wheel needs ξ < 0
    again = wr.creep_forces(HC, (r.info["xi"], 0.0, 0.0), 0.3, method=method, **opts)
    assert again.Fx == pytest.approx(r.Fx, rel=1e-9)


def test_prescribed_fx_fy_with_spin():
    r = wr.solve_creepages(HC, 0.3, Fx=-1500.0, Fy=800.0, creepage=(0.0, 0.0, 0.5),
                           method="exact", elements=16)
    assert (r.Fx, r.Fy) == pytest.approx((-1500.0, 800.0), abs=1e-5 * 3e3)
    assert r.info["phi"] == 0.5


def test_prescribed_fy_keeps_xi():
    r = wr.solve_creepages(HC, 0.3, Fy=-500.0, creepage=(2e-4, 0.0, 0.0), method="fastsim")
    assert r.info["xi"] == 2e-4
    assert r.Fy == pytest.approx(-500.0, abs=1e-2)


def test_saturated_force_rejected():
    with pytest.raises(InputError, match="μ·Fn"):
        wr.solve_creepages(HC, 0.3, Fx=3000.0, method="fastsim")
    with pytest.raises(InputError, match="μ·Fn"):
        wr.solve_creepages(HC, 0.3, Fx=2500.0, Fy=2000.0, method="fastsim")
    with pytest.raises(InputError, match="at least one"):
        wr.solve_creepages(HC, 0.3, method="fastsim")
