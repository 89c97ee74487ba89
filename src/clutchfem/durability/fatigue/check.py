"""The fatigue check of a part: load cycles (:class:`LoadCycle`), Miner's damage over the
cycle types, the load factor at which it reaches 1 at every point, and the result at the
worst point (:func:`fatigue_check`, :class:`FatigueResult`).

Input: for every *cycle type* the plane stresses (sxx, syy, sxy) [Pa] at the same points
(e.g. the raw element-vertex stresses of the elastic model) in the two extreme states of
the cycle, A and B, and the number of such cycles in the clutch's life.  Typical cycle
types (issue 14): start-stop (A = at rest, B = maximum speed; ~1e4-1e5), the two-stroke
speed ripple at the operating speed (A, B = states at w (1 -+ delta); ~1e7, one per
revolution) and the load-torque fluctuation while the clutch holds (A, B = states at the
minimum and maximum transmitted torque).  The elastic model is linear between solved
states, so a cycle's stress path is the straight line from A to B.

Damage and safety factor
------------------------
Several cycle types combine by Palmgren-Miner, D = sum n_i / N_i(s_ar,i) (s_ar, N from
:mod:`.criteria`); a cycle type below the knee contributes nothing under 'elementary', so
Miner only acts where more than one type is finite-life.

Safety factor: the load multiplier X at which the Miner sum reaches 1, all stresses (means
and amplitudes of every cycle type) scaled together: D(X) = 1, found by bisection per
point (D is monotone in X).  For one cycle type with at least N_e cycles this is Shigley's
infinite-life factor, e.g. Goodman n = 1 / (s_a/S_e + s_m/S_ut); for finite-life types it
is the factor on stress for the required life.  The governing cycle is the one with the
largest share of the damage at X at the worst point.  Langer's first-cycle yield line,
n_y = S_y / max(vM(A), vM(B)), is reported separately.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ...core import InputError, ParameterError
from .criteria import cycles_to_failure, endurance_limit, reversed_equivalent, single_cycle_factor
from .strength import ASSUMED, FatigueParams
from .stresses import amplitude_mean, equivalent_stresses, stress_array

if TYPE_CHECKING:  # (the mesh and the FE model: a fatigue check of given stresses needs neither)
    from ...mesh import ClutchMesh, Location

__all__ = ["FatigueResult", "LoadCycle", "candidate_points", "fatigue_check"]


@dataclass(frozen=True)
class LoadCycle:
    """One cycle type: the stresses at the same points in its two extreme states [Pa],
    arrays (3, npts) of (sxx, syy, sxy) or (6, npts) of 3-D Voigt stresses, and how many such cycles
    the part must survive."""

    name: str
    state_a: np.ndarray
    state_b: np.ndarray
    count: float

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name.strip():
            raise ParameterError("name", self.name, "a non-empty name of the cycle type")
        amp, mean = amplitude_mean(self.state_a, self.state_b)
        object.__setattr__(self, "state_a", stress_array("state_a", self.state_a))
        object.__setattr__(self, "state_b", stress_array("state_b", self.state_b))
        try:
            n = float(self.count)
        except (TypeError, ValueError):
            raise ParameterError("count", self.count, "a number of cycles in [1, 1e12]") from None
        if not (math.isfinite(n) and 1.0 <= n <= 1e12):
            raise ParameterError("count", self.count, "a number of cycles in [1, 1e12]")
        object.__setattr__(self, "count", n)

    @classmethod
    def from_mean_amplitude(cls, name: str, mean, amplitude, count: float) -> "LoadCycle":
        """A cycle between mean - amplitude and mean + amplitude (tensors (3, npts) [Pa])."""
        m = stress_array("mean", mean)
        a = stress_array("amplitude", amplitude)
        if m.shape != a.shape:
            raise InputError(f"mean and amplitude must have the same shape (got {m.shape} and {a.shape})")
        return cls(name=name, state_a=m - a, state_b=m + a, count=count)

    @property
    def npts(self) -> int:
        return int(self.state_a.shape[1])

    def equivalent(self) -> tuple[np.ndarray, np.ndarray]:
        """(s_a, s_m) [Pa] at every point."""
        return equivalent_stresses(*amplitude_mean(self.state_a, self.state_b))


def candidate_points(cycles: Sequence["LoadCycle"], p: FatigueParams, Se: float | None = None) -> np.ndarray:
    """Indices of the points that can hold the smallest combined safety factor: a screen
    that lets :func:`fatigue_check` bisect a few points instead of every one, exactly.

    With C cycle types, X_i(n) the closed-form factor of type i alone with n cycles
    (:func:`single_cycle_factor`): the combined factor of a point lies between
    L = min_i X_i(C n_i) (at that load every type's damage is <= 1/C, the sum <= 1) and
    U = min_i X_i(n_i) (one type alone reaches 1).  The worst point p* has
    L(p*) <= X(p*) <= min U, so it is among the points with L <= min U (all points are
    returned if there is no finite bound)."""
    if Se is None:
        Se = endurance_limit(p)[0]
    C = len(cycles)
    eq = [c.equivalent() for c in cycles]
    U = np.min([single_cycle_factor(sa, sm, c.count, p, Se) for (sa, sm), c in zip(eq, cycles)], axis=0)
    L = np.min([single_cycle_factor(sa, sm, C * c.count, p, Se) for (sa, sm), c in zip(eq, cycles)], axis=0)
    bound = float(np.min(U))
    if not math.isfinite(bound):
        return np.arange(len(U))
    return np.nonzero(L <= bound * (1.0 + 1e-9))[0]


@dataclass(frozen=True)
class FatigueResult:
    """What :func:`fatigue_check` returns (stresses in Pa, at the worst point unless noted)."""

    safety_factor: float
    worst_index: int
    governing_cycle: str
    damage_at_worst: float
    max_damage: float
    per_cycle: tuple
    point_safety_factor: np.ndarray
    yield_safety_factor: float
    yield_worst_index: int
    endurance_limit_Pa: float
    factors: dict
    params: dict
    worst_xy_m: tuple[float, float] | None = None
    location: Location | None = None
    assumed: tuple[str, ...] = field(default=())

    def to_json(self) -> dict:
        return {"fatigue_safety_factor": self.safety_factor, "governing_cycle": self.governing_cycle,
                "worst_index": self.worst_index,
                "worst_xy_m": None if self.worst_xy_m is None else list(self.worst_xy_m),
                "location": None if self.location is None else self.location.to_json(),
                "damage_at_worst": self.damage_at_worst, "max_damage": self.max_damage,
                "per_cycle": [dict(c) for c in self.per_cycle],
                "yield_safety_factor": self.yield_safety_factor, "yield_worst_index": self.yield_worst_index,
                "endurance_limit_Pa": self.endurance_limit_Pa, "factors": dict(self.factors),
                "params": dict(self.params), "assumed": list(self.assumed)}


def _damage(X: np.ndarray, sa: np.ndarray, sm: np.ndarray, n: np.ndarray, p: FatigueParams,
            Se: float) -> np.ndarray:
    """Miner damage per cycle type (C, P) with all stresses scaled by X (P,)."""
    sar = reversed_equivalent(sa * X, sm * X, p.ultimate_strength, p.mean_stress_rule)
    N = cycles_to_failure(sar, p, Se)
    with np.errstate(divide="ignore"):
        return np.where(N > 0, n[:, None] / N, np.inf)


def _load_factor(sa, sm, n, p, Se, sections: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Per point the X with D(X) = 1: ``sections``-section search in log X on [1e-6, 1e6]
    (D is monotone in X; every pass evaluates D at ``sections`` - 1 interior points of each
    point's bracket at once and keeps the sub-bracket where D crosses 1, until the brackets
    reach adjacent doubles); returns (X = geometric mean of the bracket, its upper end)."""
    P = sa.shape[1]
    lo = np.full(P, math.log(1e-6))
    hi = np.full(P, math.log(1e6))
    never = _damage(np.exp(hi), sa, sm, n, p, Se).sum(axis=0) < 1.0  # no stress: no damage at any X
    frac = np.arange(1, sections) / sections
    for _ in range(64):
        t = lo[:, None] + (hi - lo)[:, None] * frac[None, :]  # (P, sections - 1)
        X = np.exp(t)
        sar = reversed_equivalent(sa[:, :, None] * X, sm[:, :, None] * X, p.ultimate_strength, p.mean_stress_rule)
        N = cycles_to_failure(sar, p, Se)
        with np.errstate(divide="ignore"):
            D = np.where(N > 0, n[:, None, None] / N, np.inf).sum(axis=0)  # (P, sections - 1)
        up = D >= 1.0
        first = np.where(up.any(axis=1), up.argmax(axis=1), sections - 1)  # first interior point with D >= 1
        rows = np.arange(P)
        new_hi = np.where(first < sections - 1, t[rows, np.minimum(first, sections - 2)], hi)
        new_lo = np.where(first > 0, t[rows, np.maximum(first - 1, 0)], lo)
        if np.array_equal(new_hi, hi) and np.array_equal(new_lo, lo):
            break  # adjacent doubles: no interior point left
        lo, hi = new_lo, new_hi
    X = np.exp(0.5 * (lo + hi))
    X[never] = np.inf
    return X, np.exp(hi)


def fatigue_check(cycles: Sequence[LoadCycle], params: FatigueParams | None = None, *,
                  xy=None, cm: ClutchMesh | None = None, element=None) -> FatigueResult:
    """Fatigue safety factor of the part under the cycle types ``cycles`` (module docstring).

    ``xy`` (2, npts) [m]: the points' coordinates (for the worst point's position);
    with ``cm`` the worst point's location is named (:func:`name_location`), using
    ``element`` (npts,) -- the element each point belongs to, e.g. ``arange(nelem).repeat(3)``
    for the solver's raw vertex stresses -- when given."""
    p = params or FatigueParams()
    if not isinstance(p, FatigueParams):
        raise InputError(f"params must be FatigueParams (got {type(p).__name__})")
    cycles = list(cycles)
    if not cycles:
        raise InputError("fatigue_check: no load cycles given")
    for c in cycles:
        if not isinstance(c, LoadCycle):
            raise InputError(f"fatigue_check: every cycle must be a LoadCycle (got {type(c).__name__})")
    names = [c.name for c in cycles]
    if len(set(names)) != len(names):
        raise InputError(f"fatigue_check: cycle names must be unique (got {names})")
    npts = cycles[0].npts
    for c in cycles:
        if c.npts != npts:
            raise InputError(f"fatigue_check: cycle '{c.name}' has {c.npts} points, '{cycles[0].name}' {npts}")
    if xy is not None:
        xy = np.asarray(xy, dtype=float)
        if xy.shape != (2, npts) or not np.all(np.isfinite(xy)):
            raise InputError(f"fatigue_check: xy must be finite with shape (2, {npts}) (got {xy.shape})")
    Se, k = endurance_limit(p)
    eq = [c.equivalent() for c in cycles]
    sa = np.stack([e[0] for e in eq])
    sm = np.stack([e[1] for e in eq])
    n = np.array([c.count for c in cycles])
    X, Xhi = _load_factor(sa, sm, n, p, Se)
    worst = int(np.argmin(X))
    D1 = _damage(np.ones(npts), sa, sm, n, p, Se)
    Dtot = D1.sum(axis=0)
    share = _damage(Xhi[worst:worst + 1], sa[:, worst:worst + 1], sm[:, worst:worst + 1], n, p, Se)[:, 0]
    gov = int(np.argmax(share))
    sar1 = reversed_equivalent(sa[:, worst], sm[:, worst], p.ultimate_strength, p.mean_stress_rule)
    N1 = cycles_to_failure(sar1, p, Se)
    per = []
    # each type alone at the worst point: closed form (equals the bisection for one type)
    X_alone = single_cycle_factor(sa[:, worst], sm[:, worst], n, p, Se)
    for i, c in enumerate(cycles):
        Xi = X_alone[i:i + 1]
        per.append({"name": c.name, "count": float(n[i]), "amplitude_Pa": float(sa[i, worst]),
                    "mean_Pa": float(sm[i, worst]), "reversed_equivalent_Pa": float(sar1[i]),
                    "allowed_cycles": float(N1[i]), "damage": float(D1[i, worst]),
                    "safety_factor_alone": float(Xi[0]),
                    "damage_share_at_failure": (float(share[i] / share.sum())
                                                if np.isfinite(share).all() and share.sum() > 0 else float(i == gov))})
    from ...fe import von_mises

    vmax = np.max(np.stack([np.maximum(von_mises(c.state_a), von_mises(c.state_b)) for c in cycles]), axis=0)
    with np.errstate(divide="ignore"):
        ny = np.where(vmax > 0, p.yield_strength / np.where(vmax > 0, vmax, 1.0), np.inf)
    wy = int(np.argmin(ny))
    wxy = None if xy is None else (float(xy[0, worst]), float(xy[1, worst]))
    loc = None
    if cm is not None:
        if xy is None:
            raise InputError("fatigue_check: naming the location needs the points' coordinates xy")
        el = None
        if element is not None:
            element = np.asarray(element)
            if element.shape != (npts,):
                raise InputError(f"fatigue_check: element must have shape ({npts},) (got {element.shape})")
            el = int(element[worst])
        from ...mesh import name_location  # (names a point on the mesh)

        loc = name_location(cm, xy[:, worst], element=el)
    return FatigueResult(safety_factor=float(X[worst]), worst_index=worst, governing_cycle=names[gov],
                         damage_at_worst=float(Dtot[worst]), max_damage=float(Dtot.max()), per_cycle=tuple(per),
                         point_safety_factor=X, yield_safety_factor=float(ny[wy]), yield_worst_index=wy,
                         endurance_limit_Pa=float(Se), factors=k, params=p.model_dump(), worst_xy_m=wxy,
                         location=loc, assumed=ASSUMED)
