"""A small `wheelrail dynamics` case file shared by the tests of the command: a suspended
wheelset (S1002 on 60E1, fixed spin), Hertz + FASTSIM, 20 m/s, released 2 mm off centre."""

WHEELSET_CASE = """[model]
kind = "wheelset"
wheel = "S1002"
rail = "60E1"
mass = 1813.0
inertia = [1120.0, 112.0, 1120.0]
spin = "fixed"
[model.primary]
kx = 1e6
ky = 3.9e6
kz = 1.2e6
[method]
normal = "hertz"
tangential = "fastsim"
[friction]
mu = 0.3
[simulation]
speed = 20.0
duration = {duration}
initial = {{"ws0.y" = 0.002}}
"""


def wheelset_case(duration=1.0):
    """The case text with ``duration`` [s]."""
    return WHEELSET_CASE.format(duration=duration)
