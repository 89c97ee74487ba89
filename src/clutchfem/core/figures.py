"""Figures without pyplot: :func:`figure` returns a matplotlib ``Figure`` and its axes.

A ``matplotlib.figure.Figure`` draws with the Agg canvas when saved, so clutchfem never
selects a backend (no ``matplotlib.use`` at import: a user's notebook or GUI backend stays
as it is) and keeps no global pyplot state (no figure to close, nothing leaks in a long
sweep).
"""

from __future__ import annotations


def figure(nrows: int = 1, ncols: int = 1, *, figsize=(8.0, 5.0), **subplot_kw):
    """(fig, axes) like ``plt.subplots``, without pyplot."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize)
    FigureCanvasAgg(fig)  # this figure's own canvas (text extents for layout); no global backend
    return fig, fig.subplots(nrows, ncols, **subplot_kw)
