"""Force sweeps flag the rows the contact table flags.

The campaign: force sweeps reported "ok" on rows that ``wr.contact_table`` flags as
flange climb. Reference: the contact table's own status at the same rigid poses
(S1002 on 60E1, the right wheel climbs its 70° flange beyond about y = 7 mm).
"""

from __future__ import annotations

import numpy as np
import pytest

import wheelrail as wr


@pytest.mark.parametrize("batch", [True, False])
def test_force_sweep_status_follows_the_contact_table(batch):
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    y = np.array([0.0, 0.004, 0.0085, 0.0095])
    table = wr.contact_table(ws, tr, y)
    names = table.status.attrs["flag_meanings"].split()
    expected = [names[c] for c in table.status.values]
    assert expected[-1] == "flange_climb" and expected[0] == "ok"       # the table flags it
    ds = wr.wheelset_sweep(ws, tr, y, motion=wr.Motion(speed=20.0), mu=0.3,
                           vertical_load=50e3, batch=batch)
    assert list(ds.status.values) == expected
    flagged = ds.status.values == "flange_climb"
    assert all("climbs its flange" in m for m in ds.message.values[flagged])
    assert np.isfinite(ds.Fy_track.values[flagged]).all()              # forces still computed
