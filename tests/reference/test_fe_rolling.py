"""FE steady rolling against Kalker's exact half-space theory (wheelrail's exact solver).

Seed 000 (Toumi et al. 2016, §4.1.3, Fig. 8) compares the FE creep force with CONTACT.
Here: a cylindrical wheel (R = 0.46 m) on the 60E1 crown, 7.5 kN, μ = 0.2, steel,
ξ = 7e-4 and η = 4e-4 (no spin; η through the lateral rail drift), a 2 mm mesh
(a/h ≈ 1.5) with mass scaling so that the explicit run takes seconds. Exact solver
(20×20 elements): Fx = -1152 N, Fy = -606 N. Measured here: Fx -1183 N (+2.6 %),
Fy -582 N (-3.9 %); tolerance 10 % (the issue's target for Fx on the 1 mm mesh). The
lateral force is lower than the exact one, as in seed 000's Fig. 8b (FE lateral slope
below CONTACT's); pure η = 4e-4 / 7e-4: -9.6 % / -5.3 % at 2 mm, -6.9 % / -2.6 % at
1.5 mm (docs/fe.md).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.fe import RollingCase, solve

FLAT_WHEEL = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
KW = dict(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46, Fn=7500.0, mu=0.2,
          mesh_size=2e-3, element="reduced", mass_scaling=400, depth=4, half_width=3,
          half_length=3, travel=0.02)


CREEP = (7e-4, 4e-4, 0.0)

# Each expensive run is used by one test function only: pytest-xdist (-n 2) would otherwise
# compute a module-scoped fixture once per worker.


def test_steady_rolling_against_exact_halfspace_with_balanced_energy():
    r = solve(RollingCase(creepage=CREEP, **KW), progress=False)
    g = r.model.geometry
    hz = wr.hertz(7500.0, g["A"], g["B"], wr.Material(2.1e11, 0.28))
    ref = wr.creep_forces(hz, CREEP, 0.2, method="exact", elements=20)
    # creep forces (measured +2.6 % / -3.9 %)
    assert r.Fx == pytest.approx(ref.Fx, rel=0.10)
    assert r.Fy == pytest.approx(ref.Fy, rel=0.10)
    assert r.Fx < 0 and r.Fy < 0                           # positive creepage -> negative force
    # load carried, stick and slip zones, Coulomb bound
    ds = r.dataset
    n = len(ds.Fn) // 4
    assert float(ds.Fn[-n:].mean()) == pytest.approx(7500.0, rel=0.05)
    st = r.patch.status.values
    assert (st == 1).any() and (st == 2).any()
    p, q = r.patch.pressure.values, r.patch.shear.values
    assert np.all(q <= 0.2 * p * (1 + 1e-9) + 1e-6)
    # energy balance of the elastic bodies (measured 2.6 % of the contact work)
    scale = float(abs(ds.contact_work).max())
    assert float(abs(ds.energy_error).max()) < 0.1 * scale


def test_frictionless_rolling_conserves_energy_and_has_no_traction():
    r = solve(RollingCase(creepage=(7e-4, 0.0, 0.0), **dict(KW, mu=0.0, travel=0.008)),
              progress=False)
    ds = r.dataset
    assert float(ds.friction.values[-1]) == 0.0
    assert abs(r.Fx) < 1e-4 * 7500.0                        # only tilted normals of the deformed rail
    assert abs(r.Fy) < 1e-4 * 7500.0                        # symmetric case: no lateral force
    scale = float(abs(ds.kinetic).max() + abs(ds.internal).max())
    assert float(abs(ds.energy_error).max()) < 0.05 * scale


def test_unstable_time_step_is_rejected():
    from wheelrail.errors import InputError
    with pytest.raises(InputError, match="time_step 0.001"):
        solve(RollingCase(creepage=(7e-4, 0.0, 0.0), **dict(KW, time_step=1e-3)), progress=False)


def test_explicit_stiffness_proportional_damping_balances_energy():
    """Explicit run with Rayleigh β_R K (the stiffness-proportional part, evaluated with the
    elastic K on the velocities): its work enters the energy balance (measured: damping work
    8.2e-4 J, 29 % of the contact work, energy error 1.8 % of it) and it leaves the steady
    creep force unchanged (the steady state has no strain rate in the bodies' frames;
    measured −0.04 %)."""
    kw = dict(KW, travel=0.008, creepage=(7e-4, 0.0, 0.0))
    plain = solve(RollingCase(**kw), progress=False)
    r = solve(RollingCase(rayleigh=(0.0, 3e-7), **kw), progress=False)
    ds = r.dataset
    damping = float(ds.damping.values[-1])
    assert damping > 0.2 * float(abs(ds.contact_work).max())
    assert float(abs(ds.energy_error).max()) < 0.05 * damping
    assert float(plain.dataset.damping.values[-1]) < 0.01 * damping
    assert r.Fx == pytest.approx(plain.Fx, rel=0.01)


IMPLICIT = dict(KW, travel=0.0015, mass_scaling=1.0, depth=3)  # 2 steps of 72 µs


def test_implicit_hht_vs_qs_damping_energy_and_restart(tmp_path):
    """Quasi-static and HHT (α = 0: no numerical dissipation) with the same viscous
    (stiffness-proportional) Rayleigh damping; HHT also with mass-proportional damping,
    writing a restart file after every step.

    1. Steps (72 µs) far longer than the bodies' periods (~20 µs): HHT tends to the static
       solution (Fx within 2 %, Fn within 2.5 % of the load, measured 1.3 %).
    2. Newmark's average acceleration (HHT α = 0) conserves energy exactly for the linear
       part: kinetic + strain + damping work = load work + contact work (trapezoidal rule),
       up to the Newton tolerance (measured: 0.5 % of the damping work).
    3. Continuing from the last-but-one restart file gives the same numbers bit for bit.
    """
    qs = solve(RollingCase(creepage=(7e-4, 0, 0), integrator="implicit-qs",
                           rayleigh=(0.0, 2e-6), **IMPLICIT), progress=False)
    case = RollingCase(creepage=(7e-4, 0, 0), integrator="implicit-hht", hht_alpha=0.0,
                       rayleigh=(1e3, 2e-6), **IMPLICIT)
    hht = solve(case, progress=False, restart_file=tmp_path / "h_{step}.npz", restart_every=1)
    # 1. HHT ~ quasi-static
    np.testing.assert_allclose(hht.dataset.Fx.values, qs.dataset.Fx.values, rtol=0.02, atol=5.0)
    np.testing.assert_allclose(hht.dataset.Fn.values, 7500.0, rtol=0.025)
    assert float(qs.dataset.damping.values[-1]) > 0
    # 2. energy balance with the damping work
    ds = hht.dataset
    damping = float(ds.damping.values[-1])
    assert damping > 0.1 * float(abs(ds.contact_work).max())          # damping matters here
    assert np.all(np.diff(ds.damping.values) > 0)                     # dissipative every step
    assert float(abs(ds.energy_error).max()) < 0.02 * damping
    # 3. restart
    steps = hht.info["steps"]
    r2 = solve(case, progress=False, restart=tmp_path / f"h_{steps - 1}.npz")
    assert r2.info["restarted_at_step"] == steps - 1
    np.testing.assert_array_equal(r2.u, hht.u)
    for name in ("Fx", "Fn", "damping", "energy_error"):
        np.testing.assert_array_equal(r2.dataset[name].values, hht.dataset[name].values)


def test_seed000_rolling_geometric_spin_against_exact():
    """Seed 000's cone on the inclined arc at ξ = -0.7 ‰: the axle's angular velocity has the
    component Ω sin δ along the tilted normal, a spin φ = sin δ / r_c = 0.216 1/m that the FE
    gets from the geometry alone. Exact solver with that spin (Kalker's y is minus the FE's
    lateral tangent, so the FE force in the contact plane is -Fy_K): Fx 1151 N, Fy 482 N.
    Measured at 2 mm: Fx +0.9 %, Fy_contact +8.1 % (1.5 mm: +0.3 %, +5.2 %)."""
    from wheelrail.fe import seed000_case

    r = solve(seed000_case(load="printed", mesh_size=2e-3, mass_scaling=400, travel=0.02, element="reduced",
                           depth=4, half_width=3, half_length=3), progress=False)
    g = r.model.geometry
    phi = np.sin(g["delta"]) / g["r_c"]
    assert phi == pytest.approx(0.1 / np.sqrt(1.01) / 0.46, rel=1e-3)
    ref = wr.creep_forces(g["hertz"], (-7e-4, 0.0, phi), 0.2, method="exact", elements=20)
    assert r.Fx == pytest.approx(ref.Fx, rel=0.10)
    assert r.Fy_contact == pytest.approx(-ref.Fy, rel=0.20)
    # the global lateral force also carries the normal force's lateral component
    assert r.Fy == pytest.approx(r.Fy_contact * np.cos(g["delta"])
                                 - float(r.dataset.Fn_contact[-len(r.dataset.Fx) // 4:].mean())
                                 * np.sin(g["delta"]), rel=0.02, abs=5.0)


def test_creep_curve_slope_and_offset_against_exact():
    """wr.fe.creep_curve in the linear range: the initial slope of the FE curve against the
    exact theory's (Kalker 1990) at the same creepages, and a small offset (the elastic
    rolling radius; Toumi et al. 2016, §4.1.3). Measured: slope −6.4 % (2 mm mesh, a/h = 1.5,
    ξ = ±2e-4), offset −8e-6."""
    from wheelrail.fe import creep_curve

    xs = np.array([-2e-4, 2e-4])
    ds = creep_curve(RollingCase(creepage=(0.0, 0.0, 0.0), **dict(KW, travel=0.016)), xs,
                     progress=False)
    hz = wr.hertz(7500.0, *_curvatures(), wr.Material(2.1e11, 0.28))
    ex = [wr.creep_forces(hz, (x, 0, 0), 0.2, method="exact", elements=20).Fx for x in xs]
    ex_slope = np.polyfit(xs, ex, 1)[0]
    assert ds.attrs["fit_points"] == 2 and ds.attrs["force"] == "Fx"
    assert ds.attrs["slope"] == pytest.approx(ex_slope, rel=0.10)
    assert abs(ds.attrs["offset"]) < 1e-4
    assert np.all(ds.Fx_std.values < 0.05 * 0.2 * 7500.0)
    np.testing.assert_allclose(ds.shifted_creepage.values, xs - ds.attrs["offset"])


def _curvatures():
    from wheelrail.fe.model import contact_geometry

    g = contact_geometry(RollingCase(**KW))
    return g["A"], g["B"]
