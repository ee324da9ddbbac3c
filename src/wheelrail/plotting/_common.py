"""Figure creation on the Agg canvas (no pyplot, no global backend switch)."""

from __future__ import annotations

import warnings
from pathlib import Path

from .._atomic import atomic_path

__all__ = ["new_figure", "finish"]


def new_figure(nrows: int = 1, ncols: int = 1, *, size=None, **subplot_kw):
    """A :class:`~matplotlib.figure.Figure` on an Agg canvas and its axes array.

    Parameters
    ----------
    nrows, ncols : int
        Grid of axes.
    size : (float, float), optional
        Figure size in inches (default 5.5 × 4.2 per axes).

    Returns
    -------
    fig : Figure
    axes : ndarray of Axes, shape (nrows, ncols), squeezed
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    if size is None:
        size = (5.5 * ncols, 4.2 * nrows)
    fig = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, squeeze=True, subplot_kw=subplot_kw or None)
    return fig, axes


def finish(fig, path=None, title=None, dpi: int = 130):
    """Set the title and write ``fig`` to ``path`` (format from the suffix) if given."""
    if title:
        fig.suptitle(title, fontsize="medium")
    if path is not None:
        path = Path(path)
        fmt = path.suffix.lstrip(".").lower() or None
        with atomic_path(path) as tmp, warnings.catch_warnings():  # no half-written figure
            # matplotlib's quiver divides by its auto scale, zero for an all-zero field
            warnings.filterwarnings("ignore", category=RuntimeWarning, module="matplotlib")
            fig.savefig(tmp, dpi=dpi, format=fmt)
    return fig
