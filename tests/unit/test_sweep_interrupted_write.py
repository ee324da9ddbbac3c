"""A sweep interrupted while it writes a chunk resumes to the complete, correct result.

The store's contract (:mod:`wheelrail.sweeps.store`): a chunk is recorded as done only after
its data are written. Here the real write is interrupted inside the Zarr layer (an exception
from ``zarr.Array.__setitem__`` while one output of the second chunk is stored, as a full disk
or a kill would); the resumed sweep must compute that chunk again, and every point must equal
Hertz's closed form, computed here independently of the package (Johnson 1985, *Contact
Mechanics*, §3.7 eqs. (3.64)-(3.66) and §4.2, via complete elliptic integrals):

    A = p0 b (K(e) − E(e)) / (E* a² e²),   B = p0 b ((a/b)² E(e) − K(e)) / (E* a² e²),
    P = 2/3 π a b p0,   e² = 1 − b²/a²   (a > b along x when A < B).
"""

import numpy as np
import pytest
import zarr
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

import wheelrail as wr
from wheelrail.sweeps import SweepSpec

E_MOD, NU = 2.1e11, 0.28                       # the sweep's default material (steel)


def hertz_closed_form(P, A, B, E=E_MOD, nu=NU):
    """Semi-axes a (along x), b [m] and peak pressure p0 [Pa]; A < B [1/m], identical bodies."""
    assert A < B
    Es = E / (2.0 * (1.0 - nu**2))                # 1/E* = 2 (1 − ν²)/E

    def ratio(m):                                 # B/A as a function of m = e²
        K, Ee = ellipk(m), ellipe(m)
        return (Ee / (1.0 - m) - K) / (K - Ee)

    m = brentq(lambda m: ratio(m) - B / A, 1e-12, 1.0 - 1e-15, xtol=1e-15, rtol=1e-15)
    K, Ee = ellipk(m), ellipe(m)
    a = (3.0 * P * (K - Ee) / (2.0 * np.pi * A * Es * m)) ** (1.0 / 3.0)
    b = a * np.sqrt(1.0 - m)
    return a, b, 3.0 * P / (2.0 * np.pi * a * b)


def test_closed_form_sanity():
    """Circle limit (Johnson 1985, eq. 4.22): a = (3 P R/(4 E*))^(1/3) with R = 1/(2A)."""
    a, b, p0 = hertz_closed_form(1e4, 1.0, 1.0 + 1e-9)
    Es = E_MOD / (2 * (1 - NU**2))
    assert a == pytest.approx((3 * 1e4 * 0.5 / (4 * Es)) ** (1 / 3), rel=1e-6)
    assert b == pytest.approx(a, rel=1e-6)


class _Interrupted(Exception):
    """Stands for a crash while the store writes a chunk."""


def test_interrupted_chunk_write_is_not_marked_done_and_resume_computes_it(tmp_path,
                                                                          monkeypatch):
    loads, Bs = [1e4, 2e4, 3e4], [1.5, 4.0]
    spec = SweepSpec.grid(method="linear", mu=0.3, load=loads, A=1.0, B=Bs, xi=[0.0], chunk=2)
    blocks = spec.chunks()                       # 3 chunks of 2 points (one load each)
    assert len(blocks) == 3
    target = blocks[1]
    real_setitem = zarr.Array.__setitem__
    fired = []

    def setitem(self, selection, value):
        name = str(getattr(self, "basename", None) or self.path).rsplit("/", 1)[-1]
        if name == "b" and tuple(selection) == tuple(target) and not fired:
            fired.append(name)
            raise _Interrupted(f"crash while writing {name!r} of chunk 1")
        return real_setitem(self, selection, value)

    out = tmp_path / "s.zarr"
    monkeypatch.setattr(zarr.Array, "__setitem__", setitem)
    with pytest.raises(_Interrupted):
        wr.sweep(spec, out, progress=False)
    monkeypatch.undo()
    assert fired == ["b"]                        # the crash happened inside the real write
    ds, info = wr.sweep(spec, out, resume=True, progress=False, summary=True)
    # chunk 0 was complete; chunk 1 (interrupted) and chunk 2 (never started) are computed
    assert info.computed == 4
    assert np.all(ds.status.values == 1)
    for i, P in enumerate(loads):
        for j, B in enumerate(Bs):
            a, b, p0 = hertz_closed_form(P, 1.0, B)
            assert ds.a.values[i, j, 0] == pytest.approx(a, rel=1e-9)
            assert ds.b.values[i, j, 0] == pytest.approx(b, rel=1e-9)
            assert ds.p0.values[i, j, 0] == pytest.approx(p0, rel=1e-9)
