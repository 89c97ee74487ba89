"""The search space of an optimisation: the free parameters with their ranges, mapped onto
the unit box (:class:`Space`, :func:`make_space`), and the parameters a concept frees by
default (:func:`clutchfem.geometry.default_free`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import ParameterError
from ..core import values as V


@dataclass
class Space:
    """Free parameters with their search ranges, mapped to [0, 1]."""

    P: type
    names: list[str]
    lo: np.ndarray
    hi: np.ndarray

    def to_point(self, x: np.ndarray) -> tuple[dict, np.ndarray]:
        """(point texts, snapped x) of normalised x."""
        texts, xs = {}, np.empty(len(self.names))
        for k, n in enumerate(self.names):
            v = self.lo[k] + float(np.clip(x[k], 0.0, 1.0)) * (self.hi[k] - self.lo[k])
            val, txt = V.snap(self.P, n, v)
            texts[n] = txt
            xs[k] = (val - self.lo[k]) / (self.hi[k] - self.lo[k])
        return texts, xs

    def from_params(self, p) -> np.ndarray:
        return np.array([(getattr(p, n) - self.lo[k]) / (self.hi[k] - self.lo[k]) for k, n in enumerate(self.names)])

    @property
    def min_step(self) -> np.ndarray:
        """Each parameter's snapping resolution in normalised units."""
        return np.array([V.resolution(self.P, n) / (self.hi[k] - self.lo[k]) for k, n in enumerate(self.names)])


def make_space(P, free: list[str], ranges: dict | None = None, start=None) -> Space:
    """The search space of the free parameters (floats with a declared range)."""
    lo, hi = [], []
    for n in sorted(set(ranges or {}) - set(free)):
        raise ParameterError(n, ":".join(V.to_text(P, n, x) for x in ranges[n]), f"a range of a free parameter: {n} "
                             f"is not free in this search (free: "
                             f"{', '.join(free)}); add it to --free, or drop its --range", "--range")
    for n in free:
        if n not in P.model_fields:
            raise ParameterError(n, None, "a parameter of the concept; known: " + ", ".join(P.model_fields), "--free")
        f = P.model_fields[n]
        if f.annotation is not float:
            raise ParameterError(n, None, "a real-valued parameter with a range (choices and counts are set with "
                                          "--set)", "--free")
        a, b = V.param_bounds(P, n)
        if ranges and n in ranges:
            lo_d, hi_d = a, b
            a, b = ranges[n]
            text = f"{V.to_text(P, n, a)}:{V.to_text(P, n, b)}"
            if not a < b:
                raise ParameterError(n, text, "LO:HI with LO < HI", "--range")
            if (lo_d is not None and a < lo_d) or (hi_d is not None and b > hi_d):
                raise ParameterError(n, text, f"a range within the declared range [{V.to_text(P, n, lo_d)}, "
                                     f"{V.to_text(P, n, hi_d)}]", "--range")
        if a is None or b is None or not a < b:
            raise ParameterError(n, None, "a parameter with a finite range to search", "--free")
        if start is not None and not (a <= getattr(start, n) <= b):
            raise ParameterError(n, getattr(start, n), f"a start value inside the search range "
                                 f"[{V.to_text(P, n, a)}, {V.to_text(P, n, b)}]", "--range")
        lo.append(float(a))
        hi.append(float(b))
    return Space(P, list(free), np.array(lo), np.array(hi))
