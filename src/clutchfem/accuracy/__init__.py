"""Accuracy stage: the error of every answer (:mod:`.answer_error`): discretisation (the
design on a finer mesh) and model form (3-D thickness effect, :mod:`.plane_stress`;
geometric non-linearity; elastic drum), with the geometrically non-linear reference
(:mod:`.nonlinear`) that measures part of it, and the per-design correction of the peak
stress's and torque's geometric non-linearity on the best-estimate path (:mod:`.gnl_correction`)."""

from .answer_error import (
    ANSWERS,
    NOT_ESTIMATED,
    AnswerError,
    discretisation,
    discretisation_3d,
    extrapolated_peak,
    format_error,
    layers_design,
    layers_error,
    model_form,
    refined_design,
    sweep_errors,
    thick_twin,
)
from .gnl_correction import AnswerNonlinearity, answer_nonlinearity
from .nonlinear import NLState, NonlinearModel, NonlinearSettings, second_order_engagement
from .plane_stress import PlaneStressEstimate, plane_stress_estimate

__all__ = ["AnswerNonlinearity", "answer_nonlinearity", "extrapolated_peak", "discretisation_3d", "layers_design", "layers_error", "thick_twin", "ANSWERS", "NOT_ESTIMATED", "AnswerError", "NLState", "NonlinearModel", "NonlinearSettings",
           "PlaneStressEstimate", "discretisation", "format_error", "model_form", "plane_stress_estimate",
           "refined_design", "second_order_engagement", "sweep_errors"]
