"""A sweep interrupted while it writes a chunk resumes to the complete, correct result.

The store's contract (:mod:`wheelrail.sweeps.store`): a chunk is recorded as done only after
its data are written. Here the real write is interrupted inside the Zarr layer (an exception
from ``zarr.Array.__setitem__`` while one output of the second chunk is stored, as a full disk
or a kill would); the resumed sweep must compute that chunk again, and every point must equal
Hertz's closed form, computed independently of the package (``tests/_closed_form.py``:
Johnson 1985, *Contact Mechanics*, §3.7 eqs. (3.64)-(3.66) and §4.2, complete elliptic
integrals).
"""

import numpy as np
import pytest
import zarr
from _closed_form import contact_modulus, hertz_load

import wheelrail as wr
from wheelrail.sweeps import SweepSpec

ES = contact_modulus(2.1e11, 0.28)             # the sweep's default material (steel)


class _Interrupted(Exception):
    """Stands for a crash while the store writes a chunk."""


def test_interrupted_chunk_write_is_not_marked_done_and_resume_computes_it(tmp_path,
                                                                          monkeypatch):
    loads, Bs = [1e4, 2e4, 3e4], [1.5, 4.0]
    spec = SweepSpec.grid(method="linear", mu=0.3, Fn=loads, A=1.0, B=Bs, xi=[0.0], chunk=2)
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
            ref = hertz_load(P, 1.0, B, ES)
            assert ds.a.values[i, j, 0] == pytest.approx(ref["a"], rel=1e-9)
            assert ds.b.values[i, j, 0] == pytest.approx(ref["b"], rel=1e-9)
            assert ds.p0.values[i, j, 0] == pytest.approx(ref["p0"], rel=1e-9)
