"""Calibration to measured parts: which inputs of a part as built explain what the test rig
measured, how sure that is, and which measurements no input within its prior explains.

* :mod:`.inputs` (:func:`parse_measured`, :func:`parse_uncertain`: the measurements with
  their uncertainty, the uncertain inputs with their priors; :func:`torque_from_csv`);
* :mod:`.inference` (the forward model on the reduced model, the likelihood, emcee and the
  Laplace approximation);
* :mod:`.calibrate` (:func:`calibrate`, :class:`Calibration`: the posterior per input, the
  calibrated answers, the check of the fit, the pictures; several parts of one design);
* :mod:`.correct` (:func:`corrected_design`, :class:`Correction`: the drawn values whose next
  part as built meets the targets).

It stands on the reduced model (:mod:`clutchfem.reduced`), beside the tolerances.
"""

from .calibrate import Calibration, calibrate
from .correct import Correction, corrected_design, parse_target
from .inputs import (
    Measurement,
    Uncertain,
    check_measurements,
    parse_measured,
    parse_uncertain,
    torque_from_csv,
)
from .readings import combine_readings

__all__ = ["Calibration", "Correction", "Measurement", "Uncertain", "calibrate", "check_measurements",
           "combine_readings", "corrected_design", "parse_measured", "parse_target", "parse_uncertain",
           "torque_from_csv"]
