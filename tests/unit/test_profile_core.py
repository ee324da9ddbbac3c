"""Unit tests of wheelrail.profiles.Profile (construction checks, evaluation, copies)."""

import warnings

import numpy as np
import pytest

from wheelrail.errors import ProfileError
from wheelrail.profiles import Profile, ProfileWarning


def circle(R=0.3, half=0.03, n=121, kind="rail"):
    """Crowned head z = sqrt(R^2 - y^2) - R: curvature is exactly -1/R."""
    y = np.linspace(-half, half, n)
    return Profile(y, np.sqrt(R * R - y * y) - R, kind=kind, name="circle")


def test_evaluation_matches_closed_form_circle():
    p = circle()
    yq = np.linspace(-0.025, 0.025, 37)
    R = 0.3
    np.testing.assert_allclose(p(yq), np.sqrt(R * R - yq * yq) - R, atol=1e-10)
    np.testing.assert_allclose(p.slope(yq), -yq / np.sqrt(R * R - yq * yq), atol=1e-7)
    np.testing.assert_allclose(p.curvature(yq), -1.0 / R, rtol=1e-4)


def test_scalar_in_scalar_out_and_nan_outside():
    p = circle()
    assert isinstance(p(0.0), float)
    assert np.isnan(p(0.031)) and np.isnan(p.slope(-1.0)) and np.isnan(p.curvature(0.5))
    assert p.contains(0.0) and not p.contains(0.04)
    assert p.y_min == pytest.approx(-0.03) and p.y_max == pytest.approx(0.03)
    assert p.width == pytest.approx(0.06)


def test_decreasing_input_is_reversed():
    y = np.linspace(0.02, -0.02, 11)
    p = Profile(y, y ** 2, kind="wheel")
    assert np.all(np.diff(p.y) > 0)
    assert p(0.01) == pytest.approx(1e-4)


def test_arrays_are_read_only_and_copied():
    y = np.linspace(0, 0.05, 10)
    z = np.zeros(10)
    p = Profile(y, z)
    y[0] = 5.0
    assert p.y[0] == 0.0
    with pytest.raises(ValueError):
        p.y[0] = 1.0


@pytest.mark.parametrize("y, z, match", [
    ([0, 0.01, np.nan, 0.03, 0.04], [0, 0, 0, 0, 0], "not finite"),
    ([0, 0.01, 0.02], [0, 0, 0], "at least 4"),
    ([0.01] * 5, [0, 1e-3, 2e-3, 3e-3, 4e-3], "zero width"),
    ([0, 10, 20, 30, 40], [0, 1, 2, 1, 0], "looks like mm"),
    ([0, 0.01, 0.02, 0.015, 0.03], [0, 0, 0, 0, 0], "reversal"),
    ([0, 0.01, 0.01, 0.02, 0.03], [0, 0, 0.001, 0, 0], "vertical segment"),
    ([0, 0.01, 0.02, 0.03], [0, 0, 0], "different lengths"),
    ([[0, 1], [2, 3]], [[0, 1], [2, 3]], "one-dimensional"),
    (["a", "b", "c", "d"], [0, 0, 0, 0], "numeric"),
])
def test_invalid_points_raise(y, z, match):
    with pytest.raises(ProfileError, match=match):
        Profile(y, z)


def test_self_crossing_contour_is_rejected():
    t = np.linspace(0, 2 * np.pi, 40)
    with pytest.raises(ProfileError, match="looks like mm|reversal"):
        Profile(0.01 * np.cos(t), 0.01 * np.sin(t))
    with pytest.raises(ProfileError, match="reversal"):
        Profile(0.01 * np.cos(t[:30]), 0.01 * np.sin(t[:30]))


def test_duplicates_removed_with_warning():
    y = [0.0, 0.01, 0.01, 0.02, 0.03, 0.04]
    z = [0.0, 0.001, 0.001, 0.0, 0.0, 0.0]
    with pytest.warns(ProfileWarning, match="duplicated"):
        p = Profile(y, z)
    assert len(p) == 5


def test_bad_kind_and_smoothing():
    y = np.linspace(0, 0.05, 10)
    with pytest.raises(ProfileError, match="kind"):
        Profile(y, 0 * y, kind="axle")
    with pytest.raises(ProfileError, match="smoothing"):
        Profile(y, 0 * y, smoothing=-1.0)


def test_mirrored_shifted_rotated():
    p = circle(R=0.08, half=0.02, n=81)
    m = p.mirrored()
    np.testing.assert_allclose(m(-0.013), p(0.013), atol=1e-12)
    assert m.mirrored() == p
    s = p.shifted(dy=0.002, dz=-0.001)
    np.testing.assert_allclose(s(0.012), p(0.010) - 0.001, atol=1e-12)
    # a flat line rotated by +a has slope tan(a) (counter-clockwise, documented cant sign)
    flat = Profile(np.linspace(-0.03, 0.03, 31), np.zeros(31))
    a = np.arctan(1 / 40)
    np.testing.assert_allclose(flat.rotated(a).slope([-0.01, 0.0, 0.01]), 1 / 40, atol=1e-12)
    # rotation about a point keeps that point; back-rotation restores the profile
    r = p.rotated(0.1, about=(0.0, 0.0))
    assert r(0.0) == pytest.approx(0.0, abs=1e-12)
    back = r.rotated(-0.1)
    np.testing.assert_allclose(back.y, p.y, atol=1e-15)
    np.testing.assert_allclose(back.z, p.z, atol=1e-15)


def test_rotation_past_vertical_raises():
    y = np.linspace(0, 0.01, 11)
    p = Profile(y, 200.0 * y * y)  # parabola, slope 0..4
    with pytest.raises(ProfileError, match="reversal|vertical"):
        p.rotated(np.pi / 2 - 0.2)


def test_resampled():
    p = circle()
    r = p.resampled(n=13)
    assert len(r) == 13 and r.y_min == p.y_min and r.y_max == p.y_max
    np.testing.assert_allclose(r.z, p(r.y), atol=1e-15)
    r2 = p.resampled(step=0.5e-3)
    assert len(r2) == 121
    with pytest.raises(ProfileError):
        p.resampled(n=2)
    with pytest.raises(ProfileError):
        p.resampled(step=0.0)


def test_smoothing_removes_short_wave_noise():
    rng = np.random.default_rng(1)
    y = np.linspace(-0.03, 0.03, 301)
    R = 0.3
    exact = np.sqrt(R * R - y * y) - R
    noisy = exact + 5e-6 * rng.standard_normal(y.size)
    raw = Profile(y, noisy)
    smooth = Profile(y, noisy, smoothing=2e-3)
    yq = np.linspace(-0.02, 0.02, 41)
    err_raw = np.max(np.abs(raw.curvature(yq) + 1 / R))
    err_smooth = np.max(np.abs(smooth.curvature(yq) + 1 / R))
    assert err_smooth < 0.2 * err_raw
    assert err_smooth < 1.0  # curvature error below 1/m for R = 0.3 m (3.33 1/m)


def test_equality_and_hash():
    a, b = circle(), circle()
    assert a == b and hash(a) == hash(b)
    assert a != a.shifted(dz=1e-9)


def test_no_warning_for_clean_profile():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        circle()
