"""Reference geometries and closed forms for checking the dynamics.

* :func:`cone_track` — a conical wheelset (rolling radius r0 − λ y, no flange)
  on nearly knife-edge rails (a 1 mm crown), laid so that the contact points lie
  ``l0`` from the centre: the geometry of Klingel's kinematic oscillation and of
  the linear wheelset theory (constant conicity, contact points fixed on the
  rails, negligible gravitational stiffness);
* :func:`klingel_wavelength` — Klingel's kinematic wavelength
  2π √(r0 l0 / λ) (Klingel 1883; Wickens 2003, §2.2).

References
----------
.. [1] W. Klingel, Über den Lauf der Eisenbahnwagen auf gerader Bahn, Organ
   für die Fortschritte des Eisenbahnwesens 38 (1883) 113–123.
.. [2] A.H. Wickens, *Fundamentals of rail vehicle dynamics*, Swets &
   Zeitlinger 2003, §2.2 (kinematic oscillation of a wheelset).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..geometry import Track, Wheelset
from ..profiles import Profile

__all__ = ["cone_track", "klingel_wavelength"]


def klingel_wavelength(nominal_radius: float, half_distance: float, conicity: float) -> float:
    """Klingel's wavelength 2π √(r0 l0 / λ) [m].

    Examples
    --------
    >>> round(klingel_wavelength(0.46, 0.75, 0.2), 3)
    8.252
    """
    for name, v in (("nominal_radius", nominal_radius), ("half_distance", half_distance),
                    ("conicity", conicity)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise InputError(f"{name} must be > 0, got {v!r}")
    return 2.0 * math.pi * math.sqrt(nominal_radius * half_distance / conicity)


def cone_track(conicity: float = 0.2, nominal_radius: float = 0.46, half_distance: float = 0.75,
               crown_radius: float = 0.001, flange_back: float = 1.36):
    """A conical wheelset and a track on which it touches at ±``half_distance`` when centred.

    The wheel profile is the cone z = λ y (rolling radius r0 − λ y, y towards the
    field side) over −40 … +60 mm around the tape circle; the rails have a
    circular crown of radius ``crown_radius`` whose slope is λ at the rail
    profile's origin (the rail given in its inclined position), so that a centred
    wheelset touches each rail there, on its tape circle; the gauge is set so that
    this point lies ``half_distance`` from the centre line.

    The crown radius R sets how far the contact point moves on the rail when the
    wheelset rolls by θ (R θ, with θ ≈ λ y / l0 for a shift y): the effective
    conicity is λ (1 + O(R λ / l0)). The default R = 1 mm makes the rail a knife
    edge to 0.03 % (Klingel's wavelength within 0.01 %, the pure-rolling offset
    in a curve within 0.03 %); a railway crown of 300 mm would change them by
    −3.7 % and −7.3 %.

    Parameters
    ----------
    conicity : float
        λ = tan of the cone angle, in (0, 0.2].
    nominal_radius : float
        r0 [m].
    half_distance : float
        l0 [m]: half the distance between the contact points at the centred position.
    crown_radius : float
        Radius of the rail crown [m] (default 1 mm: nearly a knife edge).
    flange_back : float
        Distance between the wheels' inner faces [m] (the tape circle lies
        ``half_distance − flange_back/2`` from the inner face).

    Returns
    -------
    wheelset : Wheelset
    track : Track
    """
    if not (0.0 < conicity <= 0.2):
        raise InputError(f"conicity must lie in (0, 0.2] (the rail inclination limit), got "
                         f"{conicity!r}")
    offset = half_distance - 0.5 * flange_back
    if not 0.0 < offset < 0.2:
        raise InputError(f"half_distance − flange_back/2 must lie in (0, 0.2) m, got {offset!r}")
    yw = np.linspace(-0.040, 0.060, 401)
    wheel = Profile(yw, conicity * yw, kind="wheel", name=f"cone 1:{1 / conicity:g}")
    ws = Wheelset(wheel, nominal_radius=nominal_radius, flange_back=flange_back,
                  tape_circle_offset=offset)
    # rail head, given in its inclined position: a circle of radius R whose slope is λ at
    # the contact point y = 0, ±min(35 mm, 0.6 R) of running surface, 30 mm deep steep faces
    R = float(crown_radius)
    g = math.atan(conicity)
    y0 = R * math.sin(g)                       # circle centre abscissa (slope 0 there)
    half = min(0.035, 0.6 * R)
    yr = np.linspace(-half, half, 351)
    zr = np.sqrt(R * R - (yr - y0) ** 2) - R * math.cos(g)
    drop = np.linspace(0.0, 0.030, 31)[1:]
    y_all = np.concatenate([(yr[0] - 0.004 * drop / 0.030)[::-1], yr, yr[-1] + 0.004 * drop / 0.030])
    z_all = np.concatenate([(zr[0] - drop)[::-1], zr, zr[-1] - drop])
    rail = Profile(y_all, z_all, kind="rail", name=f"crown R{R * 1e3:g}, inclined 1:{1 / conicity:g}")
    gauge = 2.0 * half_distance
    for _ in range(8):
        track = Track(rail, gauge=gauge, inclination=conicity, canted=True)
        # the contact point (rail profile y = 0) must lie at u = l0
        uc = track.placement("right").offset
        err = uc - half_distance
        if abs(err) < 1e-10:
            break
        gauge -= 2.0 * err
    return ws, track
