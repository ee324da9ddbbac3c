"""[transient] case files, travel functions and ``wheelrail transient``."""

import json

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.cases.files import load_transient_case
from wheelrail.cli.main import main
from wheelrail.transient.loads import TravelFunction

CASE = """
[contact]
Fn = 10000.0
wheel_rolling_radius = 0.5
wheel_profile_radius = -0.409
rail_profile_radius = 0.3
[friction]
mu = 0.4
[transient]
travel = 1e-3
step = 2.5e-4
elements = 6
frames = 3
{extra}
"""


def test_travel_functions_match_their_formulas():
    sine = TravelFunction.of("sine", mean=1e4, amplitude=4.5e3, wavelength=5e-3)  # seed (3.2)
    x = np.linspace(0, 1e-2, 7)
    assert np.allclose(sine(x), 1e4 + 4.5e3 * np.sin(2 * np.pi * x / 5e-3))
    step = TravelFunction.of("step", at=1e-3, before=0.0, after=2e3)
    assert step(0.999e-3) == 0.0 and step(1e-3) == 2e3
    table = TravelFunction.of("table", x=[0.0, 1e-3, 2e-3], value=[0.0, 10.0, 30.0])
    assert table(1.5e-3) == pytest.approx(20.0) and table(5e-3) == 30.0 and table(-1) == 0.0
    with pytest.raises(wr.InputError, match="strictly increasing"):
        TravelFunction.of("table", x=[0.0, 0.0], value=[1.0, 2.0])
    with pytest.raises(wr.InputError, match="wavelength must be > 0 m, got -0.005"):
        TravelFunction.of("sine", mean=1.0, amplitude=1.0, wavelength=-5e-3)


def test_case_file_runs_like_the_python_call():
    case = load_transient_case(CASE.format(extra='Fn = {kind = "sine", mean = 1e4, '
                                           'amplitude = 2e3, wavelength = 2e-3}\n'
                                           "Fx = 1500.0"))
    res = case.run()
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.STEEL.__class__(2.1e11, 0.28))
    ref = wr.transient_rolling(
        hc, travel=1e-3, step=2.5e-4, mu=0.4, elements=6, frames=3, Fx=1500.0,
        Fn=lambda x: 1e4 + 2e3 * np.sin(2 * np.pi * x / 2e-3))
    assert res.xi == pytest.approx(ref.xi, rel=1e-9)
    assert res.Fn == pytest.approx(1e4 + 2e3 * np.sin(2 * np.pi * res.x / 2e-3), rel=1e-6)


@pytest.mark.parametrize("extra, match", [
    ("Fx = 1500.0\nstep2 = 1", r"\[transient\]: unknown key\(s\) 'step2'"),
    ('Fx = {kind = "ramp", a = 1}', r"\[transient\] Fx: kind must"),
    ("xi = -1e-4\nfriction = 'regularised'", r"\[transient\] epsilon: missing"),
    ("Fx = 1500.0\nxi = -1e-4", r"\[transient\] xi: with Fx"),
    ("", "give Fx"),
    ("Fx = 1.0\nmargin = 0.5", r"\[transient\] margin: must be > 1, got 0.5"),
    ("Fx = 1.0\nscheme = 'upwind3'", r"\[transient\] scheme: must be one of .*'upwind2'"),
])
def test_bad_case_names_table_key_and_value(extra, match):
    with pytest.raises(wr.CaseFileError, match=match):
        load_transient_case(CASE.format(extra=extra))


def test_cli_writes_netcdf_and_figures(tmp_path, capsys):
    import xarray as xr

    path = tmp_path / "case.toml"
    path.write_text(CASE.format(extra='Fx = {kind = "table", x = [0.0, 1e-3], '
                                      'value = [500.0, 1500.0]}'))
    out = tmp_path / "out"
    assert main(["transient", str(path), "--out", str(out), "--no-progress"]) == 0
    ds = xr.open_dataset(out / "history.nc")
    assert ds.Fx.values[1:] == pytest.approx(500.0 + 1e6 * ds.x.values[1:], rel=1e-6)
    ds.close()
    assert json.loads((out / "summary.json").read_text())["steps"] == 4
    for name in ("fields.nc", "creepage.png", "centreline.png", "state.png"):
        assert (out / name).stat().st_size > 0
    bad = tmp_path / "bad.toml"
    bad.write_text(CASE.format(extra="Fn = -5.0\nFx = 1.0"))
    assert main(["transient", str(bad), "--out", str(out)]) == 2
    assert "Fn(x = 0.0 m) = -5.0 N must be > 0" in capsys.readouterr().err


def test_case_file_chooses_the_second_order_scheme():
    case = load_transient_case(CASE.format(extra="Fx = 1500.0\nscheme = 'upwind2'"))
    assert case.settings["scheme"] == "upwind2"
