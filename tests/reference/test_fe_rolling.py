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
KW = dict(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46, load=7500.0, mu=0.2,
          mesh_size=2e-3, element="reduced", mass_scaling=400, depth=4, half_width=3,
          half_length=3, travel=0.02)


CREEP = (7e-4, 4e-4, 0.0)


@pytest.fixture(scope="module")
def restart_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("fe_restart")


@pytest.fixture(scope="module")
def rolled(restart_dir):
    # writes a restart file every 600 steps (one file per write: ``{step}``)
    return solve(RollingCase(creepage=CREEP, **KW), progress=False,
                 restart_file=restart_dir / "r_{step}.npz", restart_every=600)


def test_restarted_explicit_run_equals_the_uninterrupted_run(rolled, restart_dir):
    """Continuing from a mid-run restart file gives the same numbers bit for bit."""
    files = sorted(restart_dir.glob("r_*.npz"), key=lambda p: int(p.stem[2:]))
    n_total = rolled.info["steps"] - rolled.dataset.attrs["relaxation_steps"]
    assert int(files[-1].stem[2:]) == n_total and len(files) >= 3
    mid = files[len(files) // 2]
    r2 = solve(RollingCase(creepage=CREEP, **KW), progress=False, restart=mid)
    assert r2.info["restarted_at_step"] == int(mid.stem[2:]) > 0
    np.testing.assert_array_equal(r2.u, rolled.u)
    for name in ("Fx", "Fy", "Fn", "friction", "contact_work", "energy_error"):
        np.testing.assert_array_equal(r2.dataset[name].values, rolled.dataset[name].values)
    np.testing.assert_array_equal(r2.patch.shear.values, rolled.patch.shear.values)


def test_restart_file_of_another_case_is_rejected(restart_dir):
    from wheelrail.errors import InputError
    f = next(restart_dir.glob("r_*.npz"))
    with pytest.raises(InputError, match="mu"):
        solve(RollingCase(creepage=CREEP, **dict(KW, mu=0.3)), progress=False, restart=f)


def test_steady_creep_forces_match_exact_halfspace(rolled):
    g = rolled.model.geometry
    hz = wr.hertz(7500.0, g["A"], g["B"], wr.Material(2.1e11, 0.28))
    ref = wr.creep_forces(hz, CREEP, 0.2, method="exact", elements=20)
    assert rolled.Fx == pytest.approx(ref.Fx, rel=0.10)
    assert rolled.Fy == pytest.approx(ref.Fy, rel=0.10)
    assert rolled.Fx < 0 and rolled.Fy < 0                 # positive creepage -> negative force


def test_load_carried_and_patch_has_stick_and_slip(rolled):
    ds = rolled.dataset
    n = len(ds.Fn) // 4
    assert float(ds.Fn[-n:].mean()) == pytest.approx(7500.0, rel=0.05)
    st = rolled.patch.status.values
    assert (st == 1).any() and (st == 2).any()
    # Coulomb: no closed node exceeds the traction bound
    p, q = rolled.patch.pressure.values, rolled.patch.shear.values
    assert np.all(q <= 0.2 * p * (1 + 1e-9) + 1e-6)


def test_energy_balance_closes(rolled):
    ds = rolled.dataset
    scale = float(abs(ds.contact_work).max())
    assert float(abs(ds.energy_error).max()) < 0.1 * scale   # measured 2.6 %


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


IMPLICIT = dict(KW, travel=0.002, mass_scaling=1.0)          # 3 steps of 72 µs


@pytest.fixture(scope="module")
def implicit_runs(tmp_path_factory):
    """Quasi-static and HHT (α = 0: no numerical dissipation) with the same viscous
    (stiffness-proportional) Rayleigh damping; HHT also with mass-proportional damping and
    writing a restart file after every step."""
    d = tmp_path_factory.mktemp("fe_implicit")
    qs = solve(RollingCase(creepage=(7e-4, 0, 0), integrator="implicit-qs",
                           rayleigh=(0.0, 2e-6), **IMPLICIT), progress=False)
    case = RollingCase(creepage=(7e-4, 0, 0), integrator="implicit-hht", hht_alpha=0.0,
                       rayleigh=(1e3, 2e-6), **IMPLICIT)
    hht = solve(case, progress=False, restart_file=d / "h_{step}.npz", restart_every=1)
    return qs, hht, case, d


def test_hht_agrees_with_quasi_static_when_inertia_is_negligible(implicit_runs):
    """Steps (72 µs) far longer than the bodies' periods (~20 µs): HHT tends to the static solution."""
    qs, hht, _, _ = implicit_runs
    np.testing.assert_allclose(hht.dataset.Fx.values, qs.dataset.Fx.values, rtol=0.02, atol=5.0)
    np.testing.assert_allclose(hht.dataset.Fn.values, 7500.0, rtol=0.025)   # measured 1.3 %


def test_hht_energy_balance_with_rayleigh_damping(implicit_runs):
    """Newmark's average acceleration (HHT α = 0) conserves energy exactly for the linear part:
    kinetic + strain + damping work = load work + contact work (trapezoidal rule), up to the
    Newton tolerance. Measured: error 0.3 % of the damping work."""
    _, hht, _, _ = implicit_runs
    ds = hht.dataset
    damping = float(ds.damping.values[-1])
    assert damping > 0.1 * float(abs(ds.contact_work).max())          # damping matters here
    assert np.all(np.diff(ds.damping.values) > 0)                     # dissipative every step
    assert float(abs(ds.energy_error).max()) < 0.02 * damping


def test_restarted_implicit_run_equals_the_uninterrupted_run(implicit_runs):
    _, hht, case, d = implicit_runs
    steps = hht.info["steps"]
    r2 = solve(case, progress=False, restart=d / f"h_{steps - 1}.npz")
    assert r2.info["restarted_at_step"] == steps - 1
    np.testing.assert_array_equal(r2.u, hht.u)
    for name in ("Fx", "Fn", "damping", "energy_error"):
        np.testing.assert_array_equal(r2.dataset[name].values, hht.dataset[name].values)
