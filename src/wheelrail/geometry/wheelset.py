"""The :class:`Wheelset`: two wheel profiles on a rigid axle.

Frames
------
Track/wheelset cross-section: lateral ``y`` positive to the **right**
(looking in the running direction ``x``), height ``z`` positive **up**. The
wheelset is symmetric about its centre plane: the tape circles lie at
``y = ±e_tape`` with ``e_tape = flange_back/2 + tape_circle_offset``
(0.750 m for the standard 1360 mm / 70 mm).

Each wheel profile is given in the side-independent *profile frame* of
:mod:`wheelrail.profiles.core` (``y`` positive towards the field side,
flange at negative ``y``, origin on the tape circle, ``z`` the lower
boundary, up). On the right wheel the profile ``y`` points along the track
``+y``; on the left wheel the profile is mirrored (profile ``y`` points along
track ``−y``). The same profile object therefore describes a symmetric
wheelset; give ``wheel_right`` for an asymmetric one.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .._validation import in_range, positive
from ..errors import InputError, ProfileError
from ..plausibility import check_rolling_radius
from ._checks import check_profile, check_side
from ._curves import PiecewiseCubic, sample_profile

__all__ = ["Wheelset"]


@dataclass(frozen=True, eq=False)
class Wheelset:
    """A rigid wheelset with (possibly different) left and right wheel profiles.

    Parameters
    ----------
    wheel : Profile
        Wheel profile (kind ``"wheel"``) of the **left** wheel — and of the
        right wheel unless ``wheel_right`` is given — in the profile frame
        (y to the field side, origin on the tape circle, z up). It is mirrored
        when placed on the left side.
    nominal_radius : float
        Wheel radius at the tape circle r0 [m] (default 0.46).
    flange_back : float
        Distance between the backs of the flanges [m] (default 1.360).
    wheel_right : Profile, optional
        Right wheel profile in the same profile-frame convention; ``None``
        (default) uses ``wheel``.
    tape_circle_offset : float
        Lateral distance from the flange back to the profile origin (tape
        circle) [m] (default 0.070, S1002).

    Attributes
    ----------
    e_tape : float
        Half the distance between the tape circles [m].
    """

    wheel: object
    nominal_radius: float = 0.46
    flange_back: float = 1.360
    wheel_right: object = None
    tape_circle_offset: float = 0.070

    def __post_init__(self):
        if self.wheel is None:
            raise InputError("wheel must be a wheel Profile, got None")
        check_profile("wheel", self.wheel, "wheel")
        if self.wheel_right is None:
            object.__setattr__(self, "wheel_right", self.wheel)
        else:
            check_profile("wheel_right", self.wheel_right, "wheel")
        object.__setattr__(self, "nominal_radius",
                           float(positive("nominal_radius", self.nominal_radius)))
        object.__setattr__(self, "flange_back", float(positive("flange_back", self.flange_back)))
        object.__setattr__(self, "tape_circle_offset",
                           float(in_range("tape_circle_offset", self.tape_circle_offset, 0.0, 0.5)))

        check_rolling_radius(self.nominal_radius, "nominal_radius")
        if self.flange_back > 3.0:
            raise InputError(f"flange_back = {self.flange_back!r} m is implausible (mm given?)")
        for name, p in (("wheel", self.wheel), ("wheel_right", self.wheel_right)):
            z_max = float(np.max(np.asarray(p(np.linspace(p.y_min, p.y_max, 64)))))
            if z_max >= self.nominal_radius:
                raise ProfileError(f"{name}: profile rises {z_max!r} m above the tape circle, more "
                                   f"than the nominal radius {self.nominal_radius!r} m")

    @property
    def wheel_left(self):
        """Profile of the left wheel (``wheel``)."""
        return self.wheel

    @property
    def e_tape(self) -> float:
        """Half the distance between the tape circles [m]."""
        return 0.5 * self.flange_back + self.tape_circle_offset

    def profile(self, side: str):
        """Wheel profile of ``side`` ("left" or "right")."""
        return self.wheel if check_side(side) == "left" else self.wheel_right

    def curve(self, side: str) -> PiecewiseCubic:
        """Spline of the wheel profile z(s) of ``side`` in its profile frame (cached)."""
        return self._curves[check_side(side)]

    @cached_property
    def _curves(self) -> dict:
        out = {"left": PiecewiseCubic.through(*sample_profile(self.wheel))}
        out["right"] = (out["left"] if self.wheel_right is self.wheel
                        else PiecewiseCubic.through(*sample_profile(self.wheel_right)))
        return out

    def rolling_radius(self, side: str, s):
        """Radius r = r0 − z(s) [m] at wheel profile coordinate ``s`` [m]."""
        return self.nominal_radius - self.curve(side).eval(s, 0)[0]
