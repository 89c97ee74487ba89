"""The record every validation module returns: one reproduced (or not) paper number, with the
tolerance a printed number carries (:func:`printed_value`)."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from decimal import Decimal
from typing import Literal

Status = Literal["reproduced", "differs", "computed"]


@dataclass(frozen=True)
class ValidationRecord:
    """One quantity of a source paper, compared with what clutchfem computes.

    ``id`` is stable (e.g. ``wiesik.Ms_new``); ``paper`` is the published value (None when
    the paper gives none and the row only documents a computed quantity); ``tol`` is the
    relative tolerance that counts as reproduced, chosen from the precision the paper prints
    (stated, never tuned to make a row pass).  ``note`` is a one-line reason for a
    ``differs`` row, or how the number was obtained.
    """

    id: str
    module: str
    quantity: str
    paper: float | None
    computed: float
    unit: str
    tol: float = 0.02
    note: str = ""
    status: Status = field(init=False)

    def __post_init__(self):
        if self.paper is None:
            status = "computed"
        else:
            status = "reproduced" if abs(self.rel_diff) <= self.tol else "differs"
        object.__setattr__(self, "status", status)

    @property
    def rel_diff(self) -> float:
        """(computed - paper) / |paper|; NaN when there is no paper value."""
        if self.paper is None or self.paper == 0:
            return math.nan
        return (self.computed - self.paper) / abs(self.paper)

    def to_json(self) -> dict:
        d = asdict(self)
        d["rel_diff"] = None if math.isnan(self.rel_diff) else self.rel_diff
        return d


def printed_value(printed: str) -> tuple[float, float]:
    """(value, relative tol) of a number as the paper prints it (rule R1 of the paper
    modules): half a unit of its last printed digit, relative to the value (``"10.23"`` ->
    0.005 / 10.23; ``"1.52e-7"`` -> 0.005e-7 / 1.52e-7)."""
    d = Decimal(printed)
    v = float(d)
    return v, abs(0.5 * 10.0 ** d.as_tuple().exponent / v)
