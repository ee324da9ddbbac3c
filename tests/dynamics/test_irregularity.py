"""Track irregularities: standard spectra, generation from them, files, and what the rails do.

References: ORE B176 / ERRI B176 spectra (high level tabulated by the GENSYS program
TRC_IPSD in m²/(1/m)); FRA spectra in the form of Garg & Dukkipati (1984), ch. 11.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import welch

import wheelrail as wr
from wheelrail.errors import InputError

D = wr.dynamics
CH = ("alignment", "level", "cross_level", "gauge")


# the spectra written out here again from the literature (independent of _spectra)
def erri(channel, w, level):
    Aa, Av, Ag = {"low": (2.119e-7, 4.032e-7, 5.32e-8),
                  "high": (6.125e-7, 1.080e-6, 1.032e-7)}[level]
    c, r, s = 0.8246, 0.0206, 0.4380
    b = 0.75                                   # half distance of the contact points [m]
    base = c**2 / ((w**2 + r**2) * (w**2 + c**2))
    if channel == "alignment":
        return Aa * base
    if channel == "level":
        return Av * base
    angle = Av / b**2 * base * w**2 / (w**2 + s**2)      # rad²/(rad/m)
    if channel == "cross_level":
        return (2 * b) ** 2 * angle                     # height difference 2b·angle
    return Ag * base * w**2 / (w**2 + s**2)


def fra(channel, w, cls):
    Av, Aa, Ws = {1: (1.2107, 3.3634, 0.6046), 4: (0.5376, 0.3027, 1.1312),
                  6: (0.0339, 0.0339, 0.4380)}[cls]
    k, c = 0.25, 0.8245
    cm2 = 1e-4
    if channel == "alignment":
        return k * Aa * cm2 * c**2 / (w**2 * (w**2 + c**2))
    if channel == "level":
        return k * Av * cm2 * c**2 / (w**2 * (w**2 + c**2))
    return 4 * k * Av * cm2 * c**2 / ((w**2 + c**2) * (w**2 + Ws**2))


def test_erri_high_level_matches_the_tabulated_ore_b176_values():
    # GENSYS TRC_IPSD, "ORE B176 high level", [m²/(1/m)] at f [1/m]: 2π S(Ω = 2π f)
    table = [(0.0200, 2.3194e-4, 4.0897e-4), (0.1000, 6.1608e-6, 1.0863e-5),
             (0.2000, 7.3333e-7, 1.2931e-6), (100.0, 1.6790e-17, 2.9605e-17)]
    sp = D.track_spectrum("erri-high")
    for f, lat, vert in table:
        w = 2 * np.pi * f
        assert 2 * np.pi * sp.psd("alignment", w) == pytest.approx(lat, rel=2e-4)
        assert 2 * np.pi * sp.psd("level", w) == pytest.approx(vert, rel=2e-4)


@pytest.mark.parametrize("name", ["erri-low", "erri-high", "fra-1", "fra-4", "fra-6"])
def test_spectra_constants(name):
    sp = D.track_spectrum(name)
    w = np.geomspace(0.02, 5.0, 50)
    ref = (lambda c: erri(c, w, name[5:])) if name.startswith("erri") else \
        (lambda c: fra(c, w, int(name[4:])))
    for c in CH:
        np.testing.assert_allclose(sp.psd(c, w), ref(c), rtol=1e-12)


@pytest.mark.parametrize("name", ["erri-low", "fra-4"])
def test_generated_psd_within_10_percent_of_the_spectrum(name):
    """Welch PSD of generated tracks, averaged over 16 seeds and over 12 log-spaced bands
    across the wavelength band, within 10 % of the spectrum (written out in this test)."""
    sp = D.track_spectrum(name)
    lo, hi = sp.band
    step = min(0.25, lo / 8)
    nper = int(2 ** np.ceil(np.log2(4 * hi / step)))
    acc = 0.0
    for seed in range(16):
        irr = D.TrackIrregularity.from_psd(name, 4 * nper * step, seed, ramp=0.0)
        assert irr.step == pytest.approx(step)
        f, P = welch(irr.samples, fs=1 / step, nperseg=nper, axis=-1)
        acc = acc + P
    P = acc / 16 / (2 * np.pi)             # per (1/m) -> per (rad/m)
    w = 2 * np.pi * f
    edges = np.geomspace(2 * np.pi / hi * 1.12, 2 * np.pi / lo / 1.12, 13)
    ref = (lambda c, x: erri(c, x, "low")) if name == "erri-low" else (lambda c, x: fra(c, x, 4))
    for k, c in enumerate(CH):
        for a, b in zip(edges[:-1], edges[1:]):
            m = (w >= a) & (w < b)
            assert m.sum() >= 2
            ratio = P[k][m].sum() / ref(c, w[m]).sum()
            assert abs(ratio - 1) < 0.10, (c, a, b, ratio)
        # and nothing outside the band (beyond the window's leakage)
        out = w > 2 * np.pi / lo * 1.5
        assert P[k][out].sum() < 1e-3 * P[k].sum()


def test_generation_is_reproducible_by_seed_and_variance_matches():
    a = D.TrackIrregularity.from_psd("erri-high", 500.0, 7)
    b = D.TrackIrregularity.from_psd("erri-high", 500.0, 7)
    c = D.TrackIrregularity.from_psd("erri-high", 500.0, 8)
    for ch in CH:
        np.testing.assert_array_equal(getattr(a, ch), getattr(b, ch))
        assert not np.allclose(getattr(a, ch), getattr(c, ch))
    # the channels have independent phases
    assert abs(np.corrcoef(a.alignment, a.gauge)[0, 1]) < 0.3
    # the ramp: zero at both ends, no jump
    for ch in CH:
        v = getattr(a, ch)
        assert v[0] == 0.0 and v[-1] == 0.0
    # a long track's variance: ∫ S dΩ over 3-70 m (trapezoid on the independent formula)
    long = D.TrackIrregularity.from_psd("erri-high", 20000.0, 3, ramp=0.0)
    w = np.geomspace(2 * np.pi / 70, 2 * np.pi / 3, 20001)
    for ch in ("alignment", "level"):
        var = np.trapezoid(erri(ch, w, "high"), w)
        assert np.var(getattr(long, ch)) == pytest.approx(var, rel=0.05)
    only = D.TrackIrregularity.from_psd("fra-6", 400.0, 1, channels=("level",))
    assert np.all(only.alignment == 0) and np.any(only.level != 0)


def test_rails_follow_the_channels():
    s = np.arange(0.0, 50.0, 0.5)
    irr = D.TrackIrregularity(s, alignment=np.full_like(s, 0.001), level=np.full_like(s, 0.002),
                              cross_level=np.full_like(s, 0.004),
                              gauge=np.full_like(s, 0.006))
    at = irr.at(20.0)
    assert at["gauge"] == pytest.approx(0.006)
    r = irr.rails(np.array([10.0, 20.0]))
    assert r.shape == (2, 2, 2)
    # left rail: a - g/2 lateral, v - c/2 vertical; right rail: a + g/2, v + c/2
    np.testing.assert_allclose(r[0, 0], [0.001 - 0.003, 0.002 - 0.002])
    np.testing.assert_allclose(r[0, 1], [0.001 + 0.003, 0.002 + 0.002])
    assert np.all(irr.rails(-5.0) == 0.0) and np.all(irr.rails(60.0) == 0.0)


def test_interpolation_of_a_sine_and_the_layout_kernel_agree():
    s = np.arange(0.0, 60.0, 0.25)
    lam = 12.0
    irr = D.TrackIrregularity(s, alignment=0.002 * np.sin(2 * np.pi * s / lam),
                              level=0.003 * np.cos(2 * np.pi * s / lam),
                              cross_level=0.001 * np.sin(2 * np.pi * s / 8.0),
                              gauge=0.002 * np.cos(2 * np.pi * s / 8.0))
    q = np.linspace(5.0, 50.0, 37)
    # Catmull-Rom at 48 samples a wavelength: within 0.2 % of the amplitude of the sine
    np.testing.assert_allclose(irr.at(q)["alignment"], 0.002 * np.sin(2 * np.pi * q / lam),
                               atol=4e-6)
    val, der = irr.rails(q, slope=True)
    np.testing.assert_allclose(der[:, 1, 1], -0.003 * 2 * np.pi / lam * np.sin(2 * np.pi * q / lam)
                               + 0.5 * 0.001 * 2 * np.pi / 8 * np.cos(2 * np.pi * q / 8.0),
                               atol=2e-5)
    # the compiled layout (what the equations of motion use) gives the same offsets
    layout = D.TrackLayout(wr.Track(wr.profiles.load("60E1")), irregularity=irr)
    K = layout.rails(q)
    np.testing.assert_allclose(K[:, :, 0], val[:, :, 0], atol=1e-15)
    np.testing.assert_allclose(K[:, :, 2], val[:, :, 1], atol=1e-15)
    np.testing.assert_allclose(K[:, :, 1], der[:, :, 0], atol=1e-13)
    np.testing.assert_allclose(K[:, :, 3], der[:, :, 1], atol=1e-13)
    np.testing.assert_allclose(layout.at(q)[2], irr.at(q)["alignment"], atol=1e-15)
    # the lateral-only Irregularity still feeds the alignment
    old = D.TrackLayout(wr.Track(wr.profiles.load("60E1")),
                        irregularity=D.Irregularity(s, 0.002 * np.sin(2 * np.pi * s / lam)))
    np.testing.assert_allclose(old.rails(q)[:, 0, 0], old.rails(q)[:, 1, 0])
    np.testing.assert_allclose(old.rails(q)[:, 0, 2], 0.0)


def test_file_round_trip_and_mm_conversion(tmp_path):
    p = tmp_path / "track.csv"
    p.write_text("# measured 2026-01-01\n"
                 "distance_m, alignment_mm, level_mm, cross_level_mm, gauge_mm\n"
                 "0.0, 1.0, -2.0, 0.5, 3.0\n"
                 "0.25, 1.5, -1.0, 0.0, 2.0\n"
                 "\n"
                 "0.5, 2.0, 0.0, -0.5, 1.0\n"
                 "0.75, 1.0, 1.0, -1.0, 0.0\n"
                 "1.0, 0.0, 2.0, -1.5, -1.0\n")
    irr = D.TrackIrregularity.from_file(p)
    np.testing.assert_allclose(irr.distance, [0, 0.25, 0.5, 0.75, 1.0])
    np.testing.assert_allclose(irr.alignment, [1e-3, 1.5e-3, 2e-3, 1e-3, 0.0])
    np.testing.assert_allclose(irr.level, [-2e-3, -1e-3, 0.0, 1e-3, 2e-3])
    np.testing.assert_allclose(irr.cross_level, [5e-4, 0.0, -5e-4, -1e-3, -1.5e-3])
    np.testing.assert_allclose(irr.gauge, [3e-3, 2e-3, 1e-3, 0.0, -1e-3])
    # whitespace columns without a header, in metres
    q = tmp_path / "track.txt"
    q.write_text("\n".join(f"{s} 0.001 0.002 0.003 0.004" for s in (10, 10.5, 11, 11.5)))
    m = D.TrackIrregularity.from_file(q, units="m")
    assert m.step == 0.5 and m.gauge[2] == 0.004
    # write and read back
    gen = D.TrackIrregularity.from_psd("erri-low", 100.0, 2)
    gen.to_file(tmp_path / "gen.csv")
    back = D.TrackIrregularity.from_file(tmp_path / "gen.csv")
    for ch in CH:
        np.testing.assert_allclose(getattr(back, ch), getattr(gen, ch), rtol=1e-8, atol=1e-14)
    np.testing.assert_allclose(back.distance, gen.distance, atol=1e-9)


@pytest.mark.parametrize("text, msg", [
    ("0 1 2 3 4\n0.5 1 2 3\n1 1 2 3 4\n1.5 1 2 3 4\n", "line 2: expected 5 columns"),
    ("0 1 2 3 4\n0.5 1 2 3 4\n0.25 1 2 3 4\n1.5 1 2 3 4\n", "line 3: distance"),
    ("0 1 2 3 4\n0.5 1 2 3 4\n1.5 1 2 3 4\n2.0 1 2 3 4\n", "line 3: spacing"),
    ("h1 h2 h3 h4 h5\n0 1 2 3 4\n0.5 1 x 3 4\n1 1 2 3 4\n1.5 1 2 3 4\n", "line 3: non-numeric"),
    ("0 1 2 3 4\n0.5 1 2 3 4\n1 1 2 3 4\n", "at least 4 data lines"),
    ("0 1 2 3 4\n0.5 1 2 3 4\n1 900 2 3 4\n1.5 1 2 3 4\n", "line 3: irregularity"),
    ("0 1 2 3 4\n0.5 1 nan 3 4\n1 1 2 3 4\n1.5 1 2 3 4\n", "line 2: non-finite"),
])
def test_bad_files_are_refused_naming_file_and_line(tmp_path, text, msg):
    p = tmp_path / "bad.txt"
    p.write_text(text)
    with pytest.raises(InputError, match=msg) as err:
        D.TrackIrregularity.from_file(p)
    assert "bad.txt" in str(err.value)


def test_bad_inputs_are_refused(tmp_path):
    with pytest.raises(InputError, match="cannot read"):
        D.TrackIrregularity.from_file(tmp_path / "missing.csv")
    s = np.arange(10.0)
    with pytest.raises(InputError, match="implausible"):
        D.TrackIrregularity(s, level=np.full(10, 3.0))            # mm given as m
    with pytest.raises(InputError, match="uniformly"):
        D.TrackIrregularity(np.r_[0, 1, 2, 4.0], level=np.zeros(4))
    with pytest.raises(InputError, match="unknown track spectrum"):
        D.TrackIrregularity.from_psd("erri-medium", 100.0, 1)
    with pytest.raises(InputError, match="step"):
        D.TrackIrregularity.from_psd("erri-low", 100.0, 1, step=2.0)
    with pytest.raises(InputError, match="length"):
        D.TrackIrregularity.from_psd("erri-low", -1.0, 1)
    with pytest.raises(InputError, match="irregularity must be"):
        D.TrackLayout(wr.Track(wr.profiles.load("60E1")), irregularity="erri-low")


# --------------------------------------------------------------------------- wiring
@pytest.fixture(scope="module")
def wheelset_model():
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 100.0, 1120.0), axle_load=80e3,
                            primary=D.Suspension(kx=1e6, ky=1e6, half_spacing=1.0))
    return ws, tr, model


def test_wheel_inputs_see_each_rail_offset(wheelset_model):
    """The wheel's pose relative to its rail (the contact's input) moves by that rail's
    offset: lateral a ∓ g/2, vertical v ∓ c/2 (left/right), rates V d/ds of them."""
    from wheelrail.dynamics._motion import N_IN, wheel_inputs
    from wheelrail.dynamics.simulate import System
    ws, tr, model = wheelset_model
    s = np.arange(0.0, 40.0, 0.2)
    irr = D.TrackIrregularity(s, alignment=0.002 * np.sin(2 * np.pi * s / 10),
                              level=0.003 * np.sin(2 * np.pi * s / 13),
                              cross_level=0.004 * np.cos(2 * np.pi * s / 11),
                              gauge=0.001 * np.cos(2 * np.pi * s / 7))
    flat = System(model, tr, 20.0, "hertz", "fastsim")
    rough = System(model, D.TrackLayout(tr, irregularity=irr), 20.0, "hertz", "fastsim")
    x = np.zeros(flat.asm.n)
    W0, W1 = np.empty((1, 2, N_IN)), np.empty((1, 2, N_IN))
    at = 17.3
    wheel_inputs(0.0, x, flat.asm.P, flat.layout.arrays, 20.0, at, W0)
    wheel_inputs(0.0, x, rough.asm.P, rough.layout.arrays, 20.0, at, W1)
    val, der = irr.rails(at, slope=True)
    for side in range(2):
        assert W1[0, side, 0] - W0[0, side, 0] == pytest.approx(-val[side, 0], abs=1e-15)
        assert W1[0, side, 1] - W0[0, side, 1] == pytest.approx(-val[side, 1], abs=1e-15)
        assert W1[0, side, 6] - W0[0, side, 6] == pytest.approx(-20.0 * der[side, 0], abs=1e-13)
        assert W1[0, side, 7] - W0[0, side, 7] == pytest.approx(-20.0 * der[side, 1], abs=1e-13)
    # left rail: a - g/2, v - c/2, written out
    a, v, c, g = (irr.at(at)[k] for k in ("alignment", "level", "cross_level", "gauge"))
    assert val[0, 0] == pytest.approx(a - g / 2) and val[1, 1] == pytest.approx(v + c / 2)


def test_wheelset_follows_level_and_cross_level(wheelset_model):
    """Long waves of level and cross level at 20 m/s: the (vertically free) wheelset's height
    follows the level one to one, its roll the cross level over the distance of the contact
    points, c/(2 e) with e ≈ 0.75 m (within 3 %: the contact points are not exactly at the
    tape circles)."""
    ws, tr, model = wheelset_model
    s = np.arange(-5.0, 40.0, 0.2)
    lev = 0.002 * np.sin(2 * np.pi * s / 8.0)
    cl = 0.003 * np.sin(2 * np.pi * (s - 3.0) / 11.0)
    layout = D.TrackLayout(tr, irregularity=D.TrackIrregularity(s, level=lev, cross_level=cl))
    res = D.simulate(model, layout, 20.0, 1.0, "hertz", "fastsim", output_step=2e-3)
    pos = res.position
    m = pos > 4.0
    A = np.column_stack([np.interp(pos, s, lev), np.interp(pos, s, cl), np.ones(pos.size)])[m]
    kz = np.linalg.lstsq(A, res.state("ws0.z")[m], rcond=None)[0]
    kr = np.linalg.lstsq(A, res.state("ws0.roll")[m], rcond=None)[0]
    assert kz[0] == pytest.approx(1.0, abs=0.01) and abs(kz[1]) < 0.01
    assert kr[1] == pytest.approx(1 / (2 * ws.e_tape), rel=0.03) and abs(kr[0]) < 0.03


# --------------------------------------------------------------------------- case files
CASE = """
[model]
wheel = "S1002"
rail = "60E1"
mass = 1813.0
inertia = [1120.0, 100.0, 1120.0]
axle_load = 80e3
[model.primary]
kx = 1e6
ky = 1e6
[track]
irregularity = {IRR}
[friction]
mu = 0.3
[simulation]
speed = 20.0
duration = 0.1
"""


def test_case_file_irregularity_from_spectrum_and_file(tmp_path):
    from wheelrail.cli.dynamics import read_dynamics_case
    case = tmp_path / "psd.toml"
    case.write_text(CASE.replace("{IRR}", '{kind = "psd", spectrum = "fra-5", length = 300.0, '
                                          'seed = 4, ramp = 5.0}'))
    irr = read_dynamics_case(case)["layout"].irregularity
    ref = D.TrackIrregularity.from_psd("fra-5", 300.0, 4, ramp=5.0)
    np.testing.assert_array_equal(irr.level, ref.level)
    ref.to_file(tmp_path / "measured.csv")
    case = tmp_path / "file.toml"
    case.write_text(CASE.replace("{IRR}", '{kind = "file", path = "measured.csv"}'))
    irr = read_dynamics_case(case)["layout"].irregularity
    np.testing.assert_allclose(irr.gauge, ref.gauge, atol=1e-12)
    for bad, msg in (('{kind = "psd", spectrum = "erri-mid", length = 100.0}', "unknown track"),
                     ('{kind = "psd", spectrum = "erri-low", length = 100.0, seed = 1.5}',
                      "seed"),
                     ('{kind = "file", path = "nowhere.csv"}', "cannot read"),
                     ('{kind = "wave"}', "'sine', 'bump', 'file' or 'psd'")):
        case.write_text(CASE.replace("{IRR}", bad))
        with pytest.raises(wr.WheelrailError, match=msg):
            read_dynamics_case(case)
