"""How each design of a batch is evaluated: :class:`EvalSettings` (everything but the point: the
concept, the base design's ``--set`` texts, the mesh, the operating point, the engine, the
requirement factors), the study engine's :class:`Settings` it makes (picklable: shipped to
the workers) and the tolerance box's corner check (:func:`box_corners`).

Apart from the batches that evaluate them (:mod:`.batch`): a reduced model's region
(:class:`clutchfem.reduced.Region`) holds one, and a live answer reads it without the FE.
"""

from __future__ import annotations

import hashlib
import itertools
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..clutch import EngineCurve
from ..core import InputError, ParameterError, changed_texts, exact_text
from ..geometry import MeshSettings, get_concept
from ..loadcase import Design, OperatingPoint
from .store import STORE_NAME

__all__ = ["EvalSettings", "Settings", "box_corners"]


@dataclass(frozen=True)
class Settings:
    """The fixed part of a study: what every point shares (picklable: shipped to workers).

    concept: concept name (or None with ``mesh_file``); fixed: concept parameters held fixed
    (name, value) pairs in the parameter's unit; op: the operating point (material, mu,
    rotation, softening, formulation, drum wall ...); mesh: mesh settings; engine: the
    full-throttle curve (None: the built-in ASSUMED 56.5 cc curve); idle_rpm: overrides the
    curve's idle speed; a, b: requirement factors; min_safety_factor: required yield safety
    factor at the engine's maximum speed; mesh_file / mesh_bytes: a user mesh (its content
    travels with the settings, so remote workers need no shared disk); morph: the reference
    design of morphed meshes (None: each design meshed from scratch).
    """

    concept: str | None
    fixed: tuple[tuple[str, Any], ...] = ()
    op: Any = None
    mesh: Any = None
    engine: Any = None
    idle_rpm: float | None = None
    a: float = 1.3
    b: float = 1.0
    min_safety_factor: float = 1.0
    mesh_file: str | None = None
    mesh_bytes: bytes | None = field(default=None, repr=False)
    #: morph every design's mesh from this reference design's ((name, value) pairs over the
    #: concept's defaults, :mod:`clutchfem.mesh.morph`), meshing from scratch only where the
    #: morph is refused; None: every design meshed from scratch
    morph: tuple[tuple[str, Any], ...] | None = None

    @property
    def design_name(self) -> str:
        return self.concept if self.concept else Path(self.mesh_file or "mesh").name

    def canonical(self) -> dict:
        """The defining fixed inputs as plain JSON data (for the design hash and the row)."""
        op = self.op if self.op is not None else OperatingPoint()
        ms = self.mesh if self.mesh is not None else MeshSettings.preset(op.fidelity)
        eng = None
        if self.engine is not None:
            eng = {"rpm": list(self.engine.rpm), "torque": list(self.engine.torque),
                   "idle_rpm": self.engine.idle_rpm}
        doc = {"concept": self.concept, "fixed": dict(self.fixed),
                "mesh_file_sha256": hashlib.sha256(self.mesh_bytes).hexdigest() if self.mesh_bytes else None,
                "op": op.model_dump(mode="json"), "mesh": ms.model_dump(mode="json"),
                "engine": eng, "idle_rpm": self.idle_rpm,
                "requirements": {"a": self.a, "b": self.b, "min_safety_factor": self.min_safety_factor}}
        if self.morph is not None:  # a morphed mesh is another discretisation of the design
            doc["morph_reference"] = dict(self.morph)
        return doc


@dataclass(frozen=True)
class EvalSettings:
    """Everything but the point: the concept, the base design's ``--set`` texts, the mesh
    size, the operating point overrides, the engine and the requirement factors; ``store``:
    the study store file (None: a temporary one per batch); ``min_safety_factor`` enters the
    study rows' own feasibility flag (and their design hash).  Usually made from a design
    (:meth:`from_design`); optimisation, tolerances and sensitivities take it in place of one.

    Parameters
    ----------
    concept : str
    base : tuple of str
        The base design's ``name=value`` texts (``"flexure_thickness=2.4mm"``).
    mesh_size : float, optional
        Global element size [m] (default: the fidelity's).
    op : dict
        Operating point fields that differ from :class:`~clutchfem.OperatingPoint`'s defaults.
    engine_csv, curve : optional
        The engine curve (a CSV path, or an :class:`~clutchfem.EngineCurve`; default built-in).
    idle_rpm : float, optional
    a, b, min_safety_factor : float
        Requirement factors and the rows' yield safety factor.
    store : str, optional

    Examples
    --------
    >>> import clutchfem as cf
    >>> es = cf.EvalSettings("concept1", base=("flexure_thickness=2.4mm",), mesh_size=0.003)
    >>> es.values({"clearance": "0.5mm"}), es.set_args({"clearance": "0.5mm"})
    ({'flexure_thickness': 0.0024, 'clearance': 0.0005}, ['flexure_thickness=2.4mm', 'clearance=0.5mm'])
    >>> es.params().flexure_thickness, es.mesh_settings().size
    (0.0024, 0.003)
    """

    concept: str
    base: tuple[str, ...] = ()
    mesh_size: float | None = None
    op: dict = field(default_factory=dict)
    engine_csv: str | None = None
    idle_rpm: float | None = None
    a: float = 1.3
    b: float = 1.0
    min_safety_factor: float = 1.5
    store: str | None = None
    #: an engine curve given as an object (the API); wins over ``engine_csv``
    curve: EngineCurve | None = None
    #: morph the designs' meshes from this reference design ((name, SI value) pairs,
    #: :attr:`clutchfem.evaluation.Settings.morph`); None: mesh every design from scratch
    morph: tuple | None = None
    #: the mesh settings as an object (the API; a guideline study's): wins over ``mesh_size``
    mesh: MeshSettings | None = None
    #: ((name, half-width SI), ...): a design is admitted only if the concept's rules also
    #: hold at every corner of this tolerance box around it (robust design: every part a
    #: drawing's tolerances allow can be built, :func:`.robust.robust_optimize`)
    tolerance_box: tuple | None = None

    @classmethod
    def from_design(cls, design, *, engine=None, idle_rpm: float | None = None, requirements=None,
                    min_safety_factor: float = 1.5, store: str | None = None,
                    out: str | Path | None = None) -> "EvalSettings":
        """The settings whose base design is ``design`` (a concept's :class:`~clutchfem.Design`:
        its parameters as exact ``--set`` texts, its operating point and mesh size), with the
        engine (an :class:`~clutchfem.EngineCurve` or the path of its CSV; default: the
        built-in curve), the idle speed and the requirement factors of ``requirements``
        (default: a = 1.3, b = 1.0); the store: ``store``, or ``out/results.sqlite`` in a run's
        output folder ``out`` (None: a temporary store per batch)."""
        if store is None and out is not None:
            store = str(Path(out) / STORE_NAME)
        if not isinstance(design, Design):
            raise InputError(f"a design study needs a clutchfem Design (Design.from_concept), not "
                             f"{type(design).__name__}")
        if design.params is None:
            raise InputError(f"{design.name}: a user mesh has no concept parameters to vary; studies, optimisation "
                             "and tolerances work on a concept's design (Design.from_concept)")
        P = type(design.params)
        base = tuple(f"{k}={v}" for k, v in changed_texts(design.params).items())
        op0 = OperatingPoint()
        op = {k: getattr(design.op, k) for k in OperatingPoint.model_fields
              if getattr(design.op, k) != getattr(op0, k) and k not in ("rpm",)}
        if "material" in op:
            op["material"] = op["material"].model_dump()
        if design.op.fidelity == "live":  # its designs are evaluated by the FE it stands for: the best path
            op["fidelity"] = "best"
            if op0.fidelity == "best":
                del op["fidelity"]
        size = design.mesh_settings.size
        size = None if size is None or size == MeshSettings.preset(design.op.fidelity).size else float(size)
        req_a = getattr(requirements, "a", 1.3)
        req_b = getattr(requirements, "b", 1.0)
        P(**P.parse_assignments(list(base)))  # the texts read back as this design
        csv = str(engine) if isinstance(engine, (str, Path)) else None
        curve = engine if isinstance(engine, EngineCurve) else None
        return cls(concept=design.name, base=base, mesh_size=size, op=op, engine_csv=csv, idle_rpm=idle_rpm, a=req_a,
                   b=req_b, min_safety_factor=min_safety_factor, store=store, curve=curve)

    def params(self, point: dict | None = None):
        """The concept's parameter set for ``point`` on the base (raises ParameterError)."""
        P = get_concept(self.concept).Params
        vals = self.values(point)
        p = P(**vals)
        if self.tolerance_box:
            box_corners(P, dict(vals, **{n: getattr(p, n) for n, _ in self.tolerance_box}), self.tolerance_box)
        return p

    def values(self, point: dict | None = None) -> dict:
        """Parameter values (SI) of the base plus the point, as the parser reads the texts."""
        P = get_concept(self.concept).Params
        values = P.parse_assignments(list(self.base))
        if point:
            values.update(P.parse_assignments([f"{k}={v}" for k, v in point.items()]))
        return values

    def engine(self):
        if self.curve is not None:
            return self.curve
        return EngineCurve.from_csv(self.engine_csv, idle_rpm=self.idle_rpm) if self.engine_csv \
            else EngineCurve.default()

    def operating_point(self):
        return OperatingPoint(**self.op)

    def mesh_settings(self):
        """``mesh`` if given, else the fidelity's mesh (:meth:`MeshSettings.preset`), with
        ``mesh_size`` if given."""
        if self.mesh is not None:
            return self.mesh
        return MeshSettings.preset(self.operating_point().fidelity,
                                   **({} if self.mesh_size is None else {"size": self.mesh_size}))

    def set_args(self, point: dict | None = None) -> list[str]:
        """The ``--set`` arguments of the base plus the point (the point wins)."""
        names = set(point or {})
        out = [a for a in self.base if a.split("=", 1)[0].strip() not in names]
        return out + [f"{k}={v}" for k, v in (point or {}).items()]

    def study(self):
        """The study engine's :class:`clutchfem.evaluation.Settings` (the base as fixed values)."""
        fixed = tuple(sorted(self.values().items()))
        return Settings(concept=self.concept, fixed=fixed, op=self.operating_point(), mesh=self.mesh_settings(),
                        engine=self.engine() if (self.engine_csv or self.curve is not None) else None, idle_rpm=self.idle_rpm, a=self.a,
                        b=self.b, min_safety_factor=self.min_safety_factor, morph=self.morph)


def box_corners(P, values: dict, box) -> None:
    """Raise the concept's ParameterError, prefixed by the corner, where its rules refuse a
    corner of the tolerance ``box`` ((name, half-width), ...) around ``values`` (SI): for a
    rule linear in the toleranced dimensions the box is admissible iff its corners are."""
    for signs in itertools.product((1.0, -1.0), repeat=len(box)):
        corner = dict(values)
        for (n, t), sg in zip(box, signs):
            corner[n] = values[n] + sg * t
        try:
            P(**corner)
        except ParameterError as exc:
            at = ", ".join(f"{n} {'+' if sg > 0 else '-'}{exact_text(P, n, t)}" for (n, t), sg in zip(box, signs))
            raise ParameterError(exc.name, exc.value, f"{exc.allowed} -- at the tolerance corner {at}: a part "
                                 "within the drawing's tolerances could not be built", exc.context,
                                 shown=exc.shown) from None
