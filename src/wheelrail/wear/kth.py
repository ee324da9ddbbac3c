"""Archard's law with the KTH wear map: the coefficient by pressure and sliding velocity.

Jendel (2002) applies Archard's law per contact element, Δz = k p s_slip / H,
with a wear coefficient k read from a wear map of wheel and rail steel in
dry contact (after Olofsson & Telliskivi) with four regions of the contact
pressure p and the sliding velocity v = ‖s‖ V:

====================  ==========================  =======================
region                condition                   k (default, range)
====================  ==========================  =======================
seizure               p > 0.8 H                   300e-4 ((300–400)e-4)
mild                  v < 0.2 m/s                 5e-4   ((1–10)e-4)
severe                0.2 ≤ v ≤ 0.7 m/s           35e-4  ((30–40)e-4)
mild (oxidative)      v > 0.7 m/s                 5e-4   ((1–10)e-4)
====================  ==========================  =======================

with H the hardness. Enblom & Berg (2005) use the same map, scaled down for
lubricated or contaminated contact (``scale``).

Source status: the method (per-element Archard law with a map) is confirmed;
the region values and bounds could not be read in the primary sources. They
are given as options with the values as recalled from secondary
descriptions; the project's reference notes list (150–400)e-4 for the
seizure region and place the (30–40)e-4 region above 0.7 m/s instead, so
**the velocity regions of this table are unconfirmed** and the options are
there to be set from the paper.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..options import configured, option
from ._base import WearLaw, _arrays

__all__ = ["KTHMap"]


@configured
class KTHMap(WearLaw):
    """Archard's law with Jendel's KTH wear map: k by contact pressure and sliding velocity.

    Other Parameters
    ----------------
    hardness : float, default 2.6e9
        Hardness H [Pa].
    k_seizure, k_low, k_severe, k_high : float
        Coefficients of the four regions (module docstring) [-].
    v_low, v_high : float, default 0.2, 0.7
        Sliding-velocity bounds of the severe region [m/s].
    seizure_pressure : float, default 0.8
        Pressure above which the seizure coefficient applies, as a fraction of H.
    scale : float, default 1.0
        Factor on every coefficient (Enblom & Berg 2005: lubrication, contamination).

    References
    ----------
    .. [1] T. Jendel, Prediction of wheel profile wear — comparisons with field
       measurements, Wear 253 (2002) 89–99.
    .. [2] R. Enblom, M. Berg, Simulation of railway wheel profile development
       due to wear — influence of disc braking and contact environment, Wear
       258 (2005) 1055–1063.
    """

    name = "kth"
    aliases = ("kth-map", "jendel")
    needs_speed = True
    references = (
        "T. Jendel, Prediction of wheel profile wear - comparisons with field measurements, "
        "Wear 253 (2002) 89-99.",
        "R. Enblom, M. Berg, Simulation of railway wheel profile development due to wear - "
        "influence of disc braking and contact environment, Wear 258 (2005) 1055-1063.",
    )

    hardness: float = option(2.6e9, lo=0.0, lo_open=True, unit="Pa", doc="hardness")
    k_seizure: float = option(300e-4, lo=0.0, doc="k where p > seizure_pressure · H")
    k_low: float = option(5e-4, lo=0.0, doc="k below v_low")
    k_severe: float = option(35e-4, lo=0.0, doc="k between v_low and v_high")
    k_high: float = option(5e-4, lo=0.0, doc="k above v_high")
    v_low: float = option(0.2, lo=0.0, unit="m/s", doc="lower sliding-velocity bound")
    v_high: float = option(0.7, lo=0.0, unit="m/s", doc="upper sliding-velocity bound")
    seizure_pressure: float = option(0.8, lo=0.0, lo_open=True,
                                     doc="seizure bound as a fraction of the hardness")
    scale: float = option(1.0, lo=0.0, doc="factor on every coefficient")

    def _check(self):
        if self.v_high < self.v_low:
            raise InputError(f"v_high ({self.v_high}) must be >= v_low ({self.v_low})")

    def coefficient(self, pressure, sliding_velocity):
        """k [-] at pressure p [Pa] and sliding velocity v [m/s] (arrays broadcast)."""
        p = np.asarray(pressure, dtype=float)
        v = np.abs(np.asarray(sliding_velocity, dtype=float))
        k = np.where(v < self.v_low, self.k_low,
                     np.where(v <= self.v_high, self.k_severe, self.k_high))
        k = np.where(p > self.seizure_pressure * self.hardness, self.k_seizure, k)
        return self.scale * k

    def depth_rate(self, pressure, traction, slip, speed=None):
        """dz/dx = k(p, ‖s‖V) p ‖s‖ / H [m/m] per cell; ``speed`` V [m/s] is required."""
        if speed is None:
            raise InputError("the KTH wear map needs the rolling speed (speed=... in m/s) "
                             "to turn the slip into a sliding velocity")
        speed = float(speed)
        if not (np.isfinite(speed) and speed >= 0):
            raise InputError(f"speed must be a finite number >= 0 m/s, got {speed!r}")
        p, _, s = _arrays(pressure, traction, slip)
        p = np.clip(p, 0.0, None)
        s = np.abs(s)
        return self.coefficient(p, s * speed) * p * s / self.hardness
