"""``wheelrail solve CASE.toml``: solve one case file, write JSON, optionally a plot."""

from __future__ import annotations

from ._output import esc

HELP = "solve a TOML case file (normal contact + creep forces)"


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="case file (see wheelrail.cases.files)")
    p.add_argument("--json", metavar="OUT.json", help="write the results (SI units) as JSON")
    p.add_argument("--plot", metavar="OUT.png",
                   help="plot the traction/adhesion-slip fields (methods with fields, e.g. "
                        "FASTSIM) or else the pressure")
    p.add_argument("--quiet", "-q", action="store_true", help="print nothing on success")


def plot_result(result, path) -> str:
    """Draw the traction field if the method returned one, else the pressure; return which."""
    from pathlib import Path

    from ..plotting import field_arrays, pressure_map, traction_field

    fields = result.forces.fields
    title = f"{result.case.source}: {result.case.normal.name} + {result.summary['method']}"
    bem = result.normal  # the boundary-element NormalResult (normal = "bem") or None
    if fields is not None and field_arrays(fields) is not None:
        traction_field(fields, mu=result.case.mu, contact=result.contact, path=path, title=title)
        if bem is None:
            return "traction field"
        path = Path(path)  # the boundary-element pressure goes beside the traction figure
        extra = path.with_name(f"{path.stem}_pressure{path.suffix}")
        pressure_map(result.contact, x=bem.grid.x, y=bem.grid.y, p=bem.pressure, path=extra,
                     title=title)
        return f"traction field; pressure map in {extra}"
    if bem is not None:
        pressure_map(result.contact, x=bem.grid.x, y=bem.grid.y, p=bem.pressure, path=path,
                     title=title)
        return "pressure (boundary elements)"
    pressure_map(result.contact, path=path, title=title)
    return "pressure (Hertz)"


def run(args, console) -> int:
    from ..cases.files import load_contact_case as load_case
    from ..cases import solve_case
    from ._output import check_outputs, summary_table, write_json

    check_outputs(json=args.json, plot=args.plot)  # before the solve: paths and formats
    case = load_case(args.case)
    result = solve_case(case)
    if args.json:
        write_json(result.summary, args.json)
    what = plot_result(result, args.plot) if args.plot else None
    if not args.quiet:
        console.print(summary_table(result.summary, title=f"wheelrail solve {esc(args.case)}"))
        if args.json:
            console.print(f"results written to [bold]{esc(args.json)}[/bold]")
        if what:
            console.print(f"{what} plotted to [bold]{esc(args.plot)}[/bold]")
    return 0
