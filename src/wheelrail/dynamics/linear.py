"""Linear stability: the classical two-degree-of-freedom wheelset and the linearised models.

* :class:`LinearWheelset` — the wheelset of the linear theory (Wickens 2003,
  ch. 4; Iwnicki 2006, ch. 8): lateral y and yaw ψ, conicity λ, linear creep
  coefficients f11 (longitudinal) and f22 (lateral), no spin creep, primary
  lateral stiffness k_y and yaw stiffness k_ψ to a frame moving at V::

      m ÿ + 2 f22 (ẏ/V − ψ) + (k_y + k_g) y = 0
      Iz ψ̈ + 2 f11 l0² ψ̇/V + 2 f11 l0 λ y/r0 + k_ψ ψ = 0

  Its characteristic polynomial a4 s⁴ + … + a0 gives the linear critical speed
  both from the eigenvalues (the largest real part crosses zero) and from the
  Routh–Hurwitz condition a3 a2 a1 − a4 a1² − a3² a0 = 0 (all a_i > 0).
* :func:`linearise` — the Jacobian of the full nonlinear model (any profiles,
  any contact methods) about its equilibrium on tangent track by central
  differences, the fast positions (heights, rolls, pitch, rail deflections)
  condensed statically (their accelerations set to zero), leaving the lateral,
  yaw and spin dynamics; :func:`eigenvalues_over_speed` and
  :func:`linear_critical_speed` on it.

References
----------
.. [1] A.H. Wickens, *Fundamentals of rail vehicle dynamics: guidance and
   stability*, Swets & Zeitlinger 2003, ch. 4 (the wheelset's stability,
   critical speed of the wheelset with yaw and lateral restraint).
.. [2] S. Iwnicki (ed.), *Handbook of railway vehicle dynamics*, CRC 2006,
   ch. 8 (A.H. Wickens, J.P. Pascal: stability; the 2-DOF wheelset).
.. [3] E.J. Routh, *A treatise on the stability of a given state of motion*,
   Macmillan 1877; A. Hurwitz, Math. Ann. 46 (1895) 273–284.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..errors import ConvergenceError, InputError

__all__ = ["LinearWheelset", "linearise", "eigenvalues_over_speed", "linear_critical_speed",
           "hurwitz_quartic"]


def hurwitz_quartic(a) -> float:
    """Routh–Hurwitz determinant of a quartic a4 s⁴ + a3 s³ + a2 s² + a1 s + a0.

    With all coefficients positive, the roots lie in the left half plane iff
    Δ3 = a3 a2 a1 − a4 a1² − a3² a0 > 0 (Δ2 = a3 a2 − a4 a1 > 0 then follows).
    """
    a4, a3, a2, a1, a0 = (float(v) for v in a)
    return a3 * a2 * a1 - a4 * a1 * a1 - a3 * a3 * a0


@dataclass(frozen=True)
class LinearWheelset:
    """The classical two-degree-of-freedom wheelset (frozen, SI; see the module docstring).

    Parameters
    ----------
    mass, yaw_inertia : float
        m [kg], Iz [kg m²].
    nominal_radius, half_distance, conicity : float
        r0 [m], l0 [m], λ [-].
    f11, f22 : float
        Longitudinal and lateral creep coefficients of one wheel [N].
    lateral_stiffness, yaw_stiffness : float
        k_y [N/m] and k_ψ [N m/rad] of the primary suspension (whole wheelset).
    gravitational_stiffness : float
        k_g [N/m] (0: not included).

    Examples
    --------
    The wheelset of Wickens' example (Iwnicki 2006, ch. 8):

    >>> w = LinearWheelset(1813.0, 1120.0, 0.46, 0.7465, 0.2, 8.229e6, 7.133e6,
    ...                    2 * 3.884e6, 2 * 1e6 * 1.0 ** 2)
    >>> round(w.critical_speed(), 2)
    74.04
    """

    mass: float
    yaw_inertia: float
    nominal_radius: float
    half_distance: float
    conicity: float
    f11: float
    f22: float
    lateral_stiffness: float
    yaw_stiffness: float
    gravitational_stiffness: float = 0.0

    def __post_init__(self):
        for name in ("mass", "yaw_inertia", "nominal_radius", "half_distance", "conicity", "f11",
                     "f22"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"LinearWheelset: {name} must be > 0, got {v!r}")
        for name in ("lateral_stiffness", "yaw_stiffness", "gravitational_stiffness"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise InputError(f"LinearWheelset: {name} must be >= 0, got {v!r}")

    def matrices(self, speed: float):
        """Mass, damping and stiffness matrices (2, 2) at ``speed`` [m/s] for (y, ψ)."""
        V = float(speed)
        if not V > 0:
            raise InputError(f"speed must be > 0, got {speed!r}")
        l0, r0, lam = self.half_distance, self.nominal_radius, self.conicity
        M = np.diag([self.mass, self.yaw_inertia])
        C = np.diag([2.0 * self.f22 / V, 2.0 * self.f11 * l0 * l0 / V])
        K = np.array([[self.lateral_stiffness + self.gravitational_stiffness, -2.0 * self.f22],
                      [2.0 * self.f11 * l0 * lam / r0, self.yaw_stiffness]])
        return M, C, K

    def state_matrix(self, speed: float) -> np.ndarray:
        """A (4, 4) of ẋ = A x, x = (y, ψ, ẏ, ψ̇)."""
        M, C, K = self.matrices(speed)
        Mi = np.linalg.inv(M)
        return np.block([[np.zeros((2, 2)), np.eye(2)], [-Mi @ K, -Mi @ C]])

    def eigenvalues(self, speed: float) -> np.ndarray:
        """The four eigenvalues at ``speed`` [1/s]."""
        return np.linalg.eigvals(self.state_matrix(speed))

    def characteristic(self, speed: float) -> np.ndarray:
        """(a4, a3, a2, a1, a0) of det(M s² + C s + K)."""
        M, C, K = self.matrices(speed)
        m, I = M[0, 0], M[1, 1]
        c1, c2 = C[0, 0], C[1, 1]
        return np.array([m * I, m * c2 + I * c1, m * K[1, 1] + c1 * c2 + I * K[0, 0],
                         c1 * K[1, 1] + c2 * K[0, 0], K[0, 0] * K[1, 1] - K[0, 1] * K[1, 0]])

    def critical_speed(self, method: str = "eigenvalues", bracket=(0.5, 2000.0)) -> float:
        """Linear critical speed [m/s]: the lowest speed at which the motion is undamped.

        ``method``: ``"eigenvalues"`` (largest real part = 0) or ``"routh-hurwitz"``
        (Δ3 = 0), both by Brent's method to 1e-12 relative on the first sign change
        in ``bracket`` (scanned on a log grid).
        """
        if method == "eigenvalues":
            def f(V):
                return float(np.max(self.eigenvalues(V).real))
        elif method == "routh-hurwitz":
            def f(V):
                return -hurwitz_quartic(self.characteristic(V))
        else:
            raise InputError(f"method must be 'eigenvalues' or 'routh-hurwitz', got {method!r}")
        return _first_crossing(f, bracket)


def _first_crossing(f, bracket, n=200):
    lo, hi = (float(v) for v in bracket)
    grid = np.geomspace(lo, hi, n)
    prev = f(grid[0])
    if prev > 0:
        raise ConvergenceError(f"unstable already at {lo!r} m/s")
    for a, b in zip(grid[:-1], grid[1:]):
        cur = f(b)
        if cur > 0:
            return float(brentq(f, a, b, xtol=1e-12 * b, rtol=1e-14))
        prev = cur
    raise ConvergenceError(f"no critical speed below {hi!r} m/s")


# --------------------------------------------------------------------------- full models
def linearise(system, *, y=0.0, steps=None):
    """State matrix of a :class:`~wheelrail.dynamics.simulate.System` about its equilibrium.

    The equilibrium on tangent track at the lateral position ``y`` (heights,
    rolls, rails and the free wheelsets' spin solved) is perturbed state by state
    (central differences: 20 µm, 20 µrad, 20 µm/s, 20 µrad/s, 2e-4 rad/s of spin); the fast
    positions are condensed statically: with the Jacobian J, slow states S and
    fast positions F whose acceleration rows R vanish, F = G S with
    G = −J_RF⁻¹ J_RS, their velocities Ḟ = G_q q̇ (G_q: the part of G on the slow
    positions q), and

        A = J_SS + J_SF G + J_SV G_q (q̇ columns)

    (J_SV: the slow equations' dependence on the fast velocities; the roll rate
    that follows the lateral motion moves the contact points laterally by r0 θ̇,
    which with the roll-induced shift of the contact points keeps the kinematic
    wavelength of a cone at Klingel's).

    Returns
    -------
    A : ndarray, shape (k, k)
    names : list of str
        The slow states (lateral, yaw and their rates, spin, frame lateral and yaw,
        relaxation states).
    x0 : ndarray
        The equilibrium state.
    """
    asm = system.asm
    given = {f"ws{i}.y": y for i in range(asm.n_ws)}
    x0 = system.initial_state(given)
    if getattr(asm, "vehicle", False):      # frames and car body stay dynamic
        cols, rows, _, _ = asm.quasi_static(spin=False, linear=True)
    else:
        cols, rows, _, _ = asm.quasi_static(spin=False)
    fast_vel = set()
    for c, r in zip(cols, rows):
        if r != c:
            fast_vel.add(r)
    fast_pos = list(cols)
    slow = [k for k in range(asm.n) if k not in fast_pos and k not in fast_vel]
    # central differences with small steps: FASTSIM's partial slip makes the forces
    # cubic in the creepages already at ~1e-4, and the contact search resolves 0.2 µm
    h = np.empty(asm.n)
    for k, name in enumerate(asm.names):
        leaf = name.rsplit(".", 1)[-1]
        if leaf == "omega":
            h[k] = 2e-4
        elif leaf.startswith("Qt_"):
            h[k] = 1.0           # relaxed creep forces [N]
        else:
            h[k] = 2e-5          # m, rad, m/s, rad/s
    if steps is not None:
        h[:] = steps
    n = asm.n
    J = np.empty((n, n))
    for k in range(n):
        xp, xm = x0.copy(), x0.copy()
        xp[k] += h[k]
        xm[k] -= h[k]
        J[:, k] = (system.rhs(0.0, xp) - system.rhs(0.0, xm)) / (2.0 * h[k])
    R = list(rows)
    # fast positions follow the slow states quasi-statically, ΔF = G ΔS, and so do their
    # velocities, ΔḞ = G ΔṠ = G A ΔS (the roll rate of a wheelset moves its contact
    # points laterally: this term sets the kinematic wavelength)
    G = -np.linalg.solve(J[np.ix_(R, fast_pos)], J[np.ix_(R, slow)])
    A = J[np.ix_(slow, slow)] + J[np.ix_(slow, fast_pos)] @ G
    # fast velocities: Ḟ = G_q q̇ with G_q the part of G on the slow positions q (their
    # velocities are slow states); each fast position's acceleration row is its velocity
    # state (a rail's support point has none)
    vel_of = {}
    for j, k in enumerate(slow):
        name = asm.names[k]
        for pos, v in ((".y", ".vy"), (".yaw", ".yaw_rate")):
            if name.endswith(pos):
                vel_of[j] = slow.index(asm.names.index(name[: -len(pos)] + v))
    for k, (c, r) in enumerate(zip(cols, rows)):
        if r == c:
            continue
        for jq, jv in vel_of.items():
            A[:, jv] += J[slow, r] * G[k, jq]
    return A, [asm.names[k] for k in slow], x0


def eigenvalues_over_speed(make_system, speeds) -> np.ndarray:
    """Eigenvalues of the linearised model at each speed: array (n_speeds, k), each row
    sorted by decreasing real part. ``make_system(V)`` returns the System at speed V."""
    out = []
    for V in np.atleast_1d(speeds):
        A, _, _ = linearise(make_system(float(V)))
        ev = np.linalg.eigvals(A)
        out.append(ev[np.argsort(-ev.real)])
    return np.array(out)


def linear_critical_speed(make_system, bracket=(5.0, 200.0), n=16, xtol=0.01) -> dict:
    """Lowest speed at which an eigenvalue of the linearised model crosses to Re > 0.

    Scans ``n`` speeds in ``bracket`` (linear), then bisects (Brent) the first
    sign change of the largest real part to ``xtol`` [m/s].

    Returns
    -------
    dict
        ``speed`` [m/s], ``frequency`` [Hz] of the critical mode, ``wavelength`` [m],
        ``scan`` (speeds, largest real parts).
    """
    def growth(V):
        A, _, _ = linearise(make_system(float(V)))
        ev = np.linalg.eigvals(A)
        # structural zero modes (the spin held at V/r0, a neutral position) carry no
        # stability information: their eigenvalue is 0 up to round-off
        ev = ev[np.abs(ev) > 1e-6]
        return float(np.max(ev.real)), ev

    grid = np.linspace(bracket[0], bracket[1], n)
    vals = []
    prev = None
    for a in grid:
        g, _ = growth(a)
        vals.append(g)
        if g > 0:
            if prev is None:
                raise ConvergenceError(f"the linearised model is unstable already at "
                                       f"{a!r} m/s")
            Vc = float(brentq(lambda V: growth(V)[0], prev, a, xtol=xtol))
            _, ev = growth(Vc)
            k = int(np.argmax(ev.real))
            f = abs(ev[k].imag) / (2 * np.pi)
            return {"speed": Vc, "frequency": f, "wavelength": Vc / f if f > 0 else math.inf,
                    "scan": (grid[:len(vals)], np.array(vals))}
        prev = a
    raise ConvergenceError(f"the linearised model is stable up to {bracket[1]!r} m/s")


@dataclass(frozen=True)
class LinearBogie:
    """Boocock's linear theory of steady curving for a two-axle bogie (frozen, SI).

    Two wheelsets at x = ±a (a = ``semi_wheelbase``, leading first) with conicity λ,
    linear creep coefficients f11, f22 per wheel (no spin creep, no gravitational
    stiffness), each joined to the frame by primary springs kx (longitudinal, at ±b)
    and ky (lateral) per side; the frame joined to the car body, which follows the
    track, by secondary springs (lateral ``ky2`` per side, yaw stiffness ``k_yaw2``).
    In a curve of radius R (to the right; no cant deficiency, quasi-static), with y
    and ψ of each body relative to its local track tangent::

        lateral creep on wheelset i:  F_y = 2 f22 ψ_i
        creep yaw moment:             M_i = −2 f11 l0 (λ y_i / r0 + l0 / R)
        primary lateral:   −2 ky (y_i + a_i²/(2R) − y_f − a_i ψ_f)
        primary yaw:       −2 kx b² (ψ_i + a_i/R − ψ_f)

    and the frame's equilibrium with the reactions and its secondary suspension.

    References
    ----------
    .. [1] D. Boocock, Steady-state motion of railway vehicles on curved track,
       J. Mech. Eng. Sci. 11 (1969) 556–566.
    .. [2] A.H. Wickens, *Fundamentals of rail vehicle dynamics*, 2003, ch. 9.
    """

    semi_wheelbase: float
    nominal_radius: float
    half_distance: float
    conicity: float
    f11: float
    f22: float
    kx: float
    ky: float
    b: float
    ky2: float = 0.0
    k_yaw2: float = 0.0

    def curving(self, radius: float, direction: str = "right") -> dict:
        """Steady curving: y [m] and yaw ψ [rad] of both wheelsets and the frame."""
        a, r0, l0, lam = self.semi_wheelbase, self.nominal_radius, self.half_distance, self.conicity
        f11, f22, kx, ky, b = self.f11, self.f22, self.kx, self.ky, self.b
        k = (1.0 if direction == "right" else -1.0) / float(radius)
        # unknowns u = (y1, ψ1, y2, ψ2, yf, ψf); rows: forces and moments = 0
        A = np.zeros((6, 6))
        rhs = np.zeros(6)
        for i, xi in enumerate((a, -a)):
            jy, jp = 2 * i, 2 * i + 1
            # wheelset lateral: 2 f22 ψ − 2 ky (y + κ x²/2 − yf − x ψf) = 0
            A[jy, jp] += 2 * f22
            A[jy, jy] += -2 * ky
            A[jy, 4] += 2 * ky
            A[jy, 5] += 2 * ky * xi
            rhs[jy] += 2 * ky * k * xi * xi / 2
            # wheelset yaw: −2 f11 l0 (λ y / r0 + l0 κ) − 2 kx b² (ψ + κ x − ψf) = 0
            A[jp, jy] += -2 * f11 * l0 * lam / r0
            A[jp, jp] += -2 * kx * b * b
            A[jp, 5] += 2 * kx * b * b
            rhs[jp] += 2 * f11 * l0 * l0 * k + 2 * kx * b * b * k * xi
            # frame lateral and yaw: the reactions
            A[4, jy] += 2 * ky
            A[4, 4] += -2 * ky
            A[4, 5] += -2 * ky * xi
            rhs[4] += -2 * ky * k * xi * xi / 2
            A[5, jy] += 2 * ky * xi
            A[5, 4] += -2 * ky * xi
            A[5, 5] += -2 * ky * xi * xi
            rhs[5] += -2 * ky * xi * k * xi * xi / 2
            A[5, jp] += 2 * kx * b * b
            A[5, 5] += -2 * kx * b * b
            rhs[5] += -2 * kx * b * b * k * xi
        A[4, 4] += -2 * self.ky2
        A[5, 5] += -self.k_yaw2
        u = np.linalg.solve(A, rhs)
        return {"y": u[[0, 2]], "yaw": u[[1, 3]], "frame_y": float(u[4]),
                "frame_yaw": float(u[5])}
