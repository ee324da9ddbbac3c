"""The Manchester contact benchmark, case A-2.2: its set-up as wheelrail objects.

Shackleton & Iwnicki (2008) defined the benchmark: S1002 wheels on UIC60
rails canted 1:40 (gauge 1435 mm at 14 mm below the rail top, flange-back
distance 1360 mm, nominal radius 460 mm), 21 wheelset positions y = 0…10 mm
with yaw 2.4 mrad/mm and prescribed roll, 10 kN vertical force on each wheel,
V = 2 m/s, μ = 0.3, G = 82 GPa and ν = 0.28 for both bodies. The package does
not ship the benchmark's files; :func:`manchester_a22` reads the input table
and the two profile files given to it (the project's copies are in
``shared/data`` beside the repository).

Sign conversions: the input table uses CONTACT's track frame (z down), where
a positive roll lowers the right wheel and a negative pitch rate rolls the
wheelset forwards; wheelrail's roll is positive when the right wheel is
higher and ``omega`` is positive rolling forwards, so both change sign. Yaw
has the same sign in both (nose to the right).

References
----------
.. [1] P. Shackleton, S. Iwnicki, Comparison of wheel–rail contact codes for
   railway vehicle simulation: an introduction to the Manchester Contact
   Benchmark and initial results, VSD 46 (2008) 129–149.
.. [2] E.A.H. Vollebregt, Detailed wheel/rail geometry processing using the
   planar contact approach, VSD 60 (2022) 1253–1291.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import profiles
from ..errors import InputError
from ..geometry import Track, Wheelset
from ..geometry.kinematics import Motion
from ..materials import Material
from .wheelrail import WheelRailPosition

__all__ = ["ManchesterCase", "manchester_a22", "MU", "G", "NU"]

MU = 0.3
G = 82e9
NU = 0.28


@dataclass(frozen=True)
class ManchesterCase:
    """One load case: its number, the wheel–rail position and the motion."""

    case: int
    position: object
    motion: object
    mu: float = MU


def manchester_a22(inputs, wheel_profile, rail_profile) -> list[ManchesterCase]:
    """The 21 load cases of Manchester benchmark A-2.2.

    Parameters
    ----------
    inputs : path
        ``manchester_a22_inputs.csv`` (columns case, y_mm, yaw_rad, roll_rad,
        Fz_per_wheel_N, V_mm_s, omega_rad_s; CONTACT's signs).
    wheel_profile, rail_profile : path
        ``MBench_S1002_v3.prw`` and ``MBench_UIC60_v3.prr`` (rail already canted 1:40).

    Returns
    -------
    list of ManchesterCase
    """

    path = Path(inputs)
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except OSError as exc:
        raise InputError(f"cannot read the Manchester input table {str(path)!r}: {exc}") from None
    body = [ln for ln in lines if ln.strip() and not ln.startswith("#")
            and not ln.startswith("case")]
    try:
        data = np.array([[float(v) for v in ln.split(",")] for ln in body])
    except ValueError as exc:
        raise InputError(f"{str(path)!r}: not a Manchester input table ({exc})") from None
    if data.ndim != 2 or data.shape[1] != 7:
        raise InputError(f"{str(path)!r}: expected 7 columns (case, y_mm, yaw_rad, roll_rad, "
                         "Fz_per_wheel_N, V_mm_s, omega_rad_s)")
    ws = Wheelset(wheel=profiles.read(wheel_profile), nominal_radius=0.46, flange_back=1.360)
    tr = Track(rail=profiles.read(rail_profile), gauge=1.435, inclination=1 / 40, canted=True,
               gauge_height=0.014)
    mat = Material(E=2.0 * G * (1.0 + NU), nu=NU)
    out = []
    for case, y, yaw, roll, fz, v, om in data:
        pos = WheelRailPosition(ws, tr, y * 1e-3, yaw, -roll, vertical_load=fz, material=mat)
        out.append(ManchesterCase(int(case), pos, Motion(speed=v * 1e-3, omega=-om)))
    return out
