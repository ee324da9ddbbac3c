"""Profile file readers/writers: every shared file reads, conventions, errors, round trips."""

import warnings

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.errors import ProfileError
from wheelrail.profiles import ProfileWarning
from wheelrail.profiles.io import detect_format

MM = 1e-3

EXPECTED = {  # file -> (format, kind)
    "MBench_S1002_v3.prw": ("simpack", "wheel"),
    "MBench_UIC60_v3.prr": ("simpack", "rail"),
    "MBench_UIC60_v3.ban": ("miniprof", "rail"),
    "avg_HR.BAN": ("miniprof", "rail"),
    "avg_wheel.whl": ("miniprof", "wheel"),
    "circ_r100.prw": ("simpack", "wheel"),
    "circ_r300.prr": ("simpack", "rail"),
    "flat_plane.prr": ("simpack", "rail"),
    "site_b_hr.prr": ("simpack", "rail"),
    "uic60_true.prr": ("simpack", "rail"),
    "worn_high_mileage.prw": ("simpack", "wheel"),
}


def _read(path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ProfileWarning)
        return wr.profiles.read(path, **kw)


def test_every_shared_file_reads(shared_profiles):
    files = sorted(p.name for p in shared_profiles.iterdir() if p.name != "NOTICE")
    assert set(files) == set(EXPECTED)
    for fname in files:
        fmt, kind = EXPECTED[fname]
        assert detect_format(shared_profiles / fname) == fmt
        p = _read(shared_profiles / fname)
        assert p.kind == kind and p.meta["format"] == fmt
        assert np.all(np.diff(p.y) > 0) and p.width < 0.5 and len(p) >= 100


def test_rail_files_are_z_up_with_crown_on_top(shared_profiles):
    for fname in ("MBench_UIC60_v3.prr", "MBench_UIC60_v3.ban", "avg_HR.BAN", "site_b_hr.prr",
                  "uic60_true.prr", "circ_r300.prr"):
        p = _read(shared_profiles / fname)
        i = np.argmax(p.z)
        assert abs(p.z[i]) < 0.5 * MM, fname             # top of rail at z ~ 0
        assert p.y_min < p.y[i] < p.y_max, fname          # crown in the interior
        assert p.z[0] < -0.1 * MM or p.z[-1] < -0.1 * MM, fname


def test_circle_files_have_the_stated_radius(shared_profiles):
    r300 = _read(shared_profiles / "circ_r300.prr")
    assert r300.curvature(0.0) == pytest.approx(-1 / 0.300, rel=1e-3)  # crown: z'' < 0
    r100 = _read(shared_profiles / "circ_r100.prw")
    y = np.array([-0.03, -0.01, 0.01, 0.03])
    np.testing.assert_allclose(r100.curvature(y), 1 / 0.100, rtol=5e-2)  # wheel lower boundary
    assert r100(0.0) == pytest.approx(0.0, abs=1e-9)
    # the file's z values near y = 0 carry 1e-6 mm rounding noise: the interpolating spline
    # shows it in z'' (about -11.5 1/m at y = 0); a 0.5 mm smoothing spline removes it
    assert r100.curvature(0.0) < 0
    smooth = _read(shared_profiles / "circ_r100.prw", smoothing=0.5e-3)
    np.testing.assert_allclose(smooth.curvature(np.r_[y, 0.0]), 1 / 0.100, rtol=3e-3)


def test_wheel_files_follow_wheel_convention(shared_profiles):
    s = _read(shared_profiles / "MBench_S1002_v3.prw")   # mirror.y/inversion applied, z negated
    assert s(0.0) == pytest.approx(0.0, abs=1e-6)
    assert s.y[np.argmin(s.z)] == pytest.approx(-55 * MM, abs=1 * MM)
    assert s.z.min() == pytest.approx(-28 * MM, abs=0.01 * MM)
    w = _read(shared_profiles / "avg_wheel.whl")           # MiniProf: origin moved to tape circle
    assert w.meta["origin_shift"][0] == pytest.approx(0.070)
    assert w(0.0) == pytest.approx(0.0, abs=1e-3 * MM)
    assert -60 * MM < w.y[np.argmin(w.z)] < -50 * MM      # flange on the negative side
    assert w.z.min() == pytest.approx(-28 * MM, abs=1 * MM)
    h = _read(shared_profiles / "worn_high_mileage.prw")   # flange near the low-y end
    assert h.y[np.argmin(h.z)] < h.y_min + 0.03


def test_single_valued_part_kept_with_warning(shared_profiles):
    with pytest.warns(ProfileWarning, match="single-valued"):
        p = wr.profiles.read(shared_profiles / "site_b_hr.prr")
    assert p.meta["n_foldback"] > 0


def test_commented_points_are_ignored(shared_profiles):
    p = _read(shared_profiles / "circ_r300.prr")           # '%' lines switch points off
    assert p.y_min == pytest.approx(-0.2121)
    s = _read(shared_profiles / "MBench_S1002_v3.prw")     # '!' comment hides the flange back
    assert s.y_min == pytest.approx(-69.612628 * MM)


def test_kind_override_and_guess(tmp_path, shared_profiles):
    p = _read(shared_profiles / "flat_plane.prr", kind="wheel")
    assert p.kind == "wheel"
    f = tmp_path / "noext.csv"
    f.write_text("0,0\n0.01,0.001\n0.02,0.002\n0.03,0.004\n")
    with pytest.raises(ProfileError, match="kind"):
        wr.profiles.read(f)
    assert _read(f, kind="rail").kind == "rail"


@pytest.mark.parametrize("content, units", [
    ("y,z\n-20,-1\n-10,-0.2\n0,0\n10,-0.2\n20,-1\n", "mm"),
    ("# units: m\n-0.02;-0,001\n-0.01;-0,0002\n0;0\n0.01;-0,0002\n0.02;-0,001\n", "m"),
    ("-0.02\t-0.001\n-0.01\t-0.0002\n0\t0\n0.01\t-0.0002\n0.02\t-0.001\n", "m"),
    ("y [mm]  z [mm]\n-20 -1 7\n-10 -0.2 7\n0 0 7\n10 -0.2 7\n20 -1 7\n", "mm"),
])
def test_text_delimiters_and_units(tmp_path, content, units):
    f = tmp_path / "p.txt"
    f.write_text(content)
    p = _read(f, kind="rail")
    assert p.meta["units"] == units
    assert p(0.02) == pytest.approx(-1 * MM) and p(-0.01) == pytest.approx(-0.2 * MM)


def test_text_unit_guess_warns(tmp_path):
    f = tmp_path / "p.csv"
    f.write_text("-20,-1\n-10,-0.2\n0,0\n10,-0.2\n20,-1\n")
    with pytest.warns(ProfileWarning, match="assuming mm"):
        p = wr.profiles.read(f, kind="rail")
    assert p.width == pytest.approx(0.040)


@pytest.mark.parametrize("fmt, ext", [("text", ".csv"), ("simpack", ".prw")])
def test_write_read_round_trip(tmp_path, fmt, ext):
    s = wr.profiles.load("S1002")
    f = tmp_path / f"s1002{ext}"
    wr.profiles.write(s, f)
    back = wr.profiles.read(f)
    assert back.kind == "wheel" and back.meta["format"] == fmt
    np.testing.assert_allclose(back.y, s.y, atol=1e-12)
    np.testing.assert_allclose(back.z, s.z, atol=1e-12)


def test_write_rail_simpack_round_trip(tmp_path):
    r = wr.profiles.load("60E1").rotated(np.arctan(1 / 40))
    f = tmp_path / "rail.prr"
    wr.profiles.write(r, f, fmt="simpack")
    back = wr.profiles.read(f)
    np.testing.assert_allclose(back.z, r.z, atol=1e-12)


def _write(tmp_path, name, text):
    f = tmp_path / name
    f.write_text(text)
    return f


SIMPACK_OK = ("header.begin\n type = 0\nheader.end\nspline.begin\n units.len.f = 1000.\n"
              " point.begin\n-20 1\n-10 0.2\n0 0\n10 0.2\n20 1\n point.end\nspline.end\n")


@pytest.mark.parametrize("text, match", [
    (SIMPACK_OK.replace("10 0.2\n20", "10 0.2\n20 abc\n20"), r"line 11: .*not a number"),
    (SIMPACK_OK.replace("0 0\n", "0 0 1 2\n"), r"line 9: expected 'y z \[weight\]'"),
    (SIMPACK_OK.replace(" point.end\n", ""), "unterminated|without matching"),
    (SIMPACK_OK.replace("-10 0.2", "-10 nan"), r"line 8: .*not finite"),
    (SIMPACK_OK.replace("type = 0", "type = 7"), "type must be 0"),
    (SIMPACK_OK.replace("units.len.f = 1000.", "units.len.f = -1"), "units.len.f"),
    (SIMPACK_OK.replace("-10 0.2\n0 0\n10 0.2\n", ""), "at least 4"),
    (SIMPACK_OK.replace("header.begin", "bogus.begin"), "line 1: unknown section"),
    ("header.begin\nheader.end\n", "no 'point.begin'"),
])
def test_malformed_simpack_names_file_and_line(tmp_path, text, match):
    f = _write(tmp_path, "bad.prr", text)
    with pytest.raises(ProfileError, match=match) as exc:
        wr.profiles.read(f)
    assert "bad.prr" in str(exc.value)


def test_simpack_processing_keys(tmp_path):
    text = SIMPACK_OK.replace(" units.len.f = 1000.\n",
                              " units.len.f = 1000.\n shift.z = 5\n mirror.y = 1\n")
    p = wr.profiles.read(_write(tmp_path, "s.prr", text))
    assert p(0.0) == pytest.approx(-5 * MM)  # z downward in the file, shifted by +5 mm


def test_malformed_miniprof_and_text(tmp_path):
    f = _write(tmp_path, "bad.ban", "ColumnDef=X,Y\n\n1 2\n3 4\n5\n7 8\n")
    with pytest.raises(ProfileError, match=r"bad.ban, line 5: .*columns"):
        wr.profiles.read(f)
    f = _write(tmp_path, "bad2.ban", "ColumnDef=A,B\n\n1 2\n3 4\n5 6\n7 8\n")
    with pytest.raises(ProfileError, match="ColumnDef"):
        wr.profiles.read(f)
    f = _write(tmp_path, "bad.csv", "# kind: rail\ny,z\n0,0\n1,x\n2,0\n3,0\n")
    with pytest.raises(ProfileError, match=r"bad.csv, line 4"):
        wr.profiles.read(f)


def test_closed_contour_is_refused(tmp_path):
    t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    rows = "\n".join(f"{30 * np.cos(a):.6f},{30 * np.sin(a):.6f}" for a in t)
    f = _write(tmp_path, "closed.csv", "# kind: rail\n# units: mm\n" + rows + "\n")
    with pytest.raises(ProfileError, match="not single-valued"):
        wr.profiles.read(f)


def test_missing_binary_and_bad_options(tmp_path):
    with pytest.raises(ProfileError, match="cannot read"):
        wr.profiles.read(tmp_path / "missing.prr")
    f = tmp_path / "bin.prr"
    f.write_bytes(b"\x00\x01\x02" * 100)
    with pytest.raises(ProfileError, match="binary"):
        wr.profiles.read(f)
    g = _write(tmp_path, "ok.prr", SIMPACK_OK)
    with pytest.raises(ProfileError, match="invalid option"):
        wr.profiles.read(g, bogus=1)
    with pytest.raises(ProfileError, match="unknown profile format"):
        wr.profiles.read(g, fmt="vampire")


def test_load_takes_a_name_or_a_file(tmp_path):
    """``wr.profiles.load`` reads a file given by path (as ``read``) and says what it looked for."""
    import wheelrail as wr
    from wheelrail.errors import ProfileError

    s1002 = wr.profiles.load("s1002")
    path = tmp_path / "s1002.csv"
    wr.profiles.write(s1002, path)
    again = wr.profiles.load(path, kind="wheel")
    assert again.kind == "wheel"
    np.testing.assert_allclose(again.z, s1002.z, atol=1e-9)
    with pytest.raises(ProfileError, match="neither a built-in profile.*S1002.*nor an existing"):
        wr.profiles.load(tmp_path / "missing.whl")


def test_old_style_miniprof_without_a_blank_line_after_the_header(tmp_path):
    """Old-style MiniProf files whose header is followed directly by the data rows (seen in
    the field) read like those with the blank line: the same points."""
    import wheelrail as wr

    rows = "\n".join(f"{x:.1f} {max(0.0, 28.0 - 0.9 * x) + 0.01 * x:.3f}" for x in range(0, 131, 5))
    with_blank = tmp_path / "a.whl"
    without = tmp_path / "b.whl"
    with_blank.write_text("MINIPROF wheel\nSerial 1234\n\n" + rows + "\n")
    without.write_text("Miniprof wheel\nSerial 1234\n" + rows + "\n")
    a = wr.profiles.read(with_blank)
    b = wr.profiles.read(without)
    np.testing.assert_array_equal(a.y, b.y)
    np.testing.assert_array_equal(a.z, b.z)
