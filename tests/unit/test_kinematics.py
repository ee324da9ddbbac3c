"""Creepages from wheelset motion (wheelrail.geometry.kinematics).

References: hand-derived cases (pure rolling, yaw, lateral velocity, conical
tread spin, roller-rig spin excess, Jaschinski et al. 1999) and an independent
finite-difference evaluation of the rigid-body motion: positions of a wheel
material point and of the wheelset orientation are differentiated in time
numerically, without the kernel's angular-velocity formula.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wheelrail.errors import InputError
from wheelrail.geometry.kinematics import Motion, creepage_kernel, creepages

R0 = 0.46


def _c(side, motion, gamma=0.0, x=0.0, y=0.75, z=0.0, yaw=0.0, roll=0.0, yc=0.0, zc=R0,
       rail_z=0.0):
    return creepages(motion, side=side, contact_point=(x, y if side == "right" else -y, z),
                     axle_centre=(yc, zc), yaw=yaw, roll=roll, contact_angle=gamma,
                     nominal_radius=R0, rail_z=rail_z)


@pytest.mark.parametrize("side", ["left", "right"])
def test_pure_rolling_of_a_cylinder_gives_zero_creepage(side):
    xi, eta, phi = _c(side, Motion(speed=20.0))
    assert abs(xi) < 1e-15 and abs(eta) < 1e-15 and abs(phi) < 1e-15


@pytest.mark.parametrize("side", ["left", "right"])
def test_driving_wheel_has_negative_longitudinal_creepage(side):
    # omega r > V: the contact point moves backwards relative to the rail, xi = (V - omega r)/V
    xi, _, _ = _c(side, Motion(speed=10.0, omega=1.01 * 10.0 / R0))
    assert xi == pytest.approx(-0.01, rel=1e-12)


@pytest.mark.parametrize("side", ["left", "right"])
@pytest.mark.parametrize("psi", [-0.01, 0.004, 0.02])
def test_yaw_gives_lateral_creepage_minus_psi(side, psi):
    xi, eta, phi = _c(side, Motion(speed=10.0), yaw=psi)
    assert eta == pytest.approx(-np.sin(psi), rel=1e-12)
    assert xi == pytest.approx(1 - np.cos(psi), abs=1e-12)


@pytest.mark.parametrize("side", ["left", "right"])
def test_lateral_velocity_gives_lateral_creepage(side):
    _, eta, _ = _c(side, Motion(speed=10.0, lateral_velocity=0.05))
    assert eta == pytest.approx(0.005, rel=1e-12)


@pytest.mark.parametrize("gamma", [0.025, 0.05, 1.2])
def test_conical_tread_spin(gamma):
    """phi = -sin(gamma)/r on the right wheel, +sin(gamma)/r on the left (y right on both)."""
    r = 0.45
    m = Motion(speed=30.0, omega=30.0 / r)
    _, _, phr = _c("right", m, gamma=gamma, zc=r)
    _, _, phl = _c("left", m, gamma=gamma, zc=r)
    assert phr == pytest.approx(-np.sin(gamma) / r, rel=1e-12)
    assert phl == pytest.approx(np.sin(gamma) / r, rel=1e-12)


def test_roller_rig_spin_excess():
    """On a roller of radius R the spin of a cone is sin(gamma)(1/r + 1/R) (Jaschinski 1999)."""
    r, R, g = 0.46, 0.70, 0.05
    m = Motion(speed=10.0, omega=10.0 / r, roller_radius=R)
    xi, eta, phi = _c("right", m, gamma=g, zc=r)
    assert phi == pytest.approx(-np.sin(g) * (1 / r + 1 / R), rel=1e-12)
    assert abs(xi) < 1e-14 and abs(eta) < 1e-14
    # and the contact point ahead of the top of the roller does not change xi at first order
    xi2, _, _ = _c("right", m, gamma=0.0, zc=r, x=1e-3, z=r - np.sqrt(r * r - 1e-6))
    assert abs(xi2) < 1e-5


def _rot(axis, a):
    c, s = np.cos(a), np.sin(a)
    if axis == "x":
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == "y":
        return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


@settings(max_examples=40, deadline=None)
@given(side=st.sampled_from([1.0, -1.0]), gamma=st.floats(-0.2, 1.2),
       yaw=st.floats(-0.02, 0.02), roll=st.floats(-0.01, 0.01),
       yaw_rate=st.floats(-0.5, 0.5), roll_rate=st.floats(-0.5, 0.5),
       vy=st.floats(-0.3, 0.3), vz=st.floats(-0.1, 0.1), slip=st.floats(-0.01, 0.01),
       x=st.floats(-0.01, 0.01))
def test_kernel_matches_finite_differences_of_the_rigid_motion(side, gamma, yaw, roll, yaw_rate,
                                                               roll_rate, vy, vz, slip, x):
    """Independent check: differentiate R(t) = Rz(-psi) Rx(-theta) Ry(beta) numerically.

    Frame (X forward, Y left, Z up); yaw positive turns the right wheel backwards (about -Z),
    roll positive lifts the right wheel (about -X), pitch beta about the wheelset axle (+Y).
    """
    V = 10.0
    Om = V / R0 * (1 + slip)
    d_track = np.array([x, side * 0.75, -R0 + 0.001])        # P - C in the track frame
    dR = np.array([d_track[0], -d_track[1], d_track[2]])

    def orient(t):
        return (_rot("z", -(yaw + yaw_rate * t)) @ _rot("x", -(roll + roll_rate * t))
                @ _rot("y", Om * t))

    R0m = orient(0.0)
    body = R0m.T @ dR                                      # material coordinates of P
    h = 1e-6
    centre = lambda t: np.array([V * t, -vy * t, vz * t])  # noqa: E731
    pos = lambda t: centre(t) + orient(t) @ body           # noqa: E731
    v = (pos(h) - pos(-h)) / (2 * h)
    Wskew = ((orient(h) - orient(-h)) / (2 * h)) @ R0m.T
    w = np.array([Wskew[2, 1], Wskew[0, 2], Wskew[1, 0]])
    cg, sg = np.cos(gamma), np.sin(gamma)
    ey = np.array([0.0, -cg, side * sg])
    ez = np.array([0.0, -side * sg, -cg])
    ref = (v[0] / V, v @ ey / V, w @ ez / V)
    got = creepage_kernel(side, V, Om, vy, vz, yaw_rate, roll_rate, yaw, roll, *d_track, gamma)
    np.testing.assert_allclose(got, ref, rtol=0, atol=2e-8)


def test_bad_motion_is_rejected_naming_the_value():
    with pytest.raises(InputError, match="speed"):
        Motion(speed=-1.0)
    with pytest.raises(InputError, match="omega"):
        Motion(speed=1.0, omega=-4.3)
    with pytest.raises(InputError, match="roller_radius"):
        Motion(speed=1.0, roller_radius=0.0)
    with pytest.raises(InputError, match="side"):
        creepages(Motion(speed=1.0), side="middle", contact_point=(0, 0, 0),
                  axle_centre=(0, R0), contact_angle=0.0, nominal_radius=R0)
