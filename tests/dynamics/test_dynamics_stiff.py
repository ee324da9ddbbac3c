"""The stiff parts of the dynamics with the real-time integrator (RK4, 1 ms step).

* Creep relaxation, ``simulate(..., creep_relaxation=...)``: the relaxation states
  obey the first-order lag dq/dt = (F − q) V/L (Kalker's instationary rolling to
  first order; Kalker 1990, §5.2; Shen, Hedrick & Elkins 1984) whose time
  constant L/V is far below the step. Checked end to end, free and fixed spin,
  wheelset and bogie: (a) the steady state of a run through a curve equals the
  run without relaxation (the lag has no effect on a steady force); (b) after a
  step in creepage the relaxed force follows the closed-form response of the
  lag, q(t) = ∫ k e^{−k(t−s)} F(s) ds with k = V/L, written out here for F
  piecewise linear between the outputs — over the first step F(1 − exp(−Vt/L)).
* Low speed with free spin: the creep forces damp the spin with the time constant
  Iy V / (2 f11 r0²), 0.1 ms at 3 m/s; RK4 at 1 ms is unstable there (stable to
  2.79 time constants) and the saturating creep force turned that instability
  into a false longitudinal creepage of 4e-3 (3 m/s) and 1.6e-2 (1 m/s), with no
  warning. Reference: a conical wheelset on knife-edge rails at low speed rolls
  kinematically (Klingel 1883; Wickens 2003, §2.2): wavelength 2π √(r0 l0/λ)
  and creepages of the order of the inertia forces only (below 1e-6 here).
"""

from __future__ import annotations

import importlib
import math
import warnings

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics._fastcontact import PATCH_FIELDS, WHEEL_FIELDS
from wheelrail.dynamics.reference import cone_track, klingel_wavelength

D = wr.dynamics
SIM = importlib.import_module("wheelrail.dynamics.simulate")
W = {n: i for i, n in enumerate(WHEEL_FIELDS)}
XI = PATCH_FIELDS.index("xi")
R0, L0 = 0.46, 0.75


def _model(kind, spin, ws):
    prim = D.Suspension(kx=2e6, ky=2e6, kz=1.22e6, cy=2e4, half_spacing=1.0)
    if kind == "wheelset":
        return D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), axle_load=80e3,
                               primary=prim, spin=spin)
    return D.BogieModel(ws, 1813.0, (1120.0, 112.0, 1120.0), prim, 2615.0,
                        (1722.0, 1476.0, 3067.0), 1.25,
                        secondary=D.Suspension(kx=1.5e5, ky=1.5e5, kz=4e5, cy=3e4, cz=2e4),
                        spin=spin)


@pytest.mark.parametrize("kind", ["wheelset", "bogie"])
@pytest.mark.parametrize("spin", ["fixed", "free"])
def test_relaxation_steady_curving_equals_the_unrelaxed_run(kind, spin):
    """λ = 0.05 cones on knife-edge rails, 1000 m curve, 20 m/s, RK4 at 1 ms (the lag's
    time constant a/V ≈ 0.15 ms): after 2 s both runs sit at the same steady state,
    and the relaxation states equal the steady creep forces."""
    ws, tr = cone_track(0.05, R0, L0)
    layout = D.TrackLayout(tr, (D.Curve(1000.0, start=-100.0),))
    model = _model(kind, spin, ws)
    runs = {r: D.simulate(model, layout, 20.0, 2.0, "hertz", "fastsim", creep_relaxation=r,
                          output_step=0.01)
            for r in (False, True)}
    ref, rel = runs[False], runs[True]
    assert rel.info["integrator"].startswith("fixed step rk4")
    assert np.all(np.isfinite(rel.states))
    for i in range(model.n_wheelsets):
        y = ref.state(f"ws{i}.y")[-1]
        assert abs(y) > 1e-3                                 # a real curving offset
        assert rel.state(f"ws{i}.y")[-1] == pytest.approx(y, rel=1e-4)
        assert rel.state(f"ws{i}.yaw")[-1] == pytest.approx(ref.state(f"ws{i}.yaw")[-1],
                                                            rel=1e-3)
    ox = rel.names.index("relax0.left.Qt_y")
    q = rel.states[-1, ox:ox + 10 * model.n_wheelsets]
    steady = rel.wheels[-1, ..., W["Qt_y"]:W["Qt_y"] + 5].reshape(-1)
    assert np.max(np.abs(q - steady)) < 1e-3 * np.max(np.abs(steady))


def _lag(t, F, k, q0):
    """The first-order lag dq/dt = k (F − q) driven by F linear between the samples t,
    exactly (k held over each interval): q(h) = e^{−kh} q0 + F0 (A − B) + F1 B with
    A = 1 − e^{−kh}, B = A − (1 − e^{−kh}(1 + kh))/(kh)."""
    q = np.empty_like(F)
    q[0] = q0
    for n in range(len(t) - 1):
        h = t[n + 1] - t[n]
        kh = 0.5 * (k[n] + k[n + 1]) * h
        e = math.exp(-kh)
        A = 1.0 - e
        B = A - (1.0 - e * (1.0 + kh)) / kh
        q[n + 1] = e * q[n] + F[n] * (A - B) + F[n + 1] * B
    return q


@pytest.mark.parametrize("spin", ["fixed", "free"])
def test_relaxation_step_in_creepage_against_the_closed_form_lag(spin):
    """A wheelset yawed by 1 mrad at t = 0 with its relaxation states at zero: a step
    in lateral creepage. Relaxation length 20 a (time constant 3 ms at 20 m/s, so
    that the 1 ms outputs resolve it); the relaxed lateral forces of both wheels
    against the lag's closed form driven by the recorded steady forces."""
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), axle_load=80e3,
                            primary=D.Suspension(kx=1e6, ky=3.884e6, kz=1.22e6), spin=spin)
    V, n_a = 20.0, 20.0
    init = {"ws0.yaw": 1e-3}
    for side in ("left", "right"):
        for c in ("y", "z", "roll", "yaw", "spin"):
            init[f"relax0.{side}.Qt_{c}"] = 0.0
    res = D.simulate(model, tr, V, 0.03, "hertz", "fastsim", creep_relaxation=n_a,
                     initial=init)
    t = res.t
    for s, side in enumerate(("left", "right")):
        q = res.state(f"relax0.{side}.Qt_y")
        F = res.wheels[:, 0, s, W["Qt_y"]]
        k = V / (n_a * res.wheels[:, 0, s, W["a_mean"]])
        assert abs(F[0]) > 1e3                               # a real step
        ref = _lag(t, F, k, 0.0)
        assert np.max(np.abs(q - ref)) < 0.01 * np.max(np.abs(F))
        # over the first step q = F (1 − exp(−V t/L)), F its mean over the step
        A = 1.0 - math.exp(-k[0] * t[1])
        assert q[1] == pytest.approx(0.5 * (F[0] + F[1]) * A, rel=0.05)


def _kinematic(V, duration, monkeypatch=None):
    ws, tr = cone_track(0.2, R0, L0)
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), axle_load=80e3, spin="free")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = D.simulate(model, tr, V, duration, "hertz", "fastsim",
                         integrator=D.FixedStep(dt=1e-3), initial={"ws0.y": 0.001})
    return res, [w for w in caught if issubclass(w.category, SIM.StepWarning)]


def _upcrossings(t, y):
    i = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    return t[i] - y[i] * (t[i + 1] - t[i]) / (y[i + 1] - y[i])


def test_free_spin_at_3_m_s_rolls_kinematically_with_rk4_at_1_ms():
    res, warned = _kinematic(3.0, 20.0 / 3.0)
    # after the start (released with no yaw rate: creepage ±λ y0/r0 = 4e-4 at t = 0)
    xi = res.patches[res.t > 0.2, 0, :, 0, XI]
    assert np.max(np.abs(xi)) < 2e-6                         # was 4e-3 without the control
    # the step is divided, and the user is told why and at what cost
    assert res.info["substeps"] >= 2
    assert len(warned) == 1
    msg = str(warned[0].message)
    assert "spin" in msg and "sub-steps" in msg and "3 m/s" in msg
    wavelength = 3.0 * np.diff(_upcrossings(res.t, res.state("ws0.y")))
    np.testing.assert_allclose(wavelength, klingel_wavelength(R0, L0, 0.2), rtol=1e-3)


def test_free_spin_at_1_m_s_rolls_kinematically_with_rk4_at_1_ms():
    res, warned = _kinematic(1.0, 2.0)
    xi = res.patches[res.t > 0.2, 0, :, 0, XI]
    assert np.max(np.abs(xi)) < 2e-6                         # was 1.6e-2 without the control
    assert res.info["substeps"] >= 5 and len(warned) == 1
    # kinematic: y follows y0 cos(2π s / λ_K)
    s = 1.0 * res.t
    np.testing.assert_allclose(res.state("ws0.y"),
                               1e-3 * np.cos(2 * np.pi * s / klingel_wavelength(R0, L0, 0.2)),
                               atol=2e-5)


def test_a_step_needing_too_many_substeps_is_refused_with_the_step_it_needs(monkeypatch):
    monkeypatch.setattr(SIM, "_MAX_SUBSTEPS", 4)
    with pytest.raises(wr.InputError, match=r"FixedStep\(dt=") as err:
        _kinematic(1.0, 0.01)
    assert "spin" in str(err.value) and "time constant" in str(err.value)
