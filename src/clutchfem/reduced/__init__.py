"""The reduced model: the best estimate of a design next to ones already solved, in
milliseconds, with its own measured error.

* :mod:`.region` (:class:`Region`: the free parameters and their box around a design, the
  key a reduced model is cached under);
* :mod:`.surrogate` (:class:`AnswerModel`: one answer's Gaussian process on a linear trend;
  :class:`StatusModel`: where the full FE answers at all).
"""

from __future__ import annotations

from ..core import lazy_names

_NAMES: dict[str, str] = {
    "AnswerModel": "surrogate",
    "OK_PROBABILITY": "surrogate",
    "Region": "region",
    "SPAN": "region",
    "StatusModel": "surrogate",
}

__all__ = sorted(_NAMES)

__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
