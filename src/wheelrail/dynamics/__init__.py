"""Wheelset and bogie dynamics with online multi-point contact.

Vehicle models (:class:`WheelsetModel`, :class:`BogieModel`, the whole
:class:`VehicleModel` — car body on two bogies or two wheelsets — with their
:class:`Suspension` and :class:`RailSupport`) run on a :class:`TrackLayout`
(curves with cant and transitions, :class:`TrackIrregularity` in alignment, level,
cross level and gauge) with the
contact forces of every wheel evaluated by any normal × tangential method of
the library at every evaluation (:func:`simulate`). Linear analysis and
critical speeds: :func:`critical_speed`; quasi-static flange climb:
:func:`flange_climb`; steady curving: :func:`steady_curving`; running-safety,
track-loading and ride assessment (EN 14363, Sperling): :func:`assess`.

References
----------
.. [1] J. Piotrowski, H. Chollet, Wheel–rail contact models for vehicle system
   dynamics including multi-point contact, VSD 43 (2005) 455–483.
"""

from __future__ import annotations

from ._filters import bandpass, lowpass, sliding_mean, sperling_weighting, sperling_wz
from ._spectra import TrackSpectrum, track_spectrum
from .assess import assess
from .contact import FastContact, GenericContact, configured_methods, contact_model
from .irregularity import TrackIrregularity
from .layout import Curve, Irregularity, TrackLayout
from .linear import LinearBogie, LinearWheelset, eigenvalues_over_speed, linearise
from .model import BogieModel, RailSupport, Suspension, WheelsetModel
from .quasistatic import (CurvingResult, FlangeClimbResult, cant_deficiency, flange_climb, nadal,
                          steady_curving)
from .reference import cone_track, klingel_wavelength
from .results import SimulationResult
from .simulate import Adaptive, FixedStep, System, simulate
from .store import open_result
from .speed import SpeedProfile
from .stability import CriticalSpeedResult, critical_speed
from .vehicle import (BumpStop, CarBody, SecondarySuspension, VehicleModel, YawDamper,
                      manchester_bogie, manchester_vehicle1)

__all__ = ["Suspension", "RailSupport", "WheelsetModel", "BogieModel", "Curve", "Irregularity",
           "TrackLayout", "simulate", "open_result", "SpeedProfile", "FixedStep", "Adaptive", "SimulationResult", "System",
           "FastContact", "GenericContact", "contact_model", "configured_methods",
           "critical_speed", "CriticalSpeedResult", "flange_climb", "FlangeClimbResult",
           "steady_curving", "CurvingResult", "cant_deficiency", "nadal", "LinearWheelset", "LinearBogie",
           "linearise", "eigenvalues_over_speed", "cone_track", "klingel_wavelength",
           "VehicleModel", "CarBody", "SecondarySuspension", "YawDamper", "BumpStop",
           "manchester_bogie", "manchester_vehicle1",
           "TrackIrregularity", "TrackSpectrum", "track_spectrum", "assess", "lowpass", "bandpass",
           "sliding_mean", "sperling_wz", "sperling_weighting"]
