"""Elastic half-space foundations: grids, influence coefficients, FFT operators,
the normal contact problem on a grid (BEM) and subsurface stresses.

Sign conventions of tractions, displacement differences and the gap are written
down once in :mod:`wheelrail.halfspace.influence`.
"""

from .fft import ConvolutionOperator, InfluenceOperator
from .grid import Grid
from .influence import influence_kernel, point_influence, rectangle_influence

# the grid normal solver lives with the normal methods; re-exported here (public entry)
from ..normal.bem import (ContactTruncatedWarning, NormalSolution, contact_outline,  # noqa: E402
                          hertz_grid, solve_normal)
from .tangential import (GapSolution, TangentialSolution, solve_gap, solve_rolling,  # noqa: E402
                         solve_shift)

__all__ = ["Grid", "influence_kernel", "point_influence", "rectangle_influence",
           "ConvolutionOperator", "InfluenceOperator",
           "solve_normal", "NormalSolution", "ContactTruncatedWarning", "hertz_grid",
           "contact_outline",
           "solve_gap", "GapSolution", "solve_rolling", "solve_shift", "TangentialSolution"]

from .subsurface import SubsurfaceStresses, subsurface_stresses  # noqa: E402

__all__ += ["subsurface_stresses", "SubsurfaceStresses"]

from .window import contact_patches, potential_contact_grid, solve_gap_auto

__all__ += ["contact_patches", "potential_contact_grid", "solve_gap_auto"]
