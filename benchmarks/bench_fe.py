"""FE engine benchmark: element kernel cost, explicit step cost, memory, and problem sizes.

Run:  python benchmarks/bench_fe.py [--mesh 1e-3]            (explicit cost, as below)
      python benchmarks/bench_fe.py --implicit 1.5e-3         (implicit linear solvers)
      python benchmarks/bench_fe.py --lateral 1.5e-3          (lateral creepage vs exact)
      python benchmarks/bench_fe.py --toumi2016 1.5e-3        (Toumi et al.'s cone/arc case)
      python benchmarks/bench_fe.py --creep-curve 1.5e-3      (creep curve vs exact)

Prints, with the problem sizes and the machine load (uptime):
* ns per element per internal-force evaluation (hex8 full 2x2x2 and reduced 1-point + hourglass);
* ns per element per complete explicit step (contact, kinematics and bookkeeping included)
  and steps per second, on a rolling mesh like Toumi et al.'s (2016);
* memory per element of the precomputed element data;
* the stable time step and the number of steps the default rolling run needs, and the
  resulting time estimate.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import wheelrail as wr
from wheelrail.fe import RollingCase
from wheelrail.fe.model import build_model
from wheelrail.fe.rolling import _speed_profile, stable_time_step


def load():
    return os.getloadavg()[0]


def kernel_cost(model, repeat=20):
    u = np.random.default_rng(0).normal(size=(model.n_nodes, 3)) * 1e-7
    f = np.zeros_like(u)
    model.internal_force(u, f)               # compile / warm
    t = time.perf_counter()
    for _ in range(repeat):
        f[:] = 0
        model.internal_force(u, f)
    dt = (time.perf_counter() - t) / repeat
    return dt / model.n_elements * 1e9


def step_cost(case, steps):
    """Time a whole explicit run (relaxation + rolling) on a coarser, mass-scaled copy.

    The per-element cost of a step does not depend on the mesh size; the copy (mesh 2 h,
    mass scaling 100, a short travel) keeps the timed run short.
    """
    from wheelrail.fe import solve

    short = case.replace(mesh_size=2 * case.mesh_size, mass_scaling=100.0, travel=0.012)
    t = time.perf_counter()
    r = solve(short, progress=False)
    wall = time.perf_counter() - t
    n = r.info["steps"]
    return wall / n / r.model.n_elements * 1e9, n / wall, r.model.n_elements, n


SMALL = dict(element="reduced", depth=4, half_width=3, half_length=3)


def implicit_solvers(h, repeats=2):
    """Linear-solve time per Newton iteration and wall time per step of implicit-HHT runs
    (3 steps, xi = 7e-4) with the pivoted SuperLU solve, the symmetric-mode solve and the
    reused factorisation + GMRES, interleaved so that they share the machine's load."""
    import warnings

    import wheelrail.fe._newton as N
    from wheelrail.fe import solve

    warnings.simplefilter("ignore")
    wheel = wr.fe.cone_wheel(0.0)
    print(f"\nimplicit-hht, mesh {h * 1e3:g} mm (kept bodies 4 a deep, 3 b wide), 3 steps")
    for rep in range(repeats):
        for mode in ("pivoted", "symmetric", "reuse"):
            N.SYMMETRIC_FACTOR = mode != "pivoted"
            case = RollingCase(wheel=wheel, rail=wr.profiles.load("60E1"), radius=0.46,
                               Fn=7500.0, mu=0.2, creepage=(7e-4, 0, 0), mesh_size=h,
                               integrator="implicit-hht", travel=0.002,
                               linear_solver="reuse" if mode == "reuse" else "direct", **SMALL)
            t = time.perf_counter()
            r = solve(case, progress=False)
            wall = time.perf_counter() - t
            i = r.info
            print(f"  {mode:9s}: {r.model.n_elements} elements, {3 * r.model.n_nodes} dofs, "
                  f"{i['newton_iterations']} Newton iterations, {i['factorizations']} "
                  f"factorisations, {i['krylov_iterations']} GMRES iterations; linear solves "
                  f"{i['linear_solve_seconds']:.2f} s "
                  f"({i['linear_solve_seconds'] / i['linear_solves']:.3f} s/iteration), run "
                  f"{wall:.1f} s ({wall / i['steps']:.2f} s/step incl. build and statics); "
                  f"Fx[-1] = {float(r.dataset.Fx[-1]):.4f} N; load {load():.2f}", flush=True)
    N.SYMMETRIC_FACTOR = True


def lateral(h):
    """Fy for pure lateral creepage against the exact half-space solver (explicit, mass
    scaling 400, 20 mm travel)."""
    import warnings

    from wheelrail.fe import solve

    warnings.simplefilter("ignore")
    print(f"\nlateral creepage, mesh {h * 1e3:g} mm, explicit, mass scaling 400")
    for cr in ((0.0, 4e-4, 0.0), (0.0, 7e-4, 0.0), (7e-4, 4e-4, 0.0)):
        case = RollingCase(wheel=wr.fe.cone_wheel(0.0), rail=wr.profiles.load("60E1"),
                           radius=0.46, Fn=7500.0, mu=0.2, creepage=cr, mesh_size=h,
                           mass_scaling=400, travel=0.02, **SMALL)
        t = time.perf_counter()
        r = solve(case, progress=False)
        g = r.model.geometry
        ref = wr.creep_forces(wr.hertz(7500.0, g["A"], g["B"], wr.Material(2.1e11, 0.28)), cr,
                              0.2, method="exact", elements=20)
        print(f"  creepage {cr}: FE Fx {r.Fx:8.1f} N Fy {r.Fy:8.1f} N | exact Fx {ref.Fx:8.1f} "
              f"N Fy {ref.Fy:8.1f} N | Fy error {r.Fy / ref.Fy - 1:+.1%} "
              f"({r.model.n_elements} elements, {time.perf_counter() - t:.1f} s, load "
              f"{load():.2f})", flush=True)


def toumi2016(h):
    """Toumi, Chollet & Yin's (2016) Hertzian set-up (1/10 cone on a 300 mm arc inclined
    1/10): indentation against Hertz, then an explicit rolling run (xi = -0.7 permille) against the exact solver."""
    import warnings

    from wheelrail.fe import indent, seed000_case, solve

    warnings.simplefilter("ignore")
    case = seed000_case(load="printed", mesh_size=h, depth=4, half_width=4, half_length=4)
    t = time.perf_counter()
    r = indent(case)
    hz = r.hertz
    print(f"\nToumi et al. cone/arc, mesh {h * 1e3:g} mm, indentation ({r.model.n_elements} "
          f"elements, {time.perf_counter() - t:.1f} s): contact angle "
          f"{np.degrees(r.model.geometry['delta']):.2f} deg, normal force {r.Fn:.1f} N "
          f"(load/cos = {r.model.geometry['normal_load']:.1f} N)")
    print(f"  p_max {r.p_max / 1e6:.1f} MPa vs Hertz {hz.p0 / 1e6:.1f} ({r.p_max / hz.p0 - 1:+.1%})"
          f"; a {r.a * 1e3:.3f} mm vs {hz.a * 1e3:.3f} ({r.a / hz.a - 1:+.1%}); b "
          f"{r.b * 1e3:.3f} mm vs {hz.b * 1e3:.3f} ({r.b / hz.b - 1:+.1%}); a/b {r.a / r.b:.3f} "
          f"vs {hz.a / hz.b:.3f}; load {load():.2f}", flush=True)
    rc = seed000_case(load="printed", mesh_size=h, mass_scaling=400, travel=0.02, **SMALL)
    t = time.perf_counter()
    rr = solve(rc, progress=False)
    # the cone on the inclined arc spins: phi = sin(delta) / r_c (the axle's angular velocity
    # has the component Omega sin(delta) along Kalker's z, the normal into the rail). The
    # FE frame (x rolling, y lateral, z up) is right-handed, so Kalker's y is minus the FE
    # lateral tangent: eta_K = -eta, and the FE lateral force is -Fy_K.
    g = rr.model.geometry
    phi = float(np.sin(g["delta"]) / g["r_c"])
    ref = wr.creep_forces(g["hertz"], (rc.creepage[0], -rc.creepage[1], phi), 0.2,
                          method="exact", elements=20)
    ref_fy = -float(ref.Fy)
    print(f"  rolling xi = -0.7 permille, geometric spin phi = {phi:.4f} 1/m "
          f"({rr.model.n_elements} elements, explicit, mass "
          f"scaling 400, {time.perf_counter() - t:.1f} s): Fx {rr.Fx:.1f} N vs exact "
          f"{ref.Fx:.1f} N ({rr.Fx / ref.Fx - 1:+.1%}), Fy in the contact plane "
          f"{rr.Fy_contact:.1f} N vs exact {ref_fy:.1f} N ({rr.Fy_contact / ref_fy - 1:+.1%}) "
          f"(global Fy {rr.Fy:.1f} N); p_max {rr.p_max / 1e6:.1f} MPa, a {rr.a * 1e3:.3f} mm, b "
          f"{rr.b * 1e3:.3f} mm; load {load():.2f}", flush=True)


def creep_curve(h):
    """Creep curve Fx(xi) on a finer mesh against the exact solver (explicit, mass scaling 400)."""
    import warnings

    from wheelrail.fe import solve

    warnings.simplefilter("ignore")
    print(f"\ncreep curve, mesh {h * 1e3:g} mm, explicit, mass scaling 400, 20 mm travel")
    for xi in (-2e-3, -7e-4, 2e-4, 5e-4, 1e-3, 2e-3):
        case = RollingCase(wheel=wr.fe.cone_wheel(0.0), rail=wr.profiles.load("60E1"),
                           radius=0.46, Fn=7500.0, mu=0.2, creepage=(xi, 0, 0), mesh_size=h,
                           mass_scaling=400, travel=0.02, **SMALL)
        t = time.perf_counter()
        r = solve(case, progress=False)
        g = r.model.geometry
        ref = wr.creep_forces(wr.hertz(7500.0, g["A"], g["B"], wr.Material(2.1e11, 0.28)),
                              (xi, 0, 0), 0.2, method="exact", elements=20)
        print(f"  xi {xi:+.1e}: FE {r.Fx:8.1f} N, exact {ref.Fx:8.1f} N, error "
              f"{r.Fx / ref.Fx - 1:+.1%} ({r.model.n_elements} elements, "
              f"{time.perf_counter() - t:.1f} s, load {load():.2f})", flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mesh", type=float, default=1e-3)
    ap.add_argument("--steps", type=int, default=0, help=argparse.SUPPRESS)
    ap.add_argument("--implicit", type=float, metavar="H")
    ap.add_argument("--lateral", type=float, metavar="H")
    ap.add_argument("--toumi2016", "--seed000", type=float, metavar="H")
    ap.add_argument("--creep-curve", type=float, metavar="H")
    args = ap.parse_args()
    extra = [(args.implicit, implicit_solvers), (args.lateral, lateral),
             (args.toumi2016, toumi2016), (args.creep_curve, creep_curve)]
    if any(h is not None for h, _ in extra):
        print(f"load average before: {load():.2f} (2-core machine shared with other agents)")
        for h, fn in extra:
            if h is not None:
                fn(h)
        print(f"\nload average after: {load():.2f}")
        return
    wheel = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
    print(f"load average before: {load():.2f} (2-core machine shared with other agents)")
    for element in ("reduced", "full"):
        case = RollingCase(wheel=wheel, rail=wr.profiles.load("60E1"), radius=0.46, Fn=7500.0,
                           creepage=(7e-4, 0, 0), mu=0.2, mesh_size=args.mesh, element=element)
        t = time.perf_counter()
        model = build_model(case)
        t_build = time.perf_counter() - t
        ns_el = kernel_cost(model)
        mem = (model.edata_w.nbytes + model.edata_r.nbytes) / model.n_elements
        dt = case.courant * stable_time_step(model)
        _, t_end = _speed_profile(case, model.geometry["travel"])
        n2 = int(np.ceil(t_end / dt))
        print(f"\n[{element}] mesh {args.mesh * 1e3:g} mm: {model.n_elements} elements, "
              f"{model.n_nodes} nodes, travel {model.geometry['travel'] * 1e3:.1f} mm, "
              f"build {t_build:.1f} s")
        print(f"  internal force: {ns_el:.0f} ns/element/evaluation; element data "
              f"{mem:.0f} B/element")
        print(f"  stable step {dt:.3g} s (courant {case.courant}); rolling needs {n2} steps")
        ns_step, sps, ne, n = step_cost(case, args.steps)
        print(f"  explicit loop: {ns_step:.0f} ns/element/step, {sps:.1f} steps/s "
              f"({n} steps timed on {ne} elements)")
        print(f"  estimate for the rolling run ({n2} steps x {model.n_elements} elements): "
              f"{n2 * ns_step * 1e-9 * model.n_elements / 60:.1f} min on one core")
    print(f"\nload average after: {load():.2f}")


if __name__ == "__main__":
    main()
