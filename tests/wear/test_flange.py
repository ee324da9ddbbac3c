"""Flange dimensions of the new S1002 against its nominal values.

Nominal S1002 (EN 13715; EN 15313 definitions Sh, Sd at 10 mm above the tread
datum, qR between that point and 2 mm below the flange tip): Sh = 28 mm,
Sd = 32.5 mm, qR = 10.8 mm. The qR value is also derived here independently from the
section equations: Sd point on arc D (centre (−26.210665, 16.446), R13) at F = 10 mm,
qR point on arc F (centre (−58.558326413, 8.834924130), R20) at F = 26 mm.
"""

import math

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import ProfileError


def test_s1002_nominal():
    p = wr.profiles.load("S1002")
    Sh, Sd, qR = wr.profiles.flange_dimensions(p)
    assert Sh == pytest.approx(0.028, abs=1e-6)
    assert Sd == pytest.approx(0.0325, abs=1e-6)
    assert qR == pytest.approx(0.0108, abs=0.05e-3)
    # independent: the arcs of the section equations
    s_sd = -26.210665 - math.sqrt(13.0 ** 2 - (16.446 - 10.0) ** 2)
    s_qr = -58.558326413 + math.sqrt(20.0 ** 2 - (26.0 - 8.834924130) ** 2)
    assert qR == pytest.approx((s_sd - s_qr) * 1e-3, abs=1e-6)


def test_worn_flange_thinner():
    # remove 1 mm normal to the flange face on the field side of the tip: Sd falls ~1 mm/cos
    p = wr.profiles.load("S1002")
    y = np.asarray(p.y)
    z = np.asarray(p.z).copy()
    band = (y > -0.052) & (y < -0.030)
    slope = np.gradient(z, y)
    z[band] += 1e-3 * np.sqrt(1 + slope[band] ** 2)
    worn = wr.Profile(y, z, kind="wheel", meta=p.meta)
    new = wr.profiles.flange_dimensions(p)
    old_sd = new.Sd
    w = wr.profiles.flange_dimensions(worn)
    assert w.Sd < old_sd - 0.5e-3
    assert w.Sh == pytest.approx(new.Sh, abs=1e-9)


def test_rail_refused():
    with pytest.raises(ProfileError, match="wheel"):
        wr.profiles.flange_dimensions(wr.profiles.load("60E1"))
