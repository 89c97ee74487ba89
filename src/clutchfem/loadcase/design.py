"""One design -> one FE model -> several load cases.

A :class:`Design` is a meshed part (a concept with its parameters, or a user mesh) at an
:class:`~clutchfem.loadcase.OperatingPoint`.  It builds the FE model (K, f1, constraints,
one factorisation) and the contact nodes once, and hands out load cases by (mu, spin
softening) that all share them: a sweep, friction off, mu +-30 %, a tolerance sample's
other speeds never re-assemble or re-factorise.  A sweep point, an optimiser step and a
Monte Carlo sample are each one ``Design``.

A concept's design is meshed, and its FE model built, when an answer first needs them: the
mesh, the FE model, the contact and the load cases are imported there, so a design answered
live (by the reduced model, :mod:`clutchfem.reduced`) loads none of the FE stack.
"""

from __future__ import annotations

import copy
import math
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..core import ParameterError, UnitError, as_bool, as_path, parse_quantity
from ..geometry import Concept, MeshSettings, get_concept
from .identity import DesignIdentity, design_identity
from .operating import OperatingPoint
from .record import design_hash, design_inputs, design_label

if TYPE_CHECKING:
    from ..contact import DrumContact
    from ..fe import Solver
    from ..mesh import ClutchMesh
    from .case import LoadCase

#: axial thickness of a user mesh when none is given [m] (ASSUMED: the thesis's 10-12 mm)
USER_THICKNESS = 11e-3
#: a user mesh's drum radius may exceed the contact surface's outer radius by at most this
#: factor (a units check: a gap of half the part's radius cannot close elastically)
DRUM_GAP_LIMIT = 1.5



def split_values(concept, values: dict) -> tuple[dict, dict]:
    """(geometry, operating) of keyword values: each name is a parameter of ``concept`` or
    of :class:`OperatingPoint`; any other name is refused, listing both."""
    geometry, op_values = {}, {}
    for name, value in values.items():
        if name in concept.Params.model_fields:
            geometry[name] = value
        elif name in OperatingPoint.model_fields:
            op_values[name] = value
        else:
            raise ParameterError(name, value, "a parameter of the concept (" + ", ".join(concept.Params.model_fields)
                                 + ") or of the operating point (" + ", ".join(
                                     n for n in OperatingPoint.model_fields if n not in ("drum_radius", "thickness"))
                                 + ")", concept.name)
    return geometry, op_values


class Design:
    """A meshed design at an operating point (see module docstring): one FE model and
    factorisation, any number of load cases.  Made with :meth:`from_concept` or
    :meth:`from_mesh`.

    Parameters
    ----------
    cm : ClutchMesh
        The meshed part.
    op : OperatingPoint, optional
        The operating point (drum radius and thickness default to the concept's, i.e.
        ``params``).
    params : ConceptParams, optional
        The concept's parameter set, or None for a user mesh.
    solver : str or callable, optional
        The sparse solver back-end (name or factory), injected into the FE model.
    name, concept : optional
        The design's name and its concept (None for a user mesh).

    Attributes
    ----------
    model : FEModel
        K, f1, constraints, one factorisation.
    drum_radius, thickness : float
        [m].

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> r = d.sweep("0:14000:7000")                 # a speed sweep: cf.SweepResult
    >>> list(r.curve["rpm"]), r.engagement_rpm > 3000
    ([0.0, 7000.0, 14000.0], True)
    >>> r0 = d.sweep("8000", mu=0.0)                # another load case, same factorisation
    >>> float(r0.curve["torque_Nm"].iloc[0])
    0.0
    """

    def __init__(self, cm: ClutchMesh | None, op: OperatingPoint | None = None, *, params=None,
                 solver: Solver = None, name: str = "", concept=None, mesh_settings: MeshSettings | None = None):
        op = op if op is not None else OperatingPoint()
        if not isinstance(op, OperatingPoint):
            raise ParameterError("op", type(op).__name__, "an OperatingPoint")
        if cm is None:  # a concept's design, meshed on first use (:attr:`cm`)
            if concept is None or params is None:
                raise ParameterError("cm", None, "a ClutchMesh, or a concept with its params (meshed on first use)")
        else:
            from ..mesh import ClutchMesh  # (a mesh given: the FE stack is wanted)

            if not isinstance(cm, ClutchMesh):
                raise ParameterError("cm", type(cm).__name__, "a ClutchMesh (from clutchfem.mesh.mesh_concept "
                                     "or load_user_geometry)")
            self.__dict__["cm"] = cm
        self.op = op
        self.params = params
        #: the concept (geometry plug-in) of a concept design, None for a user mesh
        self.concept = concept
        self.name = name or (cm.source if cm is not None else concept.name)
        self._solver = solver
        self._mesh_settings = mesh_settings if mesh_settings is not None else MeshSettings.preset(op.fidelity)
        self.drum_radius = _first(op.drum_radius, getattr(params, "drum_radius", None),
                                  None if cm is None else cm.drum_radius)
        self.thickness = _first(op.thickness, getattr(params, "thickness", None), None if cm is None else cm.thickness)
        if self.thickness is None:
            raise ParameterError("thickness", None, "the axial thickness in m (a user mesh carries none; "
                                 "e.g. 0.011 for 11 mm)")
        if params is None and self.drum_radius is not None:
            self._check_user_drum()
        self._cases: dict = {}
        if cm is not None:
            self.model  # a mesh given: its FE model at once (assembled once, every load case shares it)

    @cached_property
    def cm(self) -> ClutchMesh:
        """The meshed part.  A concept's design is meshed when an answer first needs it (a live
        answer from the reduced model needs none: :mod:`clutchfem.reduced`)."""
        from ..mesh import mesh_concept

        return mesh_concept(self.concept, self.params, self._mesh_settings)

    @property
    def mesh_settings(self) -> MeshSettings:
        """The mesh settings a concept's design is (or will be) meshed with."""
        return self._mesh_settings

    @property
    def meshed(self) -> bool:
        """Whether the design has its mesh yet."""
        return "cm" in self.__dict__

    @cached_property
    def model(self):
        """The FE model of the operating point's formulation (K, f1, constraints, one
        factorisation), built on first use."""
        from ..fe import ExtrusionSettings, FEModel, FEModel3D, FEModelThick, ThickSettings, check_3d_size

        op, cm = self.op, self.cm
        form = op.model_formulation
        if form == "thick":
            return FEModelThick(cm, op.material, self.thickness, settings=ThickSettings(order=op.thick_order),
                                solver=self._solver)
        if form == "3d":
            check_3d_size(cm, op.layers)  # before any 3-D array is made
            return FEModel3D(cm, op.material, self.thickness, settings=ExtrusionSettings(layers=op.layers),
                             solver=self._solver)
        return FEModel(cm, op.material, self.thickness, formulation=form, solver=self._solver)

    @classmethod
    def from_concept(cls, concept, params=None, operating: OperatingPoint | None = None, mesh=None, *,
                     solver: Solver = None, **values) -> "Design":
        """Mesh a concept and build its design (FE model, contact nodes; load cases on demand).

        Parameters
        ----------
        concept : str or Concept
            The concept's name (:func:`clutchfem.concepts` lists them) or the concept itself.
        params : ConceptParams, optional
            A full parameter set of the concept (default: its defaults); ``values`` change it.
        operating : OperatingPoint, optional
            The operating point (friction, rotation, material, model choices); default:
            :class:`OperatingPoint` ``()``.  The drum radius and the thickness of a concept are
            geometry parameters (``drum_radius=...``, ``thickness=...``).
        mesh : MeshSettings, optional
            Element sizes and sector or full model (default: the fidelity's,
            ``MeshSettings.preset(operating.fidelity)``).
        solver : str or callable, optional
            Sparse solver back-end: ``"cholmod"``, ``"superlu"`` or a factory ``A -> .solve(B)``.
        **values
            Concept parameters (``flexure_thickness="2.4mm"``, SI floats or strings with a
            unit suffix) and operating-point fields that are not geometry (``mu=0.2``,
            ``rotation="cw"``, ``material="titanium"``, ``softening="ritz"``, ...).

        Returns
        -------
        Design
            The meshed design; refusals are :class:`~clutchfem.ParameterError` naming the
            parameter, its value and the allowed range.

        Examples
        --------
        >>> import clutchfem as cf
        >>> d = cf.Design.from_concept("concept1", flexure_thickness="2.4mm", mu=0.2)
        >>> d.params.flexure_thickness, d.op.mu
        (0.0024, 0.2)
        >>> round(d.case().engagement_rpm, -1) > 3000
        True
        """
        c = concept if isinstance(concept, Concept) else get_concept(concept)  # (anything else refused, named)
        geometry, op_values = split_values(c, values)
        if params is not None and not isinstance(params, c.Params):
            raise ParameterError("params", type(params).__name__, f"a {c.Params.__name__} of {c.name} (or None)")
        p = params if params is not None else c.params()
        if geometry:
            p = p.replace(**geometry)
        if operating is not None and not isinstance(operating, OperatingPoint):
            raise ParameterError("operating", type(operating).__name__, "an OperatingPoint (or None)")
        op = operating if operating is not None else OperatingPoint()
        if op_values:
            op = op.replace(**op_values)
        if mesh is not None and not isinstance(mesh, MeshSettings):
            raise ParameterError("mesh", type(mesh).__name__, "a MeshSettings (or None)")
        d = cls(None, op, params=p, solver=solver, name=c.name, concept=c,
                mesh_settings=mesh if mesh is not None else MeshSettings.preset(op.fidelity))
        if op.fidelity != "live":  # an FE answer needs the mesh and the model: a refused geometry is said now
            d.model
        return d

    @classmethod
    def from_mesh(cls, path, *, drum_radius=None, thickness=None, operating: OperatingPoint | None = None,
                  mesh_size=None, solver: Solver = None, **op_values) -> "Design":
        """A design from your own part: a gmsh ``.msh`` or a STEP file.

        Parameters
        ----------
        path : str or Path
            The mesh (2-D in x-y, metres, rotation axis at the origin, physical curve groups
            ``bore`` and ``contact``; ``contact_0``, ``contact_1``, ... for per-shoe answers) or
            a STEP file (meshed here; the bore is the loop around the origin).
        drum_radius : float or str
            The drum's inner radius (``"34.4mm"``): a part has no drum of its own.  Required
            for every answer that involves the drum.
        thickness : float or str, optional
            The part's axial thickness (default: a STEP solid's height, else 11 mm, ASSUMED:
            :data:`USER_THICKNESS`).
        operating : OperatingPoint, optional
            The operating point; ``drum_radius``/``thickness`` given here override its own.
        mesh_size : float or str, optional
            Element size for a STEP file (``"1mm"``).
        **op_values
            Further operating-point fields (``mu=0.2``, ...).

        Returns
        -------
        Design

        Examples
        --------
        >>> import clutchfem as cf
        >>> cf.Design.from_mesh("no-such-part.msh", drum_radius="34.4mm")
        Traceback (most recent call last):
        ...
        clutchfem.core.errors.MeshError: mesh file no-such-part.msh does not exist
        """
        if operating is not None and not isinstance(operating, OperatingPoint):
            raise ParameterError("operating", type(operating).__name__, "an OperatingPoint (or None)")
        path = as_path(path, "path", "the path of a gmsh .msh or STEP file")
        op = operating if operating is not None else OperatingPoint()
        given = {k: v for k, v in (("drum_radius", drum_radius), ("thickness", thickness)) if v is not None}
        op = op.replace(**given, **op_values) if (given or op_values) else op
        size = MeshSettings.parse_value("size", mesh_size) if isinstance(mesh_size, str) else mesh_size
        from ..mesh import load_user_geometry

        cm = load_user_geometry(path, mesh_size=size, thickness=op.thickness, drum_radius=op.drum_radius)
        if op.thickness is None:  # a STEP solid's own height, else the assumed default
            op = op.replace(thickness=cm.thickness if cm.thickness is not None else USER_THICKNESS)
        return cls(cm, op, solver=solver, name=Path(path).name.rsplit(".", 1)[0])

    # -- contact and load cases ---------------------------------------------------------
    @cached_property
    def nodes(self):
        """Contact nodes (None without a drum)."""
        from ..contact import contact_nodes

        if self.drum_radius is None:
            return None
        return contact_nodes(self.model, self.drum_radius)

    @cached_property
    def drum(self):
        """The elastic drum (:class:`clutchfem.contact.RingDrum`), or None for a rigid drum."""
        return self.ring(self.op.drum_wall_m)

    def ring(self, wall: float | None):
        """The ring drum of wall thickness ``wall`` [m] (the operating point's state and
        material), None for a rigid drum (``wall`` None) or without a drum."""
        from ..contact import DrumWall, RingDrum

        if self.drum_radius is None or wall is None:
            return None
        return RingDrum(self.drum_radius, DrumWall(wall_thickness=wall, state=self.op.drum_state,
                                                   material=self.op.material))

    def contact(self, mu: float | None = None, drum_wall: float | str | None = "design") -> DrumContact | None:
        """The drum as a load-case part with friction ``mu`` (default: the operating point's),
        None without a drum.  ``drum_wall``: another drum wall [m] (None: rigid) than the
        design's, for the sensitivity to that assumed input."""
        from ..contact import DrumContact

        if self.nodes is None:
            return None
        sectors = self.cm.sector_copies
        drum = self.drum if drum_wall == "design" else self.ring(drum_wall)
        return DrumContact(self.nodes, self.op.mu if mu is None else mu, self.op.rotation, drum=drum,
                           sectors=sectors, symmetry=float(getattr(self.model, "symmetry_factor", 1.0)),
                           smoothing=self.op.contact_smoothing)

    def case(self, mu: float | None = None, softening=None, drum_wall: float | str | None = "design") -> LoadCase:
        """The load case with friction ``mu`` (default: the operating point's) and spin
        softening ``softening`` (default: the operating point's); cached.  ``drum_wall``:
        another drum than the design's (:meth:`contact`), on the same model and factorisation."""
        from ..softening import get_softening
        from .case import LoadCase

        if mu is not None:
            try:
                mu = parse_quantity(mu, "-")
            except UnitError:
                raise ParameterError("mu", mu, "a friction coefficient in [0, 1] (a number)") from None
            if not 0.0 <= mu <= 1.0:
                raise ParameterError("mu", mu, "a friction coefficient in [0, 1]")
        mu = self.op.mu if mu is None else mu
        soft = get_softening(self.op.softening if softening is None else softening)
        key = (mu, soft) if drum_wall == "design" else (mu, soft, drum_wall)
        if key not in self._cases:
            self._cases[key] = LoadCase(self.model, self.contact(mu, drum_wall), soft,
                                        engagement_hint=getattr(self, "_engagement_hint", None))
        return self._cases[key]

    def with_fidelity(self, fidelity: str) -> "Design":
        """The same concept design at another fidelity (``"best"``, ``"fast"``, ``"live"``):
        a new design, meshed and modelled as that fidelity asks (a live design's FE twin)."""
        if self.params is None:
            raise ParameterError("fidelity", fidelity, "a concept's design (a user mesh has one fidelity: its own)")
        op = self.op.replace(fidelity=fidelity)
        same = self._mesh_settings == MeshSettings.preset(self.op.fidelity)
        return Design.from_concept(self.concept, self.params, op, None if same else self._mesh_settings,
                                   solver=self._solver)

    def with_softening(self, softening: str) -> "Design":
        """The same design (mesh, FE model and its factorisation shared) with the operating
        point's spin-softening strategy ``softening`` (a name of
        :class:`~clutchfem.loadcase.OperatingPoint`'s ``softening``)."""
        other = copy.copy(self)
        other.op = OperatingPoint(**{**self.op.model_dump(), "softening": softening})
        # the engagement this design found already (friction does not move it): where the
        # other strategy's search starts (LoadCase.engagement_hint)
        found = (c.known_engagement for c in self._cases.values())
        other._engagement_hint = next((w for w in found if w), getattr(self, "_engagement_hint", None))
        other._cases = {}
        return other

    def sweep(self, rpm=None, *, mu: float | None = None, softening=None, stresses: bool = True):
        """Sweep the speeds ``rpm`` (default: the operating point's, else 0:14000:250)."""
        from .case import sweep

        speeds = self.op.speeds() if rpm is None else rpm
        return sweep(self.case(mu, softening), speeds, stresses=as_bool(stresses, "stresses"))

    @property
    def label(self) -> str:
        """The design's file-name stem: the concept name at its defaults, else the name plus
        :attr:`hash` (every file a command writes for this design carries it)."""
        return design_label(self)

    @property
    def identity(self) -> "DesignIdentity":
        """The design's identity (:mod:`clutchfem.loadcase.identity`): the document of
        everything that defines its answers (concept, full parameters, operating point with
        material, fidelity and model settings, mesh settings, code version) and its hash,
        computed in that one place and carried by every file, JSON, report, drawing, app
        download and study row of this design.  Needs no mesh.

        Examples
        --------
        >>> import clutchfem as cf
        >>> d = cf.Design.from_concept("concept4", flexure_thickness="1.9mm", fidelity="live")
        >>> d.identity.hash == d.hash == d.inputs()["design_hash"], d.label == f"concept4-{d.hash}"
        (True, True)
        """
        return design_identity(self)

    @property
    def hash(self) -> str:
        """12 hex digits of SHA-256 over the design's :attr:`identity` (not a file's path)."""
        return design_hash(self)

    def inputs(self) -> dict:
        """The inputs that define this design's answers, JSON-ready: the concept and every
        parameter (or the mesh file and its SHA-256), the mesh settings and size, the
        operating point (material included) and the software versions."""
        return design_inputs(self)

    @property
    def scale(self) -> float:
        """Totals of the whole clutch / totals of the model (sector and mid-plane symmetry)."""
        return self.cm.sector_copies * getattr(self.model, "symmetry_factor", 1.0)

    def _check_user_drum(self) -> None:
        b = self.cm.mesh.boundaries or {}
        if "contact" in b and len(b["contact"]):
            mesh = self.cm.mesh
            r_c = float(np.hypot(*mesh.p[:, mesh.facets[:, b["contact"]].ravel()]).max())
            R = self.drum_radius
            if R > DRUM_GAP_LIMIT * r_c:
                raise ParameterError("drum_radius", R, f"a radius in m between the contact surface's outer radius "
                                     f"{r_c:.6g} m and {DRUM_GAP_LIMIT:g} x that ({DRUM_GAP_LIMIT * r_c:.6g} m): a "
                                     "larger gap cannot close elastically (lengths are in metres, not mm)",
                                     context="user mesh")


def _first(*values):
    for v in values:
        if v is not None and not (isinstance(v, float) and math.isnan(v)):
            return float(v)
    return None
