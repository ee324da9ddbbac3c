"""wheelrail — wheel–rail contact mechanics.

Geometry, normal contact (Hertz and non-Hertzian), kinematics and creep
forces (Carter, Kalker's linear theory, FASTSIM, Shen–Hedrick–Elkins, Polach,
Kalker's exact theory) behind one API. SI units everywhere; Kalker's sign
convention (:mod:`wheelrail.conventions`).

Every entry function and every method class is one attribute away
(``wr.solve``, ``wr.creep_forces``, ``wr.tangential.Fastsim`` or
``wr.Fastsim``, ``wr.normal.Bem`` or ``wr.Bem``); :func:`normal_methods` and
:func:`tangential_methods` give name -> class. Everything but the core types
is imported on first use, so that ``import wheelrail`` stays fast.
"""

from __future__ import annotations

import importlib

from . import _numba_cache, conventions
from ._version import __version__
from .errors import (
    CaseFileError,
    ConvergenceError,
    InputError,
    NoContactError,
    OptionError,
    ProfileError,
    WheelrailError,
)
from .materials import STEEL, Material, MaterialPair
from .results import CreepForcesResult, Status

_numba_cache.install()  # kernels' numba cache follows every kernel source (see the module)

# name -> (module, attribute); resolved on first access
_LAZY = {
    # entry functions
    "solve": ("wheelrail.api", "solve"),
    "creep_forces": ("wheelrail.api", "creep_forces"),
    "normal_methods": ("wheelrail.api", "normal_methods"),
    "tangential_methods": ("wheelrail.api", "tangential_methods"),
    "hertz": ("wheelrail.hertzian", "hertz"),
    "hertz_from_semiaxes": ("wheelrail.hertzian", "hertz_from_semiaxes"),
    "hertz_from_radii": ("wheelrail.hertzian", "hertz_from_radii"),
    "hertz_from_penetration": ("wheelrail.hertzian", "hertz_from_penetration"),
    "hertz_line": ("wheelrail.hertzian", "hertz_line"),
    "curvatures_from_radii": ("wheelrail.hertzian", "curvatures_from_radii"),
    "HertzContact": ("wheelrail.hertzian", "HertzContact"),
    # method classes (also wr.normal.<Class>, wr.tangential.<Class>)
    **{c: ("wheelrail.normal", c) for c in ("Hertz", "MultiHertz", "Linder", "KikPiotrowski",
                                            "Stripes", "Bem")},
    **{c: ("wheelrail.tangential", c) for c in ("Carter", "Linear", "Fastsim", "Fastrip",
                                                "ShenHedrickElkins", "Polach", "Exact",
                                                "Table")},
    "tangential": ("wheelrail.tangential", None),
    "options": ("wheelrail.options", None),
    "cases": ("wheelrail.cases", None),
    "casefile": ("wheelrail.casefile", None),      # deprecated name of cases.files
    "transient_rolling": ("wheelrail.transient", "transient_rolling"),
    "kalker_coefficients": ("wheelrail.tangential.linear", "kalker_coefficients"),
    "load_case": ("wheelrail.cases.files", "load_case"),
    "run_case": ("wheelrail.cases", "run_case"),
    "profiles": ("wheelrail.profiles", None),
    "geometry": ("wheelrail.geometry", None),
    "halfspace": ("wheelrail.halfspace", None),
    "plotting": ("wheelrail.plotting", None),
    "plausibility": ("wheelrail.plausibility", None),
    "fe": ("wheelrail.fe", None),
    "dynamics": ("wheelrail.dynamics", None),
    "wear": ("wheelrail.wear", None),
    "Profile": ("wheelrail.profiles", "Profile"),
    "Wheelset": ("wheelrail.geometry", "Wheelset"),
    "Track": ("wheelrail.geometry", "Track"),
    "contact_table": ("wheelrail.geometry", "contact_table"),
    "equivalent_conicity": ("wheelrail.geometry", "equivalent_conicity"),
    "contact_points": ("wheelrail.geometry", "contact_points"),
    "elastic_contact": ("wheelrail.geometry", "elastic_contact"),
    "solve_normal": ("wheelrail.normal.bem", "solve_normal"),
    "solve_gap": ("wheelrail.tangential.exact", "solve_gap"),
    "solve_gap_auto": ("wheelrail.contact", "solve_gap_auto"),
    "WheelRailPosition": ("wheelrail.contact.wheelrail", "WheelRailPosition"),
    "WheelRailResult": ("wheelrail.contact.wheelrail", "WheelRailResult"),
    "wheelset_sweep": ("wheelrail.contact.sweep", "wheelset_sweep"),
    "ContactPatch": ("wheelrail.patch", "ContactPatch"),
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


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "__version__", "Material", "MaterialPair", "STEEL", "CreepForcesResult", "Status", "conventions",
    "WheelrailError", "InputError", "OptionError", "ConvergenceError", "NoContactError",
    "ProfileError", "CaseFileError",
    *_LAZY,
]
