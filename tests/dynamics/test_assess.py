"""Running-safety assessment: filters, sliding means and Sperling's index on signals with known
answers, and :func:`assess` on a short simulation against the same quantities computed here
independently (EN 14363:2016; Prud'homme 1967; Sperling 1941 in the form of Garg & Dukkipati
1984)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import butter, lfilter, lfilter_zi

import wheelrail as wr
from wheelrail.errors import InputError

D = wr.dynamics
FS = 1000.0


def amplitude(y, f, fs, skip):
    """Amplitude and phase of the f-component of y[skip:] (least squares on sin, cos)."""
    t = np.arange(y.size)[skip:] / fs
    A = np.column_stack([np.sin(2 * np.pi * f * t), np.cos(2 * np.pi * f * t)])
    (a, b), *_ = np.linalg.lstsq(A, y[skip:], rcond=None)
    return np.hypot(a, b), np.arctan2(b, a)


def warped(f, fs):
    """Bilinear-transform frequency Ω = 2 fs tan(π f / fs) (pre-warped edges)."""
    return 2 * fs * np.tan(np.pi * f / fs)


@pytest.mark.parametrize("f", [2.0, 10.0, 20.0, 30.0, 60.0])
def test_lowpass_gain_is_butterworths(f):
    t = np.arange(0, 4.0, 1 / FS)
    x = np.sin(2 * np.pi * f * t)
    order, fc = 4, 20.0
    g = 1 / np.sqrt(1 + (warped(f, FS) / warped(fc, FS)) ** (2 * order))   # Butterworth
    amp, _ = amplitude(D.lowpass(x, FS, fc, order), f, FS, 2000)
    assert amp == pytest.approx(g, rel=2e-3, abs=1e-5)
    # zero phase: gain squared and no phase shift
    zp = D.lowpass(x, FS, fc, order, zero_phase=True)[:3000]     # away from both ends
    amp2, ph = amplitude(zp, f, FS, 1000)
    assert amp2 == pytest.approx(g * g, rel=2e-3, abs=1e-5)
    assert abs(ph) < 1e-3          # (the causal filter: about -1 rad here)


def test_lowpass_passes_a_constant_without_a_start_transient():
    x = np.full((500, 2, 2), 40e3)
    np.testing.assert_allclose(D.lowpass(x, FS, 20.0), 40e3, rtol=1e-12)
    with pytest.raises(InputError, match="fs/2"):
        D.lowpass(x, 30.0, 20.0)


@pytest.mark.parametrize("f", [0.1, 0.4, 2.0, 10.0, 25.0])
def test_bandpass_gain_is_butterworths(f):
    t = np.arange(0, 60.0, 1 / 200.0)
    x = np.sin(2 * np.pi * f * t)
    lo, hi, n, fs = 0.4, 10.0, 4, 200.0
    W, Wl, Wh = warped(f, fs), warped(lo, fs), warped(hi, fs)
    g = 1 / np.sqrt(1 + ((W ** 2 - Wl * Wh) / (W * (Wh - Wl))) ** (2 * n))
    amp, _ = amplitude(D.bandpass(x, fs, lo, hi, n), f, fs, int(30 * fs))
    assert amp == pytest.approx(g, rel=5e-3, abs=1e-4)
    if f in (0.4, 10.0):
        assert amp == pytest.approx(2 ** -0.5, rel=5e-3)       # −3 dB at the edges
    np.testing.assert_allclose(D.bandpass(np.full(400, 3.0), fs, lo, hi), 0.0, atol=1e-9)


def test_sliding_mean_of_constant_sine_and_step():
    s = np.arange(0.0, 30.0 + 1e-9, 0.1)
    c, m = D.sliding_mean(np.full_like(s, 7.0), s, 2.0, 0.5)
    assert c[0] == pytest.approx(1.0) and c[-1] == pytest.approx(29.0) and c.size == 57
    np.testing.assert_allclose(m, 7.0, rtol=1e-13)
    # a sine of wavelength = window averages to zero (up to the linear interpolation)
    _, m = D.sliding_mean(np.sin(2 * np.pi * s / 2.0), s, 2.0, 0.5)
    np.testing.assert_allclose(m, 0.0, atol=2e-3)
    # a step at 10 m, sampled every 0.1 m (its interpolant ramps over 9.9-10.0 m)
    x = (s >= 10.0 - 1e-9).astype(float)
    c, m = D.sliding_mean(x, s, 2.0, 0.05)

    def G(u):            # ∫_{-inf}^{u} of the interpolant, written out
        return np.where(u <= 9.9, 0.0, np.where(u <= 10.0, (u - 9.9) ** 2 / 0.2,
                                                0.05 + (u - 10.0)))
    np.testing.assert_allclose(m, (G(c + 1.0) - G(c - 1.0)) / 2.0, atol=1e-12)
    assert m[c <= 8.9].max() == 0.0 and np.allclose(m[c >= 11.0], 1.0, rtol=1e-12)


def test_sliding_mean_of_a_rectangular_pulse_at_varying_spacing():
    # samples at a varying spacing (a speed ramp), a 0.5 m pulse of 3.0 from 20 m
    u = np.linspace(0.0, 1.0, 4001)
    s = 40.0 * u ** 1.5
    x = np.where((s >= 20.0) & (s <= 20.5), 3.0, 0.0)
    c, m = D.sliding_mean(x, s, 2.0, 0.01)
    h = np.max(np.diff(s)[(s[:-1] > 19) & (s[:-1] < 21.5)])
    # the largest 2 m mean: 3 x 0.5/2 = 0.75, within the interpolant's edge ramps
    assert m.max() == pytest.approx(0.75, abs=3.0 * h / 2.0)
    assert np.all(m[np.abs(c - 20.25) > 1.30] == 0.0)
    with pytest.raises(InputError, match="less than the window"):
        D.sliding_mean(x[:10], s[:10], 2.0)
    with pytest.raises(InputError, match="increasing"):
        D.sliding_mean(x, s[::-1], 2.0)


def test_sperling_index_of_sines():
    fs = 200.0
    t = np.arange(0, 10.0, 1 / fs)                 # whole periods of 1, 3 and 8 Hz
    # vertical, 0.5 m/s² = 50 cm/s² at 1 Hz: F = 0.325 f² = 0.325
    wz = 0.896 * (50.0 ** 3 * 0.325 / 1.0) ** 0.1
    assert D.sperling_wz(0.5 * np.sin(2 * np.pi * t), fs) == pytest.approx(wz, rel=1e-10)
    assert wz == pytest.approx(2.5893, abs=1e-4)
    # lateral, 0.3 m/s² at 8 Hz: F = 650/f² (5.4-26 Hz)
    wl = 0.896 * (30.0 ** 3 * (650.0 / 64.0) / 8.0) ** 0.1
    a8 = 0.3 * np.cos(2 * np.pi * 8 * t)
    assert D.sperling_wz(a8, fs, "lateral") == pytest.approx(wl, rel=1e-10)
    # two components: Wz = (Wz1^10 + Wz2^10)^(1/10); lateral 3 Hz: F = 0.8 f²
    w3 = 0.896 * (20.0 ** 3 * 0.8 * 9.0 / 3.0) ** 0.1
    both = D.sperling_wz(a8 + 0.2 * np.sin(2 * np.pi * 3 * t), fs, "lateral")
    assert both == pytest.approx((wl ** 10 + w3 ** 10) ** 0.1, rel=1e-10)
    # a constant (or a component below 0.5 Hz) does not count
    assert D.sperling_wz(np.full(t.size, 2.0) + 0.5 * np.sin(2 * np.pi * t), fs) == \
        pytest.approx(wz, rel=1e-10)
    np.testing.assert_allclose(D.sperling_weighting([5.9, 20.0, 40.0]),
                               [0.325 * 5.9 ** 2, 1.0, 1.0])


# --------------------------------------------------------------------------- assess
@pytest.fixture(scope="module")
def run():
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0), axle_load=80e3,
                            primary=D.Suspension(kx=1e6, ky=1e6, half_spacing=1.0))
    irr = D.TrackIrregularity.from_psd("erri-high", 40.0, 11, start=-2.0, ramp=3.0)
    layout = D.TrackLayout(tr, irregularity=irr)
    return D.simulate(model, layout, 20.0, 1.0, "hertz", "fastsim", output_step=1e-3)


def test_assess_against_an_independent_evaluation(run):
    a = D.assess(run)
    ds = run.dataset
    t = ds["time"].values
    pos = ds["position"].values
    b, c = butter(4, 20.0, fs=1000.0)              # transfer-function form, lfilter
    def filt(x):
        return np.apply_along_axis(lambda v: lfilter(b, c, v, zi=lfilter_zi(b, c) * v[0])[0],
                                   0, x)
    sumY = filt(-(ds["wheel_Fy"].values[:, 0, 0] + ds["wheel_Fy"].values[:, 0, 1]))
    Y = filt(ds["lateral_force"].values[:, 0])
    Q = filt(ds["vertical_load"].values[:, 0])
    yq = Y / Q
    centres = a["distance"].values
    assert centres[0] == pytest.approx(pos[0] + 1.0) and np.allclose(np.diff(centres), 0.5)
    fine = np.linspace(pos[0], pos[-1], 200001)

    def boxcar(x):          # the 2 m mean by brute force on a fine grid
        xf = np.interp(fine, pos, x)
        return np.array([np.trapezoid(xf[(fine >= c0 - 1) & (fine <= c0 + 1)],
                                      fine[(fine >= c0 - 1) & (fine <= c0 + 1)]) / 2.0
                         for c0 in centres])
    np.testing.assert_allclose(a["sum_Y_2m"].values[:, 0], boxcar(sumY), rtol=1e-4, atol=0.5)
    for k in range(2):
        np.testing.assert_allclose(a["Y_over_Q_2m"].values[:, 0, k], boxcar(yq[:, k]),
                                   rtol=1e-4, atol=1e-5)
    # Prud'homme: 10 kN + P0/3 with the model's 80 kN axle load
    assert float(a["sum_Y_limit"][0]) == pytest.approx(10e3 + 80e3 / 3)
    assert bool(a["sum_Y_ok"][0]) and bool(a["Y_over_Q_ok"].all())
    assert float(a["sum_Y_2m_max"][0]) == pytest.approx(np.max(np.abs(boxcar(sumY))), rel=1e-4)
    np.testing.assert_allclose(a["Q_max"].values[0], Q.max(axis=0), rtol=1e-9)
    np.testing.assert_allclose(a["Y_max"].values[0], np.abs(Y).max(axis=0), rtol=1e-9)
    np.testing.assert_allclose(a["wear_number_mean"].values,
                               ds["wear_number"].values.mean(axis=0), rtol=1e-12)
    # the irregular track loads the wheels: Q varies by more than 1 % of the static 40 kN
    assert float(a["Q_max"].max()) > 40.4e3 and float(a["Q_min"].min()) < 39.6e3
    assert a.attrs["car_body"].startswith("not in the result")
    assert t.size == run.t.size
    with pytest.raises(InputError, match="SimulationResult"):
        D.assess(np.zeros(3))


def test_assess_uses_car_body_channels_when_present(run):
    ds = run.dataset
    t = ds["time"].values
    vy = 0.01 * np.sin(2 * np.pi * 1.5 * t)            # body lateral velocity [m/s]
    vz = 0.004 * np.sin(2 * np.pi * 4.0 * t)
    with_body = ds.assign(body_vy=("time", vy), body_vz=("time", vz))
    a = D.assess(with_body, axle_load=80e3)
    ay = np.gradient(vy, t[1] - t[0])
    az = np.gradient(vz, t[1] - t[0])
    assert float(a["sperling_lateral"]) == pytest.approx(D.sperling_wz(ay, 1000.0, "lateral"))
    assert float(a["sperling_vertical"]) == pytest.approx(D.sperling_wz(az, 1000.0))
    # the band-pass 0.4-10 Hz of the accelerations (the filter is tested above); 4 Hz lies in
    # the band: over this 1 s record (with the 0.4 Hz edge's start-up) the r.m.s. is within
    # 10 % of the sine's 0.004 (2π 4)/√2
    fz = D.bandpass(az, 1000.0, 0.4, 10.0)
    assert float(a["body_vertical_acc_rms"]) == pytest.approx(np.sqrt(np.mean(fz ** 2)))
    assert float(a["body_vertical_acc_rms"]) == pytest.approx(0.004 * 8 * np.pi / np.sqrt(2),
                                                              rel=0.10)
    assert float(a["body_lateral_acc_max"]) == pytest.approx(
        np.max(np.abs(D.bandpass(ay, 1000.0, 0.4, 10.0))))
    assert a.attrs["car_body"] == "assessed"


def test_assess_resamples_uneven_output_times(run):
    ds = run.dataset
    n = ds.sizes["time"]
    uneven = ds.isel(time=np.r_[0:400, 401:n])          # one output missing
    a, b = D.assess(ds, axle_load=80e3), D.assess(uneven, axle_load=80e3)
    assert float(b["sum_Y_2m_max"][0]) == pytest.approx(float(a["sum_Y_2m_max"][0]), rel=0.01)
    assert b.attrs["sampling_rate_Hz"] == pytest.approx(1000.0)
    assert b.attrs["axle_load_source"] == "given"
