"""Finite-element frictional rolling contact of a wheel on a rail (3-D, hex8, SI units).

Public names
------------
``RollingCase``
    Frozen input: wheel and rail profiles, rolling radius, load, creepage,
    friction, material, mesh size and integrator.
``seed000_case(**changes)``, ``cone_wheel``, ``head_arc_rail``
    Seed 000's Hertzian case: a 1/10 cone on a 300 mm head arc inclined by 1/10.
``indent(case)``
    Static normal contact (seed 000's first step): ``p_max``, ``a``, ``b``,
    ``pressure``.
``solve(case)``
    Rolling (both steps) with the explicit or the implicit quasi-static
    integrator: histories over the travel, the final patch, ``Fx``, ``Fy``.
``Hex8``, ``LinearElastic``
    The element and the material law (swappable parts).
``build_model``, ``write_vtu``
    The meshed model, and VTU output for ParaView.
``saturation_creepage``
    The creepage beyond which the patch slides entirely (warning threshold).
``read_restart``, ``write_restart``
    Restart files of a rolling run (``solve(case, restart=...)``).

Parts: :mod:`.mesh` (structured generator), :mod:`.elements`, :mod:`.materials`,
:mod:`._kernels` (numba element and contact kernels), :mod:`.model`
(kinematics and assembly), :mod:`.static`, :mod:`.rolling`, :mod:`.patch`,
:mod:`.output`, :mod:`.restart`.

References
----------
.. [1] M. Toumi, H. Chollet, H. Yin, "Finite element analysis of the frictional
   wheel-rail rolling contact using explicit and implicit methods", Wear 366-367
   (2016) 157-166 (seed paper 000).
"""

from .case import INTEGRATORS, RollingCase, cone_wheel, head_arc_rail, seed000_case
from .elements import Hex8
from .materials import LinearElastic
from .mesh import MeshQualityError, check_quality
from .model import build_model
from .output import write_vtu
from .restart import read_restart, write_restart
from .rolling import RollingResult, saturation_creepage, solve, stable_time_step
from .static import IndentResult, indent

__all__ = ["RollingCase", "INTEGRATORS", "seed000_case", "cone_wheel", "head_arc_rail",
           "solve", "indent", "RollingResult", "IndentResult",
           "Hex8", "LinearElastic", "build_model", "write_vtu", "check_quality",
           "MeshQualityError", "stable_time_step", "saturation_creepage", "read_restart",
           "write_restart"]
