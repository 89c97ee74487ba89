"""The shoe's outer profile: the clearance to the drum along the shoe, from the profile kinds
(concentric, eccentric, linear) to the ``table`` profile of 17 control values joined by a C2
cubic spline (what shoe-profile compensation writes)."""

from __future__ import annotations

from functools import lru_cache
from typing import TYPE_CHECKING, Literal

import numpy as np

from ..core import param

if TYPE_CHECKING:
    from scipy.interpolate import CubicSpline

__all__ = ["MIN_PROFILE_CLEARANCE", "Profile", "TABLE_FIELDS", "TABLE_N", "table_cardinal", "table_param",
           "table_spline"]

Profile = Literal["concentric", "eccentric", "linear", "table"]

#: number of clearance control values of the ``table`` profile (equally spaced along the shoe;
#: 17: the contact pressure on a rigid drum moves by MPa per micrometre of profile, and 9
#: values left a 0.3-10 um misfit near the ends of an 80 % target arc, 17 values 0.2-2 nm;
#: see clutchfem.targets.compensation)
TABLE_N = 17
#: names of the table profile's control values, root (s = 0) to tip (s = 1)
TABLE_FIELDS = tuple(f"table_c{k}" for k in range(TABLE_N))
#: smallest clearance [m] a profile may leave anywhere along the shoe (a rest gap below this
#: is a part touching the drum, in the model and on the bench)
MIN_PROFILE_CLEARANCE = 0.02e-3


def _spline(values: np.ndarray) -> CubicSpline:
    """The one spline of the table profile: cubic, not-a-knot (C2), through ``values`` (along
    axis 0) at n equally spaced knots s = 0, 1/(n-1), ..., 1."""
    from scipy.interpolate import CubicSpline  # (a table profile's only: 0.35 s of a live answer's start)

    return CubicSpline(np.linspace(0.0, 1.0, len(values)), values, bc_type="not-a-knot", axis=0)


@lru_cache(maxsize=256)
def table_spline(values: tuple[float, ...]) -> CubicSpline:
    """The clearance c(s) [m] of a table profile: a cubic spline (not-a-knot, C2) through the
    control values at s = 0, 1/(n-1), ..., 1 (s: arc fraction from root to tip)."""
    return _spline(np.asarray(values, dtype=float))


def table_cardinal(s, n: int = TABLE_N) -> np.ndarray:
    """(len(s), n) cardinal functions phi_k of the table spline at arc fractions ``s``: the
    spline is linear in its control values, c(s) = sum_k v_k phi_k(s) (what shoe-profile
    compensation fits)."""
    return _spline(np.eye(n))(np.asarray(s))


def table_param(k: int):
    return param(0.6e-3, "m", 0.05e-3, 3e-3,
                 f"clearance at {k}/{TABLE_N - 1} of the shoe arc from the root (table profile only; "
                 "a C2 cubic spline through all of them)", f"c_{k}")
