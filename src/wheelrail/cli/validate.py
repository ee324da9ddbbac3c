"""``wheelrail validate``: every method against independent references, as a report."""

from __future__ import annotations

HELP = ("run every method against independent references (closed forms, published tables, "
        "CONTACT, convergence orders) and write an HTML/JSON/Markdown report")


def add_arguments(parser):
    parser.add_argument("--quick", action="store_true",
                        help="small grids and fewer cases (under a minute on one core)")
    parser.add_argument("--out", metavar="DIR", default="validation-report",
                        help="directory for report.html, report.json, report.md and "
                             "citations.bib (default: ./validation-report)")
    parser.add_argument("--only", metavar="CHECK", nargs="+", default=None,
                        help="run only these checks (names as in the report's 'check' field)")


def run(args, console) -> int:
    from rich.markup import escape
    from rich.table import Table

    from .. import validation

    report = validation.run(quick=args.quick, progress=True, only=args.only, console=console)
    paths = validation.write_report(report, args.out)
    from rich import box

    # a narrow terminal (80 columns) drops tolerance and time (they are in the report files)
    # so that the quantity keeps a readable width instead of one word per line
    narrow = getattr(console, "width", 200) < 120
    cols = ("method", "quantity", "error", "status") if narrow else (
        "method", "quantity", "error", "tolerance", "status", "time [s]")
    table = Table(title="wheelrail validate" + (" --quick" if args.quick else ""),
                  show_lines=False, box=box.SIMPLE_HEAD if narrow else box.HEAVY_HEAD)
    for col in cols:
        table.add_column(col, no_wrap=col != "quantity", min_width=20 if col == "quantity"
                         else None)
    from ..validation._report import _err, _tol

    style = {"passed": "green", "failed": "bold red", "known-failure": "yellow",
             "skipped": "dim"}
    for r in report.rows:
        cells = {"method": escape(r.method), "quantity": escape(r.quantity), "error": _err(r),
                 "tolerance": _tol(r), "status": f"[{style[r.status]}]{r.status}[/]",
                 "time [s]": f"{r.time:.2f}" if r.time == r.time else "-"}
        table.add_row(*(cells[c] for c in cols))
    console.print(table)
    c = report.counts()
    console.print(f"{len(report.rows)} rows: {c['passed']} passed, {c['failed']} failed, "
                  f"{c['known-failure']} known failures, {c['skipped']} skipped; total time "
                  f"{report.total_time:.1f} s")
    for r in report.rows:
        if r.status in ("failed", "known-failure"):
            console.print(escape(f"  {r.status}: {r.method}, {r.quantity}: {r.note}"))
    console.print(f"report: {escape(str(paths['html']))} (also {paths['json'].name}, {paths['md'].name}, "
                  f"{paths['bib'].name})")
    return 0 if report.passed else 1
