"""Console output shared by the commands (rich tables)."""

from __future__ import annotations

import json
from pathlib import Path

#: key -> (label, unit shown, factor from SI)
ROWS = [
    ("Fn", "normal force Fn", "N", 1.0),
    ("a", "semi-axis a", "mm", 1e3),
    ("b", "semi-axis b", "mm", 1e3),
    ("p0", "max. Hertz pressure p0", "MPa", 1e-6),
    ("p_max", "max. pressure", "MPa", 1e-6),
    ("penetration", "penetration", "µm", 1e6),
    ("area", "contact area", "mm²", 1e6),
    ("adhesion_area", "adhesion area", "mm²", 1e6),
    ("xi", "creepage ξ", "-", 1.0),
    ("eta", "creepage η", "-", 1.0),
    ("phi", "spin φ", "1/m", 1.0),
    ("mu", "friction μ", "-", 1.0),
    ("Fx", "Fx", "N", 1.0),
    ("Fy", "Fy", "N", 1.0),
    ("Mz", "Mz", "N·m", 1.0),
    ("utilisation", "|Ft| / (μ Fn)", "-", 1.0),
]


def esc(value) -> str:
    """``str(value)`` with rich markup escaped: user-given names (files, profiles) are echoed
    literally, so ``c[/bold].toml`` prints as it is instead of raising ``MarkupError``."""
    from rich.markup import escape

    return escape(str(value))


def _fmt(v) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def summary_table(summary: dict, title: str):
    """A rich Table of the main results of :func:`wheelrail.run_case`."""
    from rich.table import Table

    table = Table(title=title, title_justify="left")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_column("unit")
    for key, label, unit, factor in ROWS:
        v = summary.get(key)
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            table.add_row(label, _fmt(v * factor), unit)
    it = summary.get("iterations")
    table.add_row("method", f"{summary.get('normal_method', 'hertz')} + {summary.get('method')}", "")
    table.add_row("status", f"{summary.get('status')}"
                  + (f" ({it} iterations)" if it is not None else ""), "")
    return table


#: Figure formats of matplotlib's Agg/vector backends (checked before any work).
FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".svgz", ".eps", ".ps", ".jpg", ".jpeg", ".tif",
                   ".tiff", ".webp", ".pgf")


def check_outputs(**outputs) -> None:
    """Check output options before solving: ``name=path`` (None skipped).

    Names ending in ``plot``/``out``/``figure`` must have a figure suffix of
    :data:`FIGURE_SUFFIXES`; ``json`` a ``.json`` suffix; ``csv`` ``.csv``.
    Every path must be a writable file location (not a directory).
    """
    from .._atomic import check_output_path

    for name, path in outputs.items():
        if path is None:
            continue
        opt = "--" + name.replace("_", "-")
        if name in ("plot", "out", "figure"):
            check_output_path(path, what=opt, suffixes=FIGURE_SUFFIXES)
        elif name in ("json", "csv"):
            check_output_path(path, what=opt, suffixes=(f".{name}",))
        else:
            check_output_path(path, what=opt)


def _finite_or_null(obj):
    """Replace NaN and ±inf floats by None, recursively (JSON has no NaN)."""
    import math

    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _finite_or_null(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite_or_null(v) for v in obj]
    return obj


def write_json(data: dict, path) -> Path:
    """Write ``data`` as JSON atomically (a full disk leaves no half-written file).

    The text is produced completely before the file is opened; NaN and inf
    (not valid JSON) are written as ``null``.
    """
    from .._atomic import atomic_open

    path = Path(path)
    text = json.dumps(_finite_or_null(data), indent=2, allow_nan=False) + "\n"
    with atomic_open(path, "w", encoding="utf-8") as fh:
        fh.write(text)
    return path
