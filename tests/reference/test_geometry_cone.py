"""Rigid contact of a conical wheelset on circular rail heads against closed-form tangency.

Reference: for a cone (wheel profile z_w = λ s, radius r0 − λ s) on a rail head
that is a circle of radius R, the contact point is where the wheel generatrix
is tangent to the circle: the tangent point is T = C + R(−sin γ, cos γ) with
γ = atan λ ± θ the slope angle of the rolled generatrix (+ right, − left,
θ > 0 right wheel up). Both tangency conditions are linear in the height of
the axle, so θ follows from one scalar equation (solved here with brentq) —
independent of the library's grid search and Newton iteration (seed 002,
eqs. 2.1–2.3; Klingel's cone: Δr ≈ 2λy).
"""

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.geometry.conicity import conicity_from_delta_r
from wheelrail.validation.checks_other import R_RAIL, cone_tangency

LAM = 1.0 / 20.0
R0 = 0.46


def cone_wheel(lam=LAM):
    s = np.linspace(-0.05, 0.06, 221)
    return wr.Profile(s, lam * s, kind="wheel", name=f"cone 1:{1 / lam:g}")


def circle_rail(R=R_RAIL):
    y = np.linspace(-0.035, 0.035, 281)
    return wr.Profile(y, np.sqrt(R * R - y * y) - R, kind="rail", name=f"circle R{R}")


def make(inclination=1 / 40, lam=LAM):
    ws = wr.Wheelset(cone_wheel(lam), nominal_radius=R0)
    tr = wr.Track(circle_rail(), inclination=inclination, gauge_height=0.001)
    return ws, tr


# the closed-form tangency of the module docstring (shared with the validation report)
reference = cone_tangency


@pytest.mark.parametrize("inclination", [0.0, 1 / 40])
@pytest.mark.parametrize("y", [-0.005, -0.0013, 0.0, 0.002, 0.0047])
def test_cone_on_circle_matches_tangency(inclination, y):
    ws, tr = make(inclination)
    ref = reference(ws, tr, y)
    cp = wr.contact_points(ws, tr, y)
    assert cp.roll == pytest.approx(ref["roll"], abs=1e-10)
    assert cp.z == pytest.approx(ref["z"], abs=1e-9)
    assert cp.delta_r == pytest.approx(ref["delta_r"], abs=1e-9)
    for side in ("left", "right"):
        pts = cp.side(side)
        assert pts.n == 1
        assert pts.wheel_y[0] == pytest.approx(ref[side]["s"], abs=1e-7)
        assert pts.contact_angle[0] == pytest.approx(ref[side]["gamma"], abs=1e-7)
        assert pts.rolling_radius[0] == pytest.approx(ref[side]["r"], abs=1e-9)
        assert abs(pts.separation[0]) < 1e-10
        # curvatures: cone has no profile curvature, circle 1/R; wheel along x cos(beta)/r
        assert pts.wheel_curvature_y[0] == pytest.approx(0.0, abs=1e-6)
        assert pts.rail_curvature_y[0] == pytest.approx(1 / R_RAIL, rel=1e-5)
        assert pts.A[0] == pytest.approx(0.5 / (ref[side]["r"] * np.sqrt(1 + LAM**2)), rel=1e-7)
    # Klingel: delta_r ≈ 2 lambda y (the roll moves the contact on the curved rail head by
    # ~R·θ, a few per cent here)
    assert cp.delta_r == pytest.approx(2 * LAM * y, rel=0.08, abs=1e-12)


def test_gauge_placement_on_circle():
    """The gauge point 1 mm below the top of a vertical R300 head lies sqrt(R²-(R-h)²) inside."""
    ws, tr = make(0.0)
    h = tr.gauge_height
    expected = 0.5 * tr.gauge + np.sqrt(R_RAIL**2 - (R_RAIL - h) ** 2)
    assert tr.placement("right").offset == pytest.approx(expected, abs=1e-8)
    assert tr.placement("left").offset == pytest.approx(expected, abs=1e-8)
    # with the cant the top of the circle moves by R sin(alpha) towards the track centre
    tr2 = wr.Track(circle_rail(), inclination=1 / 40, gauge_height=0.001)
    a = np.arctan(1 / 40)
    assert tr2.placement("right").z_top == pytest.approx(R_RAIL * (1 - np.cos(a)), abs=1e-9)


def test_yawed_cone_contact_locus_against_brute_force():
    """Yaw: the library's contact point is the 3-D minimum of the vertical wheel-rail distance.

    Brute force over the wheel surface (s, φ) of the yawed, rolled wheel with
    Nelder-Mead; the first-order locus x ≈ r tanψ (θ − r'(a)) (Wang 1984) is
    also checked.
    """
    from scipy.optimize import minimize

    ws, tr = make(1 / 40)
    psi, y = 0.01, 0.002
    cp = wr.contact_points(ws, tr, y, yaw=psi)
    th, zc = cp.roll, R0 + cp.z
    rc = tr.curve("right")
    e = ws.e_tape

    def gap(v):
        s, phi = v
        r = R0 - LAM * s
        a = e + s
        body = np.array([r * np.sin(phi), a, -r * np.cos(phi)])
        Rx = np.array([[1, 0, 0], [0, np.cos(th), -np.sin(th)], [0, np.sin(th), np.cos(th)]])
        Rz = np.array([[np.cos(psi), -np.sin(psi), 0], [np.sin(psi), np.cos(psi), 0], [0, 0, 1]])
        X, Y, Z = Rz @ Rx @ body + np.array([0.0, y, zc])
        return Z - rc.eval(Y, 0)[0]

    pts = cp.right
    s0 = pts.wheel_y[0]
    res = minimize(gap, [s0 + 1e-3, 0.0], method="Nelder-Mead",
                   options={"xatol": 1e-11, "fatol": 1e-15, "maxiter": 4000})
    assert res.fun == pytest.approx(0.0, abs=1e-10)       # rigid contact, no penetration
    assert res.x[0] == pytest.approx(s0, abs=2e-5)
    r = R0 - LAM * res.x[0]
    x_brute = r * np.sin(res.x[1]) * np.cos(psi) - r * np.cos(res.x[1]) * np.sin(th) * np.sin(psi)
    assert pts.x[0] == pytest.approx(x_brute, abs=2e-7)
    # first order: x ≈ r tanψ (θ + λ) for the right wheel (r'(a) = −λ)
    assert pts.x[0] == pytest.approx(r * np.tan(psi) * (th + LAM), rel=2e-2)
    assert abs(pts.x[0]) > 1e-4  # the yaw does move the contact point (~0.2 mm here)


@pytest.mark.parametrize("inclination", [0.0, 1 / 20])
def test_equivalent_conicity_of_the_cone(inclination):
    """EN 15302 on a cone: tan γ_e equals the slope Δr/(2y) of the cone's (linear) Δr.

    Rolling the wheelset moves the contact points laterally by (R_rail + r0)·θ,
    with θ ≈ Δr/(2e), so that on a rail head of radius R the cone's effective
    slope is λ/(1 − λ(R + r0)/e) (5 % above λ = 1/20 for R = 300 mm); for a
    linear Δr = 2λy the kernel returns λ exactly (next test). The reference
    slope here comes from the closed-form tangency solution above.
    """
    ws, tr = make(inclination)
    y = 1e-4
    ref = reference(ws, tr, y)
    lam_eff = ref["delta_r"] / (2 * y)
    e_c = reference(ws, tr, 0.0)["right"]["u"]
    assert lam_eff == pytest.approx(LAM / (1 - LAM * (R_RAIL + R0) / e_c), rel=2e-3)
    for method in ("integration", "regression"):
        for amp in (0.001, 0.003):
            lam_e = wr.equivalent_conicity(ws, tr, amp, method=method)
            assert lam_e == pytest.approx(lam_eff, rel=1e-4), (method, amp)


def test_conicity_kernel_exact_for_linear_delta_r():
    y = np.linspace(-0.01, 0.01, 41)
    for lam in (0.02, 0.15, 0.4):
        for method in ("integration", "regression"):
            assert conicity_from_delta_r(y, 2 * lam * y, 0.003, method) == \
                pytest.approx(lam, rel=1e-9)
    # an offset equilibrium (asymmetric wheelset) does not change the result
    assert conicity_from_delta_r(y, 2 * 0.1 * (y - 0.001), 0.003) == pytest.approx(0.1, rel=1e-9)


def test_conicity_kernel_cubic_against_time_integration():
    """Non-linear delta_r: quadrature of the period equals direct integration of Klingel's ODE."""
    from scipy.integrate import solve_ivp

    lam, c, amp = 0.1, 3000.0, 0.004
    y = np.linspace(-0.01, 0.01, 4001)
    dr = 2 * lam * y + c * y**3
    e_r0 = 0.75 * 0.46

    def rhs(x, v):
        return [v[1], -(2 * lam * v[0] + c * v[0] ** 3) / (2 * e_r0)]

    def up_cross(x, v):
        return v[0]
    up_cross.direction = 1
    sol = solve_ivp(rhs, [0, 200], [-amp, 0.0], events=up_cross, rtol=1e-11, atol=1e-14)
    L = 2 * (sol.t_events[0][0])  # quarter wave to the first zero crossing ×4 / 2
    L = 4 * sol.t_events[0][0]
    lam_ref = e_r0 * (2 * np.pi / L) ** 2
    assert conicity_from_delta_r(y, dr, amp) == pytest.approx(lam_ref, rel=1e-5)
    assert lam_ref > lam * 1.1  # the cubic term matters at this amplitude


def test_conicity_kernel_dead_zone_closed_form():
    """Δr = 0 for |y| < p and 2λ(|y| − p) sign(y) outside (a cylindrical band, cf. the
    E4 reference case of EN 15302 annex E whose Δr vanishes for |y| < 1.65 mm).

    Closed form of Klingel's y'' = −Δr/(2 e r0): outside the band the motion is
    harmonic with k² = λ/(e r0) (half a period π/k on each side, entry speed
    v = k(ŷ − p)); the band is crossed at constant speed, 2p/v each way, so
    L = (2π + 4p/(ŷ − p))/k and tan γ_e = e r0 (2π/L)² = λ / (1 + 2p/(π(ŷ − p)))².
    Inside the band (ŷ <= p) there is no restoring term: tan γ_e = 0.
    """
    lam, p = 0.15, 0.0015
    y = np.unique(np.r_[np.linspace(-0.012, 0.012, 2401), -p, p])
    dr = np.where(np.abs(y) > p, 2 * lam * (np.abs(y) - p) * np.sign(y), 0.0)
    for amp in (0.002, 0.003, 0.005):
        ref = lam / (1 + 2 * p / (np.pi * (amp - p))) ** 2
        assert conicity_from_delta_r(y, dr, amp) == pytest.approx(ref, rel=1e-5)
    assert conicity_from_delta_r(y, dr, 0.001) == 0.0
    assert conicity_from_delta_r(y, dr, 0.001, "regression") == 0.0


def test_conicity_regression_centres_the_cycle_on_zero_mean_delta_r():
    """Δr = 2λy + κy² (asymmetric): the harmonic cycle c + ŷ sin t with zero mean Δr has
    2λc + κ(c² + ŷ²/2) = 0, and the regression slope gives tan γ_e = λ + κc (closed form).
    Centring on the zero of Δr instead (c = 0) would give λ.
    """
    lam, kap, amp = 0.1, 20.0, 0.003
    y = np.linspace(-0.008, 0.008, 16001)
    dr = 2 * lam * y + kap * y**2
    c = (-2 * lam + np.sqrt(4 * lam**2 - 2 * kap**2 * amp**2)) / (2 * kap)
    got = conicity_from_delta_r(y, dr, amp, "regression")
    assert got == pytest.approx(lam + kap * c, rel=1e-6)
    assert abs(got - lam) > 0.005


def test_conicity_kernel_amplitude_range():
    """The table must contain both turning points, no more (symmetric case: ±ŷ)."""
    y = np.linspace(-0.01, 0.01, 201)
    for method in ("integration", "regression"):
        assert conicity_from_delta_r(y, 0.3 * y, 0.0095, method) == pytest.approx(0.15, rel=1e-9)
        with pytest.raises(wr.errors.InputError, match="range"):
            conicity_from_delta_r(y, 0.3 * y, 0.0105, method)
