"""Plots of contact results (matplotlib, imported lazily; Agg canvas, no pyplot state).

A leaf of the package: nothing in the solvers imports it. Every function
returns a :class:`matplotlib.figure.Figure` and writes it to ``path`` when one
is given.

==========================  ========================================================================
function                    draws
==========================  ========================================================================
:func:`creep_curves`        normalised creep force against creepage, several methods
:func:`traction_field`      tangential traction and adhesion/slip areas (FASTSIM, exact)
:func:`pressure_map`        normal pressure: Hertz ellipse or a pressure grid
:func:`subsurface_section`  von Mises / maximum shear stress in a section below the contact
:func:`contact_profiles`    wheel–rail profiles at the solved pose, patches and pressure on the rail
:func:`adhesion_maps`       adhesion/slip areas of every wheel–rail patch
:func:`sweep_forces`        patch forces and positions over a lateral-shift sweep
==========================  ========================================================================
"""

from __future__ import annotations

import importlib

__all__ = ["creep_curves", "traction_field", "pressure_map", "subsurface_section", "field_arrays",
           "new_figure", "contact_profiles", "adhesion_maps", "sweep_forces"]

_LAZY = {
    "creep_curves": "wheelrail.plotting.creep",
    "traction_field": "wheelrail.plotting.fields",
    "pressure_map": "wheelrail.plotting.fields",
    "subsurface_section": "wheelrail.plotting.subsurface",
    "field_arrays": "wheelrail.plotting._fields",
    "new_figure": "wheelrail.plotting._common",
    "contact_profiles": "wheelrail.plotting.wheelrail",
    "adhesion_maps": "wheelrail.plotting.wheelrail",
    "sweep_forces": "wheelrail.plotting.wheelrail",
}


def __getattr__(name):
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'wheelrail.plotting' has no attribute {name!r}")
