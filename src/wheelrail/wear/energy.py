"""Wear proportional to the frictional work (energy dissipation), per contact cell.

The worn volume is proportional to the work of the friction forces: per unit
area of a cell with traction ‖τ‖ and slip ‖s‖ (slip velocity / rolling speed),
a surface point rolled through the cell dissipates ‖τ‖ ‖s‖ Δx, and

    dz/dx = k_E · ‖τ‖ · ‖s‖,

k_E the worn volume per dissipated energy [m³/J]. Summed over a patch,
Σ ‖τ‖‖s‖ ΔA is the wear number Tγ (frictional power per metre rolled, Pearce &
Sherratt 1991), so the worn volume per metre rolled is k_E · Tγ.
"""

from __future__ import annotations

import numpy as np

from ..options import configured, option
from ._base import WearLaw, _arrays

__all__ = ["Energy", "USFD_MILD_ENERGY_COEFFICIENT"]

#: The USFD law's mild-regime slope, 5.3 µg/(m·mm²) per N/mm², as worn volume per
#: dissipated energy for steel of density 7850 kg/m³: 5.3e-9 kg/J / 7850 kg/m³ [m³/J].
USFD_MILD_ENERGY_COEFFICIENT = 5.3e-9 / 7850.0


@configured
class Energy(WearLaw):
    """Frictional-work (energy) law: dz/dx = k_E ‖τ‖ ‖s‖ per cell.

    Other Parameters
    ----------------
    coefficient : float, default 6.75e-13
        Worn volume per dissipated frictional energy k_E [m³/J]. The
        coefficient is case-specific; the default is the mild-regime slope of
        the USFD law (5.3 µg/(m·mm²) per N/mm² of Tγ/A, :class:`USFD`)
        divided by the density of steel (7850 kg/m³), so that below
        Tγ/A = 10.4 N/mm² the two laws coincide.

    References
    ----------
    .. [1] T.G. Pearce, N.D. Sherratt, Prediction of wheel profile wear, Wear
       144 (1991) 343–351 (wear proportional to Tγ).
    .. [2] F. Braghin, R. Lewis, R.S. Dwyer-Joyce, S. Bruni, A mathematical model
       to predict railway wheel profile evolution due to wear, Wear 261 (2006)
       1253–1264 (the USFD coefficients; secondary, see :class:`USFD`).
    """

    name = "energy"
    aliases = ("frictional-work",)
    references = (
        "T.G. Pearce, N.D. Sherratt, Prediction of wheel profile wear, Wear 144 (1991) 343-351.",
    )

    coefficient: float = option(USFD_MILD_ENERGY_COEFFICIENT, lo=0.0, unit="m^3/J",
                                doc="worn volume per dissipated frictional energy")

    def depth_rate(self, pressure, traction, slip, speed=None):
        """dz/dx = k_E ‖τ‖ ‖s‖ [m/m] per cell (``pressure`` unused)."""
        _, t, s = _arrays(pressure, traction, slip)
        return self.coefficient * np.abs(t) * np.abs(s)
