"""Multi-Hertz, Linder and Kik–Piotrowski on quadratic gaps, against closed forms.

The closed forms (``tests/_closed_form.py``: Hertz's ellipse from Johnson 1985, §3.7 and
§4.2, with SciPy's elliptic integrals) are written independently of wheelrail; each test
states the published relation it evaluates.
"""

import math

import numpy as np
import pytest
from _closed_form import contact_modulus, hertz_approach, hertz_ellipse_load

import wheelrail as wr
from wheelrail.normal._strips import _LN_MAX   # the Hertz table's range (Kik–Piotrowski)

ES = contact_modulus(2.1e11, 0.28)             # wr.STEEL on wr.STEEL


def _solve(gap, normal, search, **kw):
    with wr.plausibility.disabled():           # some gaps below are deliberately extreme
        return wr.solve(wr.GapProblem(gap, wr.STEEL, search=search, **kw), creepage=(0, 0, 0),
                        mu=0.3, normal=normal)


# ---------------------------------------------------------------- multi-Hertz (Sauvage)
@pytest.mark.parametrize("zones", [7, 3])
def test_sauvage_gives_one_hertz_ellipse_per_separate_zone_up_to_max_ellipses(zones):
    """A gap of ``zones`` separate, equal paraboloids h = A x² + B (y − y_k)² pressed by δ:
    Sauvage's successive ellipses (Piotrowski & Chollet 2005, §2.1) find one ellipse per zone,
    each Hertz's contact at the approach δ (Johnson 1985, §4.2), with ``max_ellipses`` equal
    to the number of zones (7 is the default, Sauvage's code)."""
    A, B, spacing, delta = 2.0, 50.0, 8e-3, 2e-5
    centres = (np.arange(zones) - (zones - 1) / 2) * spacing

    def gap(x, y):
        y = np.asarray(y, dtype=float)
        return A * np.asarray(x) ** 2 + B * np.min((y[..., None] - centres) ** 2, axis=-1)

    half = centres[-1] + spacing / 2
    opts = {} if zones == 7 else {"max_ellipses": zones}
    with wr.plausibility.disabled():
        r = wr.solve(wr.GapProblem(gap, wr.STEEL, penetration=delta,
                                   search=(-0.01, 0.01, -half, half)),
                     creepage=(0, 0, 0), mu=0.3, normal="multi-hertz", variant="sauvage",
                     **opts)
    ref = hertz_approach(delta, A, B, ES)
    assert len(r.patches) == zones
    # each zone's centre lies within half a node of the line (0.04 mm nodes): the depth is
    # δ to 4e-4 relative, the load (∝ δ^1.5) to 1e-3
    for p in r.patches:
        assert p.Fn == pytest.approx(ref["load"], rel=2e-3)
        assert p.area == pytest.approx(ref["area"], rel=2e-3)
        assert p.p_max == pytest.approx(ref["p0"], rel=2e-3)


# ---------------------------------------------------------------- Linder
@pytest.mark.parametrize("A, B", [(1.0, 1.0), (0.5, 2.0), (5.0, 0.2)])
def test_linder_on_a_quadratic_gap_is_its_closed_form_ellipse(A, B):
    """Linder's method (Piotrowski & Chollet 2005, §3.1, eqs. 5–10) on h = A x² + B y² at
    approach δ, in closed form: the region of δ0 = 0.55 δ has half-width b_e = √(δ0/B)
    (eq. 6, half the region's width) and x_l = √(δ0/A) √(1 − y²/b_e²), so every strip's
    virtual ellipse (eq. 7) is the same, a_e = √(δ0/A); its penetration (eq. 8, the circle
    through (±b_e, 0) and (y, g(y)), whose centre lies 1/(2B) − g/2 below the chord) is
    δ_e = B b_e² + 0.45 δ = δ to O(δ0 B) = 1e-5; its Hertz load N = 2π a_e b_e E* δ/(3 s K)
    (Johnson 1985, §4.2) and eqs. (9)–(10), N = ½ π Σ x_l p0i Δy, give the patch load N,
    area π a_e b_e and peak 3N/(2π a_e b_e).
    """
    delta = 5e-5
    d0 = 0.55 * delta
    ae, be = math.sqrt(d0 / A), math.sqrt(d0 / B)
    N = hertz_ellipse_load(ae, be, delta, ES)
    L = 3 * max(ae, be)
    (p,) = _solve(lambda x, y: A * x**2 + B * y**2, "linder", (-L, L, -L, L),
                  penetration=delta).patches
    # discretisation of the line (801 nodes): measured 3e-4 (load), 1.3e-3 (area, p_max)
    assert p.Fn == pytest.approx(N, rel=2e-3)
    assert p.area == pytest.approx(math.pi * ae * be, rel=5e-3)
    assert p.p_max == pytest.approx(1.5 * N / (math.pi * ae * be), rel=5e-3)
    if A == B:   # circle: π 0.55 δ/A against Hertz's π R δ = π δ/(2A), a ratio of 1.1
        assert p.area / hertz_approach(delta, A, B, ES)["area"] == pytest.approx(1.1, rel=5e-3)


# ---------------------------------------------------------------- Kik–Piotrowski
def test_kik_piotrowski_beyond_the_hertz_table_reproduces_hertz():
    """Kik–Piotrowski with the Hertz penetration factor and the shape correction reproduces
    Hertz's contact on a quadratic gap (Piotrowski & Kik 2008; Piotrowski & Chollet 2005,
    §3.2, eqs. 12–22): load at the approach δ, area and peak pressure. Here the region is
    4000 times longer than wide (B/A = 5e6), beyond the tabulated Hertz shapes of the
    compiled kernel, so the Python path computes it (the original method's path: the
    ellipticity correction clips ln(A/B) to the table)."""
    A, B = 0.02, 1e5
    assert math.log(B / A) > _LN_MAX            # the region's (W/L)² is off the table
    delta = 3.4e-6
    ref = hertz_approach(delta, A, B, ES)
    Lx, Ly = 4 * ref["a"], 4 * ref["b"]
    (p,) = _solve(lambda x, y: A * x**2 + B * y**2,
                  wr.normal.KikPiotrowski(ellipticity_correction=False), (-Lx, Lx, -Ly, Ly),
                  penetration=delta).patches
    # measured: load 1e-5, area 1.4e-3, peak 2.1e-3
    assert p.Fn == pytest.approx(ref["load"], rel=1e-3)
    assert p.area == pytest.approx(ref["area"], rel=5e-3)
    assert p.p_max == pytest.approx(ref["p0"], rel=5e-3)
