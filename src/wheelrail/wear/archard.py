"""Archard's wear law with a constant coefficient, applied per contact cell.

Archard's law for sliding wear: the worn volume is V = k N s / H for a
normal force N over a sliding distance s on a surface of hardness H. Applied
locally (Jendel 2002, eq. 1, per element of the contact grid): the depth
removed where the pressure is p and the local sliding distance s_slip is

    Δz = k · p · s_slip / H.

A surface point crossing a cell of length Δx with the dimensionless slip
‖s‖ (slip velocity / rolling speed) slides s_slip = ‖s‖ Δx, so the depth rate
per metre rolled through the cell is dz/dx = k p ‖s‖ / H.
"""

from __future__ import annotations

import numpy as np

from ..options import configured, option
from ._base import WearLaw, _arrays

__all__ = ["Archard"]


@configured
class Archard(WearLaw):
    """Archard's law with a constant wear coefficient: Δz = k p s_slip / H per cell.

    Other Parameters
    ----------------
    k : float, default 1e-4
        Dimensionless wear coefficient. The default is the order of the mild
        regions of the KTH wear map ((1–10)·10⁻⁴, :class:`KTHMap`); it is a
        placeholder to be calibrated, not a material constant.
    hardness : float, default 2.6e9
        Hardness H of the worn surface [Pa] (the KTH map's value for wheel and
        rail steel, see :class:`KTHMap`).

    References
    ----------
    .. [1] J.F. Archard, Contact and rubbing of flat surfaces, Journal of
       Applied Physics 24 (1953) 981–988.
    .. [2] T. Jendel, Prediction of wheel profile wear — comparisons with field
       measurements, Wear 253 (2002) 89–99, eq. (1) (local application per
       contact element).
    """

    name = "archard"
    references = (
        "J.F. Archard, Contact and rubbing of flat surfaces, J. Appl. Phys. 24 (1953) 981-988.",
        "T. Jendel, Prediction of wheel profile wear - comparisons with field measurements, "
        "Wear 253 (2002) 89-99.",
    )

    k: float = option(1e-4, lo=0.0, unit="", doc="dimensionless wear coefficient")
    hardness: float = option(2.6e9, lo=0.0, lo_open=True, unit="Pa",
                             doc="hardness of the worn surface")

    def depth_rate(self, pressure, traction, slip, speed=None):
        """dz/dx = k p ‖s‖ / H [m/m] per cell (arrays of one shape; ``traction`` unused)."""
        p, _, s = _arrays(pressure, traction, slip)
        return self.k * np.clip(p, 0.0, None) * np.abs(s) / self.hardness
