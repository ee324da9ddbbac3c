"""``wheelrail compile``: compile (or load from numba's cache) every kernel family once.

The numerical kernels are numba functions compiled on their first call and cached on
disk (``cache=True``; :mod:`wheelrail._numba_cache` invalidates the cache when a kernel
source changes). A fresh install therefore spends its first runs compiling: about a
minute and a half for the finite elements, most of a minute for the dynamics. This
command does it at once, each family in its own process (``--jobs``, default: the
cores, at most 4), by running a small problem through every compiled path of the family:

* ``contact`` — contact search and separation lines, Hertz, Kik–Piotrowski, STRIPES and
  boundary-element normal problems; FASTSIM, FaStrip, Polach, the table law and Kalker's
  exact theory (steady);
* ``dynamics`` — the compiled wheelset, bogie and vehicle time loops with Hertz and
  Kik–Piotrowski contact, FASTSIM and the table law;
* ``fe`` — the explicit rolling kernels (elastic and elasto-plastic) and the static
  indentation;
* ``transient`` — transient rolling (Kalker's instationary theory).

A family whose kernels are all cached loads in seconds. Later runs of any command then
start at once.
"""

from __future__ import annotations

import os
import time

HELP = "compile every numba kernel once (in parallel processes), so that first runs start at once"

#: Kernel families in the order of their compile time (longest first).
FAMILIES = ("fe", "dynamics", "contact", "transient")


def add_arguments(p) -> None:
    p.add_argument("families", nargs="*", metavar="FAMILY",
                   help=f"kernel families to compile (default all: {', '.join(FAMILIES)})")
    p.add_argument("--jobs", "-j", type=int, default=None,
                   help="processes compiling at once (default: the cores, at most 4)")


# --------------------------------------------------------------------------- warm-up problems
def _contact():
    import numpy as np

    import wheelrail as wr

    c = wr.hertz(1e4, 1.0, 2.0, wr.STEEL)
    for law in ("fastsim", "fastrip", "polach", "shen-hedrick-elkins", "table", "linear"):
        wr.solve(c, creepage=(1e-3, 5e-4, 0.3), mu=0.3, tangential=law)
    wr.solve(c, creepage=(1e-3, 5e-4, 0.3), mu=0.3, tangential=wr.tangential.Exact(elements=12))
    batch = wr.hertz(np.array([1e4, 2e4]), 1.0, 2.0, wr.STEEL)
    for law in ("fastsim", "table"):
        wr.creep_forces(batch, (1e-3, 5e-4, 0.3), 0.3, method=law)
    ws = wr.Wheelset(wheel=wr.profiles.load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = wr.Track(rail=wr.profiles.load("60E1"), gauge=1.435, inclination=1 / 40)
    pos = wr.WheelRailPosition(ws, tr, 0.003, vertical_load=70e3)
    motion = wr.Motion(speed=10.0, omega=10.0 / 0.46 * 1.001)
    for normal, tangential in (("hertz", "fastsim"), ("kik-piotrowski", "fastsim"),
                               ("stripes", "fastsim"), ("hertz", "table")):
        wr.solve(pos, motion=motion, mu=0.3, normal=normal, tangential=tangential)
    wr.solve(pos, motion=motion, mu=0.3, normal=wr.normal.Bem(grid_elements=16),
             tangential=wr.tangential.Exact(elements=16))


def _dynamics():
    import wheelrail as wr

    D = wr.dynamics
    ws = wr.Wheelset(wr.profiles.load("S1002"))
    tr = wr.Track(wr.profiles.load("60E1"))
    prim = D.Suspension(kx=1e6, ky=3.884e6, kz=1.22e6, cy=2e4, half_spacing=1.0)
    model = D.WheelsetModel(ws, 1813.0, (1120.0, 112.0, 1120.0), primary=prim, axle_load=80e3)
    curve = D.TrackLayout(tr, curves=(D.Curve(600.0, start=0.0, length=100.0, cant=0.1,
                                              transition=0.0),))
    for normal, tangential in (("hertz", "fastsim"), ("kik-piotrowski", "fastsim"),
                               ("hertz", "table")):
        D.simulate(model, curve, 20.0, 0.003, normal, tangential, creep_relaxation=True)
    D.simulate(D.manchester_vehicle1(), tr, 20.0, 0.003, "kik-piotrowski", "fastsim")


def _fe():
    import numpy as np

    import wheelrail as wr
    from wheelrail.fe import J2Plastic, RollingCase, solve
    from wheelrail.fe.materials import R900A_HARDENING

    flat = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
    base = dict(wheel=flat, rail=wr.profiles.load("60E1"), radius=0.46, Fn=7500.0, mu=0.2,
                creepage=(7e-4, 2e-4, 0.0), mesh_size=2e-3, element="reduced",
                mass_scaling=400, depth=3, half_width=3, half_length=3, travel=0.001)
    solve(RollingCase(**base), progress=False)
    plastic = J2Plastic(2.1e11, 0.28, 1.7e8, hardening=R900A_HARDENING)
    solve(RollingCase(**base, material=plastic), progress=False)
    wr.fe.indent(RollingCase(**base))


def _transient():
    import wheelrail as wr

    c = wr.hertz(1e4, 1.0, 1.0, wr.STEEL)
    wr.transient_rolling(c, travel=2e-3, step=4e-4, mu=0.3, creepage=(1e-3, 0.0, 0.0),
                         elements=12)


_WARMUPS = {"fe": _fe, "dynamics": _dynamics, "contact": _contact, "transient": _transient}


def warm(family: str) -> dict:
    """Run the family's warm-up problem in this process: CPU and wall time [s]."""
    import warnings

    cpu, wall = time.process_time(), time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _WARMUPS[family]()
    return {"family": family, "cpu": time.process_time() - cpu,
            "wall": time.perf_counter() - wall, "pid": os.getpid()}


def compile_families(families=FAMILIES, jobs=None, on_done=None) -> list:
    """Compile the kernel ``families``, ``jobs`` processes at once (1: in this process).

    Returns
    -------
    list of dict
        Per family: ``family``, ``cpu`` and ``wall`` [s] of its process.
    """
    families = list(families)
    jobs = max(1, min(jobs or min(os.cpu_count() or 1, 4), len(families)))
    out = []
    if jobs == 1:
        for f in families:
            out.append(warm(f))
            if on_done:
                on_done(out[-1])
        return out
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed

    ctx = mp.get_context("spawn")       # a clean interpreter: no inherited numba state
    with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
        futures = [pool.submit(warm, f) for f in families]
        for fut in as_completed(futures):
            out.append(fut.result())
            if on_done:
                on_done(out[-1])
    return out


def run(args, console) -> int:
    from ..errors import InputError

    families = list(args.families) or list(FAMILIES)
    bad = [f for f in families if f not in FAMILIES]
    if bad:
        raise InputError(f"unknown kernel family {bad[0]!r}; families: {', '.join(FAMILIES)}")
    if args.jobs is not None and args.jobs < 1:
        raise InputError(f"--jobs must be >= 1, got {args.jobs}")
    jobs = args.jobs or min(os.cpu_count() or 1, 4)
    console.print(f"compiling {', '.join(families)} with {min(jobs, len(families))} "
                  "process(es); cached families load in seconds")
    wall = time.perf_counter()

    def done(r):
        console.print(f"  {r['family']:10s} {r['cpu']:7.1f} s CPU, {r['wall']:7.1f} s")

    results = compile_families(families, jobs, on_done=done)
    total_cpu = sum(r["cpu"] for r in results)
    console.print(f"done in {time.perf_counter() - wall:.1f} s ({total_cpu:.1f} s CPU in all "
                  "processes)")
    return 0
