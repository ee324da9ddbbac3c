"""FE steady rolling against Kalker's exact half-space theory (wheelrail's exact solver).

Seed 000 (Toumi et al. 2016, §4.1.3, Fig. 8) compares the FE creep force with CONTACT.
Here: a cylindrical wheel (R = 0.46 m) on the 60E1 crown, 7.5 kN, μ = 0.2, steel,
ξ = 7e-4 (no spin), a 2 mm mesh (a/h ≈ 1.5) with mass scaling so that the explicit run
takes seconds. Exact solver: Fx = -1228 N. Measured here: -1248 N (+1.6 %); tolerance 10 %
(the issue's target for the 1 mm mesh).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.fe import RollingCase, solve

FLAT_WHEEL = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
KW = dict(wheel=FLAT_WHEEL, rail=wr.profiles.load("60E1"), radius=0.46, load=7500.0, mu=0.2,
          mesh_size=2e-3, element="reduced", mass_scaling=400, depth=4, half_width=3,
          half_length=3, travel=0.02)


@pytest.fixture(scope="module")
def rolled():
    return solve(RollingCase(creepage=(7e-4, 0.0, 0.0), **KW), progress=False)


def test_steady_longitudinal_force_matches_exact_halfspace(rolled):
    g = rolled.model.geometry
    hz = wr.hertz(7500.0, g["A"], g["B"], wr.Material(2.1e11, 0.28))
    ref = wr.creep_forces(hz, (7e-4, 0.0, 0.0), 0.2, method="exact", elements=20).Fx
    assert rolled.Fx == pytest.approx(ref, rel=0.10)
    assert abs(rolled.Fy) < 0.02 * abs(ref)                 # symmetric case: no lateral force
    assert rolled.Fx < 0                                    # positive creepage -> negative force


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
    scale = float(abs(ds.kinetic).max() + abs(ds.internal).max())
    assert float(abs(ds.energy_error).max()) < 0.05 * scale


def test_unstable_time_step_is_rejected():
    from wheelrail.errors import InputError
    with pytest.raises(InputError, match="time_step 0.001"):
        solve(RollingCase(creepage=(7e-4, 0.0, 0.0), **dict(KW, time_step=1e-3)), progress=False)


def test_hht_agrees_with_quasi_static_when_inertia_is_negligible():
    """Steps (72 µs) far longer than the bodies' periods (~20 µs): HHT-α tends to the static solution."""
    kw = dict(KW, travel=0.003, mass_scaling=1.0)
    qs = solve(RollingCase(creepage=(7e-4, 0, 0), integrator="implicit-qs", **kw), progress=False)
    hht = solve(RollingCase(creepage=(7e-4, 0, 0), integrator="implicit-hht", **kw),
                progress=False)
    np.testing.assert_allclose(hht.dataset.Fx.values, qs.dataset.Fx.values, rtol=0.02, atol=5.0)
    np.testing.assert_allclose(hht.dataset.Fn.values, 7500.0, rtol=0.02)   # measured 1.1 %
