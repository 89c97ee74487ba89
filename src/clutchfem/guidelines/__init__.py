"""Design guidelines: which parameter moves which answer, and by how much (thesis 4.4,
with numbers).

* :mod:`.elasticity` (:class:`GuidelineSettings`, the plan of designs, the elasticities
  with their step-stability check, :class:`GuidelineResult`);
* :mod:`.study` (:func:`run_guidelines`: the plan on the study engine, the sensitivities
  on morphed meshes, the tables);
* :mod:`.live` (:func:`live_guidelines`: a live design's, from the reduced model's
  derivatives with their band, a few checked by the FE).

The charts and the terminal table of a result are the report stage's
(:mod:`clutchfem.report`), drawn by the faces.
"""

from .elasticity import (
    ANSWERS,
    CHECK_FACTOR,
    SENSITIVITY_KEY,
    SHORT,
    STABLE_ABS,
    STABLE_REL,
    GuidelineResult,
    GuidelineSettings,
)
from .live import live_guidelines
from .study import run_guidelines, why_no_answer

__all__ = ["ANSWERS", "CHECK_FACTOR", "SENSITIVITY_KEY", "SHORT", "STABLE_ABS", "STABLE_REL", "GuidelineResult",
           "GuidelineSettings", "live_guidelines", "run_guidelines", "why_no_answer"]
