"""Steady curving of a bogie with flange contact in a 300 m curve (Manchester vehicle 1).

The bogie is that of vehicle 1 of the Manchester benchmarks (built in as
``wr.dynamics.manchester_bogie()``; Iwnicki 1998:
wheelset 1813 kg, primary stiffness per axlebox kx = 31.391 MN/m, ky =
3.884 MN/m, kz = 1.22 MN/m at ±1 m, frame 2615 kg, semi-wheelbase 1.28 m,
secondary per side kx = ky = 0.16 MN/m, kz = 0.43 MN/m; a quarter of the
32 t car body on each axle) with S1002 wheels on 60E1 rails at 1:40, rigid
track, Hertz + FASTSIM, μ = 0.3. References the checks use:

* the flange angle of S1002, 70° (EN 13715), reached by the flange patch;
* Newton's law for the whole bogie with its share of the car body: the wheels'
  vertical forces carry M (g cos φ + V²/R sin φ) and their lateral forces the
  unbalanced M (V²/R cos φ − g sin φ) (M = 2 axle loads / g, φ the cant angle)
  plus the secondary springs' force 2 k_y2 y_frame towards the car body (which
  runs on the track centre line);
* Nadal's limit (Nadal 1896) as the bound of Y/Q.

No published angle of attack for this vehicle in a 300 m curve was at hand,
so the values are checked for smoothness over the cant deficiency, not against
a number.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics import cant_deficiency, manchester_bogie, nadal, steady_curving
from wheelrail.errors import ConvergenceError

R, CANT, G = 300.0, 0.1, 9.81


@pytest.fixture(scope="module")
def manchester():
    tr = wr.Track(wr.profiles.load("60E1"))
    return manchester_bogie(), tr


def test_cant_deficiency_sweep_is_smooth_with_flange_contact(manchester):
    """R = 300 m, 100 mm cant, 12 … 18 m/s (cant deficiency −27 … +65 mm; 15 m/s
    failed before with ConvergenceError): every point converges; the leading
    wheelset's angle of attack (toward the outer rail) falls smoothly with the
    speed; the outer wheel of the leading wheelset runs on flange root and flange
    (70°, EN 13715) with Y/Q below Nadal's limit and a positive wear number."""
    bogie, tr = manchester
    speeds = np.array([12.0, 13.5, 15.0, 16.5, 18.0])
    yaw, flange_load = [], []
    M = 2.0 * bogie.axle_load / G
    phi = math.asin(CANT / 1.5)
    for V in speeds:
        r = steady_curving(bogie, tr, R, float(V), "hertz", "fastsim", cant=CANT)
        assert r.info["continuation"] == (1.0,)
        yaw.append(r.yaw[0])
        fl = r.flange_contact(0)
        assert fl is not None and fl["side"] == "left"          # outer wheel, curve to the right
        assert math.degrees(fl["contact_angle"]) == pytest.approx(70.0, abs=0.5)
        assert fl["n_patches"] == 2
        assert 0.0 < fl["Y_over_Q"] < nadal(fl["contact_angle"], 0.3)
        assert fl["wear_number"] > 0.0 and fl["wheel_wear_number"] > fl["wear_number"]
        flange_load.append(fl["Fn"])
        # Newton's law for the bogie with its share of the car body
        Fz = r.vertical_load.sum()
        assert Fz == pytest.approx(M * (G * math.cos(phi) + V * V / R * math.sin(phi)), rel=1e-3)
        # track-frame y on the wheels: the unbalanced force, plus the secondary springs'
        # pull of the frame back to the car body (which runs on the centre line)
        Fy = r.wheels[..., 12].sum()
        secondary = 2.0 * bogie.secondary.ky * r.state[r.names.index("frame.y")]
        assert abs(Fy - M * (V * V / R * math.cos(phi) - G * math.sin(phi)) - secondary) < (
            1e-4 * np.abs(r.lateral_force).sum())
    yaw = np.array(yaw)
    # toward the outer (left) rail: nose left, negative; magnitude ~ 2a/R = 8.5 mrad
    assert np.all((yaw < -7e-3) & (yaw > -9.5e-3))
    d1 = np.diff(yaw)
    assert np.all(d1 > 0)                                        # smaller with more speed
    assert np.max(np.abs(np.diff(d1))) < 0.25 * np.max(np.abs(d1))
    assert np.all(np.diff(flange_load) > 0)                      # flange takes more load


def test_no_equilibrium_is_a_convergence_error_naming_the_case(manchester):
    """With the gap minima of one region counted separately and the coarse search
    grid the flange patch vanishes while carrying load; at 15 m/s and 100 mm cant
    the equations then have no root: a ConvergenceError naming radius, speed, cant
    and cant deficiency (not a silent wrong state)."""
    bogie, tr = manchester
    with pytest.raises(ConvergenceError, match=r"radius = 300.0 m, speed = 15.0 m/s, "
                                               r"cant = 0.1 m \(cant deficiency 15 mm\)"):
        steady_curving(bogie, tr, R, 15.0, "hertz", "fastsim", cant=CANT,
                       contact_options={"connected": "separate", "search_step": 5e-4})


def test_cant_deficiency_closed_form():
    """EN 13803: cant deficiency V² G/(g R) − cant."""
    assert cant_deficiency(300.0, 15.0, 0.1) == pytest.approx(225 * 1.5 / (9.81 * 300) - 0.1)


def test_shared_depths_are_continuous_where_a_minimum_merges_or_a_region_splits():
    """``connected="shared"``: two gap minima (depths d1 < d2 < 0) joined by a saddle H.
    Separate regions (H ≥ 0): each its own depth −d. One region (H < 0): the basins
    b_k = H − d_k plus the common −H shared as b_k/Σb, so the total is −d1 − d2 + H
    (the common part once) and the shallow minimum's depth → 0 as its basin → 0."""
    from wheelrail.dynamics._fastcontact import _depths

    def depths(d1, hump, d2, shared=True):
        d = np.array([1.0, d1, hump, d2, 1.0])
        return _depths(d, np.array([1, 3]), np.array([d1, d2]), 2, shared)

    np.testing.assert_allclose(depths(-9e-5, 1e-6, -6e-5), [9e-5, 6e-5])
    np.testing.assert_allclose(depths(-9e-5, -1e-12, -6e-5), [9e-5, 6e-5], atol=1e-11)
    dep = depths(-9e-5, -5e-5, -6e-5)
    np.testing.assert_allclose(dep, [4e-5 + 5e-5 * 4 / 5, 1e-5 + 5e-5 * 1 / 5])
    assert dep.sum() == pytest.approx(9e-5 + 6e-5 - 5e-5)
    np.testing.assert_allclose(depths(-9e-5, -6e-5 + 1e-12, -6e-5)[1], 0.0, atol=1e-11)
    np.testing.assert_allclose(depths(-9e-5, -5e-5, -6e-5, shared=False), [9e-5, 6e-5])
    with pytest.raises(wr.errors.InputError, match="connected"):
        wr.dynamics.FastContact(wr.Wheelset(wr.profiles.load("S1002")),
                                wr.Track(wr.profiles.load("60E1")), wr.STEEL,
                                wr.normal.get("hertz"), wr.tangential.get("fastsim"),
                                connected="merged")
