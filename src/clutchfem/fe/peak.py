"""Peak stress converged where it governs: the free-spin von Mises peak refined locally
(a disc of elements around it, halved level by level) until Richardson's estimate of its
discretisation error is within a tolerance, with the feature that carries it.

Load: by default the free spin (no contact), plane stress or strain, stress per unit
omega^2 [Pa / (rad/s)^2] (linear in omega^2 before the shoes touch the drum); any other
analysis is passed as ``evaluate(mesh) -> (peak, point)`` (``benchmarks/bench_peak.py``
converges analyze's 14 000 rpm contact peak that way).  On concepts 1 and 4 at their
defaults the peak sits on the same fillet at 4000 (free), 8000 and 14 000 rpm (measured
2026-11-26, fast and best presets).

Levels: level 0 is the given mesh; its peak point x0 and the size h0 = sqrt(2 A) of the
element there set the disc: centre x0, radius max(R, 4 h0) with R the outline's radius
of curvature at x0 (a fillet's stress gradient decays over ~R), size h0 / 2^k at level k
(growing to the global size over 4 global sizes outside it: ``MeshSettings.refine_*``).
The peak is taken over the whole mesh at every level (it may move).

Error (levels k-2, k-1, k of the refined family, ratio 2): d1 = v(k-1) - v(k-2), d2 = v(k)
- v(k-1).  Monotone (d1 / d2 > 1): observed order p = log2(d1 / d2), error of v(k) =
d2 / (2^min(p, 2) - 1) (Richardson; the order capped at P2's nominal order 2 of the vertex
stress, ASSUMED (section 12 measured 1.86-2.27): a faster observed decay is not trusted to
continue, so the estimate stays conservative).  Otherwise (oscillating, or not yet
asymptotic): error = max(|d1|, |d2|), p reported as NaN.  (A disc of radius R / 2 cost
2.5x fewer elements but oscillated by 0.1-0.6 % between levels on concepts 1 and 4; the
radius max(R, 4 h0) gave monotone sequences with observed orders 2.6-3.5, 2026-11-26.)
With two refined levels only: error = |d2|.  Stop when the error <= ``tol`` x the peak
(at least three refined levels), at ``max_levels``, or before a level would exceed
``max_elements`` (then ``converged`` is False).

The sequence must be of one feature: if a peak of the last three levels lies outside the
disc (another feature, unrefined, took over: concept 3, 17.35 against 17.38 MPa), the
result says so and is not ``converged``.

Feature: the outline's radius of curvature at the peak (a circle fitted to the five P2
nodes of the two outline edges at the peak vertex) and the zone (shoe / flexure / hub)
of the element; a radius below 0.25 x the drum radius is called a fillet.
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field

import numpy as np

from ..core import Material, ParameterError
from ..geometry import Concept, ConceptParams, MeshSettings
from ..mesh import ClutchMesh, mesh_concept
from .model import FEModel

#: the refined levels' curved elements below this scaled Jacobian are reshaped (module docstring)
RESHAPE_BELOW = 0.2
#: what the refinement converges: mesh -> (peak, (x, y) [m])
Evaluate = Callable[[ClutchMesh], tuple[float, tuple[float, float]]]


@dataclass(frozen=True)
class PeakLevel:
    """One refinement level: peak [Pa/(rad/s)^2], its point [m], elements, seconds."""

    peak: float
    at: tuple[float, float]
    elements: int
    refine_size: float
    time_s: float


@dataclass(frozen=True)
class PeakStress:
    """The converged free-spin peak von Mises (module docstring)."""

    peak: float
    """the peak at the finest level (free spin: von Mises per unit omega^2 [Pa / (rad/s)^2])"""
    at: tuple[float, float]
    """its point [m] (final frame)"""
    feature: str
    """the outline feature carrying it, e.g. 'fillet R 0.80 mm, shoe_0'"""
    radius: float
    """the outline's radius of curvature there [m] (inf: straight)"""
    error: float
    """estimated discretisation error of ``peak`` [Pa / (rad/s)^2] (>= 0)"""
    order: float
    """observed convergence order (NaN if not observable)"""
    converged: bool
    levels: list[PeakLevel] = field(default_factory=list)

    def at_rpm(self, rpm: float) -> float:
        """The peak [Pa] at ``rpm`` of free spin (for the default ``evaluate`` only)."""
        return self.peak * (rpm * math.pi / 30.0) ** 2

    def to_json(self) -> dict:
        return asdict(self)


def peak_stress_converged(concept: Concept, p: ConceptParams, ms: MeshSettings | None = None, *,
                          material: Material | None = None, evaluate: Evaluate | None = None, tol: float = 0.01,
                          max_levels: int = 4, max_elements: int = 60_000,
                          formulation: str = "plane-stress") -> PeakStress:
    """The peak von Mises of ``concept`` with ``p``, refined locally around it until its
    estimated discretisation error is <= ``tol`` of the peak (module docstring).

    Parameters
    ----------
    concept, p : Concept, ConceptParams
        The design.
    ms : MeshSettings, optional
        Level 0's mesh (default: the best preset); the refined levels add a disc to it.
    material : Material, optional
        For the default ``evaluate``: the free spin per unit omega^2 [Pa / (rad/s)^2].
    evaluate : callable, optional
        ``evaluate(cm) -> (peak, (x, y))``: the peak [any stress unit] and its point [m]
        of the analysis wanted on a mesh (e.g. a contact state at one speed, built by the
        caller; ``benchmarks/bench_peak.py``).
    tol : float
        Relative error at which to stop (default 1 %).
    max_levels, max_elements : int
        At most this many refined levels (>= 3), none above this many elements.
    formulation : {"plane-stress", "plane-strain"}
        Of the default ``evaluate``.

    Returns
    -------
    PeakStress
        The finest level's peak and point, the feature carrying it, its error estimate and
        observed order, ``converged`` (error <= tol), and every level.

    Examples
    --------
    >>> from clutchfem.core import get_material
    >>> from clutchfem.geometry import get_concept
    >>> c = get_concept("concept4")
    >>> r = peak_stress_converged(c, c.params(), material=get_material("51CrV4"))
    >>> r.feature, r.converged
    ('fillet R 0.80 mm, flexure_0', True)
    """
    if isinstance(tol, bool) or not isinstance(tol, (int, float)) or not (0 < tol < 1):
        raise ParameterError("tol", tol, "a relative error in (0, 1), e.g. 0.01")
    if isinstance(max_levels, bool) or not isinstance(max_levels, int) or max_levels < 3:
        raise ParameterError("max_levels", max_levels, "an integer >= 3 (three refined levels give the observed order)")
    if evaluate is None:
        if material is None:
            raise ParameterError("material", None, "a Material (or give evaluate=...)")
        evaluate = functools.partial(free_spin_peak, material=material, formulation=formulation)
    ms = ms or MeshSettings.preset("best")
    t0 = time.perf_counter()
    cm = mesh_concept(concept, p, ms)
    v, x = evaluate(cm)
    levels = [PeakLevel(v, x, cm.n_elements, 0.0, time.perf_counter() - t0)]
    disc, h0 = peak_disc(cm, x, p.drum_radius)
    err, order = math.inf, math.nan
    for k in range(1, max_levels + 1):
        s = h0 / 2 ** k
        if k > 1 and levels[-1].elements * 4 > max_elements:
            break
        t0 = time.perf_counter()
        cm = mesh_concept(concept, p, ms.replace(refine_x=x[0], refine_y=x[1], refine_radius=disc, refine_size=s,
                                                 reshape_below=RESHAPE_BELOW))
        vk, xk = evaluate(cm)
        levels.append(PeakLevel(vk, xk, cm.n_elements, s, time.perf_counter() - t0))
        if k >= 3:
            err, order = richardson([lv.peak for lv in levels[-3:]])
        elif k == 2:
            err = abs(levels[-1].peak - levels[-2].peak)
        if k >= 3 and err <= tol * abs(vk):
            break
    last = levels[-1]
    radius, where = _feature(cm, last.at, p.drum_radius)
    if math.isnan(radius):
        kind = "inside the part"
    elif radius < 0.25 * p.drum_radius:
        kind = f"fillet R {radius * 1e3:.2f} mm"
    else:
        kind = "straight edge" if math.isinf(radius) else f"arc R {radius * 1e3:.1f} mm"
    # the Richardson sequence is one feature's only if its peaks sit in the refined disc
    inside = all(math.hypot(lv.at[0] - x[0], lv.at[1] - x[1]) <= disc + h0 for lv in levels[-3:])
    if not inside:
        where += " (the peak left the refined disc: another feature, not converged)"
    return PeakStress(peak=last.peak, at=last.at, feature=f"{kind}, {where}", radius=radius, error=err, order=order,
                      converged=bool(err <= tol * abs(last.peak) and inside), levels=levels)


def peak_disc(cm: ClutchMesh, x: tuple[float, float], drum_radius: float) -> tuple[float, float]:
    """(radius [m], h0 [m]) of the disc that refines the peak at ``x`` (module docstring):
    h0 = sqrt(2 A) of the element there, radius max(R, 4 h0) with R the outline's radius of
    curvature at x (4 h0 where the outline is straight or x is inside the part)."""
    radius, _ = _feature(cm, x, drum_radius)
    h0 = math.sqrt(2.0 * _area_at(cm, x))
    return max(radius if math.isfinite(radius) else 0.0, 4.0 * h0), h0


def free_spin_peak(cm: ClutchMesh, material: Material, formulation: str = "plane-stress") -> tuple[float, tuple]:
    """(peak von Mises per unit omega^2 [Pa / (rad/s)^2], its point [m]) of the free spin
    (no contact, no softening) on ``cm``: raw P2 vertex stresses."""
    m = FEModel(cm, material, formulation=formulation)
    vm = m.von_mises(m.stress(m.u1))
    i = int(np.argmax(vm))
    x = m.stress.points[:, i]
    return float(vm[i]), (float(x[0]), float(x[1]))


def richardson(v: list[float], ratio: float = 2.0, p_max: float = 2.0) -> tuple[float, float]:
    """(error of v[-1], observed order) from three values at sizes h, h/ratio, h/ratio^2
    (module docstring: the order used capped at ``p_max``; order NaN and error the larger
    change when not monotone)."""
    d1, d2 = v[1] - v[0], v[2] - v[1]
    if d2 == 0.0:
        return 0.0, math.nan
    q = d1 / d2
    if q > 1.0:
        p = math.log(q) / math.log(ratio)
        return abs(d2) / (ratio ** min(p, p_max) - 1.0), p
    return max(abs(d1), abs(d2)), math.nan


def _element_at(cm: ClutchMesh, x: tuple[float, float]) -> tuple[int, int]:
    """(nearest vertex, an element having it) of the point ``x``."""
    v = int(np.argmin(np.hypot(cm.mesh.p[0] - x[0], cm.mesh.p[1] - x[1])))
    return v, int(np.nonzero(np.any(cm.mesh.t == v, axis=0))[0][0])


def _area_at(cm: ClutchMesh, x: tuple[float, float]) -> float:
    """The straight-sided area [m^2] of the element at ``x``."""
    a, b, c = cm.mesh.p[:, cm.mesh.t[:, _element_at(cm, x)[1]]].T
    return 0.5 * abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))


def _feature(cm: ClutchMesh, x: tuple[float, float], drum_radius: float) -> tuple[float, str]:
    """(outline radius of curvature at x [m]: inf straight, NaN not on the outline; zone
    name of the element there)."""
    mesh = cm.mesh
    v, e = _element_at(cm, x)
    zone = next((k for k, v in (mesh.subdomains or {}).items() if k != "solid" and e in set(np.asarray(v).tolist())),
                "solid")
    bf = mesh.boundary_facets()
    facets = bf[np.any(mesh.facets[:, bf] == v, axis=0)]
    if facets.size == 0:
        return math.nan, zone
    pts = np.concatenate([mesh.p[:, mesh.facets[:, facets].ravel()], mesh.doflocs[:, mesh.nvertices + facets]], axis=1)
    pts = np.unique(np.round(pts.T, 12), axis=0)
    if len(pts) < 3:
        return math.inf, zone
    # algebraic circle fit x^2 + y^2 + D x + E y + F = 0
    A = np.column_stack([pts[:, 0], pts[:, 1], np.ones(len(pts))])
    rhs = -(pts[:, 0] ** 2 + pts[:, 1] ** 2)
    (D, E, F), *_ = np.linalg.lstsq(A, rhs, rcond=None)
    r2 = D * D / 4 + E * E / 4 - F
    r = math.sqrt(r2) if r2 > 0 else math.inf
    return (r if r < 10 * drum_radius else math.inf), zone
