"""Kik–Piotrowski + FASTSIM on Manchester A-2.2 against CONTACT's full solution.

Reference: CONTACT's full (half-space) solution of the benchmark (eve70a/CONTACT
``examples/mbench_a22_right.ref_out`` and ``_left``, tests/reference/data/contact_mbench_a22.csv;
forces converted to Kalker's convention), 21 cases × 2 wheels, errors in % of μFn.
CONTACT's own approximation (KPEC + FASTSIM with the flexibilities of the equivalent ellipse,
``examples/mbench_a22_kpec.ref_out``) stays within 11.4 % of μFn; the goal here is 11.5 %.

Measured with ``ellipticity_correction=True, fastsim_flexibility="combined"`` (Vollebregt's
KPEC and the combined flexibility of Vollebregt & Voltr 2023): max 4.2 % in Fx (case 2 left)
and 11.05 % in Fs (case 2 right). The defaults (Kik & Piotrowski's constant-factor patch with
the shape correction and Kalker's weighted flexibility): 11.5 % and 24.7 %. KPEC is not the
default: see the option's docstring (flange-climb contact angle).
"""

import numpy as np
import pytest
from test_wheelrail_contact import _contact_reference

import wheelrail as wr


@pytest.fixture(scope="module")
def cases():
    from conftest import SHARED_DATA, require_shared

    from wheelrail.contact.manchester import manchester_a22

    shared_data = require_shared(SHARED_DATA)
    return manchester_a22(shared_data / "benchmarks" / "manchester_a22_inputs.csv",
                          shared_data / "profiles" / "MBench_S1002_v3.prw",
                          shared_data / "profiles" / "MBench_UIC60_v3.prr")


def _errors(c, side, res):
    r = _contact_reference()[(c.case, side)]
    ps = res.side(side)
    s = 0.3 * float(r["Fn_N"])
    return (abs(sum(p.Fx for p in ps) + float(r["Fx_N"])) / s,
            abs(sum(p.Fs for p in ps) + float(r["Fs_N"])) / s)


KPEC = {"ellipticity_correction": True, "fastsim_flexibility": "combined"}


def test_kpec_combined_within_contact_kpec_error_on_all_42_wheels(cases):
    ex, es = [], []
    for c in cases:
        res = wr.solve(c.position, motion=c.motion, mu=c.mu, normal="kik-piotrowski",
                       tangential="fastsim", **KPEC)
        for side in ("left", "right"):
            e = _errors(c, side, res)
            ex.append(e[0])
            es.append(e[1])
    ex, es = 100 * np.array(ex), 100 * np.array(es)
    assert ex.size == es.size == 42
    # measured 4.23 % (case 2 left) and 11.05 % (case 2 right); goal 11.5 %
    assert ex.max() == pytest.approx(4.23, abs=0.3)
    assert es.max() == pytest.approx(11.05, abs=0.3)
    assert max(ex.max(), es.max()) <= 11.5
    assert int(np.argmax(es)) == 3                      # case 2, right wheel


@pytest.mark.parametrize("opts, lo, hi", [
    (KPEC, 0.105, 0.115),                                                   # measured 11.05 %
    ({"ellipticity_correction": True}, 0.20, 0.24),                         # 22.2 %
    ({"ellipticity_correction": True, "fastsim_flexibility": "three"}, 0.115, 0.125),  # 12.0 %
    ({}, 0.23, 0.27),                                                       # default: 24.7 %
])
def test_case2_right_lateral_force_by_method(cases, opts, lo, hi):
    """The worst wheel: the patch (the ellipticity correction's area is 81 % of CONTACT's,
    Kik & Piotrowski's 67 %) and the flexibility both matter."""
    c = cases[1]
    res = wr.solve(c.position, motion=c.motion, mu=c.mu, normal="kik-piotrowski",
                   tangential="fastsim", **opts)
    err = _errors(c, "right", res)[1]
    assert lo < err < hi, err
    (p,) = res.side("right")
    area = float(_contact_reference()[(2, "right")]["area_mm2"]) * 1e-6
    kpec = opts.get("ellipticity_correction", False)
    assert p.area / area == pytest.approx(0.81 if kpec else 0.67, abs=0.02)
