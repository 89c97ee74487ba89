"""The size of a 3-D model before it is built: its unknowns and peak memory from the 2-D
mesh and the layer count, and the refusal of a model that would not fit (issue 24).

The node count of the extruded P2 tetrahedra is exact ((2 layers + 1) x the 2-D P2 nodes);
the memory is a fit to measured peak resident sets (the sparse factor's fill grows faster
than the unknowns), an estimate, stated as one in the refusal.
"""

from __future__ import annotations

import math
import os

from ..core import ParameterError
from ..mesh import ClutchMesh

__all__ = ["estimate_3d", "check_3d_size", "max_model_memory"]

#: peak memory of a 3-D analysis [bytes] ~ MEMORY_BASE + MEMORY_COEF N^MEMORY_POWER (N the
#: unknowns): fitted as an upper bound to the peak resident set (ru_maxrss) of
#: ``analyze(errors=False)`` on concept 4, best mesh, 1 / 2 / 3 layers: 21 258 / 35 430 /
#: 49 602 unknowns, 0.54 / 1.07 / 1.80 GB measured, 0.56 / 1.08 / 1.85 GB estimated
#: (BENCHMARKS.md section 14, 2026-11-26); the factor's fill makes it grow faster than N.
#: Beyond ~50 000 unknowns it is an extrapolation (stated in the refusal as an estimate)
MEMORY_BASE = 0.25e9
MEMORY_COEF = 1.12
MEMORY_POWER = 1.95


def estimate_3d(n_nodes_2d: int, layers: int, half: bool = True) -> tuple[int, float]:
    """(unknowns, peak memory [bytes]) of the 3-D model of a 2-D P2 mesh with ``n_nodes_2d``
    nodes extruded into ``layers`` layers: the P2 tetrahedra of a layer of prisms add the
    vertices and edge midpoints of a level, the vertical edges and the side-face diagonals,
    so the node count is (2 layers + 1) x the 2-D count (3 unknowns each; ``half=False``:
    the layers span the whole thickness the same way)."""
    n = 3 * (2 * int(layers) + 1) * int(n_nodes_2d)
    return n, MEMORY_BASE + MEMORY_COEF * float(n) ** MEMORY_POWER


def max_model_memory() -> float:
    """The memory one model may use [bytes]: ``CLUTCHFEM_MAX_MEMORY_GB`` if set, else half of
    the machine's physical memory (several workers and the rest of the machine share it)."""
    raw = os.environ.get("CLUTCHFEM_MAX_MEMORY_GB")
    if raw:
        try:
            v = float(raw)
        except ValueError:
            raise ParameterError("CLUTCHFEM_MAX_MEMORY_GB", raw, "a number of gigabytes > 0 (environment "
                                 "variable)") from None
        if not (math.isfinite(v) and v > 0):
            raise ParameterError("CLUTCHFEM_MAX_MEMORY_GB", raw, "a number of gigabytes > 0 (environment variable)")
        return v * 1e9
    try:
        return 0.5 * os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):  # pragma: no cover - not POSIX
        return 8e9


def check_3d_size(cm: ClutchMesh, layers: int) -> tuple[int, float]:
    """Refuse a 3-D model whose estimated memory (:func:`estimate_3d`) exceeds
    :func:`max_model_memory`, naming ``layers``, the estimate, the limit and the largest layer
    count that fits; returns (unknowns, bytes) otherwise."""
    n, mem = estimate_3d(cm.n_nodes, layers)
    limit = max_model_memory()
    if mem > limit:
        fit = [L for L in range(1, int(layers)) if estimate_3d(cm.n_nodes, L)[1] <= limit]
        what = (f"at most {fit[-1]} on this mesh ({cm.n_elements} elements)" if fit else
                "fewer elements first (a coarser --mesh-size): even 1 layer does not fit")
        raise ParameterError("layers", layers, f"{what}: {layers} layers would give about {n:,} unknowns and need "
                             f"about {mem / 1e9:.1f} GB (estimate), more than the limit {limit / 1e9:.1f} GB (half of "
                             "this machine's memory; CLUTCHFEM_MAX_MEMORY_GB sets it); the thick plane model "
                             "(--formulation thick) gives the 3-D answer at 2-D cost", "3-D model")
    return n, mem
