"""``wheelrail build-table``: compute the creep-force table of the table law with the exact solver."""

from __future__ import annotations

from ._output import esc

HELP = "build the creep-force table of method 'table' with the exact solver (resumable)"


def add_arguments(p) -> None:
    from ..sweeps.tables import (
        ELEMENTS,
        EXTRAPOLATION_STRIDE,
        FIRST_PLANE_ELEMENTS,
        NU_STRIDE,
        ORDER,
    )
    from ..tangential.table import DEFAULT_TABLE

    p.add_argument("--out", default=str(DEFAULT_TABLE), metavar="TABLE.npz",
                   help="output table (default: the shipped file)")
    p.add_argument("--elements", type=int, nargs="+", default=list(ELEMENTS), metavar="N",
                   help="exact-solver elements across the contact, N1 ... Nk: Nk-1 on every node "
                        "and nu, the others on every node at the first nu; the table is their "
                        "fitted grid limit (one value: no extrapolation; default "
                        f"{' '.join(map(str, ELEMENTS))})")
    p.add_argument("--order", type=float, default=ORDER, metavar="P",
                   help=f"convergence order of the grid-limit fit (default {ORDER:g})")
    p.add_argument("--extrapolation-stride", type=int, default=EXTRAPOLATION_STRIDE, metavar="K",
                   help="stride along r, theta, s of the sub-grid of the grid-limit fit (1: every "
                        f"node; default {EXTRAPOLATION_STRIDE})")
    p.add_argument("--nu-stride", type=int, default=NU_STRIDE, metavar="K",
                   help="stride along r, theta, s of the sub-grid of the other Poisson's ratio "
                        f"(1: every node; default {NU_STRIDE})")
    p.add_argument("--first-plane-elements", type=int, nargs="*",
                   default=list(FIRST_PLANE_ELEMENTS), metavar="N",
                   help="resolutions of a separate grid-limit fit on the smallest creepages "
                        "(r = dr), where the slip zone spans few elements (none: fit it like "
                        f"the others; default {' '.join(map(str, FIRST_PLANE_ELEMENTS))})")
    p.add_argument("--workers", type=int, default=2, metavar="N", help="local workers (default 2)")
    p.add_argument("--executor", choices=("serial", "processes", "dask"),
                   help="executor of the sweeps (default: serial for 1 worker, else dask)")
    p.add_argument("--work", default=None, metavar="DIR",
                   help="directory of the Zarr work stores (default <out>.work); an interrupted "
                        "build resumes from it, nodes already in its stores are reused")
    p.add_argument("--keep-work", action="store_true",
                   help="keep the work stores after writing the table")
    p.add_argument("--refine-only", action="store_true",
                   help="only recompute the refined regions of the existing table --out "
                        "(small creepage with large spin on wide patches, and the last theta "
                        "nodes of slender patches), with the first-plane resolutions; the "
                        "other nodes are kept")


def run(args, console) -> int:
    from ..sweeps.tables import build_table, refine_table

    if args.refine_only:
        path = refine_table(args.out, elements=tuple(args.first_plane_elements),
                            order=args.order, workers=args.workers, executor=args.executor,
                            work=args.work, keep_work=args.keep_work)
        console.print(f"wrote [bold]{esc(path)}[/bold]")
        return 0
    path = build_table(args.out, elements=tuple(args.elements), order=args.order,
                       extrapolation_stride=args.extrapolation_stride, nu_stride=args.nu_stride,
                       first_plane_elements=tuple(args.first_plane_elements),
                       workers=args.workers, executor=args.executor, work=args.work,
                       keep_work=args.keep_work)
    console.print(f"wrote [bold]{esc(path)}[/bold]")
    return 0
