"""Results print as one short line (their forces and status), never their arrays: a
``print(result)`` of a contact solve used to dump the patch grids (1 600 lines)."""

from __future__ import annotations

import numpy as np

import wheelrail as wr


def _one_line(obj, limit=300):
    text = repr(obj)
    assert "\n" not in text and len(text) <= limit, text
    return text


def test_contact_and_creep_results_print_one_short_line():
    c = wr.hertz(Fn=1e4, A=1.0, B=2.0, material=wr.STEEL)
    r = wr.creep_forces(c, (1e-4, 0.0, 0.0), 0.3, method="fastsim")
    text = _one_line(r)
    assert text.startswith("CreepForcesResult(") and "Fx=" in text and "fastsim" in text
    res = wr.solve(c, creepage=(1e-3, 0.0, 0.0), mu=0.3, tangential="exact")
    text = _one_line(res)
    assert text.startswith("ContactResult(") and f"Fx={res.Fx:.4g} N" in text
    assert "patches=1" in text
    _one_line(res.patches[0])


def test_grid_results_print_one_short_line():
    c = wr.hertz(Fn=1e4, A=1.0, B=2.0, material=wr.STEEL)
    r = wr.solve(c, creepage=(1e-3, 0.0, 0.0), mu=0.3, normal="bem", tangential="exact")
    for obj in (r, r.patches[0]):
        _one_line(obj)
    from wheelrail.results import _short

    assert _short(np.arange(10000.0), "Pa") == "array(10000,) 0..9999 Pa"


def test_gap_results_print_one_short_line():
    gap = lambda x, y: x ** 2 / (2 * 0.5) + y ** 2 / (2 * 0.3)  # noqa: E731
    r = wr.solve_gap_auto(gap, wr.STEEL, Fn=1e4, creepage=(1e-3, 0.0, 0.0), mu=0.3,
                          elements=20)
    for obj, name in ((r, "GapResult("), (r.normal, "NormalResult("),
                      (r.tangential, "TangentialResult(")):
        assert _one_line(obj).startswith(name)
