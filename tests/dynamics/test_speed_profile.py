"""A speed that varies along the run: :class:`wheelrail.dynamics.SpeedProfile` and
``simulate(..., speed=SpeedProfile)``.

References (independent of the code):

* kinematics of a speed linear in time: s = v0 t + a t²/2 (constant acceleration);
  of a speed linear in distance, dV/ds = g: dt = ds/V gives V = v0 e^{g t},
  s = v0 (e^{g t} − 1)/g and the time ln(v1/v0)/g over a segment (integrated here
  by hand for each case);
* the wheelset's yaw equation in the track frame (Wickens 2003, §2.1): the
  reference turns at V κ, so its yaw acceleration carries − V̇ κ;
* the free-spin wheelset's spin equation Iy Ω̇ = Q_spin: rolling at Ω = V/r0 while
  V changes at V̇ needs the creep moment Iy V̇ / r0;
* low speed: the creep damping's time constants go as V (test_dynamics_stiff.py),
  so a run that slows to 1 m/s must divide the 1 ms step as the constant 1 m/s run
  does, and its creepage stays that of kinematic rolling.
"""

from __future__ import annotations

import importlib
import math
import warnings

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics._fastcontact import PATCH_FIELDS, WHEEL_FIELDS
from wheelrail.dynamics.reference import cone_track

D = wr.dynamics
SP = D.SpeedProfile
SIM = importlib.import_module("wheelrail.dynamics.simulate")
W = {n: i for i, n in enumerate(WHEEL_FIELDS)}
XI = PATCH_FIELDS.index("xi")
R0, L0 = 0.46, 0.75


# --------------------------------------------------------------------------- the profile
def test_time_profile_against_the_hand_integral():
    """V: 10 → 4 m/s over 2 s (a = −3), held 3 s, 4 → 0 over 1 s (a = −4)."""
    p = SP.from_time([0.0, 2.0, 5.0, 6.0], [10.0, 4.0, 4.0, 0.0])
    t = np.array([0.0, 1.0, 2.0, 3.5, 5.0, 5.5, 6.0, 7.0])
    s_hand = np.array([0.0, 10 - 1.5, 20 - 6.0, 14 + 6.0, 14 + 12.0,
                       26 + 2.0 - 0.5, 26 + 4.0 - 2.0, 28.0])
    np.testing.assert_allclose(p.position(t), s_hand, rtol=0, atol=1e-12)
    np.testing.assert_allclose(p.speed(t), [10, 7, 4, 4, 4, 2, 0, 0], atol=1e-12)
    np.testing.assert_allclose(p.acceleration([0.5, 3.0, 5.5, 6.5]), [-3, 0, -4, 0])
    # start: a shift of the position only
    assert p.position(1.0, start=100.0) == pytest.approx(108.5, abs=1e-12)
    assert p.time_at(20.0) == pytest.approx(3.5, abs=1e-12)
    assert p.time_at(8.5) == pytest.approx(1.0, abs=1e-12)


def test_distance_profile_against_the_closed_form():
    """V linear in s from 20 m/s at 100 m to 10 m/s at 200 m: g = −0.1 1/s, so
    V = 20 e^{−0.1 t}, s = 100 + 200 (1 − e^{−0.1 t}), the segment takes 10 ln 2 s;
    then held at 10 m/s."""
    p = SP.from_distance([100.0, 200.0, 400.0], [20.0, 10.0, 10.0])
    T = 10.0 * math.log(2.0)
    t = np.array([0.0, 1.0, 3.0, T, T + 5.0])
    V = np.where(t <= T, 20.0 * np.exp(-0.1 * t), 10.0)
    s = np.where(t <= T, 100.0 + 200.0 * (1.0 - np.exp(-0.1 * t)), 200.0 + 10.0 * (t - T))
    np.testing.assert_allclose(p.speed(t), V, rtol=1e-13)
    np.testing.assert_allclose(p.position(t), s, rtol=1e-13)
    np.testing.assert_allclose(p.acceleration(t[:3]), -0.1 * V[:3], rtol=1e-13)
    assert p.time_at(200.0) == pytest.approx(T, rel=1e-14)
    # a run that starts inside the segment, at 150 m (V = 15 m/s there)
    assert p.speed(0.0, start=150.0) == pytest.approx(15.0, rel=1e-14)
    assert p.time_at(200.0, start=150.0) == pytest.approx(10.0 * math.log(1.5), rel=1e-13)
    # before the first breakpoint the first speed holds
    assert p.time_at(200.0, start=50.0) == pytest.approx(2.5 + T, rel=1e-13)


def test_distance_profile_round_trip():
    """position(time_at(s)) = s and the speed there is the one given, linear in s."""
    s_k, v_k = [0.0, 50.0, 120.0, 300.0, 310.0], [25.0, 25.0, 1.0, 8.0, 8.0]
    p = SP.from_distance(s_k, v_k)
    s = np.linspace(0.0, 330.0, 67)
    t = p.time_at(s)
    assert np.all(np.diff(t) > 0)
    np.testing.assert_allclose(p.position(t), s, rtol=0, atol=1e-9)
    np.testing.assert_allclose(p.speed(t), np.interp(s, s_k, v_k), rtol=1e-11)


@pytest.mark.parametrize("make, match", [
    (lambda: SP.from_time([0, 2, 1], [5, 5, 5]), r"t\[2\] = 1.0 follows t\[1\] = 2.0"),
    (lambda: SP.from_time([0, 1], [5, -1]), r"v\[1\] = -1.0 must be ≥ 0"),
    (lambda: SP.from_time([0, 1], [5, math.nan]), r"v\[1\] = nan is not finite"),
    (lambda: SP.from_time([1, 2], [5, 5]), r"t\[0\] = 1.0 s must be 0"),
    (lambda: SP.from_time([0, 1, 2], [5, 5]), r"differ in length"),
    (lambda: SP.from_time([0], [5]), r"at least 2"),
    (lambda: SP.from_distance([0, 10], [0, 5]), r"v\[0\] = 0.0 must be > 0"),
    (lambda: SP.from_distance([0, 10, 10], [1, 5, 5]), r"s\[2\] = 10.0 follows"),
    (lambda: SP.from_distance([0, "x"], [1, 5]), r"list of numbers"),
])
def test_bad_profiles_are_refused_naming_the_value(make, match):
    with pytest.raises(wr.InputError, match=match):
        make()


# --------------------------------------------------------------------------- in simulate
@pytest.fixture(scope="module")
def cone():
    return cone_track(0.2, R0, L0)


def _wheelset(ws, spin):
    return D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), axle_load=80e3, spin=spin,
                           primary=D.Suspension(kx=2e6, ky=2e6, kz=1.22e6, half_spacing=1.0))


def test_bad_profile_runs_are_refused(cone):
    ws, tr = cone
    model = _wheelset(ws, "fixed")
    with pytest.raises(wr.InputError, match="deceleration = 1.0"):
        D.simulate(model, tr, SP.from_time([0, 1], [10, 9]), 0.01, "hertz", "fastsim",
                   deceleration=1.0)
    with pytest.raises(wr.InputError, match="does not accelerate"):
        D.System(model, tr, SP.from_time([0, 1], [0, 0]), "hertz", "fastsim")
    with pytest.raises(wr.InputError, match="beyond any railway speed"):
        D.simulate(model, tr, SP.from_time([0, 1], [10, 300]), 2.0, "hertz", "fastsim")


def test_profile_run_equals_the_constant_deceleration_run(cone):
    """10 m/s braking at 2 m/s² in a 500 m curve (fast path, RK4 1 ms): a profile with the
    same ramp gives the same run."""
    ws, tr = cone
    layout = D.TrackLayout(tr, (D.Curve(500.0, start=-50.0, transition=20.0),))
    model = _wheelset(ws, "free")
    kw = dict(normal="hertz", tangential="fastsim", initial={"ws0.y": 1e-3}, start=10.0)
    ref = D.simulate(model, layout, 10.0, 0.3, deceleration=2.0, **kw)
    run = D.simulate(model, layout, SP.from_time([0.0, 1.0], [10.0, 8.0]), 0.3, **kw)
    assert run.info["contact_path"] == ref.info["contact_path"]
    assert run.t.shape == ref.t.shape
    np.testing.assert_allclose(run.states, ref.states, rtol=0, atol=1e-10)
    np.testing.assert_allclose(run.speed, 10.0 - 2.0 * ref.t, atol=1e-12)
    np.testing.assert_allclose(run.position, 10.0 + 10.0 * ref.t - ref.t ** 2, atol=1e-12)
    np.testing.assert_allclose(ref.speed, run.speed, atol=1e-12)


def test_vehicle_profile_run_equals_the_constant_deceleration_run():
    """The Manchester vehicle (car body on two bogies) braking at 1.5 m/s² from 30 m/s."""
    model = D.manchester_vehicle1()
    track = wr.Track(wr.profiles.load("60E1"))
    kw = dict(normal="hertz", tangential=wr.tangential.Fastsim(nx=10),
              initial={"ws0.y": 0.003})
    ref = D.simulate(model, track, 30.0, 0.02, deceleration=1.5, **kw)
    run = D.simulate(model, track, SP.from_time([0.0, 2.0], [30.0, 27.0]), 0.02, **kw)
    np.testing.assert_allclose(run.states, ref.states, rtol=0, atol=1e-10)
    np.testing.assert_allclose(run.speed, 30.0 - 1.5 * run.t, atol=1e-12)


def test_generic_path_follows_the_profile_and_its_acceleration(cone):
    """The library's contact path: a profile equals the deceleration run's right-hand side
    (1e-10); at equal speed and position, the acceleration a adds −a κ to the yaw
    acceleration (the turning track frame) and a/r0 to the fixed spin's rate."""
    ws, tr = cone
    layout = D.TrackLayout(tr, (D.Curve(400.0, start=-100.0),))
    model = _wheelset(ws, "fixed")
    ramp = D.System(model, layout, 12.0, "hertz", "fastsim", deceleration=1.5,
                    contact="generic")
    prof = D.System(model, layout, SP.from_time([0.0, 4.0], [12.0, 6.0]), "hertz", "fastsim",
                    contact="generic")
    assert not prof.fast
    x = ramp.initial_state({"ws0.y": 2e-3})
    for t in (0.0, 0.37, 1.2):
        np.testing.assert_allclose(prof.rhs(t, x), ramp.rhs(t, x), rtol=1e-12, atol=1e-10)
    # the same speed and position held (no acceleration) at t = 0
    t, a = 1.2, -1.5
    held = D.System(model, layout, prof.V(t), "hertz", "fastsim", start=prof.s_ref(t),
                    contact="generic")
    d = prof.rhs(t, x) - held.rhs(0.0, x)
    kappa = 1.0 / 400.0
    assert d[7] == pytest.approx(-a * kappa, rel=1e-9)
    assert d[8] == pytest.approx(a / model.wheelset.nominal_radius, rel=1e-9)
    d[7] = d[8] = 0.0
    assert np.max(np.abs(d)) < 1e-9


def test_distance_profile_run_reports_the_profile_and_spins_with_it(cone):
    """A free-spin wheelset braked from 20 to 16 m/s over 20 m (V linear in s, g = −0.2
    1/s): the result reports V = 20 e^{−0.2 t}, s = 100 (1 − e^{−0.2 t}); the wheelset
    spins at V/r0 (rolling, creepage ~1e-4) and the creep moment about the axle
    decelerates it, ΣQt_spin = Iy V̇ / r0 = −0.2 Iy V / r0 (2 %: the rolling radius
    varies with the oscillation)."""
    ws, tr = cone
    model = _wheelset(ws, "free")
    res = D.simulate(model, tr, SP.from_distance([0.0, 20.0], [20.0, 16.0]), 0.3, "hertz",
                     "fastsim", output_step=0.01)
    t = res.t
    V = 20.0 * np.exp(-0.2 * t)
    np.testing.assert_allclose(res.speed, V, rtol=1e-12)
    np.testing.assert_allclose(res.position, 100.0 * (1.0 - np.exp(-0.2 * t)), atol=1e-10)
    np.testing.assert_allclose(res.dataset["speed"].values, V, rtol=1e-12)
    r0 = model.wheelset.nominal_radius
    np.testing.assert_allclose(res.state("ws0.omega"), V / r0, rtol=1e-3)
    brake = t > 0.05
    q = res.wheels[brake, 0, :, W["Qt_spin"]].sum(axis=1)
    np.testing.assert_allclose(q, 112.0 * (-0.2 * V[brake]) / r0, rtol=0.02)


def test_a_profile_down_to_1_m_s_divides_the_step_as_the_constant_run():
    """Free spin, slowing from 6 to 1 m/s in 0.5 s then held: the 1 ms RK4 step is divided
    (StepWarning, at least the sub-steps of the constant 1 m/s run), and at 1 m/s the
    wheelset rolls kinematically (creepage < 2e-6, as the constant runs; it was 1.6e-2
    without the control)."""
    ws, tr = cone_track(0.2, R0, L0)
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), axle_load=80e3, spin="free")
    prof = SP.from_time([0.0, 0.5, 2.0], [6.0, 1.0, 1.0])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = D.simulate(model, tr, prof, 0.8, "hertz", "fastsim",
                         integrator=D.FixedStep(dt=1e-3), initial={"ws0.y": 0.001})
    warned = [w for w in caught if issubclass(w.category, SIM.StepWarning)]
    assert len(warned) == 1 and "sub-steps" in str(warned[0].message)
    const = D.System(model, tr, 1.0, "hertz", "fastsim")
    x = const.initial_state({"ws0.y": 0.001})
    n1, _, _ = const.substeps(0.0, x, 1e-3)
    assert n1 >= 5 and res.info["substeps"] >= n1
    xi = res.patches[res.t > 0.6, 0, :, 0, XI]
    assert np.max(np.abs(xi)) < 2e-6
    assert np.all(np.isfinite(res.states))


def test_substeps_take_the_least_speed_of_the_span(cone):
    """The sub-step count for a stretch of the run is that of its least speed: from 3 m/s
    falling to 1 m/s within the span, the count at 1 m/s (creep rates ∝ 1/V)."""
    ws, tr = cone
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), axle_load=80e3, spin="free")
    prof = D.System(model, tr, SP.from_time([0.0, 0.05, 1.0], [3.0, 1.0, 1.0]), "hertz",
                    "fastsim")
    const = D.System(model, tr, 3.0, "hertz", "fastsim")
    x = const.initial_state({"ws0.y": 0.001})
    n3, rate3, _ = const.substeps(0.0, x, 1e-3)
    n_span, rate, _ = prof.substeps(0.0, x, 1e-3, 0.05)
    assert rate == pytest.approx(3.0 * rate3, rel=1e-9)
    assert n_span == math.ceil(1e-3 * 3.0 * rate3 / 2.0) and n_span > n3
    assert prof.substeps(0.0, x, 1e-3)[0] == n3           # at t = 0 alone: 3 m/s


def test_profile_past_standstill_ends_the_run(cone):
    ws, tr = cone
    model = _wheelset(ws, "fixed")
    with pytest.warns(SIM.RunWarning, match=r"speed profile brings the speed to 0.5 m/s.*"
                                            r"t = 0.15 s"):
        res = D.simulate(model, tr, SP.from_time([0.0, 0.2], [2.0, 0.0]), 1.0, "hertz",
                         "fastsim", output_step=0.01)
    assert res.t[-1] == pytest.approx(0.15, abs=1e-3)


# --------------------------------------------------------------------------- the case file
def _case(tmp_path, speed_lines):
    from pathlib import Path

    example = Path(__file__).parents[2] / "docs" / "examples" / "dynamics_wheelset.toml"
    text = example.read_text().replace("speed = 40.0                         # [m/s]",
                                       speed_lines)
    case = tmp_path / "case.toml"
    case.write_text(text)
    return case


def test_case_file_speed_profile(tmp_path):
    from wheelrail.cli.dynamics import read_dynamics_case

    case = _case(tmp_path, "speed_profile = {distance = [0.0, 100.0], speed = [40.0, 30]}")
    p = read_dynamics_case(case)["simulate"]["speed"]
    assert isinstance(p, SP) and p.kind == "distance"
    assert p.time_at(100.0) == pytest.approx(100.0 * math.log(40 / 30) / 10.0, rel=1e-14)
    case = _case(tmp_path, "speed_profile = {time = [0, 2], speed = [0.0, 3.0]}")
    p = read_dynamics_case(case)["simulate"]["speed"]
    assert p.kind == "time" and p.position(2.0) == pytest.approx(3.0)


def test_cli_dynamics_runs_a_speed_profile(tmp_path):
    """``wheelrail dynamics`` with a profile against distance: the summary and result.nc
    report the speed V = 40 e^{−0.1 t} (40 → 30 m/s over 100 m, g = −0.1 1/s)."""
    import json

    import xarray as xr

    from wheelrail.cli.main import main

    case = _case(tmp_path, "speed_profile = {distance = [0.0, 100.0], speed = [40.0, 30]}")
    out = tmp_path / "out"
    assert main(["dynamics", str(case), "--out", str(out), "--duration", "0.05",
                 "--no-figures", "--no-progress"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["speed_max_m_s"] == pytest.approx(40.0, rel=1e-12)
    assert summary["speed_min_m_s"] == pytest.approx(40.0 * math.exp(-0.005), rel=1e-12)
    with xr.open_dataset(out / "result.nc") as ds:
        assert ds.attrs["speed_profile"].startswith("SpeedProfile.from_distance([0.0, 100.0]")
        t = ds["time"].values
        np.testing.assert_allclose(ds["speed"].values, 40.0 * np.exp(-0.1 * t), rtol=1e-12)
        np.testing.assert_allclose(ds["position"].values, 400.0 * (1 - np.exp(-0.1 * t)),
                                   rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("lines, match", [
    ("speed_profile = {distance = [0.0, 100.0], speed = [40.0, -1]}",
     r"\[simulation.speed_profile\]: SpeedProfile.from_distance: v\[1\] = -1.0"),
    ("speed_profile = {distance = [0.0, 100.0], time = [0, 1], speed = [40.0, 30]}",
     r"either distance"),
    ("speed_profile = {distance = [0.0], speed = [40.0]}", r"at least 2 numbers"),
    ("speed_profile = {distance = [0.0, 1], speeds = [40.0, 1]}", r"unknown key\(s\) 'speeds'"),
    ("speed = 40.0\nspeed_profile = {time = [0.0, 1], speed = [40.0, 1]}",
     r"\[simulation\] speed: given with speed_profile"),
])
def test_case_file_bad_speed_profile_names_table_and_key(tmp_path, lines, match):
    from wheelrail.cli.dynamics import read_dynamics_case

    with pytest.raises(wr.WheelrailError, match=match):
        read_dynamics_case(_case(tmp_path, lines))
