"""One design -> one FE model -> several load cases.

A :class:`Design` is a meshed part (a concept with its parameters, or a user mesh) at an
:class:`~clutchfem.loadcase.OperatingPoint`.  It builds the FE model (K, f1, constraints,
one factorisation) and the contact nodes once, and hands out load cases by (mu, spin
softening) that all share them: a sweep, friction off, mu +-30 %, a tolerance sample's
other speeds never re-assemble or re-factorise.  A sweep point, an optimiser step and a
Monte Carlo sample are each one ``Design``.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from ..contact import DrumContact, DrumWall, RingDrum, contact_nodes
from ..core import ParameterError
from ..fe import ExtrusionSettings, FEModel, FEModel3D, Solver
from ..geometry import get_concept
from ..mesh import ClutchMesh, mesh_concept
from ..softening import get_softening
from .case import LoadCase, sweep
from .operating import OperatingPoint

#: a user mesh's drum radius may exceed the contact surface's outer radius by at most this
#: factor (a units check: a gap of half the part's radius cannot close elastically)
DRUM_GAP_LIMIT = 1.5


class Design:
    """A meshed design at an operating point (see module docstring).

    cm: the meshed part; op: the operating point (drum radius and thickness default to the
    concept's, i.e. ``params``); params: the concept's parameter set, or None for a user
    mesh; solver: the sparse solver back-end (name or factory), injected into the FE model.
    """

    def __init__(self, cm: ClutchMesh, op: OperatingPoint | None = None, *, params=None,
                 solver: Solver = None, name: str = ""):
        if not isinstance(cm, ClutchMesh):
            raise ParameterError("cm", type(cm).__name__, "a ClutchMesh (from clutchfem.mesh.mesh_concept "
                                 "or load_user_geometry)")
        op = op if op is not None else OperatingPoint()
        if not isinstance(op, OperatingPoint):
            raise ParameterError("op", type(op).__name__, "an OperatingPoint")
        self.cm = cm
        self.op = op
        self.params = params
        self.name = name or cm.source
        self.drum_radius = _first(op.drum_radius, getattr(params, "drum_radius", None), cm.drum_radius)
        self.thickness = _first(op.thickness, getattr(params, "thickness", None), cm.thickness)
        if self.thickness is None:
            raise ParameterError("thickness", None, "the axial thickness in m (a user mesh carries none; "
                                 "e.g. 0.011 for 11 mm)")
        if params is None and self.drum_radius is not None:
            self._check_user_drum()
        if op.formulation == "3d":
            self.model = FEModel3D(cm, op.material, self.thickness, settings=ExtrusionSettings(layers=op.layers),
                                   solver=solver)
        else:
            self.model = FEModel(cm, op.material, self.thickness, formulation=op.formulation, solver=solver)
        self._cases: dict = {}

    @classmethod
    def from_concept(cls, concept, params=None, op: OperatingPoint | None = None, mesh_settings=None, *,
                     solver: Solver = None) -> "Design":
        """Mesh ``concept`` (name or Concept) with ``params`` (defaults) and build the design."""
        c = get_concept(concept) if isinstance(concept, str) else concept
        p = params if params is not None else c.params()
        cm = mesh_concept(c, p, mesh_settings)
        return cls(cm, op, params=p, solver=solver, name=c.name)

    # -- contact and load cases ---------------------------------------------------------
    @cached_property
    def nodes(self):
        """Contact nodes (None without a drum)."""
        if self.drum_radius is None:
            return None
        return contact_nodes(self.model, self.drum_radius)

    @cached_property
    def drum(self):
        """The elastic drum (:class:`clutchfem.contact.RingDrum`), or None for a rigid drum."""
        if self.drum_radius is None or self.op.drum_wall is None:
            return None
        return RingDrum(self.drum_radius, DrumWall(wall_thickness=self.op.drum_wall, state=self.op.drum_state,
                                                   material=self.op.material))

    def contact(self, mu: float | None = None) -> DrumContact | None:
        """The drum as a load-case part with friction ``mu`` (default: the operating point's),
        None without a drum."""
        if self.nodes is None:
            return None
        sectors = self.cm.sector_copies
        return DrumContact(self.nodes, self.op.mu if mu is None else mu, self.op.rotation, drum=self.drum,
                           sectors=sectors)

    def case(self, mu: float | None = None, softening=None) -> LoadCase:
        """The load case with friction ``mu`` (default: the operating point's) and spin
        softening ``softening`` (default: the operating point's); cached."""
        mu = self.op.mu if mu is None else float(mu)
        soft = get_softening(self.op.softening if softening is None else softening)
        key = (mu, soft)
        if key not in self._cases:
            self._cases[key] = LoadCase(self.model, self.contact(mu), soft)
        return self._cases[key]

    def sweep(self, rpm=None, *, mu: float | None = None, softening=None, stresses: bool = True):
        """Sweep the speeds ``rpm`` (default: the operating point's, else 0:14000:250)."""
        speeds = self.op.speeds() if rpm is None else rpm
        return sweep(self.case(mu, softening), speeds, stresses=stresses)

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
