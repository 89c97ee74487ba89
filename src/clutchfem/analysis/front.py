"""The analysis stage's front door: :func:`analyze` checks its inputs and hands the design to
the live answerer (a design whose fidelity is ``"live"``: the reduced model's,
:data:`~.idle.LIVE`) or to the FE steps (:func:`~.pipeline.run_steps`).

The FE steps are imported when a design needs them: a live answer loads neither them nor the
mesh and the FE model (docs/reduced.md).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..clutch import EngineCurve
from ..core import ParameterError, as_bool
from ..loadcase import Design
from .answers import Analysis, Requirements
from .idle import LIVE

if TYPE_CHECKING:
    from ..clutch import RippleModel  # (the FE steps' 2-stroke ripple: scipy.special)

__all__ = ["analyze"]


def analyze(design, *, engine: EngineCurve | None = None, requirements: Requirements | None = None,
            idle_rpm: float | None = None, ripple_model: RippleModel | None = None,
            errors: bool = True, fatigue_loads=None, fatigue_params=None) -> Analysis:
    """Run the steps of an analysis (:mod:`.pipeline`) on ``design`` (a :class:`~clutchfem.loadcase.Design`:
    mesh, parameters, material, mu, rotation, drum, thickness, softening and output speeds in
    its operating point).  engine: full-throttle curve (default: the ASSUMED 56.5 cc saw
    curve); requirements: factors a, b; idle_rpm: overrides the engine's idle speed (else the
    curve's, else 2700 rpm, ASSUMED); errors: estimate the error of the main answers (step
    9: a mesh twice as fine and its solves, ~3x the time; off for bulk studies that rank
    designs, whose error the study states from a sample); fatigue_loads, fatigue_params: the
    service loads (:class:`~clutchfem.durability.FatigueLoads`) and fatigue strength
    (:class:`~clutchfem.durability.FatigueParams`) of step 11.  A user mesh
    (``design.params`` None) gets every FE answer; the analytical curves are then NaN and
    ``analytical_available`` is False.

    Parameters
    ----------
    design : Design
    engine : EngineCurve, optional
    requirements : Requirements, optional
    idle_rpm : float, optional
    ripple_model : RippleModel, optional
        The 2-stroke speed ripple (default: seed 000's).
    errors : bool
        Estimate the error of the main answers.
    fatigue_loads, fatigue_params : optional

    Returns
    -------
    Analysis
        Every answer with its unit and error band, warnings where the model is stretched or
        the design fails, the curves against rpm and the design's inputs.

    Examples
    --------
    >>> import clutchfem as cf
    >>> a = cf.analyze(cf.Design.from_concept("concept4", flexure_thickness="2.0mm"))
    >>> 4000 < a.engagement_rpm < 6000, a.errors["engagement_rpm"]["unit"]
    (True, 'rpm')"""
    if not isinstance(design, Design):
        raise ParameterError("design", type(design).__name__, "a clutchfem Design (Design.from_concept or Design.from_mesh)")
    if design.op.fidelity == "live":
        if not LIVE:
            raise ParameterError("fidelity", "live", "a live answer needs the reduced-model stage: call it as "
                                 "clutchfem.analyze (or import clutchfem.reduced first)")
        return LIVE[0](design, engine=engine, requirements=requirements, idle_rpm=idle_rpm)
    engine = EngineCurve.of(engine)
    if requirements is not None and not isinstance(requirements, Requirements):
        raise ParameterError("requirements", type(requirements).__name__, "a Requirements(a=..., b=...) or None "
                             "(a = 1.3, b = 1.0, ASSUMED)")
    errors = as_bool(errors, "errors")
    req = requirements or Requirements()
    if design.drum_radius is None:
        raise ParameterError("drum_radius", None, "the drum's inner radius in m, larger than the outer radius "
                             "of the contact surface: a user mesh carries no drum, and without a drum there "
                             "is no friction torque", context="user mesh")
    from .pipeline import run_steps  # (the FE steps: a live design is answered above, without them)

    return run_steps(design, engine, req, idle_rpm, ripple_model, errors, fatigue_loads, fatigue_params)
