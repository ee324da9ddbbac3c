"""Elastic half-space kernels: grids, influence coefficients, FFT operators (normal,
rolling) and subsurface stresses.

This package holds array kernels only and imports nothing above the core
types; a test walks the imports. The boundary-element normal solver is
:mod:`wheelrail.normal.bem`, the exact tangential solvers (steady rolling,
shift, the Newton stepping core) are :mod:`wheelrail.tangential.exact`, the
automatic window is :mod:`wheelrail.contact.window`.

Sign conventions of tractions, displacement differences and the gap are written
down once in :mod:`wheelrail.halfspace.influence`.
"""

import importlib

# name -> submodule; resolved on first access, so that importing one kernel module (the
# core types import :mod:`.grid`) does not load the FFT and numba kernels
_NAMES = {
    "ConvolutionOperator": "fft", "InfluenceOperator": "fft",
    "Grid": "grid", "contact_outline": "grid",
    "influence_kernel": "influence", "point_influence": "influence",
    "rectangle_influence": "influence",
    "SubsurfaceStresses": "subsurface", "subsurface_stresses": "subsurface",
    "rolling_kernel": "rolling",
}

__all__ = list(_NAMES)


def __getattr__(name):
    if name in _NAMES:
        value = getattr(importlib.import_module(f"{__name__}.{_NAMES[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_NAMES))
