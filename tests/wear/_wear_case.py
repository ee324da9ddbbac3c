"""The case of the wear-loop tests: the Manchester benchmark vehicle's bogie
(``wr.dynamics.manchester_bogie()``, Iwnicki 1998) at 15 m/s in a 300 m right-hand curve
with 100 mm cant (20 m transitions), S1002 on 60E1; 5 m simulated per step after a 30 m
run-in, 10 samples and 8 cells per patch keep each wear step to seconds."""

import wheelrail as wr
from wheelrail import dynamics as dy

#: Settings of ``wr.wear.evolve`` shared by the tests.
KW = dict(law="usfd", executor="serial", samples=10, cells=8, conicity=False, profiles="sides")


def r300_case():
    """(bogie, route) of the module docstring."""
    tr = wr.Track(wr.profiles.load("60E1"))
    lay = dy.TrackLayout(tr, curves=(dy.Curve(radius=300.0, start=5.0, transition=20.0,
                                              cant=0.1, direction="right"),))
    route = wr.wear.Route((wr.wear.RouteCase(lay, 15.0, distance=5.0, run_in=30.0,
                                             name="R300"),))
    return dy.manchester_bogie(), route
