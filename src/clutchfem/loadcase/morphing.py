"""A design with changed parameters on its reference design's moved mesh: :func:`morph`.

The mesh of the reference (the design given, or the reference it was itself morphed from)
is moved onto the new geometry (:mod:`clutchfem.mesh.morph`: the nodes on the curves to
the same normalised curve parameter, the interior by a stiffened Laplace solve), so that
the answers of nearby designs differ only by what the parameters change, not by a new mesh
topology.  Where the curves differ or the moved elements would be too distorted, the design
is meshed from scratch, and ``design.cm.morph`` says so with the reason.
"""

from __future__ import annotations

from ..core import ParameterError
from ..geometry import MeshSettings
from ..mesh import morph_or_mesh
from .design import Design, split_values


def morph(design: Design, **values) -> Design:
    """The design with the concept parameters ``values`` changed, on ``design``'s moved mesh.

    Parameters
    ----------
    design : Design
        The reference: a concept's design (its mesh, operating point and mesh settings).
        A design that was itself morphed keeps its own reference, so every design morphed
        from one base shares one mesh connectivity.
    **values
        Concept parameters (``flexure_thickness="1.8mm"``, SI floats or strings with a
        unit) and operating-point fields (``mu=0.2``).

    Returns
    -------
    Design
        The new design; ``d.cm.morph`` records the reference and the mesh quality (or why
        the mesh had to be made from scratch).

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> d2 = cf.morph(d, flexure_thickness="1.8mm")
    >>> d2.cm.morph["morphed"], d2.cm.n_elements == d.cm.n_elements
    (True, True)
    >>> d2.case().engagement_rpm > d.case().engagement_rpm    # a thicker beam engages later
    True
    """
    if not isinstance(design, Design) or design.params is None or design.concept is None:
        raise ParameterError("design", type(design).__name__, "a concept's Design (Design.from_concept): a user mesh "
                             "has no parameters to change")
    c = design.concept
    geometry, op_values = split_values(c, values)
    p = design.params.replace(**geometry) if geometry else design.params
    op = design.op.replace(**op_values) if op_values else design.op
    ref = design.params
    info = design.cm.morph or {}
    if info.get("morphed"):
        ref = type(design.params)(**info["reference"])
    ms = MeshSettings(**design.cm.mesh_settings) if design.cm.mesh_settings else MeshSettings()
    cm = morph_or_mesh(c, p, ms, reference=ref)
    return Design(cm, op, params=p, name=design.name, concept=c)
