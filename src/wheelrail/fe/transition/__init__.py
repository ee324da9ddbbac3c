"""The one- to two-point contact transition: a half-wheelset rolling into flange contact on
a flexible track (explicit FE; user guide: docs/fe_transition.md).

Built on the rolling engine of :mod:`wheelrail.fe` (its hex8 element kernels, the explicit
node update, the contact laws and the closest-point projection of
:mod:`wheelrail.fe._kernels`); what is its own:

=====================  ================================================================
``model``              :class:`TransitionCase` (frozen input), the rigid pose search, the
                       assembly of wheel, rail and sleepers (:func:`build_transition_model`)
``mesh``               profile-following sections with flange and gauge face, extruded
                       (rail) and swept (wheel), tied blocks for web, foot and plate
``contact``            node-to-segment contact against arbitrary quads (bucket search), the
                       split into tread and flange patches and the per-patch summary
``track``              :class:`TrackStructure` (railpads, sleepers, ballast) and
                       :class:`WheelSuspension` (sprung mass, primary suspension, half-axle,
                       drive, optional lateral and roll degrees of freedom)
``run``                :func:`run_transition` (the time loop, restart files, outputs) and
                       :func:`seed004_case` (the published set-up)
``wave``               surface-wave speed on the case's rail: a force pulse
                       (:func:`rail_pulse`, :func:`pulse_arrivals`) and phase spectra of any
                       record (:func:`phase_velocity`)
``analysis``           onset, shear and slip direction, vertical balance, climb load
=====================  ================================================================

``wr.fe.solve(case)`` runs a :class:`TransitionCase` through :func:`run_transition`.
"""

from .model import TransitionCase, build_transition_model, yawed_contact
from .run import (
    TransitionResult,
    pose_contact,
    read_transition_restart,
    run_transition,
    seed004_case,
    transition_time_estimate,
)
from .track import TrackStructure, WheelSuspension
from .wave import elastic_wave_speeds, phase_velocity, pulse_arrivals, rail_pulse

__all__ = ["TransitionCase", "TransitionResult", "TrackStructure", "WheelSuspension",
           "seed004_case", "run_transition", "read_transition_restart",
           "transition_time_estimate", "build_transition_model", "pose_contact",
           "yawed_contact", "rail_pulse", "pulse_arrivals", "phase_velocity",
           "elastic_wave_speeds"]
