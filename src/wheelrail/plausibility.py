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
           "check_patch", "check_hertz", "LIMITS"]

#: Limits used by the checks (SI units).
LIMITS = {
    "load_warn": (100.0, 1.0e6),          # N
    "E_warn": (1.0e9, 1.0e12),            # Pa
    "mu_warn": 1.0, "mu_refuse": 2.0,     # -
    "radius_warn": (0.05, 2.0), "radius_refuse": 2.0,   # m
    "patch_warn": 0.1, "patch_refuse": 1.0,             # fraction of the relative radius
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
