"""The public interface of wheelrail.dynamics and ``wheelrail dynamics CASE.toml``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.cli.dynamics import read_dynamics_case
from wheelrail.cli.main import main

D = wr.dynamics
EXAMPLE = Path(__file__).parents[2] / "docs" / "examples" / "dynamics_wheelset.toml"


@pytest.fixture(scope="module")
def cone():
    ws, tr = D.cone_track(0.2, 0.46, 0.75, crown_radius=0.02)
    return D.WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0),
                           primary=D.Suspension(kx=1e6, ky=3.884e6, half_spacing=1.0)), tr


def test_methods_by_name_object_or_options_are_the_same(cone):
    """normal/tangential as names with options, or as configured objects: one resolution
    (wheelrail.options), the same result; an option of neither method is refused by name."""
    model, tr = cone
    kw = {"initial": {"ws0.y": 0.001}, "output_step": 0.01}
    a = D.simulate(model, tr, 10.0, 0.05, "hertz", "fastsim", nx=8, **kw)
    b = D.simulate(model, tr, 10.0, 0.05, wr.normal.Hertz(), wr.tangential.Fastsim(nx=8), **kw)
    c = D.simulate(model, tr, 10.0, 0.05, "hertz", "fastsim", **kw)
    np.testing.assert_array_equal(a.states, b.states)
    assert not np.array_equal(a.states[-1], c.states[-1])       # nx = 8 is not the default
    with pytest.raises(wr.InputError, match="'nxx' belongs to neither"):
        D.simulate(model, tr, 10.0, 0.05, "hertz", "fastsim", nxx=8)
    with pytest.raises(wr.InputError, match="unknown creep-force method 'fastsimm'"):
        D.simulate(model, tr, 10.0, 0.05, "hertz", "fastsimm")


def test_dataset_over_time(cone):
    model, tr = cone
    res = D.simulate(model, tr, 10.0, 0.02, "hertz", "fastsim", initial={"ws0.y": 0.001})
    ds = res.dataset
    assert ds["y"].dims == ("time", "wheelset")
    assert ds["Fn"].dims == ("time", "wheelset", "side", "patch")
    assert ds["time"].size == 21 and float(ds["time"][-1]) == pytest.approx(0.02)
    for name in ("Y_over_Q", "contact_angle", "xi", "eta", "phi", "wear_number"):
        assert name in ds
    # the static load is carried: the wheel loads add up to the axle load
    Q = ds["vertical_load"].isel(time=0, wheelset=0).sum("side")
    assert float(Q) == pytest.approx(model.axle_load, rel=0.01)


def test_critical_speed_linear_and_bad_method(cone):
    model, tr = cone
    model = D.WheelsetModel(model.wheelset, model.mass, model.inertia, primary=model.primary,
                            spin="fixed")
    r = D.critical_speed(model, tr, "hertz", "linear", method="linear", bracket=(20.0, 200.0))
    # an oscillatory mode (hunting) crosses, not the structural zero mode of the held spin
    assert 20.0 < r.speed < 200.0 and r.frequency > 1.0
    with pytest.raises(wr.InputError, match="method must be 'linear' or 'ramp'"):
        D.critical_speed(model, tr, method="nonlinear")


def test_nonlinear_critical_speed_not_above_linear():
    """S1002 / 60E1: the speed at which a hunting limit cycle dies out on a ramp-down
    lies at or below the linear critical speed (the limit cycle is subcritical)."""
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0),
                            primary=D.Suspension(kx=1e6, ky=3.884e6, half_spacing=1.0),
                            axle_load=80e3)
    lin = D.critical_speed(model, tr, "hertz", "fastsim", method="linear")
    ramp = D.critical_speed(model, tr, "hertz", "fastsim", method="ramp", deceleration=8.0,
                            settle=1.0, start_speed=1.2 * lin.speed)
    assert 10.0 < ramp.speed <= lin.speed


def test_cli_dynamics_writes_results_and_figures(tmp_path):
    out = tmp_path / "out"
    code = main(["dynamics", str(EXAMPLE), "--out", str(out), "--duration", "0.05",
                 "--no-progress"])
    assert code == 0
    for name in ("result.nc", "summary.json", "lateral.png", "forces.png", "contact.png"):
        assert (out / name).stat().st_size > 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["normal"] == "kik-piotrowski" and summary["simulated_s"] == pytest.approx(0.05)
    case = read_dynamics_case(EXAMPLE)
    assert case["tangential"].nx == 20 and case["layout"].curves[0].radius == 1200.0


@pytest.mark.parametrize("edit, match", [
    (("mass = 1813.0", "mass = -1.0"), r"\[model\] mass: must be > 0"),
    (("nx = 20", "nx = 0"), r"\[method.fastsim\] nx"),
    (("ky = 3.884e6", "kyy = 3.884e6"), r"\[model.primary\]: unknown key\(s\) 'kyy'"),
    (("radius = 1200.0", "radius = 0.0"), r"\[track.curves\[0\]\]"),
    (('integrator = "rk4"', 'integrator = "euler"'), r"\[simulation\]"),
])
def test_cli_dynamics_bad_case_names_table_and_key(tmp_path, edit, match):
    text = EXAMPLE.read_text().replace(*edit)
    case = tmp_path / "bad.toml"
    case.write_text(text)
    with pytest.raises(wr.WheelrailError, match=match):
        read_dynamics_case(case)
    assert main(["dynamics", str(case), "--out", str(tmp_path / "o"), "--no-progress"]) != 0


@pytest.mark.parametrize("value, ok", [("true", True), ("1.45", True), ("-1.0", False),
                                       ('"yes"', False)])
def test_cli_dynamics_creep_relaxation_length(tmp_path, value, ok):
    # A number is the relaxation length in semi-axes a (1.45 a matches Kalker's transient
    # step response, docs/dynamics.md); a negative number or a string is refused by name.
    text = EXAMPLE.read_text().replace('integrator = "rk4"',
                                       f'integrator = "rk4"\ncreep_relaxation = {value}')
    case = tmp_path / "c.toml"
    case.write_text(text)
    if ok:
        assert read_dynamics_case(case)["simulate"]["creep_relaxation"] == \
            (True if value == "true" else 1.45)
    else:
        with pytest.raises(wr.WheelrailError, match=r"creep_relaxation.*relaxation length"):
            read_dynamics_case(case)


def test_kik_piotrowski_three_flexibilities_not_silently_compiled():
    """The compiled path marches Kik–Piotrowski strips with one weighted flexibility:
    ``fastsim_flexibility="three"`` is refused there by name, and ``contact="auto"``
    takes the generic path, which honours it (never the option silently ignored)."""
    ws, tr = wr.Wheelset(wr.profiles.load("S1002")), wr.Track(wr.profiles.load("60E1"))
    kp3 = wr.normal.KikPiotrowski(fastsim_flexibility="three")
    with pytest.raises(wr.errors.InputError, match="fastsim_flexibility='three'"):
        D.FastContact(ws, tr, wr.STEEL, kp3, wr.tangential.Fastsim())
    assert isinstance(D.contact_model(ws, tr, wr.STEEL, kp3, "fastsim"), D.GenericContact)
    assert isinstance(D.contact_model(ws, tr, wr.STEEL, "kik-piotrowski", "fastsim"),
                      D.FastContact)
