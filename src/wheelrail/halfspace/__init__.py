"""Elastic half-space foundations: grids, influence coefficients, FFT operators,
the normal contact problem on a grid (BEM) and subsurface stresses.

Sign conventions of tractions, displacement differences and the gap are written
down once in :mod:`wheelrail.halfspace.influence`.
"""

from .fft import ConvolutionOperator, InfluenceOperator
from .grid import Grid
from .influence import influence_kernel, point_influence, rectangle_influence
from .tangential import GapSolution, TangentialSolution, solve_gap, solve_rolling, solve_shift

__all__ = ["Grid", "influence_kernel", "point_influence", "rectangle_influence",
           "ConvolutionOperator", "InfluenceOperator",
           "solve_normal", "NormalSolution", "ContactTruncatedWarning", "hertz_grid",
           "contact_outline",
           "solve_gap", "GapSolution", "solve_rolling", "solve_shift", "TangentialSolution"]

from .subsurface import SubsurfaceStresses, subsurface_stresses  # noqa: E402

__all__ += ["subsurface_stresses", "SubsurfaceStresses"]

from .window import contact_patches, potential_contact_grid, solve_gap_auto

__all__ += ["contact_patches", "potential_contact_grid", "solve_gap_auto"]

# the grid normal solver lives with the normal methods (wheelrail.normal.bem, which imports
# this package); re-exported here (public entry) on first access, so that either module
# can be imported first
_FROM_BEM = ("ContactTruncatedWarning", "NormalSolution", "contact_outline", "hertz_grid",
             "solve_normal")


def __getattr__(name):
    if name in _FROM_BEM:
        from ..normal import bem

        return getattr(bem, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
