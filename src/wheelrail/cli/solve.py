"""``wheelrail solve CASE.toml``: solve one case file, write JSON, optionally a plot."""

from __future__ import annotations

HELP = "solve a TOML case file (normal contact + creep forces)"


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="case file (see wheelrail.casefile)")
    p.add_argument("--json", metavar="OUT.json", help="write the results (SI units) as JSON")
    p.add_argument("--plot", metavar="OUT.png",
                   help="plot the traction/adhesion-slip fields (methods with fields, e.g. "
                        "FASTSIM) or else the pressure")
    p.add_argument("--quiet", "-q", action="store_true", help="print nothing on success")


def plot_result(result, path) -> str:
    """Draw the traction field if the method returned one, else the pressure; return which."""
    from ..plotting import field_arrays, pressure_map, traction_field

    from pathlib import Path

    fields = result.forces.fields
    title = f"{result.case.source}: {result.case.normal} + {result.summary['method']}"
    normal, grid = result.normal, result.grid
    p = None
    if normal is not None:
        p = getattr(normal, "pressure", None)
        p = getattr(normal, "p", None) if p is None else p
    has_bem = (p is not None and getattr(grid, "x", None) is not None
               and getattr(grid, "y", None) is not None)
    if fields is not None and field_arrays(fields) is not None:
        traction_field(fields, mu=result.case.mu, contact=result.contact, path=path, title=title)
        if has_bem:  # the boundary-element pressure goes beside the traction figure
            path = Path(path)
            extra = path.with_name(f"{path.stem}_pressure{path.suffix}")
            pressure_map(result.contact, x=grid.x, y=grid.y, p=p, path=extra, title=title)
            return f"traction field; pressure map in {extra}"
        return "traction field"
    if has_bem:
        try:
            pressure_map(result.contact, x=grid.x, y=grid.y, p=p, path=path, title=title)
            return "pressure (boundary elements)"
        except ValueError:
            pass
    pressure_map(result.contact, path=path, title=title)
    return "pressure (Hertz)"


def run(args, console) -> int:
    from ..casefile import load_case, solve_case
    from ._output import summary_table, write_json

    case = load_case(args.case)
    result = solve_case(case)
    if args.json:
        write_json(result.summary, args.json)
    what = plot_result(result, args.plot) if args.plot else None
    if not args.quiet:
        console.print(summary_table(result.summary, title=f"wheelrail solve {args.case}"))
        if args.json:
            console.print(f"results written to [bold]{args.json}[/bold]")
        if what:
            console.print(f"{what} plotted to [bold]{args.plot}[/bold]")
    return 0
