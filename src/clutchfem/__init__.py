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
:func:`compensate`.  Calibration to measured parts: :func:`calibrate`, :func:`corrected_design`.  Durability: :class:`SlipScenario`, :func:`slip_heat`.  Output:
:func:`write_report`, :func:`torque_speed_plot`.  Cutting: :func:`export` (DXF, STEP, drawing sheet,
manufacturability check, as-cut analysis), :class:`ProcessRules`.  Checks: :func:`validate`.  The live app: :func:`serve_app`.  Errors: :class:`ClutchfemError` and its kinds.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from ._version import __version__

#: the public API by job (the documentation's groups): name -> the package it is defined in, under
#: the same name (a public name is the name where it is defined)
_GROUPS: dict[str, dict[str, str]] = {
    "Designs": {
        "concepts": "clutchfem.geometry",
        "get_concept": "clutchfem.geometry",
        "broken_concepts": "clutchfem.geometry",
        "draw_concept": "clutchfem.geometry",
        "MeshSettings": "clutchfem.geometry",
        "Design": "clutchfem.loadcase",
        "DesignIdentity": "clutchfem.loadcase",
        "OperatingPoint": "clutchfem.loadcase",
        "parse_rpm": "clutchfem.loadcase",
        "morph": "clutchfem.loadcase",
        "Material": "clutchfem.core",
        "get_material": "clutchfem.core",
    },
    "Answers": {
        "SweepResult": "clutchfem.loadcase",
        "model_warnings": "clutchfem.loadcase",
        "sweep_errors": "clutchfem.accuracy",
        "EngineCurve": "clutchfem.clutch",
        "Requirements": "clutchfem.analysis",
        "Analysis": "clutchfem.analysis",
        "analyze": "clutchfem.analysis",
        "check_speeds": "clutchfem.analysis",
        "FatigueLoads": "clutchfem.durability",
        "FatigueParams": "clutchfem.durability",
    },
    "Durability": {
        "SlipScenario": "clutchfem.thermal",
        "ThermalEnvironment": "clutchfem.thermal",
        "ThermalMaterial": "clutchfem.thermal",
        "DrumThermal": "clutchfem.thermal",
        "slip_heat": "clutchfem.analysis",
        "SlipHeatRun": "clutchfem.analysis",
        "DriveLine": "clutchfem.durability",
        "Engagement": "clutchfem.durability",
        "engagement_transient": "clutchfem.durability",
        "StartHeating": "clutchfem.durability",
        "start_heating": "clutchfem.durability",
        "WearParams": "clutchfem.durability",
        "WearRun": "clutchfem.durability",
        "wear_rate": "clutchfem.durability",
        "integrate_wear": "clutchfem.durability",
        "DutyCycle": "clutchfem.lifetime",
        "Life": "clutchfem.lifetime",
        "life": "clutchfem.lifetime",
        "life_files": "clutchfem.lifetime",
    },
    "Studies": {
        "StudySpec": "clutchfem.studies",
        "load_study": "clutchfem.studies",
        "example_study": "clutchfem.studies",
        "run_study": "clutchfem.studies",
        "StudyResult": "clutchfem.studies",
        "StudyInterrupted": "clutchfem.evaluation",
        "finished_summary": "clutchfem.studies",
        "run_grid": "clutchfem.studies",
        "GridResult": "clutchfem.studies",
        "EvalSettings": "clutchfem.evaluation",
        "check_scheduler": "clutchfem.evaluation",
        "sensitivities": "clutchfem.evaluation",
        "Sensitivities": "clutchfem.evaluation",
    },
    "Reduced model": {
        "reduce": "clutchfem.reduced",
        "ReducedModel": "clutchfem.reduced",
        "Region": "clutchfem.reduced",
    },
    "Design guidelines": {
        "GuidelineSettings": "clutchfem.guidelines",
        "run_guidelines": "clutchfem.guidelines",
        "GuidelineResult": "clutchfem.guidelines",
    },
    "Design to targets": {
        "Targets": "clutchfem.targets",
        "optimize": "clutchfem.targets",
        "OptimizationResult": "clutchfem.targets",
        "best_estimate": "clutchfem.targets",
        "compensate": "clutchfem.targets",
        "Compensation": "clutchfem.targets",
        "optimize_for_life": "clutchfem.targets",
        "LifeDesign": "clutchfem.targets",
        "wear_allowance": "clutchfem.targets",
        "WearAllowance": "clutchfem.targets",
    },
    "Tolerances": {
        "parse_tolerance": "clutchfem.tolerances",
        "tolerance": "clutchfem.tolerances",
        "ToleranceResult": "clutchfem.tolerances",
        "robust_optimize": "clutchfem.tolerances",
        "RobustResult": "clutchfem.tolerances",
        "allocate_tolerances": "clutchfem.tolerances",
        "Allocation": "clutchfem.tolerances",
        "yield_front": "clutchfem.tolerances",
        "YieldFront": "clutchfem.tolerances",
    },
    "Calibration to measured parts": {
        "calibrate": "clutchfem.calibration",
        "Calibration": "clutchfem.calibration",
        "parse_measured": "clutchfem.calibration",
        "parse_uncertain": "clutchfem.calibration",
        "check_measurements": "clutchfem.calibration",
        "torque_from_csv": "clutchfem.calibration",
        "corrected_design": "clutchfem.calibration",
        "parse_target": "clutchfem.calibration",
        "Correction": "clutchfem.calibration",
    },
    "Output": {
        "write_report": "clutchfem.report",
        "summary_rows": "clutchfem.report",
        "torque_speed_plot": "clutchfem.report",
        "default_design_report": "clutchfem.report",
        "draw_study_charts": "clutchfem.report",
        "draw_guideline_charts": "clutchfem.report",
        "guideline_table": "clutchfem.report",
        "field_picture": "clutchfem.report",
        "write_vtk": "clutchfem.fe",
        "dumps": "clutchfem.core",
    },
    "Cutting": {
        "export": "clutchfem.cutting",
        "design_from_run": "clutchfem.cutting",
        "design_from_study": "clutchfem.cutting",
        "ExportResult": "clutchfem.cutting",
        "ProcessRules": "clutchfem.cutting",
        "CuttingError": "clutchfem.cutting",
        "thinnest_ligament": "clutchfem.cutting",
        "Ligament": "clutchfem.cutting",
    },
    "Checks, the app and the machine": {
        "validate": "clutchfem.validation",
        "ValidationRun": "clutchfem.validation",
        "serve_app": "clutchfem.app",
        "cache_dir": "clutchfem.mesh",
        "cache_entries": "clutchfem.mesh",
        "cache_foreign_files": "clutchfem.mesh",
        "cache_limit": "clutchfem.mesh",
        "clear_cache": "clutchfem.mesh",
        "tune_malloc": "clutchfem.core",
    },
    "Units": {
        "parse_quantity": "clutchfem.core",
        "format_quantity": "clutchfem.core",
    },
    "Errors": {
        "ClutchfemError": "clutchfem.core",
        "ParameterError": "clutchfem.core",
        "InputError": "clutchfem.core",
        "UnitError": "clutchfem.core",
        "GeometryError": "clutchfem.core",
        "MeshError": "clutchfem.core",
        "SolverError": "clutchfem.core",
    },
}

#: public name -> the package it is defined in
_API: dict[str, str] = {name: package for names in _GROUPS.values() for name, package in names.items()}

#: names of earlier releases -> the name now (0.3: a public name is the name where it is defined)
_RENAMED = {"guidelines": "run_guidelines"}  # the other renamed names kept their public name

__all__ = ["__version__", *_API]


#: a public name that needs another stage loaded as well: ``analyze`` answers a live design from
#: the reduced model, which sits above the analysis and registers itself there on import
_ALSO_LOAD = {"analyze": "clutchfem.reduced.live"}


def __getattr__(name: str) -> Any:
    """Import a public name on first use (PEP 562) and keep it."""
    try:
        module = _API[name]
    except KeyError:
        hint = f" (renamed to {_RENAMED[name]!r} in clutchfem 0.3)" if name in _RENAMED else ""
        raise AttributeError(f"module 'clutchfem' has no attribute {name!r}{hint}") from None
    if name in _ALSO_LOAD:
        importlib.import_module(_ALSO_LOAD[name])
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_API))


if TYPE_CHECKING:  # the same names for type checkers and IDEs (a test holds them equal to _API)
    from .accuracy import sweep_errors
    from .analysis import Analysis, Requirements, SlipHeatRun, analyze, check_speeds, slip_heat
    from .app import serve_app
    from .calibration import (
        Calibration,
        Correction,
        calibrate,
        check_measurements,
        corrected_design,
        parse_measured,
        parse_target,
        parse_uncertain,
        torque_from_csv,
    )
    from .clutch import EngineCurve
    from .core import (
        ClutchfemError,
        GeometryError,
        InputError,
        Material,
        MeshError,
        ParameterError,
        SolverError,
        UnitError,
        dumps,
        format_quantity,
        get_material,
        parse_quantity,
        tune_malloc,
    )
    from .cutting import (
        CuttingError,
        ExportResult,
        Ligament,
        ProcessRules,
        design_from_run,
        design_from_study,
        export,
        thinnest_ligament,
    )
    from .durability import (
        DriveLine,
        Engagement,
        FatigueLoads,
        FatigueParams,
        StartHeating,
        WearParams,
        WearRun,
        engagement_transient,
        integrate_wear,
        start_heating,
        wear_rate,
    )
    from .evaluation import EvalSettings, Sensitivities, StudyInterrupted, check_scheduler, sensitivities
    from .fe import write_vtk
    from .geometry import MeshSettings, broken_concepts, concepts, draw_concept, get_concept
    from .guidelines import GuidelineResult, GuidelineSettings, run_guidelines
    from .lifetime import DutyCycle, Life, life, life_files
    from .loadcase import Design, DesignIdentity, OperatingPoint, SweepResult, model_warnings, morph, parse_rpm
    from .mesh import cache_dir, cache_entries, cache_foreign_files, cache_limit, clear_cache
    from .reduced import ReducedModel, Region, reduce
    from .report import (
        default_design_report,
        draw_guideline_charts,
        draw_study_charts,
        field_picture,
        guideline_table,
        summary_rows,
        torque_speed_plot,
        write_report,
    )
    from .studies import (
        GridResult,
        StudyResult,
        StudySpec,
        example_study,
        finished_summary,
        load_study,
        run_grid,
        run_study,
    )
    from .targets import (
        Compensation,
        LifeDesign,
        OptimizationResult,
        Targets,
        WearAllowance,
        best_estimate,
        compensate,
        optimize,
        optimize_for_life,
        wear_allowance,
    )
    from .thermal import (
        DrumThermal,
        SlipScenario,
        ThermalEnvironment,
        ThermalMaterial,
    )
    from .tolerances import (
        Allocation,
        RobustResult,
        ToleranceResult,
        YieldFront,
        allocate_tolerances,
        parse_tolerance,
        robust_optimize,
        tolerance,
        yield_front,
    )
    from .validation import ValidationRun, validate
