"""Strip-wise FASTSIM on virtual-penetration patches (seed 003 §3.1.1, §3.2, §3.3).

References: on a Hertzian gap the Hertz-consistent patches (Kik–Piotrowski,
STRIPES) must give the creep forces of FASTSIM on the Hertz ellipse with the
same (semi-elliptic) traction bound (Kalker 1982); pure spin on a patch that
is asymmetric across the rail gives a longitudinal force, and Kik &
Piotrowski's shape correction keeps the area and raises L/W and |Fy|
(seed 003 §3.2.2, Table 1: L/W 1.36 → 1.51, area 153.7 → 153.7 mm², Fy
−18.58 → −20.5 kN).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.normal._base import GapProblem


def _contact(ab, load=1e5):
    b = 5e-3 / np.sqrt(ab)
    c = wr.hertz_from_semiaxes(ab * b, b, load, wr.STEEL)
    return wr.hertz(load, float(c.A), float(c.B), wr.STEEL)


@pytest.mark.parametrize("ab", [0.2, 1.0, 5.0])
@pytest.mark.parametrize("normal", ["kik-piotrowski", "stripes"])
def test_hertz_consistent_patches_give_hertz_fastsim(ab, normal):
    c = _contact(ab)
    for cr in [(1e-3, 0, 0), (0, 1e-3, 0), (0, 0, 0.5)]:
        ref = wr.solve(c, creepage=cr, mu=0.3, normal="hertz", bound="elliptic")
        r = wr.solve(c, creepage=cr, mu=0.3, normal=normal)
        # pure spin: the Hertzian FASTSIM's three flexibilities oppose the true slip in
        # slip elements, the patch's single weighted flexibility scales nothing:
        # 4.7 % apart at a/b = 0.2 (measured), within 2.5 % otherwise
        rel = 0.05 if cr[2] else 0.025
        assert r.Fx == pytest.approx(ref.Fx, rel=rel, abs=1e-3 * abs(ref.Fy))
        assert r.Fy == pytest.approx(ref.Fy, rel=rel, abs=1e-3 * abs(ref.Fx))


def test_linder_uses_per_strip_ellipses_and_parabolic_bound():
    c = _contact(1.0)
    r = wr.solve(c, creepage=(0, 0, 0.5), mu=0.3, normal="linder")
    p = r.patches[0].patch
    assert p.info["traction_bound"] == "parabolic"
    a_e, b_e = p.info["strip_semiaxes"]
    assert np.all(b_e == b_e[0]) and a_e.shape == p.y.shape
    # Hertzian gap: every strip's virtual ellipse has the region's length (eq. 7)
    assert np.allclose(a_e, np.median(a_e), rtol=0.05)


R = 1.4                   # Hertzian radius along the rail, seed 003 §3.2.2
A = 1.0 / (2.0 * R)


def _asym(y):
    return np.where(y > 0, 2.0 * y**2 + 30.0 * np.abs(y) ** 3, 0.4 * y**2)


def _spin(shape_correction, sep):
    gp = GapProblem(lambda x, y: A * np.asarray(x) ** 2 + sep(np.asarray(y)), wr.STEEL,
                    penetration=0.074e-3, search=(-0.02, 0.02, -0.03, 0.03))
    return wr.solve(gp, creepage=(0, 0, 0.3), mu=0.4, normal="kik-piotrowski",
                    penetration_factor=0.55, shape_correction=shape_correction,
                    ellipticity_correction=False)


def test_spin_on_asymmetric_patch_gives_longitudinal_force():
    sym = _spin(True, lambda y: 1.2 * y**2).patches[0]
    asym = _spin(True, _asym).patches[0]
    assert abs(sym.Fx) < 1e-3 * abs(sym.Fy)
    assert abs(asym.Fx) > 0.2 * abs(asym.Fy)


def test_shape_correction_moves_as_table_1():
    raw = _spin(False, _asym).patches[0]
    cor = _spin(True, _asym).patches[0]
    lw = [p.patch.info["L_W"][0] / p.patch.info["L_W"][1] for p in (raw, cor)]
    assert lw[1] > lw[0] * 1.05
    assert cor.area == pytest.approx(raw.area, rel=1e-3)
    assert cor.Fn == pytest.approx(raw.Fn, rel=0.02)
    assert abs(cor.Fy) > abs(raw.Fy)
