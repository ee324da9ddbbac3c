"""Wrong units and absurd values that once passed.

The campaign: semi-axes ``a = 3.0, b = 2.3`` (mm given as m) solved a 3 m patch
"converged"; BEM ``element_size = 0.4`` gave a 0.16 m² patch, exit 0;
``elements = 2`` gave an area 59 % above Hertz without a warning; a
near-conformal pair (−0.3001 m on 0.3 m) a 131 mm wide Hertz patch; ξ = 1e6,
φ = 1e6 1/m, μ = 1e-9, a speed of 1e6 m/s and a 1 mm roller were accepted; a
CSV wheel with z down became an inverted wheel; a rail with a third of its
points cut out passed silently. Each case: one test, the message names the value.
"""

from __future__ import annotations

import numpy as np
import pytest
from _helpers import assert_clean_failure, run_cli, wheelset_case

import wheelrail as wr

CASE = """
[contact]
Fn = 7500.0
{contact}
[creepage]
{creepage}
[friction]
mu = {mu}
{method}
"""
RADII = "wheel_rolling_radius = 0.46\nrail_profile_radius = 0.30"


def _case(tmp_path, contact=RADII, creepage="xi = -0.001", mu=0.3,
          method="[method.fastsim]\nnx = 8\nny = 8"):
    p = tmp_path / "case.toml"
    p.write_text(CASE.format(contact=contact, creepage=creepage, mu=mu, method=method))
    return p


def _warnings(err):
    return [ln for ln in err if ln.startswith("wheelrail: warning: ")]


def test_semi_axes_in_mm_given_as_m_refused(tmp_path, capsys):
    code, _, err = run_cli(["solve", _case(tmp_path, contact="a = 3.0\nb = 2.3")], capsys)
    assert_clean_failure(code, err, "case.toml", "[contact] a", "3 m", "mm given as m")


def test_semi_axes_api_refused():
    from wheelrail.plausibility import ImplausibleInputError

    with pytest.raises(ImplausibleInputError, match="semi-axis a = 3 m"):
        wr.hertz_from_semiaxes(3.0, 2.3, 7500.0, wr.STEEL)


def test_bem_element_size_in_mm_refused_through_the_option(tmp_path, capsys):
    case = _case(tmp_path, method='[method]\nnormal = "bem"\n[method.bem]\nelement_size = 0.4')
    code, _, err = run_cli(["solve", case], capsys)
    assert_clean_failure(code, err, "case.toml", "element_size = 0.4 m", "mm given as m")


def test_option_declaration_carries_the_range():
    from wheelrail.normal.bem import Bem

    decl = Bem.option_declarations()["element_size"]
    assert decl.typical == (1e-6, 2e-3) and decl.plausible == (None, 0.05)


def test_plausibility_override_keeps_working(tmp_path, capsys):
    from wheelrail.normal.bem import Bem
    from wheelrail.plausibility import disabled

    with disabled():
        assert Bem(element_size=0.4).element_size == 0.4


@pytest.mark.parametrize("size", ["0.01", "0.004"])
def test_coarse_bem_grid_warns_area_and_elements(size, tmp_path, capsys):
    case = _case(tmp_path, method=f'[method]\nnormal = "bem"\n[method.bem]\nelement_size = {size}')
    code, _, err = run_cli(["--no-plausibility-checks", "solve", case, "-q"], capsys)
    assert code == 0, err
    text = " ".join(_warnings(err))
    assert "element(s) across the contact patch" in text
    assert "% from the Hertz area" in text


def test_two_grid_elements_warns(tmp_path, capsys):
    case = _case(tmp_path, method='[method]\nnormal = "bem"\n[method.bem]\ngrid_elements = 2')
    code, _, err = run_cli(["solve", case, "-q"], capsys)
    assert code == 0, err
    assert any("ResolutionWarning" in ln for ln in _warnings(err))


def test_fine_bem_grid_does_not_warn(tmp_path, capsys):
    """The warning can fail the other way: a converged grid (20 elements across) is quiet."""
    case = _case(tmp_path, method='[method]\nnormal = "bem"\n[method.bem]\ngrid_elements = 24')
    code, _, err = run_cli(["solve", case, "-q"], capsys)
    assert code == 0 and not _warnings(err), err


def test_near_conformal_hertz_warns_with_the_method_to_use(tmp_path, capsys):
    contact = RADII + "\nwheel_profile_radius = -0.3001"
    code, _, err = run_cli(["solve", _case(tmp_path, contact=contact), "-q"], capsys)
    assert code == 0, err
    text = " ".join(_warnings(err))
    assert "near-conformal" in text and "-0.3001" in text and "'bem'" in text


@pytest.mark.parametrize("creepage,names", [("xi = 1e6", ["[creepage] xi", "1e+06"]),
                                            ("eta = -3.0", ["[creepage] eta", "3"]),
                                            ("phi = 1e6", ["[creepage] phi", "1e+06", "1/m"])])
def test_absurd_creepages_refused(creepage, names, tmp_path, capsys):
    code, _, err = run_cli(["solve", _case(tmp_path, creepage=creepage)], capsys)
    assert_clean_failure(code, err, "case.toml", *names)


def test_tiny_friction_warns(tmp_path, capsys):
    code, _, err = run_cli(["solve", _case(tmp_path, mu="1e-9"), "-q"], capsys)
    assert code == 0, err
    assert any("mu = 1e-09" in ln for ln in _warnings(err))




@pytest.mark.parametrize("speed,extra,names", [
    ("1e6", "", ["speed = 1e+06 m/s"]),
    ("20.0", "roller_radius = 0.001", ["roller_radius = 0.001 m"]),
])
def test_absurd_motion_refused(speed, extra, names, tmp_path, capsys):
    p = tmp_path / "ws.toml"
    p.write_text(wheelset_case(speed=speed, motion=extra))
    code, _, err = run_cli(["wheelset", p, "--out", tmp_path / "o", "--no-plots"], capsys)
    assert_clean_failure(code, err, "ws.toml", *names)


def test_speed_in_kmh_warns():
    from wheelrail.geometry.kinematics import Motion
    from wheelrail.plausibility import PlausibilityWarning

    with pytest.warns(PlausibilityWarning, match="km/h given"):
        Motion(speed=300.0)


def test_csv_wheel_with_z_down_refused(tmp_path):
    from wheelrail.errors import ProfileError

    p = wr.profiles.load("S1002")
    f = tmp_path / "wheel.csv"
    np.savetxt(f, np.c_[p.y * 1e3, -p.z * 1e3], delimiter=",")
    with pytest.raises(ProfileError, match="wheel.csv: the wheel's flange points up.*z_down"):
        wr.profiles.read(f, kind="wheel", units="mm")
    prof = wr.profiles.read(f, kind="wheel", units="mm", z_down=True)  # the fix works
    assert prof.y_max - prof.y_min > 0.1


def test_csv_wheel_z_down_on_the_command_line(tmp_path, capsys):
    p = wr.profiles.load("S1002")
    f = tmp_path / "wheel.csv"
    np.savetxt(f, np.c_[p.y * 1e3, -p.z * 1e3], delimiter=",", header="units: mm")
    code, _, err = run_cli(["geometry", "--no-plots", "--points", "5", "--out", tmp_path / "o",
                            "--wheel", f], capsys)
    assert_clean_failure(code, err, "wheel.csv", "flange points up")


def test_rail_with_a_third_of_its_points_cut_out_is_refused(tmp_path):
    from wheelrail.errors import ProfileError
    from wheelrail.profiles.core import ProfileWarning

    r = wr.profiles.load("60E1")
    keep = np.ones(r.y.size, bool)
    keep[r.y.size // 3: 2 * r.y.size // 3] = False
    f = tmp_path / "rail.csv"
    np.savetxt(f, np.c_[r.y[keep] * 1e3, r.z[keep] * 1e3], delimiter=",")
    with pytest.raises(ProfileError, match=r"rail.csv, lines \d+–\d+: no rail profile points "
                                           r"between y = .*lenient"):
        wr.profiles.read(f, kind="rail", units="mm")
    with pytest.warns(ProfileWarning, match=r"rail.csv, lines \d+–\d+: no rail profile points "
                                            r"between y = "):
        wr.profiles.read(f, kind="rail", units="mm", lenient=True)


def test_intact_rail_csv_has_no_gap_warning(tmp_path, recwarn):
    r = wr.profiles.load("60E1")
    f = tmp_path / "rail.csv"
    np.savetxt(f, np.c_[r.y * 1e3, r.z * 1e3], delimiter=",")
    wr.profiles.read(f, kind="rail", units="mm")
    assert not [w for w in recwarn if "no rail profile points" in str(w.message)]


def test_coarse_exact_grid_warns_naming_the_option(tmp_path, capsys):
    """The exact theory's grid is checked as the BEM's (elements across the patch): a
    5-element grid warns naming the option 'elements' and its value; from a case file too."""
    from wheelrail.errors import ResolutionWarning

    hc = wr.hertz(7500.0, 0.5 / 0.46, 0.5 / 0.30, wr.STEEL)
    with pytest.warns(ResolutionWarning, match=r"elements = 5 .*only \d element\(s\) across"
                                               r".*option 'elements' of 'exact', now 5"):
        wr.creep_forces(hc, (-1e-3, 0.0, 0.0), 0.3, method="exact", elements=5)
    method = '[method]\ntangential = "exact"\n[method.exact]\nelements = 5'
    code, _, err = run_cli(["solve", _case(tmp_path, method=method), "-q"], capsys)
    assert code == 0, err
    assert any("option 'elements' of 'exact'" in ln for ln in _warnings(err))


def test_fine_exact_grid_does_not_warn():
    import warnings

    from wheelrail.errors import ResolutionWarning

    hc = wr.hertz(7500.0, 0.5 / 0.46, 0.5 / 0.30, wr.STEEL)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ResolutionWarning)
        wr.creep_forces(hc, (-1e-3, 0.0, 0.0), 0.3, method="exact", elements=12)


def test_polach_speed_in_kmh_refused_through_the_option(tmp_path, capsys):
    """Polach's speed is declared with the typical/plausible ranges (one mechanism):
    1e6 m/s is refused with the km/h hint, also from a case file."""
    from wheelrail.errors import OptionError
    from wheelrail.tangential.polach import Polach

    with pytest.raises(OptionError, match=r"speed = 1e\+06 m/s is not plausible .*mm/s given "
                                          r"as m/s\? 1e\+06 mm/s = 1000 m/s"):
        Polach(speed=1e6, A=0.4, B=0.6)
    method = '[method]\ntangential = "polach"\n[method.polach]\nspeed = 1e6\nA = 0.4\nB = 0.6'
    code, _, err = run_cli(["solve", _case(tmp_path, method=method)], capsys)
    assert_clean_failure(code, err, "case.toml", "speed = 1e+06 m/s", "mm/s given as m/s")


def test_polach_speed_arrays_and_kmh_warn():
    """300 m/s (300 km/h given?) warns; in an array the largest value is named."""
    from wheelrail.plausibility import PlausibilityWarning
    from wheelrail.tangential.polach import Polach

    with pytest.warns(PlausibilityWarning, match=r"speed = 300 m/s .*300 km/h = 83.33 m/s"):
        Polach(speed=300.0)
    with pytest.warns(PlausibilityWarning, match=r"speed = 250 m/s"):
        Polach(speed=np.array([20.0, 250.0, 30.0]))
    assert Polach(speed=np.array([20.0, 40.0])).speed.shape == (2,)  # usual: quiet


def test_polach_rate_declared():
    from wheelrail.plausibility import PlausibilityWarning
    from wheelrail.tangential.polach import Polach

    decl = Polach.option_declarations()
    assert decl["speed"].plausible == (None, 1000.0) and decl["B"].typical == (0.0, 5.0)
    with pytest.warns(PlausibilityWarning, match=r"B = 600 s/m .*s/km given as s/m"):
        Polach(speed=30.0, A=0.4, B=600.0)
