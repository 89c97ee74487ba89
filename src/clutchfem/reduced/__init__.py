"""The reduced model: the best estimate of a design next to ones already solved, in
milliseconds, with its own measured error.

* :mod:`.region` (:class:`Region`: the free parameters and their box around a design, the
  key a reduced model is cached under);
* :mod:`.surrogate` (:class:`AnswerModel`: one answer's Gaussian process on a linear trend;
  :class:`StatusModel`: where the full FE answers at all);
* :mod:`.model` (:class:`ReducedModel`: every main answer over a region, the best path's
  bands, its own error measured on held-out designs);
* :mod:`.build` (:func:`reduce`: the training designs on the study engine, the cache);
* :mod:`.live` (:func:`live_analysis`: ``analyze`` of a live design).

It sits above the study engine that trains it and below the faces and the design-to-targets
layers that use it; ``clutchfem.analyze`` answers a live design through it (registered in
:data:`clutchfem.analysis.LIVE` when :mod:`.live` is imported).
"""

from __future__ import annotations

from ..core import lazy_names

_NAMES: dict[str, str] = {
    "ANSWERS": "model",
    "AnswerModel": "surrogate",
    "cache_root": "build",
    "find": "build",
    "live_analysis": "live",
    "load": "build",
    "MAX_FE_BAND": "model",
    "outside_why": "build",
    "reduce": "build",
    "save": "build",
    "ReducedModel": "model",
    "OK_PROBABILITY": "surrogate",
    "OPERATING_AXES": "region",
    "Region": "region",
    "SPAN": "region",
    "StatusModel": "surrogate",
}

__all__ = sorted(_NAMES)

__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
