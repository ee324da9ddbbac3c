"""Axle heights at which the wheels of a wheelset just touch their rails (rigid geometry)."""

from __future__ import annotations

import numpy as np

from .contact_search import _global_min, _Pose

__all__ = ["touching_heights"]

SIDES = ("left", "right")


def touching_heights(wheelset, track, y, roll, yaw):
    """Axle height at which each wheel just touches its rail, for prescribed roll (arrays).

    Raising the axle by dz raises every gap by dz, so the height is minus the
    smallest gap at height 0. Returns ``{side: z}`` and ``{side: beside}``
    (shape (n,); ``beside`` marks rows where the wheel lies entirely beside
    its rail).
    """
    pose = _Pose(np.asarray(y, float), np.zeros(np.size(y)), np.asarray(roll, float),
                 np.asarray(yaw, float))
    z, beside = {}, {}
    for side in SIDES:
        _, g, _ = _global_min(wheelset, track, side, pose, 2e-4, 5)
        beside[side] = g >= 0.5
        z[side] = -g
    return z, beside
