"""The validation modules' figures of the papers: one size, one resolution, one way to label,
finish and save a figure (the thesis's and seed 000's charts)."""

from __future__ import annotations

from pathlib import Path

from ..core import figure

__all__ = ["DPI", "finish", "paper_figure"]

#: resolution of the figures [dots per inch]
DPI = 120


def paper_figure(size=(7.0, 4.5)):
    """(figure, axes) of one chart: an Agg canvas, no global pyplot state."""
    return figure(figsize=size)


def finish(fig, ax, path: Path, paths: list[Path], *, legend: dict | None = None, **labels) -> None:
    """Label ``ax`` (``labels``: ``Axes.set``'s keywords), draw its legend (``legend``: its
    keywords), save ``fig`` to ``path`` and append the path to ``paths``."""
    ax.set(**labels)
    ax.legend(**(legend or {}))
    paths.append(path)
    fig.savefig(path, dpi=DPI)
