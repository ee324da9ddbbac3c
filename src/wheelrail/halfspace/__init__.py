"""Elastic half-space kernels: grids, influence coefficients, FFT operators,
tangential grid solvers (steady rolling, shift) and subsurface stresses.

This package holds kernels only and never imports a method package
(normal, tangential, geometry, contact, cli); a test walks the imports. The
boundary-element normal solver is :mod:`wheelrail.normal.bem`, the coupled
normal + tangential driver and the automatic window are in
:mod:`wheelrail.contact`.

Sign conventions of tractions, displacement differences and the gap are written
down once in :mod:`wheelrail.halfspace.influence`.
"""

from .fft import ConvolutionOperator, InfluenceOperator
from .grid import Grid
from .influence import influence_kernel, point_influence, rectangle_influence
from .subsurface import SubsurfaceStresses, subsurface_stresses
from .tangential import TangentialSolution, newton_step, solve_rolling, solve_shift

__all__ = ["Grid", "influence_kernel", "point_influence", "rectangle_influence",
           "ConvolutionOperator", "InfluenceOperator",
           "solve_rolling", "solve_shift", "newton_step", "TangentialSolution",
           "subsurface_stresses", "SubsurfaceStresses"]
