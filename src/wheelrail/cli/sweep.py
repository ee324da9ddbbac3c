"""``wheelrail sweep CASE.toml --out table.zarr``: run a parameter sweep (resumable)."""

from __future__ import annotations

from ._output import esc

HELP = "run a [sweep] case over axes of creepage, load, friction, ... (Zarr/NetCDF, resumable)"


def add_arguments(p) -> None:
    p.add_argument("case", metavar="CASE.toml", help="sweep file with a [sweep] table "
                   "(see wheelrail.sweeps.spec)")
    p.add_argument("--out", required=True, metavar="OUT",
                   help="result: a Zarr directory (e.g. table.zarr) or a NetCDF file (.nc)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, metavar="N",
                       help="local workers (1: serial; more: a Dask LocalCluster)")
    where.add_argument("--scheduler", metavar="ADDR",
                       help="address of a running Dask scheduler, e.g. tcp://host:8786")
    p.add_argument("--executor", choices=("serial", "processes", "dask"),
                   help="override the executor (default: serial for 1 worker, else dask)")
    p.add_argument("--resume", action="store_true",
                   help="continue the sweep stored at --out (finished chunks are kept)")
    p.add_argument("--timeout", type=float, default=10.0, metavar="S",
                   help="seconds to wait for the scheduler to answer (default 10)")
    p.add_argument("--quiet", "-q", action="store_true", help="no progress bar, no summary")


def run(args, console) -> int:
    from rich.table import Table

    from ..sweeps import load_sweep, sweep

    spec = load_sweep(args.case)
    try:
        ds, info = sweep(spec, args.out, workers=args.workers, scheduler=args.scheduler,
                         executor=args.executor, resume=args.resume, progress=not args.quiet,
                         timeout=args.timeout, summary=True)
    except KeyboardInterrupt:
        import shlex
        import sys
        import warnings

        # the Zarr write the interrupt abandoned leaves coroutines that are never awaited;
        # their RuntimeWarnings (at garbage collection, after this message) are noise: a
        # chunk counts as done only once its marker is written, so --resume redoes it
        warnings.filterwarnings("ignore", message="coroutine .* was never awaited",
                                category=RuntimeWarning)

        again = " ".join(shlex.quote(str(a)) for a in ("wheelrail", "sweep", args.case,
                                                       "--out", args.out))
        print(f"wheelrail: interrupted: the finished chunks are kept in {args.out}; continue "
              f"with: {again} --resume", file=sys.stderr)
        return 130
    if info.failed:  # one line also under -q: the exit code alone says nothing
        import sys

        first = next((str(m) for m, st in zip(ds["message"].values.ravel(),
                                               ds["status"].values.ravel()) if st == 3), "")
        print(f"wheelrail: error: {info.failed} of {info.points} points failed (first: "
              f"{' '.join(first.split())[:200]}); their messages are in the 'message' "
              f"variable of {args.out}", file=sys.stderr)
    ds.close()
    if not args.quiet:
        t = Table(title=f"wheelrail sweep {esc(args.case)}", title_justify="left")
        t.add_column("quantity")
        t.add_column("value", justify="right")
        t.add_row("points", str(info.points))
        t.add_row("computed now", str(info.computed))
        t.add_row("failed", str(info.failed))
        t.add_row("not converged", str(info.not_converged))
        t.add_row("time", f"{info.seconds:.2f} s")
        t.add_row("points/s", f"{info.points_per_second:.1f}")
        t.add_row("executor", f"{info.executor} ({info.workers} worker(s))")
        console.print(t)
        console.print(f"results in [bold]{esc(args.out)}[/bold]")
    return 1 if info.failed else 0
