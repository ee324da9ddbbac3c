"""Guards of ``wr.dynamics.simulate`` and ``wheelrail dynamics``: a run is estimated and
refused past the memory or time limit with the numbers; a diverging run stops naming the
time and a step to try; a 1 mm curve radius, an output step below the time step and
implausible speeds are refused or warned; a deceleration past standstill ends the run at
standstill; Y/Q beyond Nadal's limit is flagged; Ctrl-C keeps the simulated seconds."""

from __future__ import annotations

import importlib
import math

import numpy as np
import pytest
import xarray as xr

import wheelrail as wr
from wheelrail import _resources
from wheelrail.dynamics import _guards as GUARDS
from wheelrail.dynamics._fastcontact import WHEEL_FIELDS
from wheelrail.dynamics.reference import cone_track

from _dynamics_case import wheelset_case
from _helpers import assert_clean_failure, run_cli

D = wr.dynamics
SIM = importlib.import_module("wheelrail.dynamics.simulate")
W = {n: i for i, n in enumerate(WHEEL_FIELDS)}


@pytest.fixture(scope="module")
def setup():
    ws, tr = cone_track()
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), spin="fixed",
                            primary=D.Suspension(kx=1e6, ky=3.9e6, kz=1.2e6))
    return model, tr


def _run(setup, speed=20.0, duration=0.05, **kw):
    model, tr = setup
    kw.setdefault("initial", {"ws0.y": 0.001})
    return D.simulate(model, kw.pop("track", tr), speed, duration, "hertz", "fastsim", **kw)


def test_output_too_large_for_memory_is_refused_with_the_numbers(setup):
    with pytest.raises(_resources.ResourceLimitError) as err:
        _run(setup, duration=1e6)
    msg = str(err.value)
    assert "1e+06 s" in msg and "memory limit" in msg and "outputs" in msg and "TB" in msg


def test_run_past_the_time_limit_is_refused_with_its_estimate(setup):
    with _resources.time_limit_set(1.0), pytest.raises(_resources.ResourceLimitError) as err:
        _run(setup, duration=500.0, output_step=0.1)
    msg = str(err.value)
    assert "time limit" in msg and "ms per contact evaluation" in msg and "steps" in msg


def test_diverging_step_stops_naming_time_and_a_smaller_step(setup):
    """RK4 at 50 ms: the wheel-rail contact's vertical mode (√(k/m) ≈ 10³ rad/s) is unstable;
    the run stops at once instead of writing a lateral shift of 1e15 m."""
    with pytest.raises(wr.ConvergenceError) as err:
        _run(setup, duration=1.0, integrator=D.FixedStep(dt=0.05))
    msg = str(err.value)
    assert "diverged at t =" in msg and "fixed step 0.05 s" in msg and "FixedStep(dt=0.001)" in msg
    assert "ws0.y" in msg


@pytest.mark.parametrize("radius", [1e-3, 10.0])
def test_curve_radius_below_50_m_is_refused(setup, radius):
    model, tr = setup
    layout = D.TrackLayout(tr, (D.Curve(radius, start=10.0),))
    with pytest.raises(wr.InputError, match=rf"curve radius = {radius!r} m is below 50 m"):
        _run(setup, track=layout)


def test_output_step_below_the_time_step_is_refused(setup):
    with pytest.raises(wr.InputError, match=r"output_step = 0.0001 s is below the time step"):
        _run(setup, output_step=1e-4)


def test_speed_in_km_h_is_warned_or_refused(setup):
    with pytest.warns(SIM.RunWarning, match=r"518 km/h.*40 m/s"):
        with pytest.raises(wr.InputError):          # stop early: only the warning matters
            _run(setup, speed=144.0, output_step=-1.0)
    with pytest.raises(wr.InputError, match=r"km/h\? 300.0 km/h = 83.33 m/s"):
        _run(setup, speed=300.0)


def test_deceleration_past_standstill_ends_at_standstill(setup):
    """V(t) = 2 − 2 t reaches the creep model's least speed 0.5 m/s at t = 0.75 s: the run
    ends there (it used to hold 0.5 m/s while the position ran backwards)."""
    with pytest.warns(SIM.RunWarning, match=r"at t = 0.75 s"):
        res = _run(setup, speed=2.0, duration=5.0, deceleration=2.0, output_step=0.01)
    assert res.t[-1] == pytest.approx(0.75, abs=1e-3)
    assert np.all(np.diff(res.position) > 0)
    assert res.speed[-1] == pytest.approx(0.5, abs=2e-3)


def test_start_from_rest_with_an_acceleration(setup):
    res = _run(setup, speed=0.0, duration=0.3, deceleration=-5.0, output_step=0.01,
               initial={})
    assert res.speed[0] == pytest.approx(0.5) and res.speed[-1] == pytest.approx(1.5)
    assert np.all(np.isfinite(res.states))


def test_y_over_q_beyond_nadal_is_flagged():
    """Nadal (1896): Y/Q limit (tan γ − μ)/(1 + μ tan γ) = 1.3416 for γ = 70°, μ = 0.3;
    an S1002 wheel (flange angle 70°) with Y/Q = 3.1 on its right wheel is flagged."""
    model = D.WheelsetModel(wr.Wheelset(wr.profiles.load("S1002")), 1813.0,
                            (1120.0, 112.0, 1120.0))
    system = D.System(model, wr.Track(wr.profiles.load("60E1")), 40.0, "hertz", "fastsim")
    T = np.linspace(0.0, 1.0, 11)
    OW = np.zeros((11, 1, 2, len(WHEEL_FIELDS)))
    OW[..., W["Fz"]] = 50e3
    OW[6:, 0, 1, W["Fy"]] = -3.1 * 50e3            # right wheel pushed to the field side
    with pytest.warns(SIM.RunWarning, match=r"Y/Q reaches 3.1 .*right wheel.*t = 0.6 s.*"
                                            r"Nadal's limit 1.3"):
        d = GUARDS.nadal_check(system, T, OW)
    gamma = GUARDS.flange_angle(model.wheelset)
    assert math.degrees(gamma) == pytest.approx(70.0, abs=1.0)
    t = math.tan(gamma)
    assert d["nadal_limit"] == pytest.approx((t - 0.3) / (1 + 0.3 * t), rel=1e-12)
    assert d["side"] == "right" and d["t"] == pytest.approx(0.6)
    OW[6:, 0, 1, W["Fy"]] = -1.0 * 50e3            # below the limit: nothing
    assert GUARDS.nadal_check(system, T, OW) is None


def _interrupt_after(monkeypatch, calls):
    real = SIM.run_fixed
    n = {"k": 0}

    def fake(*args):
        n["k"] += 1
        if n["k"] > calls:
            raise KeyboardInterrupt
        return real(*args)

    monkeypatch.setattr(SIM, "run_fixed", fake)


def test_ctrl_c_keeps_the_simulated_seconds(setup, monkeypatch):
    _interrupt_after(monkeypatch, 3)               # 3 chunks of 50 ms
    with pytest.raises(SIM.SimulationInterrupted) as err:
        _run(setup, duration=1.0)
    res = err.value.result
    assert isinstance(err.value, KeyboardInterrupt)
    assert res.info["interrupted"] == 1
    assert res.t[-1] == pytest.approx(0.15, abs=1e-9) and np.all(np.isfinite(res.states))
    assert res.t.size == 151


CASE = wheelset_case(1.0)


def test_cli_ctrl_c_writes_the_simulated_seconds_and_exits_130(tmp_path, capsys, monkeypatch):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    _interrupt_after(monkeypatch, 2)
    out = tmp_path / "out"
    code, stdout, err = run_cli(["dynamics", case, "--out", out, "--no-figures",
                                 "--no-progress"], capsys)
    assert code == 130
    assert "interrupted at t = 0.1 s" in stdout
    with xr.open_dataset(out / "result.nc") as ds:
        assert int(ds.attrs["interrupted"]) == 1
        assert float(ds["time"][-1]) == pytest.approx(0.1)


def test_cli_refuses_a_run_too_long_for_memory(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    code, _, err = run_cli(["dynamics", case, "--out", tmp_path / "o", "--duration", "1e6",
                            "--no-figures"], capsys)
    assert_clean_failure(code, err, "memory limit", "1e+06 s", "outputs")
