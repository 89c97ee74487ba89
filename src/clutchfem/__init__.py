"""clutchfem: FEM toolkit for one-piece compliant centrifugal clutches.

The public API, imported lazily (``import clutchfem`` loads no numerical library; a name is
imported on first use)::

    import clutchfem as cf

    d = cf.Design.from_concept("concept1", flexure_thickness="2.4mm")   # mesh + FE model
    r = d.sweep("0:14000:250")                  # a speed sweep: cf.SweepResult
    a = cf.analyze(d)                           # every answer with its error: cf.Analysis
    print(a.engagement_rpm, a.slip_rpm)

Designs: :func:`concepts`, :class:`Design` (``from_concept``, ``from_mesh``), :func:`morph`,
:class:`OperatingPoint`, :class:`Material`, :class:`MeshSettings`.  Answers:
:func:`analyze`, :class:`Analysis`, :class:`SweepResult`, :class:`EngineCurve`,
:class:`Requirements`.  Studies and design to targets: :class:`StudySpec`, :func:`load_study`,
:func:`run_study`, :func:`run_grid`, :func:`guidelines`, :class:`Targets`, :func:`optimize`, :func:`tolerance`, :func:`sensitivities`,
:func:`robust_optimize`, :func:`allocate_tolerances`, :func:`yield_front`,
:func:`compensate`.  Durability: :class:`SlipScenario`, :func:`slip_heat`.  Output:
:func:`write_report`, :func:`torque_speed_plot`.  Cutting: :func:`export` (DXF, STEP, drawing sheet,
manufacturability check, as-cut analysis), :class:`ProcessRules`.  Checks: :func:`validate`.  The live app: :func:`serve_app`.  Errors: :class:`ClutchfemError` and its kinds.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

__version__ = "0.2.0"

#: public name -> (module it lives in, its name there)
_API: dict[str, tuple[str, str]] = {
    "concepts": ("clutchfem.geometry", "concepts"),
    "get_concept": ("clutchfem.geometry", "get_concept"),
    "MeshSettings": ("clutchfem.geometry", "MeshSettings"),
    "Design": ("clutchfem.loadcase", "Design"),
    "OperatingPoint": ("clutchfem.loadcase", "OperatingPoint"),
    "morph": ("clutchfem.loadcase", "morph"),
    "SweepResult": ("clutchfem.loadcase", "SweepResult"),
    "Material": ("clutchfem.core", "Material"),
    "get_material": ("clutchfem.core", "get_material"),
    "EngineCurve": ("clutchfem.clutch", "EngineCurve"),
    "Requirements": ("clutchfem.analysis", "Requirements"),
    "Analysis": ("clutchfem.analysis", "Analysis"),
    "analyze": ("clutchfem.analysis", "analyze"),
    "StudySpec": ("clutchfem.studies", "StudySpec"),
    "load_study": ("clutchfem.studies", "load_spec"),
    "run_study": ("clutchfem.studies", "run_study"),
    "guidelines": ("clutchfem.studies", "run_guidelines"),
    "Targets": ("clutchfem.studies", "Targets"),
    "optimize": ("clutchfem.studies", "optimize"),
    "tolerance": ("clutchfem.studies", "tolerance"),
    "sensitivities": ("clutchfem.studies", "sensitivities"),
    "robust_optimize": ("clutchfem.studies", "robust_optimize"),
    "allocate_tolerances": ("clutchfem.studies", "allocate_tolerances"),
    "yield_front": ("clutchfem.studies", "yield_front"),
    "compensate": ("clutchfem.studies", "compensate"),
    "SlipScenario": ("clutchfem.durability", "SlipScenario"),
    "slip_heat": ("clutchfem.analysis", "slip_heat"),
    "write_report": ("clutchfem.report", "design_report"),
    "torque_speed_plot": ("clutchfem.report", "comparison_plot"),
    "run_grid": ("clutchfem.studies", "run_grid"),
    "export": ("clutchfem.cutting", "export"),
    "ProcessRules": ("clutchfem.cutting", "ProcessRules"),
    "CuttingError": ("clutchfem.cutting", "CuttingError"),
    "validate": ("clutchfem.validation", "validate"),
    "serve_app": ("clutchfem.app", "serve"),
    "ClutchfemError": ("clutchfem.core", "ClutchfemError"),
    "ParameterError": ("clutchfem.core", "ParameterError"),
    "InputError": ("clutchfem.core", "InputError"),
    "GeometryError": ("clutchfem.core", "GeometryError"),
    "MeshError": ("clutchfem.core", "MeshError"),
    "SolverError": ("clutchfem.core", "SolverError"),
}

__all__ = ["__version__", *_API]


def __getattr__(name: str) -> Any:
    """Import a public name on first use (PEP 562) and keep it."""
    try:
        module, attr = _API[name]
    except KeyError:
        raise AttributeError(f"module 'clutchfem' has no attribute {name!r}") from None
    value = getattr(importlib.import_module(module), attr)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_API))


if TYPE_CHECKING:  # the same names for type checkers and IDEs
    from .analysis import Analysis, Requirements, analyze, slip_heat
    from .app import serve as serve_app
    from .clutch import EngineCurve
    from .core import (
        ClutchfemError,
        GeometryError,
        InputError,
        Material,
        MeshError,
        ParameterError,
        SolverError,
        get_material,
    )
    from .cutting import CuttingError, ProcessRules, export
    from .durability import SlipScenario
    from .geometry import MeshSettings, concepts, get_concept
    from .loadcase import Design, OperatingPoint, SweepResult, morph
    from .report import comparison_plot as torque_speed_plot
    from .report import design_report as write_report
    from .studies import (
        StudySpec,
        Targets,
        allocate_tolerances,
        compensate,
        optimize,
        robust_optimize,
        run_grid,
        run_study,
        sensitivities,
        tolerance,
        yield_front,
    )
    from .studies import load_spec as load_study
    from .studies import run_guidelines as guidelines
    from .validation import validate
