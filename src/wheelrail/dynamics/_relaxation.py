"""The creep-relaxation law of :mod:`wheelrail.dynamics` (private kernels).

The creep forces of every wheel follow their steady values Q_t with a first-order lag in
the distance rolled, dq/dt = (Q_t − q) V/L, L = ``P[relax]`` · max(a, floor): the
relaxation length in semi-axes a (the load-weighted semi-axis of the wheel's patches
along the rolling direction). One law for the wheelset, bogie and vehicle equations
(:mod:`._motion`, :mod:`._vehicle_motion`); the fixed-step integrator updates the
relaxation states exactly over each stage (:func:`wheelrail.dynamics._motion.relax_stage`).

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system dynamics
   including multi-point contact, VSD 43 (2005) 455–483 (creep-force relaxation).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._motion_common import _G_FLOOR, _G_OX, _G_RELAX

__all__ = ["relax_gains", "relax_derivative"]


@njit(cache=True)
def relax_gains(P, V, amean, k):
    """Rates k = V/L [1/s] of the creep relaxation of every wheel, ``k`` (n_ws, 2).

    L = ``P[relax]`` · max(a, floor): the relaxation length in semi-axes a (the
    load-weighted semi-axis of the wheel's patches along the rolling direction).
    """
    nw = amean.shape[0]
    for i in range(nw):
        for side in range(2):
            k[i, side] = V / (P[_G_RELAX] * max(amean[i, side], P[_G_FLOOR]))


@njit(cache=True)
def relax_derivative(x, P, V, Qt, amean, dx):
    """The creep-relaxation law: dq/dt = (Q_t − q) V/L for the relaxation states q of
    every wheel (first-order lag in the distance rolled; Q_t the steady creep forces,
    (n_ws, 2, 5)). Writes the relaxation rows of ``dx``."""
    nw = Qt.shape[0]
    ox = int(P[_G_OX])
    k = np.empty((nw, 2))
    relax_gains(P, V, amean, k)
    for i in range(nw):
        for side in range(2):
            for c in range(5):
                j = ox + 10 * i + 5 * side + c
                dx[j] = (Qt[i, side, c] - x[j]) * k[i, side]
