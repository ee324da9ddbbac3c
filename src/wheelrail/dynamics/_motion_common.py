"""What the compiled equations of motion share (private): parameter-vector indices and the
flexible rails' equations.

The indices name the places of the global and per-wheelset parameters in the vector ``P``
of :class:`wheelrail.dynamics.model.Assembly` (``GP``, ``WP``) for the kernels of the
wheelset and bogie (:mod:`._motion`), the vehicle (:mod:`._vehicle_motion`) and the creep
relaxation (:mod:`._relaxation`).

Rails (:func:`rail_rates`): per rail and direction, the rail head (mass m, displacement u,
velocity v) sits on the rail/pad element (k1, c1) above a massless intermediate point w,
which the support element (k2, c2) joins to the ground::

    m v̇ = F_r − k1 (u − w) − c1 (v − ẇ),    ẇ = (k1 (u − w) + c1 v − k2 w)/(c1 + c2)

with F_r the contact force on the rail (the opposite of the wheel's).

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system dynamics
   including multi-point contact, VSD 43 (2005) 455–483, §2.3.3.
"""

from __future__ import annotations

from numba import njit

from .model import GP, WP

# global parameters
_G_NWS = GP["n_ws"]
_G_FRAME = GP["has_frame"]
_G_RAILS = GP["rails"]
_G_RELAX = GP["relax"]
_G_SPIN = GP["spin_free"]
_G_G = GP["g"]
_G_R0 = GP["r0"]
_G_OF = GP["off_frame"]
_G_OR = GP["off_rails"]
_G_OX = GP["off_relax"]
_G_FLOOR = GP["relax_floor"]
_G_RAIL = (GP["rail_lat_k1"], GP["rail_ver_k1"])
_G_FM = GP["frame_m"]
_G_SEC = GP["sec_kx"]
_G_BODY = GP["body_m"]
_G_VEHICLE = GP["vehicle"]
# per-wheelset parameters (offsets in a wheelset's block)
_WP_IX = WP["Ix"]
_WP_IY = WP["Iy"]
_WP_IZ = WP["Iz"]
_WP_B = WP["b"]
_WP_CARRIED_M = WP["carried_m"]
_WP_CX = WP["cx"]
_WP_CY = WP["cy"]
_WP_CZ = WP["cz"]
_WP_KX = WP["kx"]
_WP_KY = WP["ky"]
_WP_KZ = WP["kz"]
_WP_M = WP["m"]
_WP_PRELOAD = WP["preload"]
_WP_X = WP["x"]


@njit(cache=True)
def rail_rates(i, orl, P, x, Qn, Qt, dx):
    """Rates ``dx`` of the rail states (w, u, v per side and direction, from ``orl`` + 12 i)
    under wheelset ``i`` from the wheels' generalised contact forces ``Qn``, ``Qt``
    (n_ws, 2, 5; components 0 and 1: lateral and vertical) — module docstring."""
    for side in range(2):
        for d in range(2):
            rb = orl + 12 * i + 6 * side + 3 * d
            gb = _G_RAIL[d]
            k1, c1, k2, c2, mr = P[gb], P[gb + 1], P[gb + 2], P[gb + 3], P[gb + 4]
            w, u, v = x[rb], x[rb + 1], x[rb + 2]
            Fr = -(Qn[i, side, d] + Qt[i, side, d])
            if c1 + c2 > 0:
                wd = (k1 * (u - w) + c1 * v - k2 * w) / (c1 + c2)
            else:
                wd = k1 * v / (k1 + k2)
            dx[rb] = wd
            dx[rb + 1] = v
            dx[rb + 2] = (Fr - k1 * (u - w) - c1 * (v - wd)) / mr
