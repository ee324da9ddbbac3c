"""Virtual-penetration and multi-Hertzian methods on a Hertzian (quadratic) gap.

Reference: Hertz's closed form (Johnson 1985, §4.2; ``wr.hertz``). Seed 003
(Piotrowski & Chollet 2005) §3: the Hertz-consistent methods (Kik–Piotrowski
with its Hertz penetration factor and shape correction, STRIPES) must give
Hertz's area, maximum pressure and load; the constant-factor methods
(δ0 = 0.55 δ: Linder, original Kik–Piotrowski) have a bias that depends on
a/b, which is tabulated in docs/nonhertzian.md (`benchmarks/bench_nonhertz.py`).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import InputError
from wheelrail.normal._base import GapProblem
from wheelrail.normal._strips import hertz_penetration_factor

RATIOS = [0.2, 0.5, 1.0, 2.0, 5.0]


def _contact(ab, load=1e5):
    b = 5e-3 / np.sqrt(ab)
    c = wr.hertz_from_semiaxes(ab * b, b, load, wr.STEEL)
    return wr.hertz(load, float(c.A), float(c.B), wr.STEEL)


def _gap(c, **kw):
    A, B = float(c.A), float(c.B)
    L = 4 * max(float(c.a), float(c.b))
    return GapProblem(lambda x, y: 1e-5 + A * (x - 1e-3) ** 2 + B * (y + 2e-3) ** 2,
                      wr.STEEL, search=(-L, L, -L, L), **kw)


@pytest.mark.parametrize("ab", RATIOS)
def test_kik_piotrowski_default_reproduces_hertz(ab):
    c = _contact(ab)
    m = wr.normal.get("kik-piotrowski")
    (p,) = m.from_gap(_gap(c, Fn=float(c.Fn)))
    assert p.Fn == pytest.approx(float(c.Fn), rel=1e-6)
    # 40 strips: the strip discretisation leaves at most 0.13 % (area), 0.21 % (p_max)
    assert p.area == pytest.approx(float(c.area), rel=0.005)
    assert p.p_max == pytest.approx(float(c.p0), rel=0.005)
    # prescribed penetration: the load of Hertz's approach
    (q,) = m.from_gap(_gap(c, penetration=1e-5 + float(c.penetration)))
    assert q.Fn == pytest.approx(float(c.Fn), rel=0.02)
    L, W = p.info["L_W"]
    assert L / W == pytest.approx(ab, rel=0.02)


@pytest.mark.parametrize("ab", [0.2, 5.0])
def test_kik_piotrowski_shape_correction_keeps_area_moves_ratio(ab):
    """Seed 003 §3.2.1: the correction keeps L·W and moves L/W to the Hertz ratio."""
    c = _contact(ab)
    m = wr.normal.get("kik-piotrowski").replace(ellipticity_correction=False)
    raw, = m.replace(shape_correction=False).from_gap(_gap(c, Fn=float(c.Fn)))
    cor, = m.from_gap(_gap(c, Fn=float(c.Fn)))
    assert cor.area == pytest.approx(raw.area, rel=0.05)
    r_raw = raw.info["L_W"][0] / raw.info["L_W"][1]
    r_cor = cor.info["L_W"][0] / cor.info["L_W"][1]
    assert abs(np.log(r_cor / ab)) < 0.3 * abs(np.log(r_raw / ab))
    # uncorrected: the interpenetration ellipse has L/W = sqrt(B/A), not Hertz's a/b
    assert r_raw == pytest.approx(np.sqrt(float(c.B) / float(c.A)), rel=0.03)


def test_original_factor_is_biased():
    """δ0 = 0.55 δ enlarges the area (0.55 > ε_Hertz ≈ 0.5) and lowers p_max, at every a/b."""
    m = wr.normal.get("kik-piotrowski")
    for ab in RATIOS:
        c = _contact(ab)
        (p,) = m.replace(penetration_factor=0.55,
                         ellipticity_correction=False).from_gap(_gap(c, Fn=float(c.Fn)))
        assert 1.05 < p.area / float(c.area) < 1.2
        assert 0.85 < p.p_max / float(c.p0) < 0.95


def test_strip_refinement_converges_to_hertz():
    """The remaining difference from Hertz is the strip discretisation: it falls with
    the strip count at an order above 1 (measured about 1.5)."""
    c = _contact(2.0)
    errs = []
    for n in (20, 40, 80):
        m = wr.normal.get("kik-piotrowski").replace(strips=n, cells=n)
        (p,) = m.from_gap(_gap(c, Fn=float(c.Fn)))
        errs.append(abs(p.p_max / float(c.p0) - 1))
    order = np.polyfit(np.log([20, 40, 80]), np.log(errs), 1)[0]
    assert order < -1.0, (errs, order)


def test_hertz_factor_is_half_for_circle():
    """A = B: a² = R δ (Johnson eq. 3.7), δ0 = a²/(2R) = δ/2."""
    assert hertz_penetration_factor(2.0, 2.0) == pytest.approx(0.5, rel=1e-9)
    assert hertz_penetration_factor(1.0, 10.0) == pytest.approx(
        hertz_penetration_factor(10.0, 1.0), rel=1e-9)


@pytest.mark.parametrize("bad", [0.0, -0.5, 1.5, "half"])
def test_bad_penetration_factor_named(bad):
    c = _contact(1.0)
    with pytest.raises(InputError, match="penetration_factor"):
        wr.solve(c, creepage=(0, 0, 0), mu=0.3, normal="kik-piotrowski", penetration_factor=bad)


def test_unrepresentable_gaps_rejected():
    """A gap without curvature along x (a line contact) or a saddle: clear InputError."""
    line = GapProblem(lambda x, y: 0.0 * x + y**2, wr.STEEL, Fn=1e4,
                      search=(-0.01, 0.01, -0.01, 0.01))
    saddle = GapProblem(lambda x, y: x**2 - 0.5 * y**2, wr.STEEL, Fn=1e4,
                        search=(-0.01, 0.01, -0.01, 0.01))
    for name in ("kik-piotrowski", "linder", "stripes", "multi-hertz"):
        m = wr.normal.get(name)
        for g in (line, saddle):
            with pytest.raises(InputError, match="search|convex|represent"):
                m.from_gap(g)
