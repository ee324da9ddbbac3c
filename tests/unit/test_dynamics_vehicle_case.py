"""Vehicle case files of ``wheelrail dynamics``: ``[model] kind = "vehicle"`` (built-in or key by
key), measured and generated ``[track.irregularity]``, and the assessment outputs."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.cli.dynamics import read_dynamics_case
from wheelrail.cli.main import main

D = wr.dynamics
EXAMPLE = Path(__file__).parents[2] / "docs" / "examples" / "dynamics_vehicle.toml"
WHEELSET_EXAMPLE = Path(__file__).parents[2] / "docs" / "examples" / "dynamics_wheelset.toml"

# A vehicle defined key by key: the Manchester vehicle 1 values (Iwnicki 1998) typed in, so
# that it must read equal to the built-in one.
EXPLICIT = """
[model]
kind = "vehicle"
mass = 1813.0
inertia = [1120.0, 112.0, 1120.0]
frame_mass = 2615.0
frame_inertia = [1722.0, 1476.0, 3067.0]
semi_wheelbase = 1.28
nominal_radius = 0.46
spin = "fixed"
bogie_semi_spacing = 9.5
frame_height = 0.6
primary_height = 0.46
[model.primary]
kx = 31.391e6
ky = 3.884e6
kz = 1.22e6
cx = 15e3
cy = 2e3
cz = 4e3
half_spacing = 1.0
[model.carbody]
mass = 32000.0
inertia = [56800.0, 1.97e6, 1.97e6]
height = 1.8
[model.secondary]
kx = 0.160e6
ky = 0.160e6
kz = 0.430e6
cy = 32e3
cz = 20e3
half_spacing = 1.0
height = 0.8275
yaw_stiffness = 10.5e3
anti_roll = 940e3
[model.secondary.bumpstop]
displacement = [0.025, 0.030, 0.035, 0.040, 0.045, 0.050, 0.055, 0.060, 0.065]
force = [0.0, 600.0, 1760.0, 3730.0, 6870.0, 11580.0, 17170.0, 29200.0, 230000.0]
[friction]
mu = 0.3
[simulation]
speed = 30.0
duration = 1.0
"""


def _write(tmp_path, text, name="case.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_builtin_vehicle_and_generated_irregularity_read():
    case = read_dynamics_case(EXAMPLE)
    model = case["model"]
    assert isinstance(model, D.VehicleModel) and model.n_wheelsets == 4
    assert model.carbody.mass == 32000.0 and model.spin == "fixed"
    irr = case["layout"].irregularity
    assert isinstance(irr, D.TrackIrregularity)
    # the seed makes the track: the same as generated through the API
    ref = D.TrackIrregularity.from_psd("erri-low", 300.0, 1)
    np.testing.assert_array_equal(irr.alignment, ref.alignment)
    np.testing.assert_array_equal(irr.gauge, ref.gauge)


def test_vehicle_key_by_key_equals_builtin(tmp_path):
    model = read_dynamics_case(_write(tmp_path, EXPLICIT))["model"]
    ref = D.manchester_vehicle1()
    assert model.axle_load == pytest.approx(ref.axle_load, rel=1e-12)
    assert model.secondary == ref.secondary
    assert model.carbody == ref.carbody
    assert model.bogies[0].primary == ref.bogies[0].primary
    assert model.bogie_semi_spacing == ref.bogie_semi_spacing


def test_measured_irregularity_file_relative_to_case(tmp_path):
    s = np.arange(0.0, 50.0, 0.25)
    data = np.column_stack([s, 2.0 * np.sin(s / 3), 1.0 * np.cos(s / 5), 0.5 * np.sin(s / 7),
                            0.3 * np.ones_like(s)])
    np.savetxt(tmp_path / "measured.csv", data, delimiter=",",
               header="distance_m,alignment_mm,level_mm,cross_level_mm,gauge_mm", comments="")
    text = WHEELSET_EXAMPLE.read_text() + (
        '\n[track.irregularity]\nkind = "file"\npath = "measured.csv"\n')
    irr = read_dynamics_case(_write(tmp_path, text))["layout"].irregularity
    np.testing.assert_allclose(irr.alignment, 2e-3 * np.sin(s / 3), atol=1e-12)   # mm -> m
    np.testing.assert_allclose(irr.gauge, 0.3e-3, atol=1e-12)


@pytest.mark.parametrize("text, match", [
    (EXAMPLE.read_text().replace('vehicle = "manchester1"', 'vehicle = "manchester2"'),
     r"\[model\] vehicle: must be one of manchester1, got 'manchester2'"),
    (EXAMPLE.read_text().replace('spin = "fixed"', 'spin = "fixed"\nmass = 1000.0'),
     r"\[model\] mass: cannot be combined with the built-in vehicle"),
    (EXAMPLE.read_text().replace('"erri-low"', '"erri-medium"'), r"\[track.irregularity\]"),
    (EXAMPLE.read_text().replace("seed = 1", "seed = -3"), r"\[track.irregularity\] seed"),
    (EXAMPLE.read_text().replace('kind = "psd"', 'kind = "file"\npath = "nowhere.csv"')
     .replace('spectrum = "erri-low"', "").replace("length = 300.0", "").replace("seed = 1", ""),
     r"nowhere.csv"),
    (WHEELSET_EXAMPLE.read_text().replace('kind = "wheelset"', 'kind = "wheelset"\n'
                                          'bogie_semi_spacing = 9.5'),
     r"\[model\] bogie_semi_spacing: belongs to a vehicle"),
    (EXPLICIT.replace("[model.carbody]", "[model.carbodyx]"), r"\[model\]: unknown"),
    (EXPLICIT.replace("mass = 32000.0", "mass = -32000.0"), r"\[model.carbody\] mass"),
    (EXPLICIT.replace("force = [0.0, 600.0", "force = [10.0, 600.0"),
     r"\[model.secondary.bumpstop\].*force must start at 0"),
])
def test_bad_vehicle_cases_name_table_and_key(tmp_path, text, match):
    case = _write(tmp_path, text)
    with pytest.raises(wr.WheelrailError, match=match):
        read_dynamics_case(case)
    assert main(["dynamics", str(case), "--out", str(tmp_path / "o"), "--no-progress"]) != 0


def test_cli_vehicle_run_writes_assessment(tmp_path):
    """A short run of the Manchester vehicle on straight track without irregularities: the
    assessment's wheel loads are the static share of the vehicle's weight, m g / 8
    (Iwnicki 1998 masses: 32 000 + 2 × 2615 + 4 × 1813 kg), and the sums of the lateral
    forces are small against Prud'homme's limit 10 kN + P0/3."""
    text = EXAMPLE.read_text()
    start = text.index("[[track.curves]]")
    text = text[:start] + text[text.index("[method]"):]
    out = tmp_path / "out"
    code = main(["dynamics", str(_write(tmp_path, text)), "--out", str(out), "--duration",
                 "0.3", "--no-progress"])
    assert code == 0
    for name in ("result.nc", "assessment.nc", "assessment.csv", "carbody.png",
                 "assessment.png"):
        assert (out / name).stat().st_size > 0
    rows = list(csv.DictReader((out / "assessment.csv").open()))
    assert len(rows) == 8
    wheel = (32000.0 + 2 * 2615.0 + 4 * 1813.0) * 9.81 / 8
    for row in rows:
        assert float(row["Q_max_N"]) == pytest.approx(wheel, rel=0.02)
        assert float(row["Q_min_N"]) == pytest.approx(wheel, rel=0.02)
        P0 = 2 * wheel
        assert float(row["sum_Y_limit_N"]) == pytest.approx(10e3 + P0 / 3, rel=1e-5)   # CSV: 6 digits
        assert abs(float(row["sum_Y_2m_max_N"])) < 0.05 * float(row["sum_Y_limit_N"])
    summary = json.loads((out / "summary.json").read_text())
    assert summary["assessment"]["Y_over_Q_2m_ok"] and summary["assessment"]["sum_Y_2m_ok"]
