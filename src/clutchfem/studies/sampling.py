"""Space-filling samples of a study: seeded points in the unit hypercube, mapped onto ranges.

Methods ``lhs`` and ``sobol`` of a spec (:mod:`.spec`) draw ``n`` points in [0, 1)^d with
``scipy.stats.qmc`` from a seeded generator (``numpy.random.default_rng(seed)``: the same
spec gives the same points on every machine and run):

* ``lhs``: a Latin hypercube (every parameter's range cut into n equal strata, one sample
  in each);
* ``sobol``: a scrambled Sobol sequence of 2^m points (its balance properties hold only
  for a power of 2, which the spec enforces).

A unit coordinate x becomes a parameter value lo + x (hi - lo), rounded to 12 significant
digits (:func:`~.values.round12`); an integer parameter takes lo + floor(x (hi - lo + 1)),
so each of its hi - lo + 1 values gets an equal share of [0, 1).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import qmc

from ..core import round12


def unit_samples(method: str, d: int, n: int, seed: int) -> np.ndarray:
    """``n`` seeded points in the unit hypercube [0, 1)^d: Latin hypercube or scrambled Sobol."""
    rng = np.random.default_rng(seed)
    if method == "lhs":
        return qmc.LatinHypercube(d, rng=rng).random(n)
    m = int(round(math.log2(n)))
    return qmc.Sobol(d, scramble=True, rng=rng).random_base2(m)


def from_unit(lo: float, hi: float, integer: bool, x: float):
    """The value of a range [lo, hi] at unit coordinate ``x`` (see module docstring)."""
    if integer:
        lo, hi = int(lo), int(hi)
        return int(min(hi, lo + math.floor(x * (hi - lo + 1))))
    return round12(lo + x * (hi - lo))
