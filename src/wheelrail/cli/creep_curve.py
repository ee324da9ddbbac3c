"""``wheelrail creep-curve``: creep force against creepage for several methods in one figure."""

from __future__ import annotations

from ._output import esc

HELP = "plot force/(mu Fn) against one creepage for several creep-force methods"

DEFAULT_METHODS = "fastsim,polach,shen-hedrick-elkins,linear,carter"
#: Force plotted for each swept creepage (spin mainly produces a lateral force).
FORCE_OF = {"xi": "Fx", "eta": "Fy", "phi": "Fy"}
#: Default sweep range: creepages [-], spin [1/m].
DEFAULT_MAX = {"xi": 0.01, "eta": 0.01, "phi": 5.0}


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", nargs="?",
                   help="case file for contact, materials, friction and the other creepages "
                        "(default: built-in steel case, 7500 N, R = 0.46/0.30 m, mu = 0.3)")
    p.add_argument("--component", choices=("xi", "eta", "phi"), default="xi",
                   help="creepage to sweep (default xi)")
    p.add_argument("--max", type=float, default=None,
                   help="largest creepage (default 0.01 for xi/eta, 5 1/m for phi)")
    p.add_argument("--min", type=float, default=0.0, help="smallest creepage (default 0)")
    p.add_argument("--points", type=int, default=101, help="number of creepages (default 101)")
    p.add_argument("--methods", default=DEFAULT_METHODS,
                   help=f"comma-separated methods (default {DEFAULT_METHODS})")
    p.add_argument("--out", metavar="FIG.png", default="creep_curve.png",
                   help="figure file (default creep_curve.png)")
    p.add_argument("--csv", metavar="OUT.csv", help="also write the curves as CSV")


def default_case():
    """The built-in case (:data:`wheelrail.cases.DEFAULT_CASE`) with zero creepages."""
    from ..cases.files import case_from_dict
    from ..cases import DEFAULT_CASE

    return case_from_dict(DEFAULT_CASE, source="<built-in case>").replace(creepage=(0.0, 0.0, 0.0))


def parse_methods(text: str) -> list[str]:
    """Split and resolve method names; unknown names are an InputError."""
    from .. import tangential
    from ..errors import InputError

    out = []
    for name in (m.strip() for m in text.split(",")):
        if not name:
            continue
        try:
            key = tangential.get_class(name, argname="creep-force").name
        except InputError as exc:
            raise InputError(f"--methods: {exc}") from None
        if key not in out:
            out.append(key)
    if not out:
        raise InputError(f"--methods {text!r} names no method")
    return out


def sweep(case, component: str, values, methods, *, progress=None):
    """Creep forces of each method along a creepage sweep.

    Parameters
    ----------
    case : Case
        Contact, materials, μ and the creepages held fixed.
    component : {"xi", "eta", "phi"}
    values : ndarray, shape (n,)
        The swept creepage.
    methods : list of str
    progress : callable, optional
        Called with the method name after each method.

    Returns
    -------
    forces : dict of str to CreepForcesResult
        The methods that ran (batch results of shape (n,)).
    skipped : dict of str to str
        Methods that cannot treat this
        sweep (``InputError``, e.g. Carter's theory and a lateral creepage),
        with the reason.
    """
    import numpy as np

    from ..api import creep_forces
    from ..errors import InputError

    idx = ("xi", "eta", "phi").index(component)
    creep = np.tile(np.asarray(case.creepage, dtype=float), (len(values), 1))
    creep[:, idx] = values
    contact = case.hertz_contact
    forces, skipped = {}, {}
    for m in methods:
        try:
            forces[m] = creep_forces(contact, creep, case.mu,
                                     method=case.with_tangential(m).tangential)
        except InputError as exc:  # e.g. Carter's theory has no lateral creepage
            skipped[m] = " ".join(str(exc).split())
        if progress is not None:
            progress(m)
    return forces, skipped


def normalised(forces, component: str):
    """Method → force/(μ Fn) of the force that belongs to ``component``."""
    import numpy as np

    key = FORCE_OF[component]
    return {m: np.asarray(getattr(r, key)) / (np.asarray(r.mu) * np.asarray(r.Fn))
            for m, r in forces.items()}


def write_csv(path, component, values, forces) -> None:
    """Columns: the creepage, then per method Fx, Fy [N], Mz [N m] and the normalised force."""
    import csv
    from pathlib import Path

    import numpy as np

    norm = normalised(forces, component)
    header = [component]
    cols = [np.asarray(values)]
    for m, r in forces.items():
        header += [f"{m}_Fx", f"{m}_Fy", f"{m}_Mz", f"{m}_{FORCE_OF[component]}_norm"]
        cols += [np.asarray(r.Fx), np.asarray(r.Fy), np.asarray(r.Mz), norm[m]]
    from .._atomic import atomic_open

    path = Path(path)
    with atomic_open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for row in np.column_stack(cols):
            w.writerow([f"{v:.9g}" for v in row])


def run_sweep_with_progress(console, case, component, values, methods, *, warn=True):
    """:func:`sweep` with a rich progress bar; warns about skipped methods if ``warn``."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    with Progress(TextColumn("{task.description}"), BarColumn(), TextColumn("{task.fields[m]}"),
                  TimeElapsedColumn(), console=console, transient=True,
                  disable=not console.is_terminal) as prog:
        task = prog.add_task(f"creep curve ({component})", total=len(methods), m="")
        forces, skipped = sweep(case, component, values, methods,
                                progress=lambda m: prog.update(task, advance=1, m=m))
    for m, why in (skipped.items() if warn else ()):
        console.print(f"[yellow]skipped {esc(m)}: {esc(why)}[/yellow]")
    return forces, skipped


def run(args, console) -> int:
    import numpy as np

    from ..cases.files import load_contact_case as load_case
    from ..errors import InputError
    from ..plotting import creep_curves

    if not 2 <= args.points <= 1_000_000:
        raise InputError(f"--points must lie in [2, 1000000], got {args.points}")
    vmax = DEFAULT_MAX[args.component] if args.max is None else args.max
    if not np.isfinite(vmax) or not np.isfinite(args.min) or vmax == args.min:
        raise InputError(f"--min and --max must be finite and differ, got {args.min!r}, {vmax!r}")
    from ..plausibility import ImplausibleInputError, check_creepage

    for flag, v in (("--max", vmax), ("--min", args.min)):  # a percentage given: refused
        try:
            check_creepage(**{args.component: v})
        except ImplausibleInputError as exc:
            raise ImplausibleInputError(f"{flag}: {exc}") from None
    methods = parse_methods(args.methods)
    from ._output import check_outputs

    check_outputs(out=args.out, csv=args.csv)
    case = load_case(args.case) if args.case else default_case()
    values = np.linspace(args.min, vmax, args.points)
    forces, skipped = run_sweep_with_progress(console, case, args.component, values, methods)
    if not forces:
        why = "; ".join(f"{m}: {r}" for m, r in skipped.items())
        raise InputError(f"no curve to plot: every method was skipped ({why})")
    c = case.hertz_contact
    title = (f"{case.source}: Fn = {c.Fn:.0f} N, a = {c.a * 1e3:.2f} mm, "
             f"b = {c.b * 1e3:.2f} mm, μ = {case.mu:g}")
    creep_curves(values, normalised(forces, args.component), component=args.component,
                 force=FORCE_OF[args.component], path=args.out, title=title)
    console.print(f"creep curves of {', '.join(forces)} plotted to [bold]{esc(args.out)}[/bold]")
    if args.csv:
        write_csv(args.csv, args.component, values, forces)
        console.print(f"curves written to [bold]{esc(args.csv)}[/bold]")
    return 0
