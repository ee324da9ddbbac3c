"""A small `wheelrail fe` indentation case shared by the tests of the command: Fn 7.5 kN on a
0.46 m wheel, 2 mm mesh in a 3 × 3 × 3 mm³ block (the seconds-long FE test size)."""

#: The case without its profiles (the hostile tests give their own).
INDENT_BASE = """[fe]
radius = 0.46
Fn = 7500.0
mesh_size = 2e-3
depth = 3.0
half_width = 3.0
half_length = 3.0
mode = "indent"
"""


def indent_case(wheel="cylinder", rail="60E1"):
    """The case text with a wheel and a rail profile."""
    return INDENT_BASE + f'wheel = "{wheel}"\nrail = "{rail}"\n'
