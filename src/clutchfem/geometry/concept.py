"""What a concept is: the contract a concept file in ``geometries/`` fulfils.

A concept file defines a :class:`Concept` subclass with a parameter class (a
:class:`ConceptParams` subclass) and a :meth:`Concept.build` that draws the full one-piece
part with gmsh-OCC in the *canonical frame* and returns its :class:`Shapes`:

* the rotation axis is z through the origin, the part lies in z = 0, lengths in metres;
* shoe ``i`` is shoe 0 rotated by ``i * 360/n`` degrees;
* shoe 0 is joined to the hub at its *root* end (the flexure) at the smaller polar angle
  and extends counter-clockwise to its free *tip*.  With the hub turning ccw against a held
  drum, friction drags each shoe towards its root (the hub pushes the shoe from behind):
  the canonical frame is the **plus** (self-energizing) arrangement.  The **minus**
  arrangement, the default, is its mirror image (y -> -y), done by the generic pipeline
  (:mod:`.build`), not in the concepts.

Also here: the parameters every concept shares (:class:`ConceptParams`: drum, clearance and
the shoe's outer profile, thickness, bore, arrangement, fillets), the mesh controls
(:class:`MeshSettings`) and the drawing callouts (:class:`Annotation`).  Everything else is
generic and lives in :mod:`.build`: mirroring, the one-sector cut, zones, boundary tags,
size fields and mass properties.
"""

from __future__ import annotations

import contextvars
import math
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import ClassVar, Literal

import numpy as np
from pydantic import model_serializer

from ..core import ParameterError, ParamSet, choice, param
from .profile import MIN_PROFILE_CLEARANCE, TABLE_FIELDS, TABLE_N, table_param, table_spline

#: the new part whose worn shoe face a ``table`` profile is (:func:`worn_from`), or None
_AS_DESIGNED: contextvars.ContextVar = contextvars.ContextVar("clutchfem_as_designed", default=None)
#: the fields that only shape the shoe's outer (rubbing) surface: the ones wear may change
_PROFILE_FIELDS = frozenset(("profile", "clearance_tip", "eccentricity", "eccentric_angle", *TABLE_FIELDS))


@contextmanager
def worn_from(new: "ConceptParams") -> Iterator[None]:
    """Inside this block a ``table`` profile that differs from the new part ``new`` only in
    its outer (rubbing) surface is *the worn face of that part*: the concept's design rules
    and inner geometry that read the shoe's outer surface
    (:meth:`ConceptParams.designed_outer_radius`) read ``new``'s, the surface the part was
    made with.  Wear removes material from the face; the flexures, heels and rounds stay
    where they were cut, so a design rule that places them against the outer surface (e.g.
    concept 4's beam end below the shoe's mid-depth) must not move with the wear.

    Parameters
    ----------
    new : ConceptParams
        The part as made (as designed).

    Examples
    --------
    >>> from clutchfem.geometry import get_concept, TABLE_FIELDS
    >>> P = get_concept("concept4").Params
    >>> new = P()
    >>> worn = {n: new.clearance + 50e-6 for n in TABLE_FIELDS}     # 50 um off the face
    >>> with worn_from(new):
    ...     p = new.replace(profile="table", **worn)
    ...     r = float(p.designed_outer_radius([0.0], 0.0, 1.0)[0])
    >>> round(r * 1e3, 4), round(float(p.outer_radius([0.0], 0.0, 1.0)[0]) * 1e3, 4)
    (33.8, 33.75)
    """
    if not isinstance(new, ConceptParams):
        raise ParameterError("new", type(new).__name__, "the ConceptParams of the part as made", "worn part")
    token = _AS_DESIGNED.set(new)
    try:
        yield
    finally:
        _AS_DESIGNED.reset(token)


class ConceptParams(ParamSet):
    """Parameters common to every one-piece concept (defaults: the 60 cc saw of the thesis)."""

    n_shoes: int = param(3, "-", 2, 6, "number of shoes", "n")
    drum_radius: float = param(34.4e-3, "m", 15e-3, 100e-3, "drum inner radius R_d", "R_d")
    clearance: float = param(0.6e-3, "m", 0.05e-3, 3e-3,
                             "radial shoe-drum clearance at rest (at the root end for a linear profile)", "c")
    profile: Literal["concentric", "eccentric", "linear", "table"] = choice(
        "concentric", "shoe outer profile (morphological row D); 'table': clearances table_c0..table_c16 "
                      "along the shoe, joined by a cubic spline")
    clearance_tip: float = param(0.6e-3, "m", 0.05e-3, 3e-3,
                                 "clearance at the shoe tip (linear profile only)", "c_tip")
    eccentricity: float = param(0.0, "m", -3e-3, 3e-3,
                                "offset of the eccentric profile's centre (eccentric profile only)", "e")
    eccentric_angle: float = param(0.0, "deg", -180.0, 180.0,
                                   "direction of the eccentric offset from the shoe's mid-angle (towards the tip > 0)", "psi_e")
    thickness: float = param(11e-3, "m", 2e-3, 40e-3, "axial thickness of the part (assumed ~10-12 mm)", "h")
    bore_radius: float = param(6.5e-3, "m", 2e-3, 20e-3, "crankshaft bore radius (assumed)", "r_b")
    arrangement: Literal["minus", "plus"] = choice(
        "minus", "flexure placement for ccw rotation: minus = shoe trails its flexure")
    fillet_radius: float = param(0.5e-3, "m", 0.0, 5e-3, "fillet radius at slot ends / flexure roots", "rho")
    table_c0: float = table_param(0)
    table_c1: float = table_param(1)
    table_c2: float = table_param(2)
    table_c3: float = table_param(3)
    table_c4: float = table_param(4)
    table_c5: float = table_param(5)
    table_c6: float = table_param(6)
    table_c7: float = table_param(7)
    table_c8: float = table_param(8)
    table_c9: float = table_param(9)
    table_c10: float = table_param(10)
    table_c11: float = table_param(11)
    table_c12: float = table_param(12)
    table_c13: float = table_param(13)
    table_c14: float = table_param(14)
    table_c15: float = table_param(15)
    table_c16: float = table_param(16)

    @model_serializer(mode="wrap")
    def _dump_without_inert_table(self, handler):
        """The table profile's control values are inert for every other profile and are then
        left out of the dump: the mesh cache key, the design hash and every recorded input of
        a concentric / eccentric / linear design stay what they were before the table profile
        existed."""
        d = handler(self)
        if self.profile != "table":
            for name in TABLE_FIELDS:
                d.pop(name, None)
        return d

    def inactive(self) -> tuple[str, ...]:
        """Parameters that have no effect on this design: the controls of the profiles it does
        not use (``clearance_tip`` unless linear, ``eccentricity`` and ``eccentric_angle`` unless
        eccentric, ``table_c0`` .. ``table_c16`` unless table).  Studies leave them out."""
        out = []
        if self.profile != "linear":
            out.append("clearance_tip")
        if self.profile != "eccentric":
            out += ["eccentricity", "eccentric_angle"]
        if self.profile != "table":
            out += list(TABLE_FIELDS)
        return tuple(n for n in out if n in type(self).model_fields)

    # ---- profile of the shoe outer surface (canonical frame, shoe 0) ----------------------
    def outer_radius(self, theta: np.ndarray, t0: float, t1: float) -> np.ndarray:
        """Radius of the shoe's outer surface at polar angle ``theta`` (rad), for a shoe
        spanning [t0 (root), t1 (tip)] in the canonical frame."""
        theta = np.asarray(theta, dtype=float)
        Rd = self.drum_radius
        if self.profile == "table":
            return Rd - self.table_clearance((theta - t0) / (t1 - t0))
        if self.profile == "concentric":
            return np.full_like(theta, Rd - self.clearance)
        if self.profile == "linear":
            s = (theta - t0) / (t1 - t0)
            return Rd - (self.clearance + (self.clearance_tip - self.clearance) * s)
        cx, cy, rho_e = self.eccentric_circle(t0, t1)
        # intersect the ray at theta with the circle |x - c| = rho_e
        ux, uy = np.cos(theta), np.sin(theta)
        b = ux * cx + uy * cy
        return b + np.sqrt(rho_e ** 2 - (cx * cx + cy * cy) + b * b)

    def designed_outer_radius(self, theta, t0: float, t1: float) -> np.ndarray:
        """Radius of the shoe's outer surface *as designed* (:meth:`outer_radius` of the part as
        made): inside :func:`worn_from` a ``table`` profile that is the worn face of that part
        reads the new part's surface; otherwise this design's own.  Design rules and the inner
        geometry placed against the outer surface use this (wear does not move them)."""
        new = _AS_DESIGNED.get()
        if new is not None and self.is_worn_face_of(new):
            return new.outer_radius(theta, t0, t1)
        return self.outer_radius(theta, t0, t1)

    def is_worn_face_of(self, new: "ConceptParams") -> bool:
        """True when this design is ``new`` with only its outer surface changed to a ``table``
        profile (every other parameter equal)."""
        if type(new) is not type(self) or self.profile != "table":
            return False
        return all(getattr(self, n) == getattr(new, n) for n in type(self).model_fields if n not in _PROFILE_FIELDS)

    @property
    def table(self) -> tuple[float, ...]:
        """The table profile's control clearances [m], root to tip."""
        return tuple(float(getattr(self, n)) for n in TABLE_FIELDS)

    def table_clearance(self, s) -> np.ndarray:
        """Clearance [m] of the table profile at arc fraction ``s`` (0 root, 1 tip)."""
        return table_spline(self.table)(np.asarray(s, dtype=float))

    def eccentric_circle(self, t0: float, t1: float) -> tuple[float, float, float]:
        """Centre (x, y) and radius of the eccentric profile: offset ``eccentricity`` in the
        direction (mid-angle + eccentric_angle), radius chosen so that the clearance at the
        shoe's mid-angle equals ``clearance``."""
        tm = 0.5 * (t0 + t1)
        a = tm + math.radians(self.eccentric_angle)
        cx, cy = self.eccentricity * math.cos(a), self.eccentricity * math.sin(a)
        r_mid = self.drum_radius - self.clearance
        px, py = r_mid * math.cos(tm), r_mid * math.sin(tm)
        return cx, cy, math.hypot(px - cx, py - cy)

    def eccentric_centre(self, t0: float, t1: float, a: float = 0.0) -> np.ndarray | None:
        """Centre (x, y) of the eccentric profile of a shoe spanning [t0, t1], rotated by
        ``a`` (rad) about the origin; None unless the profile is eccentric."""
        if self.profile != "eccentric":
            return None
        cx, cy, _ = self.eccentric_circle(t0, t1)
        c, s = math.cos(a), math.sin(a)
        return np.array([c * cx - s * cy, s * cx + c * cy])

    def flexure_thicknesses(self) -> list[float]:
        """Thicknesses [m] of the concept's flexures (every ``flexure*thickness`` parameter by
        default; concepts with tapered or derived flexures override this).  The mesh is
        refined in the flexure zones to ``flexure_factor`` x the thinnest of them."""
        return [float(getattr(self, n)) for n in type(self).model_fields
                if n.startswith("flexure") and n.endswith("thickness")]

    def min_clearance(self, t0: float, t1: float) -> float:
        th = np.linspace(t0, t1, 201 if self.profile != "table" else 801)
        return float(np.min(self.drum_radius - self.outer_radius(th, t0, t1)))

    def check_profile(self, t0: float, t1: float) -> None:
        """Raise if the shoe profile touches or crosses the drum anywhere (the table profile's
        spline is sampled at 801 points: it may dip below its control values between them)."""
        if self.profile == "eccentric":
            cx, cy, rho = self.eccentric_circle(t0, t1)
            if rho <= math.hypot(cx, cy):
                self.fail("eccentricity", "|e| smaller than the profile radius")
        if self.profile == "table":
            s = np.linspace(0.0, 1.0, 801)
            c = self.table_clearance(s)
            k = int(np.argmin(c))
            if c[k] <= MIN_PROFILE_CLEARANCE:
                near = TABLE_FIELDS[int(round(s[k] * (TABLE_N - 1)))]
                self.fail(near, f"a table whose spline keeps a clearance > {MIN_PROFILE_CLEARANCE * 1e3:.2f} mm "
                                f"everywhere (it dips to {c[k] * 1e3:.3f} mm at {s[k]:.3f} of the shoe arc from "
                                "the root, next to this control value: raise it or smooth its neighbours)")
            return
        cmin = self.min_clearance(t0, t1)
        if cmin <= MIN_PROFILE_CLEARANCE:
            name = {"linear": "clearance_tip", "eccentric": "eccentricity"}.get(self.profile, "clearance")
            self.fail(name, f"a profile whose clearance stays > 0.02 mm everywhere (minimum here "
                            f"{cmin * 1e3:.3f} mm)")

    @property
    def sector_angle(self) -> float:
        """Angle of one sector (rad)."""
        return 2 * math.pi / self.n_shoes

    @classmethod
    def rule_dimensions(cls, v: dict) -> dict:
        """Derived dimensions that the concept's rules bound and that its answers depend on
        steeply near the bound (a hub post that becomes thin, a ligament that vanishes):
        name -> value [m], vectorised (``v``: parameter name -> SI value or numpy array of
        them, in the parameters' declared units).  The reduced model takes each as one more
        coordinate (:class:`~clutchfem.reduced.ReducedModel`), so that an answer that turns
        sharply as the rule's bound nears is smooth in it.  None by default."""
        return {}


#: the mesh of each fidelity (:meth:`MeshSettings.preset`): ``fast`` is today's uniform 2-D mesh;
#: ``best`` puts the elements where the answers are decided (flexures, fillets, the contact
#: surface) and keeps the rest coarse, so that the thick plane model costs what the fast
#: path's plane-stress model does (BENCHMARKS.md, best-estimate section)
#: the best preset reshapes curved elements below scaled Jacobian 0.2 (the fast one only below
#: 0.05, its mesh pinned by tests/test_core_reference.py): the thick plane model read 1427 MPa
#: at a cusp sliver (0.1-0.14) of concept 1 design lhs03's refined mesh where its fillet peak
#: is 1077 MPa; engagement and torque move by ~1e-6 (BENCHMARKS.md section 13)
MESH_PRESETS = {"fast": {}, "best": {"size": 6e-3, "contact_factor": 0.25, "flexure_factor": 0.5,
                                     "fillet_factor": 0.25, "reshape_below": 0.2}}
MESH_PRESETS["live"] = MESH_PRESETS["best"]  # the reduced model's FE (fallback, fields) is the best path's


class MeshSettings(ParamSet):
    """Mesh controls: one global size knob plus optional local factors.

    Parameters
    ----------
    size : float or str
        Global element size (default 1.2 mm, the fast mesh; the best-estimate path uses
        :meth:`preset` ``("best")``; ``"0.8mm"``).
    flexure_factor, contact_factor, fillet_factor : float
        Local sizes: in flexures as a fraction of their thickness, on contact surfaces and on
        small arcs (fillets) relative to the global size / the arc radius.
    refine_radius, refine_x, refine_y, refine_size : float
        A disc of radius ``refine_radius`` around (``refine_x``, ``refine_y``) meshed at
        ``refine_size`` (0: none): the local refinement of a stress peak
        (:func:`clutchfem.fe.peak_stress_converged` sets it).
    reshape_below : float
        Curved elements below this scaled Jacobian get their interior mid-side nodes
        reshaped after meshing (:func:`clutchfem.mesh.guard_high_order`); below 0.05 an
        element is repaired or refused whatever this says.
    order : int
        Element order (2: curved P2 triangles).
    model : {"sector", "full"}
        One cyclic sector of identical shoes, or the full 360 degree part.

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.MeshSettings(size="0.8mm").size
    0.0008
    """

    context: ClassVar[str] = "mesh settings"
    size: float = param(1.2e-3, "m", 0.05e-3, 10e-3, "global target element size", "h_mesh")
    flexure_factor: float = param(0.4, "-", 0.05, 2.0,
                                  "element size in flexures as a fraction of the flexure thickness")
    contact_factor: float = param(0.5, "-", 0.05, 2.0, "element size on contact surfaces / global size")
    fillet_factor: float = param(0.5, "-", 0.05, 2.0, "element size on small arcs (fillets) / arc radius")
    fillet_reach: float = param(0.0, "-", 0.0, 5.0, "distance from a fillet within which its size holds / its radius "
                                "(0: on the arc only, then growing to the global size)")
    refine_radius: float = param(0.0, "m", 0.0, 0.05, "radius of a disc refined to refine_size around "
                                 "(refine_x, refine_y) (0: none; the peak-stress refinement sets it)")
    refine_x: float = param(0.0, "m", -0.5, 0.5, "centre of the refined disc, x (final frame)")
    refine_y: float = param(0.0, "m", -0.5, 0.5, "centre of the refined disc, y (final frame)")
    refine_size: float = param(1e-4, "m", 1e-6, 10e-3, "element size inside the refined disc, growing to the "
                               "global size over 4 global sizes outside it")
    reshape_below: float = param(0.05, "-", 0.05, 0.5, "curved elements below this scaled Jacobian get their "
                                 "interior mid-side nodes reshaped (clutchfem.mesh.guard_high_order; 0.05 keeps the "
                                 "presets' meshes as they were, the peak-stress refinement uses 0.2)")
    order: int = param(2, "-", 1, 2, "element order (2: curved P2 triangles)")
    model: Literal["sector", "full"] = choice("sector", "one cyclic sector or the full 360 degree part")

    @classmethod
    def preset(cls, fidelity: str = "fast", **changes) -> "MeshSettings":
        """The mesh of an analysis fidelity (:data:`MESH_PRESETS`): ``"best"`` (flexures,
        fillets and the contact surface refined, 6 mm elsewhere) or ``"fast"`` (the uniform
        1.2 mm mesh); ``changes`` override single settings (``size=...``, ``model=...``)."""
        if fidelity not in MESH_PRESETS:
            raise ParameterError("fidelity", fidelity, "one of " + ", ".join(repr(k) for k in MESH_PRESETS),
                                 cls.context)
        return cls(**{**MESH_PRESETS[fidelity], **changes})


@dataclass
class Shapes:
    """What :meth:`Concept.build` returns (all in the canonical frame, full 360 degrees)."""

    material: list[int]
    """surface tags of the whole one-piece part, without the bore (cut by the framework)"""
    shoe_zones: list[int]
    """one surface per shoe covering (at least) that shoe's body; used to partition"""
    flexure_zones: list[int] = field(default_factory=list)
    """one surface per shoe covering its flexure(s) (may be empty)"""
    sector_start: float = 0.0
    """polar angle (rad) of a radial line that crosses only hub material (sector cut)"""


@dataclass
class Annotation:
    """A labelled dimension/callout on the concept drawing (canonical frame, metres)."""

    text: str
    at: tuple[float, float]
    to: tuple[float, float] | None = None


class Concept:
    """Base class of a parametric concept (subclass it in ``geometries/<name>.py``)."""

    name: ClassVar[str] = ""
    title: ClassVar[str] = ""
    thesis: ClassVar[str] = ""
    """what the thesis says of the concept (for docs and `--list-params`)"""
    parametrisation: ClassVar[str] = ""
    """how the text description was turned into parameters"""
    Params: ClassVar[type[ConceptParams]] = ConceptParams

    def build(self, p: ConceptParams) -> Shapes:  # pragma: no cover - abstract
        raise NotImplementedError

    def shoe_arc(self, p: ConceptParams) -> tuple[float, float]:
        """(root, tip) polar angles (rad) of shoe 0's contact surface, canonical frame."""
        raise NotImplementedError

    def pivot(self, p: ConceptParams) -> tuple[float, float]:
        """Nominal pivot point of shoe 0 (canonical frame): the flexure's compliant centre."""
        raise NotImplementedError

    def annotations(self, p: ConceptParams) -> list[Annotation]:
        return []

    def params(self, **values) -> ConceptParams:
        return self.Params(**values)


def default_free(P) -> list[str]:
    """The concept's own real-valued parameters (those its parameter class adds to the
    common ones: the shape of hub, flexure and shoe), the fillet radius and the shoe-drum
    clearance.  The axial thickness (the envelope: ~10-12 mm, ASSUMED), the drum, the bore,
    the profile and the number of shoes are kept unless freed with ``--free``.

    Why the clearance is free: after contact the flexure's stress at the engine's maximum
    speed grows with the deflection it took to close the gap, so the clearance is the
    strongest lever on the safety factor; on concept 4 the shape parameters alone reached a
    safety factor of 1.14 at best (300 analysed designs) against the 1.5 asked, with the clearance free
    the targets are met (docs/design_to_targets.md)."""
    common = set(ConceptParams.model_fields)
    own = [n for n, f in P.model_fields.items() if n not in common and f.annotation is float]
    for extra in ("fillet_radius", "clearance"):
        if extra in P.model_fields and extra not in own:
            own.append(extra)
    return own
