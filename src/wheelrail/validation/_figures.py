"""Figures of the report: matplotlib (Agg) to base64 PNG (no files, no external assets)."""

from __future__ import annotations

import base64
import io


def new_figure(width=4.2, height=3.0):
    """A matplotlib figure and axes on the non-interactive Agg canvas."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), dpi=90)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    return fig, ax


def to_base64(fig) -> str:
    """The figure as a base64-encoded PNG."""
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    return base64.b64encode(buf.getvalue()).decode("ascii")


def convergence_figure(h, err, label, order, xlabel="element size h [m]"):
    """log-log error against element size with the fitted order in the legend."""
    import numpy as np

    fig, ax = new_figure()
    h, err = np.asarray(h, float), np.asarray(err, float)
    ax.loglog(h, err, "o-", label=f"{label} (fitted order {order:.2f})")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("relative error")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    return to_base64(fig)
