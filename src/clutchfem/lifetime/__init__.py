"""The clutch over its life (issue 38): the starts, their slip energy, the wear-in of the
contact arc and the drift of engagement as the shoe face wears.

* :mod:`.state` -- one worn state of a part: its FE contact with the worn clearance, its
  answers, the rebuild of the worn part (:class:`WornModel`);
* :mod:`.duty` -- :class:`DutyCycle`: starts per hour, held-drum slips, cutting share (options
  or a TOML file);
* :mod:`.run` -- :func:`life`: the states over the starts;
* :mod:`.result` -- :class:`Life`;
* :mod:`.figures` -- :func:`life_files`: the JSON and the pictures (answers against starts with the
  requirement limits; pressure along the arc new and worn; the worn profile).

The physics of one start and of the wear is the durability stage's
(:func:`clutchfem.durability.engagement_transient`, :mod:`clutchfem.durability.wear`).
"""

from .duty import DutyCycle
from .figures import life_files
from .result import Life
from .run import life
from .state import RebuildRefused, StateAnswers, WornModel, rebuild

__all__ = ["DutyCycle", "Life", "RebuildRefused", "StateAnswers", "WornModel", "life", "life_files", "rebuild"]
