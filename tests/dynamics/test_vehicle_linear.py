"""Linearised whole vehicle against an independent derivation of the same linear model.

The frames and car body of Manchester vehicle 1 (Iwnicki 1998), with a yaw damper
(Maxwell element) and longitudinal secondary damping added, the wheelsets held at
their equilibrium on tangent track: the eigenvalues of the Jacobian of the
model's compiled equations (states of frames, car body and yaw dampers) against
those of the linear model derived here independently — small rigid-body
rotations as rotation vectors ω = (θ, −χ, ψ) (roll right side up, pitch front up,
yaw nose right; point displacement t + ω × p), the stiffness and damping
matrices from the potential energy Σ ½ dᵀ K d and Rayleigh's dissipation
Σ ½ ḋᵀ C ḋ of every element (Lagrange's equations; Wickens 2003, ch. 6;
Meirovitch, *Elements of vibration analysis*, 1986, ch. 4), the Maxwell element
as the energy ½ k (d_x − u)² of its series spring and c u̇ = −∂V/∂u, the springs'
preloads (the weights they carry) as constant forces F at their points with the
potential −F·δ₂, δ₂ = ½ ω × (ω × p) the second-order displacement (the
overturning of the weights carried above the springs). Agreement 1e-6 relative
on every eigenvalue.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import wheelrail as wr
from wheelrail.dynamics import System, YawDamper, linearise, manchester_vehicle1

AXES = {"roll": np.array([1.0, 0.0, 0.0]), "pitch": np.array([0.0, -1.0, 0.0]),
        "yaw": np.array([0.0, 0.0, 1.0])}


def _point_map(p):
    """3 × 5 map from (y, z, roll, pitch, yaw) to the small displacement of point p."""
    p = np.asarray(p, dtype=float)
    G = np.zeros((3, 5))
    G[1, 0] = 1.0
    G[2, 1] = 1.0
    for k, axis in enumerate(("roll", "pitch", "yaw")):
        G[:, 2 + k] = np.cross(AXES[axis], p)
    return G


def _weight_stiffness(F, p):
    """Stiffness in (roll, pitch, yaw) of a constant force F at the point p of a body: the
    Hessian of −F·δ₂, δ₂ = ½ ω × (ω × p) the second-order displacement of p."""
    F, p = np.asarray(F, dtype=float), np.asarray(p, dtype=float)
    H = np.dot(F, p) * np.eye(3) - 0.5 * (np.outer(F, p) + np.outer(p, F))
    T = np.diag([1.0, -1.0, 1.0])          # ω = (θ, −χ, ψ)
    return T @ H @ T


def _reference_state_matrix(model):
    """State matrix over (q: frame0, frame1, body × (y, z, roll, pitch, yaw); q̇; u: yaw
    dampers 0L, 0R, 1L, 1R) of the linear model derived from energies."""
    bogie = model.bogies[0]
    sec, body = model.secondary, model.carbody
    prim = bogie.primary
    hf, hb, h2, hp = model.frame_height, body.height, sec.height, model.primary_height
    r0 = model.wheelset.nominal_radius
    nq, nu = 15, 4
    K = np.zeros((nq + nu, nq + nu))
    C = np.zeros((nq, nq))
    M = np.zeros((nq, nq))
    for j in range(2):
        M[5 * j:5 * j + 5, 5 * j:5 * j + 5] = np.diag([bogie.frame_mass, bogie.frame_mass,
                                                       *bogie.frame_inertia])
    M[10:, 10:] = np.diag([body.mass, body.mass, *body.inertia])
    kp = np.diag([prim.kx, prim.ky, prim.kz])
    cp = np.diag([prim.cx, prim.cy, prim.cz])
    ks = np.diag([sec.kx, sec.ky, sec.kz])
    cs = np.diag([sec.cx, sec.cy, sec.cz])
    yd = sec.yaw_damper
    for j, xj in enumerate((model.bogie_semi_spacing, -model.bogie_semi_spacing)):
        F = slice(5 * j, 5 * j + 5)
        # primary: frame points above the held wheelsets' axleboxes
        for xr in (bogie.semi_wheelbase, -bogie.semi_wheelbase):
            for sg in (-1.0, 1.0):
                p = (xr, sg * prim.half_spacing, hp - hf)
                G = _point_map(p)
                K[F, F] += G.T @ kp @ G
                C[F, F] += G.T @ cp @ G
                # the spring's preload carries the frame's and half the body's weight
                pre = (bogie.frame_mass + 0.5 * body.mass) * 9.81 / 4
                K[5 * j + 2:5 * j + 5, 5 * j + 2:5 * j + 5] += _weight_stiffness((0, 0, pre), p)
        assert hp == r0
        for sg in (-1.0, 1.0):
            pf = (0.0, sg * sec.half_spacing, h2 - hf)
            pb = (xj, sg * sec.half_spacing, h2 - hb)
            D = np.zeros((3, nq))
            D[:, F] = _point_map(pf)
            D[:, 10:] = -_point_map(pb)
            pre = body.mass * 9.81 / 4
            K[5 * j + 2:5 * j + 5, 5 * j + 2:5 * j + 5] += _weight_stiffness((0, 0, -pre), pf)
            K[12:15, 12:15] += _weight_stiffness((0, 0, pre), pb)
            K[:nq, :nq] += D.T @ ks @ D
            C += D.T @ cs @ D
            # yaw damper: ½ k (d_x − u)²
            E = np.zeros(nq)
            E[F] = _point_map((0.0, sg * yd.half_spacing, h2 - hf))[0]
            E[10:] = -_point_map((xj, sg * yd.half_spacing, h2 - hb))[0]
            iu = nq + 2 * j + (0 if sg < 0 else 1)
            K[:nq, :nq] += yd.stiffness * np.outer(E, E)
            K[:nq, iu] -= yd.stiffness * E
            K[iu, :nq] -= yd.stiffness * E
            K[iu, iu] += yd.stiffness
        # rotational yaw springs (two sides) and anti-roll bar on the relative angles
        for k, stiff in ((4, 2 * sec.yaw_stiffness), (2, sec.anti_roll)):
            e = np.zeros(nq)
            e[5 * j + k] = 1.0
            e[10 + k] = -1.0
            K[:nq, :nq] += stiff * np.outer(e, e)
    Minv = np.linalg.inv(M)
    A = np.zeros((2 * nq + nu, 2 * nq + nu))
    A[:nq, nq:2 * nq] = np.eye(nq)
    A[nq:2 * nq, :nq] = -Minv @ K[:nq, :nq]
    A[nq:2 * nq, nq:2 * nq] = -Minv @ C
    A[nq:2 * nq, 2 * nq:] = -Minv @ K[:nq, nq:]
    A[2 * nq:, :nq] = -K[nq:, :nq] / yd.damping
    A[2 * nq:, 2 * nq:] = -K[nq:, nq:] / yd.damping
    return A


@pytest.fixture(scope="module")
def model():
    m = manchester_vehicle1(yaw_damper=YawDamper(damping=250e3, stiffness=8e6,
                                                 half_spacing=1.3))
    return dataclasses.replace(m, secondary=dataclasses.replace(m.secondary, cx=20e3))


def test_suspension_eigenvalues_against_energy_derivation(model):
    system = System(model, wr.Track(wr.profiles.load("60E1")), 30.0, "hertz", "fastsim")
    x0 = system.initial_state()
    names = []
    for body in ("frame0", "frame1", "body"):
        names += [f"{body}.{s}" for s in ("y", "z", "roll", "pitch", "yaw")]
    for body in ("frame0", "frame1", "body"):
        names += [f"{body}.{s}" for s in ("vy", "vz", "roll_rate", "pitch_rate", "yaw_rate")]
    names += ["yawdamper0.left", "yawdamper0.right", "yawdamper1.left", "yawdamper1.right"]
    idx = [system.asm.index(n) for n in names]
    h = 1e-6
    J = np.empty((len(idx), len(idx)))
    for k, c in enumerate(idx):
        xp, xm = x0.copy(), x0.copy()
        xp[c] += h
        xm[c] -= h
        J[:, k] = (system.rhs(0.0, xp)[idx] - system.rhs(0.0, xm)[idx]) / (2 * h)
    A = _reference_state_matrix(model)
    ref = np.linalg.eigvals(A)
    got = np.linalg.eigvals(J)
    assert ref.size == got.size == 34
    for lam in ref:
        k = np.argmin(np.abs(got - lam))
        assert abs(got[k] - lam) <= 1e-6 * abs(lam), lam
        got = np.delete(got, k)
    # the reference is a real test: it has the oscillatory body modes and the yaw
    # dampers' real relaxation roots
    assert np.sum(np.abs(ref.imag) > 1.0) >= 20
    assert np.sum(np.abs(ref.imag) < 1e-9) >= 4


def test_linearise_accepts_the_vehicle(model):
    """linearise on the whole vehicle with its contact (Hertz + FASTSIM): the frames' and
    car body's vertical, roll and pitch stay dynamic; at 20 m/s on tangent track the
    linearised vehicle is stable and has the body's bounce near the held-bogie value
    √(4 kz/m) (1.17 Hz, here lowered by the primary in series)."""
    system = System(model, wr.Track(wr.profiles.load("60E1")), 20.0, "hertz", "fastsim")
    A, names, _ = linearise(system)
    assert "body.z" in names and "body.roll" in names and "yawdamper0.left" in names
    assert "ws0.z" not in names
    ev = np.linalg.eigvals(A)
    ev = ev[np.abs(ev) > 1e-6]
    assert np.max(ev.real) < 0
    f = np.abs(ev.imag) / (2 * np.pi)
    assert np.any((f > 1.0) & (f < 1.2))
