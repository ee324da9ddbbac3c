"""wheelrail — wheel–rail contact mechanics.

Geometry, normal contact (Hertz and non-Hertzian), kinematics and creep
forces (Carter, Kalker's linear theory, FASTSIM, Shen–Hedrick–Elkins, Polach,
Kalker's exact theory) behind one API. SI units everywhere; Kalker's sign
convention (:mod:`wheelrail.conventions`).

Heavy sub-packages (geometry, profiles, half-space solvers, plotting) are
imported lazily on first use.
"""

from __future__ import annotations

import importlib

from . import conventions
from .api import available_methods, creep_forces, normal_methods, solve, tangential_methods
from .errors import (CaseFileError, ConvergenceError, InputError, NoContactError, ProfileError,
                     WheelrailError)
from .materials import STEEL, Material, MaterialPair
from .normal.hertz import (HertzContact, curvatures_from_radii, hertz, hertz_from_penetration,
                           hertz_from_radii, hertz_from_semiaxes, hertz_line)
from .results import CreepForces, Status

__version__ = "0.1.0"

# name -> (module, attribute); resolved on first access
_LAZY = {
    "transient_rolling": ("wheelrail.transient", "transient_rolling"),
    "kalker_coefficients": ("wheelrail.tangential.linear", "kalker_coefficients"),
    "load_case": ("wheelrail.casefile", "load_case"),
    "run_case": ("wheelrail.casefile", "run_case"),
    "profiles": ("wheelrail.profiles", None),
    "geometry": ("wheelrail.geometry", None),
    "halfspace": ("wheelrail.halfspace", None),
    "plotting": ("wheelrail.plotting", None),
    "plausibility": ("wheelrail.plausibility", None),
    "fe": ("wheelrail.fe", None),
    "Profile": ("wheelrail.profiles", "Profile"),
    "Wheelset": ("wheelrail.geometry", "Wheelset"),
    "Track": ("wheelrail.geometry", "Track"),
    "contact_table": ("wheelrail.geometry", "contact_table"),
    "equivalent_conicity": ("wheelrail.geometry", "equivalent_conicity"),
    "contact_points": ("wheelrail.geometry", "contact_points"),
    "elastic_contact": ("wheelrail.geometry", "elastic_contact"),
    "solve_normal": ("wheelrail.normal.bem", "solve_normal"),
    "solve_gap": ("wheelrail.contact", "solve_gap"),
    "solve_gap_auto": ("wheelrail.contact", "solve_gap_auto"),
    "WheelRailPosition": ("wheelrail.contact.wheelrail", "WheelRailPosition"),
    "WheelRailResult": ("wheelrail.contact.wheelrail", "WheelRailResult"),
    "wheelset_sweep": ("wheelrail.contact.sweep", "wheelset_sweep"),
    "ContactPatch": ("wheelrail.contact.patch", "ContactPatch"),
    "Motion": ("wheelrail.geometry.kinematics", "Motion"),
    "GapProblem": ("wheelrail.normal._base", "GapProblem"),
    "normal": ("wheelrail.normal", None),
    "contact": ("wheelrail.contact", None),
    "Grid": ("wheelrail.halfspace", "Grid"),
    "solve_creepages": ("wheelrail.prescribed", "solve_creepages"),
    "hertz_grid": ("wheelrail.normal.bem", "hertz_grid"),
    "subsurface_stresses": ("wheelrail.halfspace", "subsurface_stresses"),
    "sweep": ("wheelrail.sweeps", "sweep"),
    "sweeps": ("wheelrail.sweeps", None),
    "SweepSpec": ("wheelrail.sweeps", "SweepSpec"),
    "open_sweep": ("wheelrail.sweeps", "open_sweep"),
    "citation": ("wheelrail.citations", "citation"),
}


def __getattr__(name):
    if name in _LAZY:
        module, attr = _LAZY[name]
        mod = importlib.import_module(module)
        value = mod if attr is None else getattr(mod, attr)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'wheelrail' has no attribute {name!r}")


__all__ = [
    "Material", "MaterialPair", "STEEL",
    "HertzContact", "hertz", "hertz_from_semiaxes", "hertz_from_radii", "hertz_from_penetration",
    "hertz_line", "curvatures_from_radii",
    "creep_forces", "available_methods", "solve", "normal_methods", "tangential_methods",
    "CreepForces", "Status", "conventions",
    "WheelrailError", "InputError", "ConvergenceError", "NoContactError", "ProfileError",
    "CaseFileError",
    *_LAZY,
]
