"""Plausibility checks for wheel–rail input: values that look like the wrong unit.

The solvers accept any positive numbers, so a load of 7.5 (kN meant), a
modulus of 210 (GPa meant) or radii in millimetres would be solved and
reported as converged. These checks compare inputs with the range found in
wheel–rail contact (SI units) and either

* **warn** (:class:`PlausibilityWarning`) — unusual but possibly intended
  (a 50 N load on a test rig, a rubber modulus), or
* **refuse** (:class:`ImplausibleInputError`, an
  :class:`~wheelrail.errors.InputError`) — the result would be physically
  meaningless: a contact patch larger than the radii of the bodies (the
  half-space theory behind every method no longer applies), a friction
  coefficient above 2, a wheel radius above 2 m.

The same functions are called by the API (:func:`wheelrail.hertz` and
relatives, :class:`wheelrail.Material`, :func:`wheelrail.creep_forces`), by
case files (when they are read) and by the command line, so the three give
the same answer.

Overriding
----------
For deliberate out-of-range studies switch the checks off

* in Python: ``with wheelrail.plausibility.disabled(): ...``;
* on the command line: ``wheelrail --no-plausibility-checks COMMAND ...``;
* anywhere (also case files run by other tools): the environment variable
  ``WHEELRAIL_PLAUSIBILITY=off``.

=========================  ===============================  =====================
quantity                   warning outside                   refused
=========================  ===============================  =====================
normal load Fn             100 N … 1 MN                      (via the patch size)
Young's modulus E          1 GPa … 1000 GPa                  —
friction coefficient μ     ≤ 1                               μ > 2
wheel rolling radius       0.05 … 2 m                        > 2 m (mm given?)
patch semi-axes a, b       ≤ 10 % of the relative radii      > the relative radii
given semi-axes a, b       ≤ 20 mm                           > 50 mm (mm given?)
patch against body radii   b ≤ 10 % of the profile radii     — (near-conformal)
creepages ξ, η             |ξ| ≤ 0.05                        |ξ| > 1
spin φ                     |φ| ≤ 20 1/m                      |φ| > 1000 1/m
friction coefficient μ     μ ≥ 0.01                          —
speed V                    0.1 … 150 m/s                     > 1000 m/s
roller radius              0.1 … 2 m                         < 1 cm or > 10 m
yaw angle ψ                |ψ| ≤ 0.05 rad                    |ψ| > 0.5 rad (degrees?)
gauge − flange back        30 … 150 mm                       ≤ 0 or > 300 mm
V/ω (implied radius)       0.05 … 2 m                        < 1 cm or > 10 m (rpm?)
yield stress σ_y           100 MPa … 3 GPa                   < 1 MPa or > 10 GPa (MPa?)
=========================  ===============================  =====================

The relative radii are ``R_x = 1/(2A)`` and ``R_y = 1/(2B)`` (Johnson 1985,
§4.1); Hertz theory assumes ``a ≪ R`` (Johnson 1985, §4.1, p. 90).

References
----------
.. [1] K.L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985,
   §4.1 (assumptions of the Hertz theory: a ≪ R).
.. [2] J.J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
   Kluwer 1990, ch. 1 (half-space approximation of wheel and rail).
"""

from __future__ import annotations

import contextlib
import os
import warnings

import numpy as np

from .errors import InputError

__all__ = ["PlausibilityWarning", "ImplausibleInputError", "disabled", "enabled",
           "check_load", "check_modulus", "check_friction", "check_rolling_radius",
           "check_patch", "check_hertz", "check_semi_axes", "check_conformal",
           "check_creepage", "check_speed", "check_roller_radius", "check_yaw",
           "check_flange_back", "check_omega", "check_yield_stress", "LIMITS"]

#: Limits used by the checks (SI units).
LIMITS = {
    "load_warn": (100.0, 1.0e6),          # N
    "E_warn": (1.0e9, 1.0e12),            # Pa
    "mu_warn": 1.0, "mu_refuse": 2.0,     # -
    "radius_warn": (0.05, 2.0), "radius_refuse": 2.0,   # m
    "patch_warn": 0.1, "patch_refuse": 1.0,             # fraction of the relative radius
    "semi_axis_warn": 0.02, "semi_axis_refuse": 0.05,   # m
    "conformal_warn": 0.1,                              # b / smallest profile radius
    "creepage_warn": 0.05, "creepage_refuse": 1.0,      # -
    "spin_warn": 20.0, "spin_refuse": 1000.0,           # 1/m
    "mu_low_warn": 0.01,                                # -
    "speed_warn": (0.1, 150.0), "speed_refuse": 1000.0,  # m/s
    "roller_warn": (0.1, 2.0), "roller_refuse": (0.01, 10.0),  # m
    "yaw_warn": 0.05, "yaw_refuse": 0.5,                # rad
    "flange_room_warn": (0.03, 0.15), "flange_room_refuse": 0.3,  # gauge - flange back, m
    "omega_radius_warn": (0.05, 2.0), "omega_radius_refuse": (0.01, 10.0),  # V/omega, m
    "yield_warn": (1.0e8, 3.0e9), "yield_refuse": (1.0e6, 1.0e10),  # Pa
}

_OVERRIDE_HINT = ("override with wheelrail.plausibility.disabled(), "
                  "'wheelrail --no-plausibility-checks' or WHEELRAIL_PLAUSIBILITY=off")
_state = {"off": 0}


class PlausibilityWarning(UserWarning):
    """An input lies outside the range of wheel–rail contact (wrong unit?)."""


class ImplausibleInputError(InputError):
    """An input makes the result physically meaningless (e.g. a patch larger than the radii)."""


def enabled() -> bool:
    """True unless switched off by :func:`disabled` or ``WHEELRAIL_PLAUSIBILITY=off``."""
    if _state["off"]:
        return False
    return os.environ.get("WHEELRAIL_PLAUSIBILITY", "").strip().lower() not in (
        "off", "0", "no", "false")


@contextlib.contextmanager
def disabled():
    """Context manager: no plausibility warnings or refusals inside the block."""
    _state["off"] += 1
    try:
        yield
    finally:
        _state["off"] -= 1


def _fmt(v) -> str:
    return f"{float(v):.4g}"


def _warn(msg: str) -> None:
    warnings.warn(msg, PlausibilityWarning, stacklevel=4)


def _refuse(msg: str):
    raise ImplausibleInputError(f"{msg}; {_OVERRIDE_HINT}")


def _max(v) -> float:
    return float(np.max(np.asarray(v, dtype=float)))


def _min(v) -> float:
    return float(np.min(np.asarray(v, dtype=float)))


def check_load(load, name: str = "load") -> None:
    """Warn for a normal load outside 100 N … 1 MN [N] (kN or MN meant?)."""
    if not enabled():
        return
    lo, hi = LIMITS["load_warn"]
    if _min(load) < lo:
        _warn(f"{name} = {_fmt(_min(load))} N is below {lo:g} N, unusually small for a "
              f"wheel–rail contact (kN meant? 7.5 kN = 7500 N)")
    if _max(load) > hi:
        _warn(f"{name} = {_fmt(_max(load))} N exceeds {hi:g} N, more than any wheel load")


def check_modulus(E, name: str = "E") -> None:
    """Warn for a Young's modulus outside 1 … 1000 GPa [Pa] (GPa or MPa meant?)."""
    if not enabled():
        return
    lo, hi = LIMITS["E_warn"]
    if _min(E) < lo:
        _warn(f"{name} = {_fmt(_min(E))} Pa is below {lo:g} Pa; wheel–rail steels have "
              f"about 2.1e11 Pa (GPa or MPa meant?)")
    if _max(E) > hi:
        _warn(f"{name} = {_fmt(_max(E))} Pa exceeds {hi:g} Pa, stiffer than any engineering "
              f"material (kPa given?)")


def check_friction(mu, name: str = "mu") -> None:
    """Warn for μ > 1, refuse μ > 2 (a friction coefficient, not a percentage)."""
    if not enabled():
        return
    m = _max(mu)
    if _min(mu) < LIMITS["mu_low_warn"]:
        _warn(f"{name} = {_fmt(_min(mu))} is below {LIMITS['mu_low_warn']:g}, less than any "
              f"wheel–rail friction (0.05 on a greasy rail; a factor 100 too small?)")
    if m > LIMITS["mu_refuse"]:
        _refuse(f"{name} = {_fmt(m)} is not a plausible friction coefficient (wheel–rail "
                f"friction is 0.05 … 0.6; a percentage given?)")
    if m > LIMITS["mu_warn"]:
        _warn(f"{name} = {_fmt(m)} is above 1, unusually high for wheel–rail friction")


def check_rolling_radius(r, name: str = "wheel_rolling_radius") -> None:
    """Refuse a wheel radius above 2 m (mm given?), warn below 5 cm [m]."""
    if not enabled():
        return
    lo, hi = LIMITS["radius_warn"]
    if _max(r) > LIMITS["radius_refuse"]:
        _refuse(f"{name} = {_fmt(_max(r))} m is not a wheel radius (mm given? 460 mm = 0.46 m)")
    if _min(r) < lo:
        _warn(f"{name} = {_fmt(_min(r))} m is below {lo:g} m, unusually small for a wheel")


def check_patch(a, b, A, B) -> None:
    """Compare the semi-axes a, b [m] with the relative radii 1/(2A), 1/(2B) [m].

    Refuses a patch larger than the radii (the half-space model is
    meaningless), warns above 10 % of them (Hertz assumes a ≪ R).
    """
    if not enabled():
        return
    a, b, A, B = (np.asarray(v, dtype=float) for v in (a, b, A, B))
    with np.errstate(divide="ignore", invalid="ignore"):
        ra = a * 2.0 * A   # a / R_x
        rb = b * 2.0 * B   # b / R_y
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        _refuse("contact patch size is not finite (a modulus or load beyond the range of "
                "floating-point numbers?)")
    if np.all(np.isnan(np.maximum(ra, rb))):
        return
    worst = float(np.nanmax(np.maximum(ra, rb)))
    i = int(np.nanargmax(np.maximum(ra, rb)))
    ai, bi = a.ravel()[i % a.size], b.ravel()[i % b.size]
    Rx = 1.0 / (2.0 * A.ravel()[i % A.size])
    Ry = 1.0 / (2.0 * B.ravel()[i % B.size])
    what = (f"contact patch a = {_fmt(ai)} m, b = {_fmt(bi)} m against relative radii "
            f"R_x = {_fmt(Rx)} m, R_y = {_fmt(Ry)} m")
    if worst > LIMITS["patch_refuse"]:
        _refuse(f"{what}: the patch is larger than the bodies' radii, so the half-space "
                f"result is meaningless (load too large, modulus too small or in the wrong "
                f"unit?)")
    if worst > LIMITS["patch_warn"]:
        _warn(f"{what}: the patch exceeds 10 % of the radii, beyond the small-patch "
              f"assumption of Hertz theory")


def check_hertz(contact) -> None:
    """The checks that apply to a solved Hertz contact (load, patch size).

    The modulus is checked when the :class:`~wheelrail.Material` is made.
    """
    if not enabled():
        return
    check_load(contact.Fn, "Fn")
    check_patch(contact.a, contact.b, contact.A, contact.B)


def check_semi_axes(a, b) -> None:
    """Refuse given semi-axes above 50 mm (mm given as m?), warn above 20 mm [m]."""
    if not enabled():
        return
    for name, v in (("a", a), ("b", b)):
        m = _max(v)
        if m > LIMITS["semi_axis_refuse"]:
            _refuse(f"semi-axis {name} = {_fmt(m)} m is not a wheel–rail contact patch (a few "
                    f"mm: mm given as m? {_fmt(m)} mm = {_fmt(m * 1e-3)} m)")
        if m > LIMITS["semi_axis_warn"]:
            _warn(f"semi-axis {name} = {_fmt(m)} m is above {LIMITS['semi_axis_warn']:g} m, "
                  f"unusually large for a wheel–rail contact patch")


def check_conformal(b, wheel_profile_radius, rail_profile_radius) -> None:
    """Warn when the lateral semi-axis ``b`` exceeds 10 % of the profile radii [m].

    A concave wheel profile radius close to the rail's (e.g. −0.3001 m on
    0.3 m) makes B tiny and the Hertz patch very wide, but the bodies are then
    nearly conformal: the half-space and the quadratic gap of Hertz theory no
    longer apply (Johnson 1985, §4.1), whatever the relative radius says.
    """
    if not enabled():
        return
    radii = [abs(float(r)) for r in (wheel_profile_radius, rail_profile_radius)
             if r is not None and np.isfinite(r) and r != 0]
    if not radii:
        return
    rmin = min(radii)
    bm = _max(b)
    if bm > LIMITS["conformal_warn"] * rmin:
        _warn(f"near-conformal contact: the Hertz semi-axis b = {_fmt(bm * 1e3)} mm exceeds "
              f"{LIMITS['conformal_warn'] * 100:g} % of the profile radius {_fmt(rmin)} m "
              f"(wheel {_fmt(wheel_profile_radius)} m, rail {_fmt(rail_profile_radius)} m): "
              f"Hertz theory does not apply; use a non-Hertzian normal method on the profiles "
              f"(normal = 'bem', or 'kik-piotrowski' with a wheelset case)")


def check_creepage(xi=0.0, eta=0.0, phi=0.0) -> None:
    """Refuse |ξ|, |η| > 1 and |φ| > 1000 1/m; warn above 0.05 and 20 1/m."""
    if not enabled():
        return
    for name, v in (("xi", xi), ("eta", eta)):
        m = float(np.max(np.abs(np.asarray(v, dtype=float))))
        if m > LIMITS["creepage_refuse"]:
            _refuse(f"creepage {name} = {_fmt(m)} is not a creepage (a relative slip: "
                    f"wheel–rail values are below 0.01; a percentage or a velocity given?)")
        if m > LIMITS["creepage_warn"]:
            _warn(f"creepage {name} = {_fmt(m)} is above {LIMITS['creepage_warn']:g}, far into "
                  f"full sliding for a wheel–rail contact")
    m = float(np.max(np.abs(np.asarray(phi, dtype=float))))
    if m > LIMITS["spin_refuse"]:
        _refuse(f"spin phi = {_fmt(m)} 1/m is not a wheel–rail spin (sin(contact angle) / "
                f"rolling radius is at most about 2 1/m; 1/mm or rad given?)")
    if m > LIMITS["spin_warn"]:
        _warn(f"spin phi = {_fmt(m)} 1/m is above {LIMITS['spin_warn']:g} 1/m, unusually large "
              f"for a wheel–rail contact")


def check_speed(v, name: str = "speed") -> None:
    """Refuse a speed above 1000 m/s, warn outside 0.1 … 150 m/s (km/h given?)."""
    if not enabled():
        return
    lo, hi = LIMITS["speed_warn"]
    m = _max(np.abs(np.asarray(v, dtype=float)))
    if m > LIMITS["speed_refuse"]:
        _refuse(f"{name} = {_fmt(m)} m/s is not a train speed (the record is 160 m/s; km/h "
                f"given? {_fmt(m)} km/h = {_fmt(m / 3.6)} m/s)")
    if m > hi:
        _warn(f"{name} = {_fmt(m)} m/s is above {hi:g} m/s, faster than any train in service "
              f"(km/h given? {_fmt(m)} km/h = {_fmt(m / 3.6)} m/s)")
    if 0 < m < lo:
        _warn(f"{name} = {_fmt(m)} m/s is below {lo:g} m/s, unusually slow")


def check_roller_radius(r, name: str = "roller_radius") -> None:
    """Refuse a roller radius below 1 cm or above 10 m, warn outside 0.1 … 2 m [m]."""
    if not enabled():
        return
    lo, hi = LIMITS["roller_warn"]
    rlo, rhi = LIMITS["roller_refuse"]
    m = float(r)
    if m < rlo or m > rhi:
        _refuse(f"{name} = {_fmt(m)} m is not the radius of a roller rig's roller (0.5 … 1.5 m"
                + (")" if m < rlo else "; mm given?)"))
    if m < lo or m > hi:
        _warn(f"{name} = {_fmt(m)} m is outside {lo:g} … {hi:g} m, unusual for a roller rig")


def check_yaw(yaw, name: str = "yaw") -> None:
    """Warn for |ψ| > 0.05 rad, refuse |ψ| > 0.5 rad (degrees given?).

    A wheelset's yaw in a track stays within a few milliradians: in a bogie of
    wheelbase 2a it is about a/R against the curve radius R (0.008 rad for
    a = 1.25 m in a 150 m curve), and the flange gap over the wheelbase bounds
    it on straight track.
    """
    if not enabled():
        return
    m = _max(np.abs(np.asarray(yaw, dtype=float)))
    if m > LIMITS["yaw_refuse"]:
        _refuse(f"{name} = {_fmt(m)} rad ({np.degrees(m):.3g}°) is not a wheelset yaw angle "
                f"(degrees given? {_fmt(m)}° = {np.radians(m):.4g} rad)")
    if m > LIMITS["yaw_warn"]:
        _warn(f"{name} = {_fmt(m)} rad ({np.degrees(m):.3g}°) is above "
              f"{LIMITS['yaw_warn']:g} rad; a wheelset in track yaws by about 0.01 rad at most "
              f"(degrees or mrad meant? {_fmt(m)}° = {np.radians(m):.4g} rad, {_fmt(m)} mrad = "
              f"{m * 1e-3:.4g} rad)")


def check_flange_back(flange_back, gauge, name: str = "flange_back") -> None:
    """Refuse a flange back not fitting the gauge, warn for an unusual flange room.

    ``gauge − flange_back`` is the room of both flanges and their play: about
    75 mm for standard wheels on standard gauge (1.435 − 1.360 m, EN 13715).
    Refused when the flange back is not smaller than the gauge or the room
    exceeds 300 mm (a flange back for another gauge).
    """
    if not enabled():
        return
    fb, g = float(flange_back), float(gauge)
    room = g - fb
    if room <= 0:
        _refuse(f"{name} = {_fmt(fb)} m is not smaller than the gauge {_fmt(g)} m: the wheels "
                f"would sit outside the rails (standard: 1.360 m on 1.435 m)")
    lo, hi = LIMITS["flange_room_warn"]
    if room > LIMITS["flange_room_refuse"]:
        _refuse(f"{name} = {_fmt(fb)} m with gauge = {_fmt(g)} m leaves {room * 1e3:.0f} mm for "
                f"two flanges and their play (about 75 mm for standard wheels): a flange back "
                f"for another gauge? (standard: 1.360 m on 1.435 m)")
    if not lo <= room <= hi:
        _warn(f"{name} = {_fmt(fb)} m with gauge = {_fmt(g)} m leaves {room * 1e3:.0f} mm for "
              f"two flanges and their play, outside {lo * 1e3:.0f} … {hi * 1e3:.0f} mm "
              f"(standard: 75 mm)")


def check_omega(omega, speed, name: str = "omega") -> None:
    """Check an axle angular velocity against the speed through the implied radius V/ω.

    A rolling wheel has ω ≈ V/r with r of 0.05 … 2 m; ω in rpm (× 9.55) or
    degrees per second (× 57.3) gives an implied radius far below that.
    """
    if not enabled() or omega is None:
        return
    w, v = float(omega), float(speed)
    if not (w > 0 and v > 0):
        return
    r = v / w
    lo, hi = LIMITS["omega_radius_refuse"]
    wlo, whi = LIMITS["omega_radius_warn"]
    hint = (f"free rolling at r0 = 0.46 m is V/r0 = {v / 0.46:.4g} rad/s; rpm or deg/s given? "
            f"{_fmt(w)} rpm = {w * np.pi / 30:.4g} rad/s, {_fmt(w)} deg/s = "
            f"{np.radians(w):.4g} rad/s")
    if not lo <= r <= hi:
        _refuse(f"{name} = {_fmt(w)} rad/s at speed {_fmt(v)} m/s means a rolling radius V/ω = "
                f"{_fmt(r)} m, not a wheel ({hint})")
    if not wlo <= r <= whi:
        _warn(f"{name} = {_fmt(w)} rad/s at speed {_fmt(v)} m/s means a rolling radius V/ω = "
              f"{_fmt(r)} m, outside {wlo:g} … {whi:g} m ({hint})")


def check_yield_stress(sy, name: str = "yield_stress") -> None:
    """Refuse a yield stress below 1 MPa or above 10 GPa, warn outside 100 MPa … 3 GPa [Pa].

    Wheel and rail steels yield at 300 … 1200 MPa (489 MPa for the R900A rail steel of
    Toumi, Chollet & Yin 2016); a value in MPa or kPa given as Pa is a factor 1e6 or 1e3
    too small and makes every element yield at once. The message names the unit that
    brings the value into the usual range.
    """
    if not enabled():
        return
    lo, hi = LIMITS["yield_warn"]
    rlo, rhi = LIMITS["yield_refuse"]
    m, M = _min(sy), _max(sy)

    def hint(v):
        for unit, f in (("MPa", 1e6), ("GPa", 1e9), ("kPa", 1e3)):
            if lo <= v * f <= hi:
                return f"; {unit} given? {_fmt(v)} {unit} = {v * f:.4g} Pa"
        return ""

    usual = "wheel and rail steels yield at 300 … 1200 MPa, i.e. 3e8 … 1.2e9 Pa"
    if m < rlo:
        _refuse(f"{name} = {_fmt(m)} Pa is not the yield stress of a steel ({usual}{hint(m)})")
    if M > rhi:
        _refuse(f"{name} = {_fmt(M)} Pa is above any yield stress ({usual}; a modulus given?)")
    if m < lo:
        _warn(f"{name} = {_fmt(m)} Pa is below {lo:g} Pa, softer than any wheel or rail "
              f"steel ({usual}{hint(m)})")
    if M > hi:
        _warn(f"{name} = {_fmt(M)} Pa is above {hi:g} Pa, stronger than any wheel or rail "
              f"steel ({usual})")
