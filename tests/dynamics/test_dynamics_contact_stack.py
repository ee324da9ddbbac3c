"""One contact stack: the compiled contact of the dynamics gives the forces of ``wr.solve``.

The compiled per-wheel contact (:class:`wheelrail.dynamics.FastContact`) is evaluated at
the pose and vertical approach that :func:`wheelrail.solve` found for the wheel
(``vertical="normal"``: the normal forces carry the load, as in the dynamics), with the
same velocities and friction, and every force component is compared with the library's:
Σ Fn, Σ Fx, Σ Fs over the wheel's patches and the track-frame Fy, Fz, each within
0.5 % of μQ (Q the wheel's vertical load), and the patch count.

Positions: the 21 wheelset positions of the Manchester contact benchmark, case A-2.2
(Shackleton & Iwnicki 2008, VSD 46, 129–149: S1002 on UIC60 1:40, 10 kN per wheel,
y = 0 … 10 mm, yaw 2.4 mrad/mm, prescribed roll; tread contact up to case 13, flange
contact of the right wheel from case 14), both wheels; and flange contacts of S1002 on
60E1 (Piotrowski & Chollet 2005, §2: two-point and flange contact up to 20 mrad angle of
attack) on either side, 50 kN per wheel.

Before the compiled path evaluated the library's separation line, the differences reached
6.8 % of μQ in Fn and 5.3 % in Fy (Manchester case 14, right wheel: a coarser line of its
own) — what this test would catch again.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics._fastcontact import KMAX, PATCH_FIELDS, WHEEL_FIELDS
from wheelrail.dynamics.contact import (LINE_NODES, FastContact, GenericContact,
                                       SlowContactWarning, configured_methods, contact_model)

_W = {n: i for i, n in enumerate(WHEEL_FIELDS)}
TOL = 0.005                    # of mu Q


# the library's default line and the dynamics' (contact.LINE_NODES, the method by name)
LINES = [1601, LINE_NODES]


@pytest.fixture(scope="module", params=LINES, ids=lambda n: f"{n}nodes")
def manchester(request):
    from conftest import SHARED_DATA, require_shared

    from wheelrail.contact.manchester import manchester_a22

    data = require_shared(SHARED_DATA)
    cases = manchester_a22(data / "benchmarks" / "manchester_a22_inputs.csv",
                           data / "profiles" / "MBench_S1002_v3.prw",
                           data / "profiles" / "MBench_UIC60_v3.prr")
    p = cases[0].position
    fc = FastContact(p.wheelset, p.track, p.material,
                     wr.normal.KikPiotrowski(line_nodes=request.param), wr.tangential.Fastsim())
    return cases, fc


@pytest.fixture(scope="module", params=LINES, ids=lambda n: f"{n}nodes")
def s1002_60e1(request):
    ws, tr = wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1"))
    return ws, tr, FastContact(ws, tr, wr.STEEL, wr.normal.KikPiotrowski(
        line_nodes=request.param), wr.tangential.Fastsim())


def _compare(fc, position, motion, mu, Q, normal=None):
    """Largest |compiled − wr.solve| of the force components of both wheels [of μQ]."""
    ref = wr.solve(position, motion=motion, mu=mu, normal=normal or fc.normal,
                   tangential="fastsim", vertical="normal")
    ws = position.wheelset
    r0 = ws.nominal_radius
    roll = ref.pose["roll"]
    worst = 0.0
    for side in ("left", "right"):
        op = np.zeros((KMAX, len(PATCH_FIELDS)))
        ow = np.zeros(len(WHEEL_FIELDS))
        zc = r0 + ref.pose[f"z_{side}"] - ref.pose[f"vertical_approach_{side}"]
        n = fc.wheel(side, position.y, zc, roll, position.yaw, motion.speed,
                     motion.angular_velocity(r0), 0.0, 0.0, 0.0, 0.0, mu, op, ow)
        patches = ref.side(side)
        assert n == len(patches), (side, n, len(patches))
        got = op[:n].sum(axis=0)
        want = (sum(p.Fn for p in patches), sum(p.Fx for p in patches),
                sum(p.Fs for p in patches))
        diffs = [got[0] - want[0], got[1] - want[1], got[2] - want[2],
                 ow[_W["Fy"]] - ref.force_track[side][1], ow[_W["Fz"]] - ref.force_track[side][2]]
        worst = max(worst, max(abs(d) for d in diffs) / (mu * Q))
    return worst


@pytest.mark.parametrize("case", range(1, 22))
def test_compiled_kp_fastsim_is_wr_solve_on_manchester_a22(manchester, case):
    cases, fc = manchester
    c = cases[case - 1]
    assert c.case == case
    assert _compare(fc, c.position, c.motion, c.mu, 1e4) <= TOL


@pytest.mark.parametrize("case", [1, 2, 11, 14])
def test_compiled_kpec_combined_is_wr_solve_on_manchester_a22(manchester, case):
    """The same with Vollebregt's ellipticity correction and the combined flexibility
    (the kernels of the library's options)."""
    cases, fc0 = manchester
    c = cases[case - 1]
    p = c.position
    fc = FastContact(p.wheelset, p.track, p.material, wr.normal.KikPiotrowski(
        line_nodes=fc0.normal.line_nodes, ellipticity_correction=True,
        fastsim_flexibility="combined"), wr.tangential.Fastsim())
    assert _compare(fc, p, c.motion, c.mu, 1e4) <= TOL


@pytest.mark.parametrize("y, yaw", [(0.007, 0.004), (0.008, 0.010), (0.0085, 0.020),
                                    (-0.0075, -0.005), (-0.0085, -0.015)])
def test_compiled_kp_fastsim_is_wr_solve_at_flange_contact(s1002_60e1, y, yaw):
    ws, tr, fc = s1002_60e1
    Q, V = 5e4, 20.0
    pos = wr.WheelRailPosition(ws, tr, y, yaw, vertical_load=Q)
    motion = wr.Motion(speed=V, omega=1.001 * V / ws.nominal_radius)
    assert _compare(fc, pos, motion, 0.3, Q) <= TOL


def test_the_comparison_sees_a_changed_method_option(s1002_60e1):
    """The comparison is sensitive: the compiled path with another normal method (the
    original method's constant factor 0.55 instead of the ellipticity correction) is far
    outside the tolerance."""
    ws, tr, _ = s1002_60e1
    other = FastContact(ws, tr, wr.STEEL, wr.normal.KikPiotrowski(penetration_factor=0.55,
                                                                  ellipticity_correction=False),
                        wr.tangential.Fastsim())
    pos = wr.WheelRailPosition(ws, tr, 0.008, 0.010, vertical_load=5e4)
    motion = wr.Motion(speed=20.0, omega=1.001 * 20.0 / ws.nominal_radius)
    assert _compare(other, pos, motion, 0.3, 5e4, wr.normal.KikPiotrowski()) > 10 * TOL


def test_the_dynamics_default_line_differs_from_the_converged_line_by_its_measured_bound():
    """The dynamics' Kik–Piotrowski by name has the coarse line; its forces at a flange
    contact differ from the 6401-node line's (converged to 0.01 % of μQ) by less than the
    bound stated at ``LINE_NODES`` (0.4 % of μQ in Fn, 0.2 % in Fx and Fs), and an
    explicit object keeps its own line."""
    nimpl, _ = configured_methods("kik-piotrowski", "fastsim")
    assert nimpl.line_nodes == LINE_NODES == 201
    assert configured_methods(wr.normal.KikPiotrowski(), "fastsim")[0].line_nodes == 1601
    assert configured_methods("kik-piotrowski", "fastsim",
                              {"line_nodes": 801})[0].line_nodes == 801
    ws, tr = wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1"))
    Q, mu = 5e4, 0.3
    pos = wr.WheelRailPosition(ws, tr, 0.0085, 0.020, vertical_load=Q)
    motion = wr.Motion(speed=20.0, omega=1.001 * 20.0 / ws.nominal_radius)
    sums = {}
    for n in (LINE_NODES, 6401):
        r = wr.solve(pos, motion=motion, mu=mu, normal=wr.normal.KikPiotrowski(line_nodes=n),
                     tangential="fastsim", vertical="normal")
        sums[n] = np.array([[sum(getattr(p, f) for p in r.side(s)) for f in ("Fn", "Fx", "Fs")]
                            for s in ("left", "right")]) / (mu * Q)
    d = np.abs(sums[LINE_NODES] - sums[6401])
    assert d[:, 0].max() <= 0.004 and d[:, 1:].max() <= 0.002, d
    assert d.max() > 1e-5         # the lines do differ: the comparison is not of a line with itself


# --------------------------------------------------------------------------- fallback warning
def test_a_pair_without_compiled_path_is_announced_once_with_its_cost(s1002_60e1):
    ws, tr, _ = s1002_60e1
    kp3 = wr.normal.KikPiotrowski(fastsim_flexibility="three")
    with pytest.warns(SlowContactWarning) as rec:
        c = contact_model(ws, tr, wr.STEEL, kp3, "fastsim")
    assert isinstance(c, GenericContact)
    assert len(rec) == 1
    msg = str(rec[0].message)
    assert "'kik-piotrowski'" in msg and "'fastsim'" in msg and "fastsim_flexibility" in msg
    assert " ms per evaluation" in msg and "compiled" in msg
    # chosen on purpose, or compiled: no warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", SlowContactWarning)
        assert isinstance(contact_model(ws, tr, wr.STEEL, kp3, "fastsim", contact="generic"),
                          GenericContact)
        assert isinstance(contact_model(ws, tr, wr.STEEL, "kik-piotrowski", "fastsim"),
                          FastContact)


def test_simulate_warns_once_for_a_generic_pair(s1002_60e1):
    ws, tr, _ = s1002_60e1
    model = wr.dynamics.WheelsetModel(ws, 1500.0, (800.0, 100.0, 800.0), axle_load=100e3)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        wr.dynamics.simulate(model, tr, 20.0, 0.002, "hertz", "polach",
                             integrator=wr.dynamics.FixedStep(dt=1e-3))
    slow = [w for w in rec if issubclass(w.category, SlowContactWarning)]
    assert len(slow) == 1
    assert "'hertz'" in str(slow[0].message) and "'polach'" in str(slow[0].message)
