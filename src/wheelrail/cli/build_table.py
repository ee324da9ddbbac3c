"""``wheelrail build-table``: compute the creep-force table of the table law with the exact solver."""

from __future__ import annotations

HELP = "build the creep-force table of method 'table' with the exact solver (resumable)"


def add_arguments(p) -> None:
    from ..tangential.table import DEFAULT_TABLE

    p.add_argument("--out", default=str(DEFAULT_TABLE), metavar="TABLE.npz",
                   help="output table (default: the shipped file)")
    p.add_argument("--elements", type=int, default=40, metavar="N",
                   help="exact-solver elements across the contact (default 40)")
    p.add_argument("--workers", type=int, default=2, metavar="N", help="local workers (default 2)")
    p.add_argument("--executor", choices=("serial", "processes", "dask"),
                   help="executor of the sweep (default: serial for 1 worker, else dask)")
    p.add_argument("--work", default=None, metavar="DIR",
                   help="Zarr work store (default <out>.zarr); an interrupted build resumes from it")


def run(args, console) -> int:
    from ..sweeps.tables import build_table

    path = build_table(args.out, elements=args.elements, workers=args.workers,
                       executor=args.executor, work=args.work)
    console.print(f"wrote [bold]{path}[/bold]")
    return 0
