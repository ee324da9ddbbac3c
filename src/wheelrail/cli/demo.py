"""``wheelrail demo``: run the built-in case with every available method and write figures.

The demo is a list of steps, :data:`STEPS`. A step is a function
``step(ctx: DemoContext) -> str | None`` that computes something, stores it in
``ctx.results`` (JSON-ready, SI units), writes files with :meth:`DemoContext.file`
and returns a one-line note for the console. A step that fails with a
:class:`~wheelrail.errors.WheelrailError` is reported as failed and the demo
goes on (the exit code is then non-zero); any other exception is a bug and
propagates.
To add a part (a geometry contact table, a boundary-element solution, ...)
write a step function and append ``Step("name", "title", function)`` to
:data:`STEPS`. Keep every step fast: the whole demo must take < 30 s.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from ._output import esc

HELP = "run the built-in example with all available methods; write results and figures"


@dataclass
class DemoContext:
    """What the steps share: output directory, console, the case and the results."""

    out: Path
    console: object
    case: object
    results: dict = field(default_factory=dict)
    files: list = field(default_factory=list)

    def file(self, name: str, description: str) -> Path:
        """Path of an output file in :attr:`out`, recorded for the final listing."""
        path = self.out / name
        self.files.append((path, description))
        return path


@dataclass(frozen=True)
class Step:
    name: str
    title: str
    run: Callable[[DemoContext], "str | None"]


# --------------------------------------------------------------------------- steps
def step_case(ctx: DemoContext):
    """The built-in case as a case file, to edit and run with ``wheelrail solve``."""
    path = ctx.file("case.toml", "the built-in case (wheelrail solve case.toml)")
    from .._atomic import write_text

    write_text(path, ctx.case.to_toml())
    return f"run it yourself: wheelrail solve {path} --plot fields.png"


def step_hertz(ctx: DemoContext):
    """Hertz solution of the built-in case and a table against the load."""
    import csv

    import numpy as np

    from ..hertzian import hertz
    from ..plotting import pressure_map

    c = ctx.case.hertz_contact
    ctx.results["case"] = {"material": {"E": ctx.case.materials.wheel.E,
                                        "nu": ctx.case.materials.wheel.nu},
                           "contact": ctx.case.contact.to_dict(), "mu": ctx.case.mu,
                           "creepage": dict(zip(("xi", "eta", "phi"), ctx.case.creepage))}
    ctx.results["hertz"] = c.to_dict()
    loads = np.linspace(2500.0, 20000.0, 8)
    batch = hertz(loads, c.A, c.B, ctx.case.materials)
    from .._atomic import atomic_open

    with atomic_open(ctx.file("hertz_table.csv", "Hertz a, b, p0, δ against the load"), "w",
                     newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(["load_N", "a_m", "b_m", "p0_Pa", "penetration_m", "area_m2"])
        for row in zip(batch.Fn, batch.a, batch.b, batch.p0, batch.penetration, batch.area):
            w.writerow([f"{v:.9g}" for v in row])
    pressure_map(c, path=ctx.file("hertz_pressure.png", "Hertz pressure on the contact ellipse"),
                 title="Hertz pressure, built-in case")
    return f"a = {c.a * 1e3:.3f} mm, b = {c.b * 1e3:.3f} mm, p0 = {c.p0 / 1e6:.0f} MPa"


#: Creepage combinations of the force table: (label, (ξ, η, φ [1/m])).
CREEPAGES = [
    ("longitudinal", (-1.0e-3, 0.0, 0.0)),
    ("lateral", (0.0, 1.0e-3, 0.0)),
    ("spin", (0.0, 0.0, 0.5)),
    ("combined", (-1.0e-3, 5.0e-4, 0.3)),
]
#: The creepage of the traction-field figures (FASTSIM and the exact theory).
COMBINED = dict(CREEPAGES)["combined"]


def step_creep_forces(ctx: DemoContext):
    """Every available creep-force method at a few creepage combinations."""
    from ..api import creep_forces, tangential_methods
    from ..errors import InputError

    table = {}
    for m in tangential_methods():
        if m == "exact":
            continue  # the exact theory is slow; the demo keeps to the fast laws
        rows = {}
        for label, cr in CREEPAGES:
            try:
                r = creep_forces(ctx.case.hertz_contact, cr, ctx.case.mu, method=m)
            except InputError as exc:  # e.g. Carter's theory: longitudinal creepage only
                rows[label] = {"xi": cr[0], "eta": cr[1], "phi": cr[2],
                               "error": " ".join(str(exc).split())}
                continue
            rows[label] = {"xi": cr[0], "eta": cr[1], "phi": cr[2], "Fx": float(r.Fx),
                           "Fy": float(r.Fy), "Mz": float(r.Mz)}
        table[m] = rows
    ctx.results["creep_forces"] = table
    from rich.table import Table

    t = Table(title=f"creep forces [N], μ = {ctx.case.mu:g}", title_justify="left")
    t.add_column("method")
    for label, cr in CREEPAGES:
        t.add_column(f"{label}\nξ={cr[0]:g} η={cr[1]:g} φ={cr[2]:g}", justify="right")
    for m, rows in table.items():
        t.add_row(m, *(f"Fx {round(rows[lb]['Fx'])}\nFy {round(rows[lb]['Fy'])}" if "Fx" in rows[lb]
                       else "n/a" for lb, _ in CREEPAGES))
    ctx.console.print(t)
    return f"{len(table)} methods"


def step_creep_curves(ctx: DemoContext):
    """Creep curves in ξ and η for every available fast method (two panels)."""
    import numpy as np

    from ..api import tangential_methods
    from ..plotting import creep_curves, new_figure
    from ..plotting._common import finish
    from .creep_curve import normalised, run_sweep_with_progress

    methods = [m for m in tangential_methods() if m != "exact"]
    fig, axes = new_figure(1, 2, size=(12.0, 4.6))
    case = ctx.case.replace(creepage=(0.0, 0.0, 0.0))
    curves, notes = {}, []
    for ax, comp in zip(axes, ("xi", "eta")):
        values = np.linspace(0.0, 0.01, 51)
        forces, skipped = run_sweep_with_progress(ctx.console, case, comp, values, methods,
                                                  warn=False)
        notes += [f"{m} not in the {comp} panel" for m in skipped]
        norm = normalised(forces, comp)
        creep_curves(values, norm, component=comp, ax=ax)
        curves[comp] = {"creepage": values.tolist(), **{m: v.tolist() for m, v in norm.items()}}
    c = case.hertz_contact
    finish(fig, ctx.file("creep_curves.png", "creep curves, ξ and η"),
           title=f"built-in case: Fn = {c.Fn:.0f} N, μ = {case.mu:g} (force / μFn)")
    ctx.results["creep_curves"] = curves
    return ("methods: " + ", ".join(m for m in curves["xi"] if m != "creepage")
            + (f" ({'; '.join(notes)})" if notes else ""))


def step_fastsim_fields(ctx: DemoContext):
    """FASTSIM traction and adhesion/slip areas of the built-in case."""
    from ..cases import solve_case
    from .solve import plot_result

    result = solve_case(ctx.case.replace(tangential="fastsim", creepage=COMBINED))
    what = plot_result(result, ctx.file("fastsim_fields.png", "FASTSIM traction and slip"))
    ctx.results["fastsim"] = result.summary
    return f"{what}; Fx = {result.summary['Fx']:.0f} N, Fy = {result.summary['Fy']:.0f} N"


def step_exact(ctx: DemoContext):
    """Kalker's exact theory on the built-in case: fields, BEM pressure, subsurface stresses."""
    import numpy as np

    from ..api import creep_forces
    from ..halfspace import subsurface_stresses
    from ..plotting import pressure_map, subsurface_section, traction_field

    case = ctx.case
    contact = case.hertz_contact
    exact = creep_forces(contact, COMBINED, case.mu, method="exact", elements=40)
    fast = creep_forces(contact, COMBINED, case.mu, method="fastsim", nx=40, ny=40)
    sol = exact.fields
    grid = sol.grid
    title = "built-in case, Kalker's exact theory (40 elements across)"
    traction_field(sol, mu=case.mu, contact=contact, title=title,
                   path=ctx.file("exact_fields.png", "exact theory: traction, adhesion/slip"))
    pressure_map(contact, x=grid.x, y=grid.y, p=sol.pressure, title=title,
                 path=ctx.file("exact_pressure.png", "boundary-element pressure"))
    depth = np.linspace(0.05, 2.0, 40) * float(contact.b)
    stresses = subsurface_stresses(grid, sol.px, sol.py, sol.pressure, case.materials, depth)
    subsurface_section(stresses, title=title,
                       path=ctx.file("subsurface_von_mises.png", "von Mises stress below y = 0"))
    vm, z, _, _ = stresses.max_location("von_mises")
    ctx.results["exact"] = {
        "creepage": list(COMBINED), "Fx": exact.Fx, "Fy": exact.Fy, "Mz": exact.Mz,
        "fastsim_40x40": {"Fx": fast.Fx, "Fy": fast.Fy, "Mz": fast.Mz},
        "iterations": exact.iterations,
        "von_mises_max": vm, "von_mises_depth": z, **{k: v for k, v in exact.info.items()
                                                      if np.ndim(v) == 0}}
    return (f"Fx = {exact.Fx:.0f} N, Fy = {exact.Fy:.0f} N (FASTSIM {fast.Fx:.0f}, "
            f"{fast.Fy:.0f} N); max von Mises {vm / 1e6:.0f} MPa at {z * 1e3:.2f} mm depth")


def step_geometry(ctx: DemoContext):
    """S1002 wheelset on 60E1 rails 1:40: contact table over y = −10…10 mm and figures."""
    from .geometry import geometry_demo

    out = geometry_demo(ctx.out)
    ctx.results["geometry"] = out["results"]
    ctx.files.extend(out["files"])
    return out["note"]


def step_wheelrail(ctx: DemoContext):
    """S1002 wheelset on 60E1 rails 1:40: patches and forces (Hertz + FASTSIM sweep over the
    lateral shift; one position with boundary elements + the exact theory on a coarse grid)."""
    import numpy as np

    from ..api import solve
    from ..contact.sweep import wheelset_sweep
    from ..contact.wheelrail import WheelRailPosition
    from ..geometry import Track, Wheelset
    from ..geometry.kinematics import Motion
    from ..plotting.wheelrail import adhesion_maps, contact_profiles, sweep_forces
    from ..profiles import load
    from .wheelset import write_sweep_csv

    ws = Wheelset(load("S1002"), nominal_radius=0.46, flange_back=1.360)
    tr = Track(load("60E1"), gauge=1.435, inclination=1 / 40)
    # slightly braked (Ω 0.1 % below free rolling), small yaw: all three creepages present
    motion = Motion(speed=20.0, omega=20.0 / 0.46 * (1.0 - 1e-3))
    mu, Q, yaw = 0.3, 10e3, 2e-3
    pos = WheelRailPosition(ws, tr, y=0.005, yaw=yaw, roll=None, vertical_load=Q)
    res = solve(pos, motion=motion, mu=mu, normal="hertz", tangential="fastsim")
    contact_profiles(res, path=ctx.file("wheelrail_profiles.png",
                                        "S1002/60E1, y = 5 mm: profiles, patches, pressure"))
    adhesion_maps(res, path=ctx.file("wheelrail_adhesion.png",
                                     "S1002/60E1, y = 5 mm: adhesion/slip per patch (FASTSIM)"))
    bem = solve(pos, motion=motion, mu=mu, normal="bem", tangential="exact",
                element_size=5e-4)
    contact_profiles(bem, path=ctx.file("wheelrail_profiles_bem.png",
                                        "y = 5 mm, boundary elements (0.5 mm) + exact theory"))
    adhesion_maps(bem, path=ctx.file("wheelrail_adhesion_bem.png",
                                     "y = 5 mm: adhesion/slip per patch (exact theory)"))
    ys = np.linspace(-0.008, 0.008, 21)
    ds = wheelset_sweep(ws, tr, y=ys, yaw=yaw, vertical_load=Q, motion=motion, mu=mu,
                        progress=False)
    write_sweep_csv(ds, ctx.file("wheelrail_sweep.csv", "Hertz + FASTSIM over y (CSV, SI)"))
    sweep_forces(ds, path=ctx.file("wheelrail_sweep.png",
                                   "forces and patch positions against the lateral shift"))
    ctx.results["wheelrail"] = {
        "position": {"y": 0.005, "yaw": yaw, "vertical_load": Q, "mu": mu,
                     "motion": motion.to_dict()},
        "hertz_fastsim": res.to_dict(), "bem_exact_0.5mm": bem.to_dict(),
        "sweep_y": ys.tolist(),
        "sweep_Fy_track": {s: ds["Fy_track"].sel(side=s).values.tolist() for s in ("left", "right")},
        "sweep_failed": int(np.sum(ds["status"].values != "ok")),
    }
    two = [f"{side} {len(res.side(side))}" for side in ("left", "right")]
    return (f"y = 5 mm: patches {', '.join(two)}; right-wheel F_y = "
            f"{res.force_track['right'][1]:.0f} N (Hertz+FASTSIM), "
            f"{bem.force_track['right'][1]:.0f} N (BEM+exact); sweep of {ys.size} shifts")


from .fe import demo_step as step_fe_plastic  # noqa: E402  (the FE step lives with `wheelrail fe`)

#: The demo, in order. Append a Step to add a part.
STEPS = [
    Step("case", "built-in case file", step_case),
    Step("hertz", "Hertz contact of the built-in case", step_hertz),
    Step("creep-forces", "creep forces, all fast methods", step_creep_forces),
    Step("creep-curves", "creep curves in ξ and η", step_creep_curves),
    Step("fastsim-fields", "FASTSIM traction field", step_fastsim_fields),
    Step("exact", "Kalker's exact theory (boundary elements)", step_exact),
    Step("geometry", "S1002/60E1 1:40 contact table", step_geometry),
    Step("wheelrail", "S1002/60E1 wheelset: patches and forces", step_wheelrail),
    Step("fe-plastic", "FE rolling, elastic and elasto-plastic (small mesh)", step_fe_plastic),
]


# --------------------------------------------------------------------------- command
def add_arguments(p) -> None:
    p.add_argument("--out", metavar="DIR", default="wheelrail-demo",
                   help="output directory (default ./wheelrail-demo)")
    p.add_argument("--steps", default=None,
                   help="comma-separated subset of steps: " + ", ".join(s.name for s in STEPS))


def run(args, console) -> int:
    import time

    from ..cases.files import case_from_dict
    from ..cases import DEFAULT_CASE
    from ..errors import InputError, WheelrailError
    from ._output import write_json

    steps = STEPS
    if args.steps is not None:
        wanted = [s.strip() for s in args.steps.split(",") if s.strip()]
        names = [s.name for s in STEPS]
        if not wanted:
            raise InputError(f"--steps is empty (got {args.steps!r}); give one or more of: "
                             f"{', '.join(names)} (or leave --steps out for the whole demo)")
        bad = [w for w in wanted if w not in names]
        if bad:
            raise InputError(f"unknown demo step(s) {', '.join(bad)}; steps: {', '.join(names)}")
        steps = [s for s in STEPS if s.name in wanted]
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    ctx = DemoContext(out=out, console=console,
                      case=case_from_dict(DEFAULT_CASE, source="<built-in case>"))
    console.print(f"[bold]wheelrail demo[/bold] → {esc(out.resolve())}")
    failed = []
    status = {}
    for step in steps:
        t0 = time.perf_counter()
        try:
            note = step.run(ctx)
        except WheelrailError as exc:
            status[step.name] = "failed"
            failed.append(step.name)
            console.print(f"[red]✗ {step.title}: {esc(exc)}[/red]")
            continue
        status[step.name] = "ok"
        dt = time.perf_counter() - t0
        console.print(f"[green]✓[/green] {step.title} ({dt:.1f} s)" + (f": {esc(note)}" if note else ""))
    ctx.results["steps"] = status
    write_json(ctx.results, ctx.file("results.json", "all numbers of the demo (SI units)"))
    from rich.table import Table

    t = Table(title="files written", title_justify="left")
    t.add_column("file")
    t.add_column("content")
    for path, desc in ctx.files:
        if path.exists():
            t.add_row(esc(str(path)), esc(desc))
    console.print(t)
    return 1 if failed else 0
