"""Study specifications: a TOML file -> a validated, frozen :class:`StudySpec` -> points.

A spec names one design family (a concept, or a user mesh), the settings every point
shares, the requirement factors, and the varied parameters::

    [design]
    concept = "concept4"              # or mesh = "part.msh" (relative to the spec file)
    [design.set]                      # concept parameters held fixed (concept's units)
    shoe_arc = "90deg"

    [settings]                        # operating point, engine, mesh
    material = "51CrV4"
    mu = 0.165
    mesh_size = "2mm"
    engine = "engine.csv"             # columns rpm, torque [N m]; default: built-in curve

    [requirements]
    a = 1.3                           # engagement (with ripple) > a x idle rpm
    b = 1.0                           # slip rpm < b x rpm of the engine's maximum torque
    min_safety_factor = 1.0           # yield safety factor at the engine's maximum speed

    [errors]
    sample = 3                        # designs that also get their error estimate

    [vary]
    method = "grid"                   # grid | list | lhs | sobol
    [vary.params]
    flexure_thickness = {min = "1.5mm", max = "2.1mm", steps = 4}
    shoe_thickness = {values = ["5mm", "6mm", "7mm"]}

Methods: ``grid`` is the full product of every parameter's values (a list, or a range
with ``steps`` or ``step``); ``list`` zips lists of equal length (point i takes the i-th
value of each: explicit designs); ``lhs`` and ``sobol`` draw ``samples`` seeded
space-filling points (``scipy.stats.qmc``, ``seed``: :mod:`.sampling`) over the ranges
jointly, crossed with any lists (e.g. a profile choice).  Sobol wants a power of 2 samples (its balance
properties hold only then).  Integer parameters (``n_shoes``) take integer values.

The study states its error from a sample (``[errors] sample``, default 3 designs evenly
spaced in point order): those designs are also analysed on a mesh twice as fine, and their
rows carry the error bands of engagement, slip, torque and peak stress (discretisation plus
the measured model-form terms, :mod:`clutchfem.accuracy`); every other point is analysed
without (the error estimate triples a design's time).  The sample is not part of a
design's hash: changing it recomputes only the newly sampled points.

A spec file is read and validated by :func:`~.resolve.load_study` /
:func:`~.resolve.parse_spec` (:mod:`.schema`: the raw TOML structure; :mod:`.resolve`: the
values, against the concept's parameter set), before any worker starts.  This module holds
what they produce: the frozen :class:`StudySpec` with its varied :class:`Axis` es and its
points (space-filling samples: :mod:`.sampling`), the labels and units designers read
(:func:`axis_label`, :func:`display_value`), and :data:`EXAMPLE_SPEC`, the spec that
``clutchfem study --example`` prints (the data file ``example_study.toml`` beside this
module, shipped in the wheel).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from importlib import resources

import numpy as np

from ..evaluation import Settings
from .sampling import from_unit, unit_samples

#: the example spec (``clutchfem study --example``): 12 designs of concept 4, runs as it is
EXAMPLE_SPEC = resources.files(__package__).joinpath("example_study.toml").read_text(encoding="utf-8")


def example_study() -> str:
    """The text of a commented example study spec (TOML): 12 designs of concept 4 on a grid,
    every section explained; it runs as it is (``clutchfem study --example``).

    Returns
    -------
    str
        The spec's text, to write to a file and edit.

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.studies import parse_spec
    >>> text = cf.example_study()
    >>> parse_spec(text).design, len(parse_spec(text).points())
    ('concept4', 12)
    """
    return EXAMPLE_SPEC


@dataclass(frozen=True)
class Axis:
    """One varied parameter: explicit ``values`` (a list, or a range gridded) or a sampled
    range ``lo``..``hi``; ``target`` is 'concept' (a concept parameter) or 'settings' (an
    operating-point field); ``unit`` the parameter's unit (m, deg, -)."""

    name: str
    unit: str
    target: str
    values: tuple = ()
    lo: float | None = None
    hi: float | None = None
    integer: bool = False

    @property
    def sampled(self) -> bool:
        return not self.values

    def label(self) -> str:
        return axis_label(self.name, self.unit)


def axis_label(name: str, unit: str) -> str:
    """Chart/table label of a parameter in the unit designers read (mm for lengths)."""
    shown = {"m": "mm", "-": ""}.get(unit, unit)
    return f"{name} [{shown}]" if shown else name


def display_value(x, unit: str):
    """A parameter value in the unit of :func:`axis_label` (lengths in mm), without the
    float noise of the conversion (0.36 mm, not 0.36000000000000004: 12 significant digits,
    far below any parameter's resolution).

    >>> display_value(0.36e-3, "m")
    0.36
    """
    if isinstance(x, (int, float)) and not isinstance(x, bool) and unit == "m":
        return float(f"{x * 1e3:.12g}")
    return x


@dataclass(frozen=True)
class StudySpec:
    """A validated study (see module docstring): fixed settings, varied axes and a method.
    Read from a TOML file by :func:`~clutchfem.load_study`; ``clutchfem study --example``
    prints a commented one.

    Attributes
    ----------
    settings : Settings
        The fixed design, operating point, engine and requirement factors.
    axes : tuple of Axis
        The varied parameters.
    method : {"grid", "lhs", "sobol", "list"}

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.studies import EXAMPLE_SPEC, parse_spec
    >>> spec = parse_spec(EXAMPLE_SPEC)
    >>> spec.method, len(spec.points())
    ('grid', 12)
    """

    source: str
    settings: Settings
    axes: tuple[Axis, ...]
    method: str = "grid"
    samples: int | None = None
    seed: int = 0
    text: str = ""
    error_sample: int = 3
    #: a live study's point that no cached reduced model answers: "refuse" or "fe"
    #: (:mod:`clutchfem.studies.live`)
    live_outside: str = "refuse"

    @property
    def design(self) -> str:
        return self.settings.design_name

    def count(self) -> int:
        lists = [len(a.values) for a in self.axes if not a.sampled]
        if self.method == "grid":
            return math.prod(lists)
        if self.method == "list":
            return lists[0] if lists else 0
        return (self.samples or 0) * math.prod(lists)

    def error_points(self, n: int | None = None) -> list[int]:
        """Indices of the ``error_sample`` points (evenly spaced in point order, ends
        included) whose answers also get their error estimate."""
        n = self.count() if n is None else n
        k = min(self.error_sample, n)
        if k <= 0:
            return []
        return sorted({int(round(x)) for x in np.linspace(0, n - 1, k)})

    def points(self) -> list[dict]:
        """The points, in a reproducible order (``seed`` fixes the samples)."""
        if self.method == "grid":
            names = [a.name for a in self.axes]
            return [dict(zip(names, combo)) for combo in itertools.product(*(a.values for a in self.axes))]
        if self.method == "list":
            n = len(self.axes[0].values)
            return [{a.name: a.values[i] for a in self.axes} for i in range(n)]
        ranges = [a for a in self.axes if a.sampled]
        lists = [a for a in self.axes if not a.sampled]
        u = unit_samples(self.method, len(ranges), self.samples, self.seed)
        out = []
        for row in u:
            base = {a.name: from_unit(a.lo, a.hi, a.integer, x) for a, x in zip(ranges, row)}
            for combo in itertools.product(*(a.values for a in lists)):
                out.append({**base, **dict(zip((a.name for a in lists), combo))})
        return out
