"""Case files: TOML descriptions of contact problems → validated case objects (reading only).

A case file describes one wheel–rail contact: materials, the normal contact
(load and curvatures, radii or semi-axes), creepages, friction and the methods
to use. :func:`load_case` reads and validates it into a frozen
:class:`wheelrail.cases.Case`; :func:`wheelrail.run_case` solves it and
returns a JSON-ready dictionary in SI units. This package only reads and
validates: solving lives in :mod:`wheelrail.cases`.

Schema (SI units; every table except ``[contact]`` and ``[friction]`` is
optional)::

    [material]              # same material for wheel and rail (default: steel
    E = 2.1e11              # E = 2.1e11 Pa, nu = 0.28), or the two tables
    nu = 0.28               # [material.wheel] and [material.rail], each with E, nu

    [contact]
    Fn = 7500.0           # normal force Fn [N]
    A = 1.0869565           # combined curvatures [1/m] ...
    B = 1.6666667
    # ... or principal radii [m] (concave negative, omitted = flat/straight):
    # wheel_rolling_radius, wheel_profile_radius, rail_profile_radius,
    # rail_longitudinal_radius
    # ... or the semi-axes a, b [m] of the contact ellipse.

    [creepage]              # wheel relative to rail (Kalker's convention)
    xi = -0.0007            # longitudinal [-]
    eta = 0.0               # lateral [-]
    phi = 0.0               # spin [1/m]

    [friction]
    mu = 0.2

    [method]
    normal = "hertz"        # or "bem"
    tangential = "fastsim"  # any name of wheelrail.tangential_methods()
    [method.fastsim]        # options of a method, [method.<name>]: the fields of
    nx = 40                 # its class (wheelrail.tangential.Fastsim(nx=40))
    [method.bem]
    grid_elements = 100

    [force]                 # optional: prescribed Fx and/or Fy [N] replace
    Fx = -1000.0            # the creepage xi and/or eta (solved for)

A **wheelset case** (a wheelset on a track with real profiles) has, instead
of ``[contact]``, ``[creepage]`` and ``[force]``, the tables::

    [wheelset]
    profile = "S1002"       # built-in name or a profile file (relative to the case file)
    # profile_right = "worn.prw"
    nominal_radius = 0.46   # [m]
    flange_back = 1.360     # [m]
    tape_circle_offset = 0.070

    [track]
    profile = "60E1"        # built-in name or a file; profile_right optional
    gauge = 1.435           # [m]
    inclination = "1/40"    # slope, a number or "1/n"
    canted = false          # true: the rail profile file is already inclined

    [motion]
    speed = 20.0            # forward speed V [m/s]
    # omega = 43.5          # [rad/s] about the axle; omitted: free rolling V/r0
    # lateral_velocity, vertical_velocity [m/s], yaw_rate, roll_rate [rad/s],
    # roller_radius [m] (a wheel on a roller rig)

    [position]
    y = 0.005               # lateral shift [m], or a list, or a sweep:
    # y = {start = -0.008, stop = 0.008, num = 81}
    yaw = 0.0               # [rad] (or a list, one per y), or yaw_per_y [rad/m]
    # roll = 0.0            # [rad]; omitted: from the rigid contact constraint
    vertical_load = 10e3    # [N] per wheel, or [left, right]; or z [m]

with ``[friction]``, ``[method]`` and ``[material]`` as above. Every solve
goes through :func:`wheelrail.solve` (:func:`wheelrail.cases.solve_case`,
:func:`wheelrail.cases.solve_wheelset_case`); this package only reads and validates.

The ``[method.<name>]`` tables are turned into configured method objects by
the option declarations of the method classes (:mod:`wheelrail.options`):
the API, the case files and the command line accept and refuse the same
values. Unknown tables and keys are errors (they are usually typos). Every
error is a :class:`wheelrail.errors.CaseFileError` whose one-line message
names the file, the table, the key and the bad value.
"""

from .contact import case_from_dict, load_case, load_contact_case, load_wheelset_case
from .transient import load_transient_case

__all__ = ["load_case", "case_from_dict", "load_contact_case", "load_wheelset_case",
           "load_transient_case"]

# Sweep files ([sweep]) are read by wheelrail.sweeps.load_sweep (a driver's own input).
