"""Surface-wave speed on the transition model's rail from a clean force pulse
(wheelrail.fe.transition.wave), against the Rayleigh speed of the steel."""

import numpy as np
import pytest

from wheelrail.errors import InputError
from wheelrail.fe.transition import seed004_case
from wheelrail.fe.transition.model import build_transition_model
from wheelrail.fe.transition.wave import (
    elastic_wave_speeds,
    force_pulse,
    phase_velocity,
    pulse_arrivals,
    pulse_phase,
    rail_pulse,
)


def test_elastic_wave_speeds_of_steel_against_closed_forms_and_tables():
    sp = elastic_wave_speeds(2.1e11, 0.3, 7850.0)
    G = 2.1e11 / 2.6
    assert sp["c_s"] == pytest.approx(np.sqrt(G / 7850.0), rel=1e-12)
    # c_p / c_s = sqrt(2(1 - nu) / (1 - 2 nu)) = sqrt(3.5) at nu = 0.3
    assert sp["c_p"] / sp["c_s"] == pytest.approx(np.sqrt(3.5), rel=1e-12)
    # Rayleigh root c_R / c_s at nu = 0.3: 0.9274 (Graff 1991, Fig. 6.6; Viktorov 1967 table)
    assert sp["c_R"] / sp["c_s"] == pytest.approx(0.9274, abs=2e-4)
    # nu = 0.25: the exact root is sqrt(2 - 2/sqrt(3)) (Rayleigh 1885)
    sp25 = elastic_wave_speeds(1.0, 0.25, 1.0)
    assert sp25["c_R"] / sp25["c_s"] == pytest.approx(np.sqrt(2 - 2 / np.sqrt(3)), rel=1e-10)
    # Viktorov's approximation within 0.5 %
    assert sp["c_R_viktorov"] == pytest.approx(sp["c_R"], rel=5e-3)
    with pytest.raises(InputError, match="nu"):
        elastic_wave_speeds(2.1e11, 0.5, 7850.0)


def test_force_pulses():
    f = 1e5
    t = np.linspace(0, 3e-5, 3001)
    r = force_pulse(t, "ricker", f)
    assert r.max() == pytest.approx(1.0, abs=1e-6)
    assert t[np.argmax(r)] == pytest.approx(1.2 / f, abs=2e-8)
    hs = force_pulse(t, "half-sine", f)
    assert hs.min() >= 0 and hs[t > 1 / f].max() == 0.0
    with pytest.raises(InputError, match="pulse shape"):
        force_pulse(t, "box", f)


@pytest.fixture(scope="module")
def model_4mm():
    # the reduced transition case's own 4 mm rail and track mesh, shortened (fine band
    # about ±80 mm around the source)
    case = seed004_case(0.025, travel=0.09)
    return case, build_transition_model(case)


@pytest.fixture(scope="module")
def pulse_4mm(model_4mm):
    # 80 kHz: the Rayleigh wavelength 37 mm spans 9 elements and is below the head's depth
    case, model = model_4mm
    return rail_pulse(case, model=model, frequency=80e3)


def test_pulse_on_the_rail_head_travels_at_the_rayleigh_speed(pulse_4mm):
    r = pulse_4mm
    c = r.info["speeds"]
    assert r.v.shape == (r.t.size, r.x.size, 3)
    assert r.info["source_nodes"] >= 3
    a = pulse_arrivals(r, d_min=0.03, d_max=0.07, method="xcorr")
    # Rayleigh speed within 5 %: stricter than the 3.0 ± 0.3 km/s, and it excludes
    # the shear (+7.8 %), bar (+74 %) and P waves and the slow guided motion of the head
    # (1.0-2.7 km/s by the envelope peak); measured here 2982 ± 11 m/s; on the 2 mm mesh
    # at 100 kHz 2.94-3.05 km/s (benchmarks/bench_fe_transition_wave.py)
    assert a["speed"] == pytest.approx(c["c_R"], rel=0.05)
    assert a["speed_se"] < 0.02 * a["speed"]
    # the particle motion of a Rayleigh wave: horizontal and vertical a quarter period apart
    ph = pulse_phase(r, a)
    assert 70.0 < ph["phase"] < 110.0
    # the first motion along the rail (v_x) comes with the P wave, well ahead of the pulse
    p = pulse_arrivals(r, d_min=0.03, d_max=0.07, component="x", method="first")
    assert p["speed"] == pytest.approx(c["c_p"], rel=0.12)


def test_pulse_on_the_gauge_corner_at_the_flange_contact(model_4mm):
    case, model = model_4mm
    r = rail_pulse(case, model=model, at="flange", frequency=80e3)
    # the line through the rigid flange contact (70.3° at the first flange contact)
    assert r.info["contact_angle"] == pytest.approx(70.3, abs=3.0)
    a = pulse_arrivals(r, d_min=0.02, d_max=0.08, component="n", method="xcorr")
    # measured 2911 m/s over 20-80 mm (2.91-3.11 km/s over 20-60 to 40-90 mm, 4 mm mesh)
    assert a["speed"] == pytest.approx(r.info["speeds"]["c_R"], rel=0.05)


def test_pulse_arrivals_refuses_bad_inputs(pulse_4mm, model_4mm):
    with pytest.raises(InputError, match="component"):
        pulse_arrivals(pulse_4mm, component="w")
    with pytest.raises(InputError, match="method"):
        pulse_arrivals(pulse_4mm, method="peak")
    with pytest.raises(InputError, match="fewer than 3"):
        pulse_arrivals(pulse_4mm, d_min=0.5, d_max=0.6)
    with pytest.raises(InputError, match="source_x"):
        rail_pulse(*model_4mm[:1], model=model_4mm[1], source_x=5.0)
    with pytest.raises(InputError, match="at must be"):
        rail_pulse(seed004_case(0.025, travel=0.09), at="web")


def _travelling(c_of_f, x, t, backward=None):
    """A pulse (Gaussian spectrum about 60 kHz, leaving x = 0 at 0.2 ms) travelling along +x
    with phase velocity c(f) (exact, built in the frequency domain), optionally plus the
    same pulse travelling along -x."""
    nt = t.size
    f = np.fft.rfftfreq(nt, t[1] - t[0])
    s = np.exp(-(((f - 60e3) / 30e3) ** 2) - 2j * np.pi * f * 2e-4)
    c = c_of_f(np.maximum(f, 1.0))
    v = np.fft.irfft(s[:, None] * np.exp(-2j * np.pi * f[:, None] * x[None, :] / c[:, None]),
                     n=nt, axis=0)
    if backward is not None:
        v = v + backward * np.fft.irfft(
            s[:, None] * np.exp(2j * np.pi * f[:, None] * x[None, :] / c[:, None]), n=nt, axis=0)
    out = np.zeros((nt, x.size, 3))
    out[:, :, 2] = v
    return {"x": x, "t": t, "v": out}


def test_phase_velocity_of_a_synthetic_travelling_wave():
    # the motion is built with a known phase velocity; the record resembles a 4 mm run's
    # (stations 4 mm apart, 300 ns sampling, 0.6 ms)
    x = np.arange(0.0, 0.1, 0.004)
    t = np.arange(2000) * 3e-7
    rec = _travelling(lambda f: np.full_like(f, 2975.0), x, t)
    r = phase_velocity(rec, band=(40e3, 90e3), d_min=0.0, d_max=0.09)
    assert r["speed"] == pytest.approx(2975.0, rel=2e-3)
    assert r["accepted"] == 1.0 and r["stations"] == 23
    # dispersive: c rising from 1.5 to 3 km/s over the band; each frequency's own speed
    disp = lambda f: 1500.0 + 1500.0 * np.clip((f - 20e3) / 80e3, 0, 1)  # noqa: E731
    r = phase_velocity(_travelling(disp, x, t), band=(20e3, 100e3), d_min=0.0,
                       d_max=0.09)
    np.testing.assert_allclose(r["c"], disp(r["f"]), rtol=5e-3)
    # the same wave running the other way is seen on the side behind the source
    rec_b = dict(rec, x=-x)
    assert phase_velocity(rec_b, band=(40e3, 90e3), d_min=0.0, d_max=0.09,
                          side="behind")["speed"] == pytest.approx(2975.0, rel=2e-3)
    # two equal waves in opposite directions (a standing pattern): no single wave dominates
    with pytest.raises(InputError, match="dominant"):
        phase_velocity(_travelling(lambda f: np.full_like(f, 2975.0), x, t, backward=1.0),
                       band=(40e3, 90e3), d_min=0.0, d_max=0.09, min_r2=0.99)
    with pytest.raises(InputError, match="Nyquist"):
        phase_velocity(rec, band=(40e3, 2e6), d_max=0.09)
    with pytest.raises(InputError, match="stations"):
        phase_velocity(rec, d_min=0.5, d_max=0.6)
    with pytest.raises(InputError, match="side"):
        phase_velocity(rec, side="both")
    with pytest.raises(InputError, match="wave record"):
        phase_velocity(None)


def test_phase_velocity_of_the_pulse_on_the_rail_head(pulse_4mm):
    # the same pulse as above, measured from its phase spectra instead of its arrival times:
    # 2940 and 2942 m/s over 60-120 kHz ahead and behind, every frequency accepted
    # (c_R = 2975 m/s)
    c_r = pulse_4mm.info["speeds"]["c_R"]
    for side in ("ahead", "behind"):
        r = phase_velocity(pulse_4mm, band=(60e3, 120e3), d_min=0.02, d_max=0.07, side=side)
        assert r["speed"] == pytest.approx(c_r, rel=0.05)
        assert r["accepted"] >= 0.8
