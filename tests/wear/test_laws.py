"""Closed values of the wear laws and the RCF functions.

References: the USFD law K = 5.3 x, 55.0, 61.9 x − 4778.7 µg/(m·mm²) (x = Tγ/A
in N/mm²; Braghin, Lewis, Dwyer-Joyce & Bruni, Wear 261 (2006) 1253–1264);
Archard's law Δz = k p s / H (Archard 1953; Jendel, Wear 253 (2002) 89–99);
Ekberg, Kabo & Andersson, FFEMS 25 (2002) 899–909 (FI_surf); Burstow (RSSB 2004).
"""

import math

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError, OptionError
from wheelrail.wear import usfd_rate


@pytest.mark.parametrize("x, k", [(5.0, 26.5), (50.0, 55.0), (100.0, 6190.0 - 4778.7)])
def test_usfd_closed_values(x, k):
    # 5.3·5 = 26.5; plateau 55; 61.9·100 − 4778.7 = 1411.3 (the issue quotes 1411)
    assert usfd_rate(x) == pytest.approx(k, abs=1e-9)
    assert usfd_rate(x, "as_quoted") == pytest.approx(k, abs=1e-9)
    assert round(usfd_rate(100.0)) == 1411


def test_usfd_transition_rules():
    x = np.linspace(0.0, 120.0, 12001)
    k = usfd_rate(x)
    assert np.all(np.diff(k) >= -1e-12)                       # continuous rule: monotone
    # between 77.2 and the crossing 5833.7/61.9 = 78.09 the plateau continues
    assert usfd_rate(77.5) == 55.0
    assert usfd_rate(78.5) == pytest.approx(61.9 * 78.5 - 4778.7)
    # the printed piecewise form drops to ~0 just above 77.2 (clipped at zero)
    assert usfd_rate(77.21, "as_quoted") == pytest.approx(max(61.9 * 77.21 - 4778.7, 0.0))
    assert usfd_rate(10.39, "as_quoted") == pytest.approx(5.3 * 10.39)
    assert usfd_rate(10.39) == 55.0


def test_usfd_depth_rate_units():
    # 1 µg/(m·mm²) = 1e-9 kg / (1 m · 1e-6 m²) = 1e-3 kg/m³; depth rate = K/ρ
    law = wr.wear.USFD(density=8000.0)
    tau, s = 500e6, 0.02                                        # τ s = 10 N/mm² (mild)
    assert law.depth_rate(0.0, tau, s) == pytest.approx(5.3 * 10.0 * 1e-3 / 8000.0, rel=1e-12)


def test_archard_and_energy_closed_values():
    a = wr.wear.Archard(k=2e-4, hardness=3e9)
    assert a.depth_rate(1.2e9, 0.0, 0.01) == pytest.approx(2e-4 * 1.2e9 * 0.01 / 3e9)
    e = wr.wear.Energy(coefficient=1e-12)
    assert e.depth_rate(0.0, 3e8, 0.01) == pytest.approx(1e-12 * 3e8 * 0.01)
    # the default energy coefficient is the USFD mild slope for steel
    u = wr.wear.USFD()
    assert wr.wear.Energy().depth_rate(0, 2e8, 0.03) == pytest.approx(u.depth_rate(0, 2e8, 0.03))


def test_kth_map_regions():
    m = wr.wear.KTHMap()
    H = m.hardness
    v = np.array([0.1, 0.5, 1.0])
    assert np.allclose(m.coefficient(1e9, v), [5e-4, 35e-4, 5e-4])
    assert np.allclose(m.coefficient(0.81 * H, v), 300e-4)
    # depth rate = k p s / H with the sliding velocity |s| V
    assert m.depth_rate(1e9, 0.0, 0.01, speed=50.0) == pytest.approx(35e-4 * 1e9 * 0.01 / H)
    with pytest.raises(InputError, match="speed"):
        m.depth_rate(1e9, 0.0, 0.01)
    with pytest.raises(OptionError):
        wr.wear.KTHMap(v_low=1.0, v_high=0.5)


def test_options_and_registry():
    assert set(wr.wear.wear_laws()) == {"archard", "kth", "usfd", "energy"}
    with pytest.raises(OptionError, match="k must be"):
        wr.wear.Archard(k=-1.0)
    with pytest.raises(OptionError):
        wr.wear.USFD(application="global")
    assert wr.wear.get("usfd", application="patch").is_per_patch


def test_burstow_damage_function():
    d = wr.wear.Burstow()
    assert d(10.0) == 0.0
    assert d(65.0) == pytest.approx(50e-6)
    assert d(40.0) == pytest.approx(25e-6)
    assert d(120.0) == pytest.approx(25e-6)
    assert d(175.0) == pytest.approx(0.0, abs=1e-15)
    assert d(300.0) == 0.0
    assert wr.wear.Burstow(negative=True)(285.0) == pytest.approx(-50e-6)


def test_surface_fatigue_index_closed_form():
    # FI = μ_t − k/p0 with p0 = 3 Fn/(2π a b)
    Fn, Ft, a, b, k = 1e5, 3e4, 6e-3, 5e-3, 300e6
    p0 = 3 * Fn / (2 * math.pi * a * b)
    r = wr.wear.rcf(Fn=Fn, Ft=Ft, a=a, b=b, Tgamma=65.0, yield_shear=k)
    assert r.FI_surf == pytest.approx(0.3 - k / p0)
    assert r.p0_over_k == pytest.approx(p0 / k)
    assert r.mu_t == pytest.approx(0.3)
    assert r.damage == pytest.approx(50e-6)
    assert bool(r.beyond_shakedown) == (0.3 * p0 / k > 1.0)
