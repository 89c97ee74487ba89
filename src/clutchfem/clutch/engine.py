"""Engine torque curve (full throttle) and the slip-speed crossing with a clutch curve.

A curve is a table of crank speed [rpm] vs engine torque [N m], interpolated with a
monotone, shape-preserving cubic (PCHIP, :class:`Pchip`: no overshoot, so the maximum of the
interpolant is the largest table value).  :class:`Pchip` is scipy's
``scipy.interpolate.PchipInterpolator`` (the same slopes and cubic pieces, held to it in the
tests) in a few lines of numpy: importing ``scipy.interpolate`` costs 0.35 s, a third of a
live answer's whole start (docs/reduced.md), for these 20 lines.  Queries outside the table are
errors: extrapolating an engine curve silently is how wrong slip speeds are born.

The built-in default (:meth:`EngineCurve.default`) is for the 56.5 cc Husqvarna 357 XP of
seed ``000`` (fig. 2): the paper gives only the maximum, 3.40 N m at ~8000 rpm (838 rad/s),
the mean cutting torque 3.20 N m at 950 rad/s (~9070 rpm), and the range "up to ~15 000
rpm"; idle 2700 rpm and max 14 000 rpm are typical saw data.  **The shape between these
points is an ASSUMPTION** (a smooth hump typical of 2-stroke saw engines); it is flagged in
``EngineCurve.assumed`` and must be replaced by a measured curve (CSV) for design work.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core import InputError, ParameterError, brentq
from .engine_csv import read_engine_csv

__all__ = ["EngineCurve", "Pchip", "DEFAULT_CURVE_RPM", "DEFAULT_CURVE_TORQUE", "slip_rpm", "torque_crossings"]

#: a full-throttle curve whose top speed is below this [rpm] is refused as a likely rad/s
#: table (the default saw curve in rad/s ends at 1466; real small-engine curves reach
#: several thousand rpm)
MIN_TOP_RPM = 1500.0

#: ASSUMED default full-throttle curve, 56.5 cc saw (see module docstring).  Anchors from
#: seed 000: max 3.40 N m at 8000 rpm, 3.20 N m at 950 rad/s (9072 rpm).
DEFAULT_CURVE_RPM = (2500.0, 3000.0, 4000.0, 5000.0, 6000.0, 7000.0, 8000.0, 9000.0,
                     10000.0, 11000.0, 12000.0, 13000.0, 14000.0)
DEFAULT_CURVE_TORQUE = (1.90, 2.10, 2.50, 2.85, 3.12, 3.32, 3.40, 3.22,
                        2.95, 2.60, 2.20, 1.75, 1.30)


class Pchip:
    """The piecewise cubic Hermite interpolant of ``y(x)`` with PCHIP's slopes (Fritsch and
    Butland's weighted harmonic mean inside, a one-sided three-point estimate kept
    shape-preserving at the ends; linear through 2 points): monotone where the data are, no
    overshoot.  The same slopes and cubic pieces as ``scipy.interpolate.PchipInterpolator``
    (module docstring).  ``x``: increasing; a query outside ``[x[0], x[-1]]`` gives NaN.

    Examples
    --------
    >>> from clutchfem.clutch.engine import Pchip
    >>> p = Pchip([0.0, 1.0, 2.0], [0.0, 1.0, 1.0])
    >>> float(p(1.0)), float(p(1.5)) <= 1.0
    (1.0, True)
    """

    def __init__(self, x, y):
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        h = np.diff(x)
        m = np.diff(y) / h
        if len(x) == 2:
            d = np.array([m[0], m[0]])
        else:
            d = np.zeros_like(y)
            flat = (np.sign(m[1:]) != np.sign(m[:-1])) | (m[1:] == 0) | (m[:-1] == 0)
            w1, w2 = 2 * h[1:] + h[:-1], h[1:] + 2 * h[:-1]
            with np.errstate(divide="ignore", invalid="ignore"):
                whmean = (w1 / m[:-1] + w2 / m[1:]) / (w1 + w2)
            d[1:-1][~flat] = 1.0 / whmean[~flat]
            d[0] = self._end(h[0], h[1], m[0], m[1])
            d[-1] = self._end(h[-1], h[-2], m[-1], m[-2])
        t = (d[:-1] + d[1:] - 2 * m) / h
        #: the cubic of each interval in powers of (x - x_i), highest first
        self.c = np.stack((t / h, (m - d[:-1]) / h - t, d[:-1], y[:-1]))
        self.x = x

    @staticmethod
    def _end(h0: float, h1: float, m0: float, m1: float) -> float:
        """The slope at an end: one-sided three-point, kept shape-preserving."""
        d = ((2 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
        if np.sign(d) != np.sign(m0):
            return 0.0
        if np.sign(m0) != np.sign(m1) and abs(d) > 3.0 * abs(m0):
            return 3.0 * m0
        return d

    def __call__(self, q) -> np.ndarray:
        q = np.asarray(q, dtype=float)
        x = self.x
        i = np.clip(np.searchsorted(x, q, side="right") - 1, 0, len(x) - 2)
        s = q - x[i]
        c = self.c[:, i]
        out = ((c[0] * s + c[1]) * s + c[2]) * s + c[3]
        return np.where((q >= x[0]) & (q <= x[-1]), out, np.nan)


@dataclass(frozen=True)
class EngineCurve:
    """Full-throttle engine torque vs crank speed.

    rpm: strictly increasing speeds [rpm] (>= 2 points, > 0); torque: [N m], >= 0.
    ``assumed`` is True when the curve is not measured data (the built-in default);
    ``source`` says where it came from; ``idle_rpm`` is optional metadata [rpm].

    Parameters
    ----------
    rpm, torque : sequence of float
        Speeds [rpm] (strictly increasing) and full-throttle torques [N m].
    source : str
    assumed : bool
    idle_rpm : float, optional

    Examples
    --------
    >>> import clutchfem as cf
    >>> e = cf.EngineCurve((2500, 8000, 14000), (1.9, 3.4, 1.0), source="my dyno run")
    >>> e.rpm_max_torque, e.torque_at(8000), e.max_torque
    (8000.0, 3.4, 3.4)
    >>> cf.EngineCurve.default().rpm_range
    (2500.0, 14000.0)
    """

    rpm: tuple[float, ...]
    torque: tuple[float, ...]
    source: str = "user"
    assumed: bool = False
    idle_rpm: float | None = None
    _interp: Pchip = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        where = f"engine curve ({self.source})"
        try:
            rpm = np.asarray(self.rpm, dtype=float).ravel()
            tq = np.asarray(self.torque, dtype=float).ravel()
        except (TypeError, ValueError):
            raise InputError(f"{where}: rpm and torque must be sequences of numbers (rpm, N m), got "
                             f"{type(self.rpm).__name__} {self.rpm!r:.60} and {type(self.torque).__name__} "
                             f"{self.torque!r:.60}") from None
        if rpm.size != tq.size:
            raise InputError(f"{where}: {rpm.size} rpm values but {tq.size} torque values")
        if rpm.size < 2:
            raise InputError(f"{where}: needs at least 2 points (rpm, torque), got {rpm.size}")
        if not np.all(np.isfinite(rpm)) or not np.all(np.isfinite(tq)):
            raise InputError(f"{where}: rpm and torque must be finite numbers (no NaN/inf)")
        if np.any(rpm <= 0.0):
            raise InputError(f"{where}: rpm must be > 0, got min {rpm.min():g}")
        d = np.diff(rpm)
        if np.any(d == 0.0):
            dup = rpm[1:][d == 0.0]
            raise InputError(f"{where}: duplicate rpm value(s) {dup.tolist()}; rpm must be unique")
        if np.any(d < 0.0):
            i = int(np.argmax(d < 0.0))
            raise InputError(
                f"{where}: rpm must be sorted increasing; {rpm[i + 1]:g} follows {rpm[i]:g}"
            )
        if np.any(tq < 0.0):
            i = int(np.argmax(tq < 0.0))
            raise InputError(
                f"{where}: torque must be >= 0 N m; got {tq[i]:g} at {rpm[i]:g} rpm"
            )
        if not np.any(tq > 0.0):
            raise InputError(f"{where}: every torque value is 0 N m; a full-throttle curve must deliver "
                             "torque somewhere")
        if rpm.max() < MIN_TOP_RPM:
            raise InputError(
                f"{where}: the speeds end at {rpm.max():g}, but a full-throttle curve of a small engine "
                f"reaches several thousand rpm (saws 10 000-15 000): are they in rad/s? "
                f"(rpm = rad/s x 60 / (2 pi): {rpm.max():g} rad/s = {rpm.max() * 60 / (2 * np.pi):.0f} rpm)")
        if self.idle_rpm is not None and not (float(self.idle_rpm) > 0.0):
            raise ParameterError("idle_rpm", self.idle_rpm, "> 0 rpm")
        if self.idle_rpm is not None and float(self.idle_rpm) >= rpm.max():
            raise ParameterError("idle_rpm", self.idle_rpm, f"an idle speed below the curve's top speed "
                                 f"{rpm.max():g} rpm (is the curve or the idle speed in other units?)")
        object.__setattr__(self, "rpm", tuple(rpm.tolist()))
        object.__setattr__(self, "torque", tuple(tq.tolist()))
        object.__setattr__(self, "_interp", Pchip(rpm, tq))

    # ---- constructors ---------------------------------------------------------------
    @property
    def is_default(self) -> bool:
        """Whether this is the built-in curve (:meth:`default`): the same speeds, torques and
        idle speed."""
        d = self.default()
        return (np.array_equal(self.rpm, d.rpm) and np.array_equal(self.torque, d.torque)
                and self.idle_rpm == d.idle_rpm)

    @classmethod
    def default(cls) -> "EngineCurve":
        """ASSUMED curve of the 56.5 cc Husqvarna 357 XP (3.40 N m max at 8000 rpm)."""
        return cls(
            DEFAULT_CURVE_RPM,
            DEFAULT_CURVE_TORQUE,
            source="built-in 56.5 cc saw (ASSUMED shape; anchors: 3.40 N m @ 8000 rpm, "
            "3.20 N m @ 9072 rpm, seed 000)",
            assumed=True,
            idle_rpm=2700.0,
        )

    @classmethod
    def from_csv(cls, path: str | Path, idle_rpm: float | None = None) -> "EngineCurve":
        """Read a CSV with a header row naming a speed and a torque column, each with its
        unit (``rpm, torque [lbf ft]``; no unit: rpm and N m), in UTF-8 (with or without a
        byte-order mark), UTF-16 or Latin-1, separated by ``,`` or by ``;``/tab with
        decimal commas; at most :data:`~clutchfem.clutch.engine_csv.MAX_ROWS` rows sorted by
        speed.  What is read and refused: :mod:`clutchfem.clutch.engine_csv`."""
        t = read_engine_csv(path)
        source = str(path) + (f" ({'; '.join(t.notes)})" if t.notes else "")
        return cls(t.rpm, t.torque, source=source, assumed=False, idle_rpm=idle_rpm)

    @classmethod
    def of(cls, value, name: str = "engine") -> "EngineCurve":
        """The engine curve an API argument means: None -> the built-in (ASSUMED) curve, an
        :class:`EngineCurve` as it is, a path (str or Path) -> :meth:`from_csv`; anything
        else is refused naming the argument ``name``."""
        if value is None:
            return cls.default()
        if isinstance(value, cls):
            return value
        if isinstance(value, (str, os.PathLike)):
            return cls.from_csv(value)
        raise ParameterError(name, type(value).__name__, "an EngineCurve, the path of an engine curve CSV, or None "
                             "(the built-in curve)")

    # ---- queries --------------------------------------------------------------------
    @property
    def rpm_range(self) -> tuple[float, float]:
        """(min, max) rpm of the table."""
        return self.rpm[0], self.rpm[-1]

    @property
    def max_torque(self) -> float:
        """Largest torque [N m] (a table value: PCHIP does not overshoot)."""
        return max(self.torque)

    @property
    def rpm_max_torque(self) -> float:
        """Crank speed [rpm] of the maximum torque (first one if several)."""
        return self.rpm[int(np.argmax(self.torque))]

    def torque_at(self, rpm) -> np.ndarray | float:
        """Engine torque [N m] at speed(s) ``rpm`` (scalar in -> float out).

        Raises InputError naming the offending rpm and the curve's range when any query lies
        outside the table.
        """
        q = np.asarray(rpm, dtype=float)
        lo, hi = self.rpm_range
        bad = ~np.isfinite(q) | (q < lo) | (q > hi)
        if np.any(bad):
            first = q[bad].ravel()[0] if q.ndim else float(q)
            raise InputError(
                f"rpm = {first:g} is outside the engine curve's range [{lo:g}, {hi:g}] rpm "
                f"({self.source}); extend the curve or restrict the query"
            )
        out = self._interp(q)
        return float(out) if q.ndim == 0 else out

    __call__ = torque_at


def slip_rpm(
    curve: EngineCurve,
    clutch_torque_at_rpm: Callable[[np.ndarray], np.ndarray],
    rpm_min: float | None = None,
    rpm_max: float | None = None,
    n_grid: int = 2001,
    grid: np.ndarray | None = None,
) -> float | None:
    """Slip speed [rpm]: first speed where the clutch torque reaches the engine torque.

    With the drum locked (chain brake) and full throttle the engine runs up its curve until
    the clutch's slip torque equals the engine torque (thesis 2.1).  The crossing is bracketed
    on ``grid`` (default: ``n_grid`` equal steps over [rpm_min, rpm_max], the curve's range)
    and refined by bisection (robust to an ``inf`` clutch torque of a self-locking shoe).
    Returns ``None`` when the clutch never holds the engine over the whole range (it slips at
    every speed and the engine runs to its governed maximum); returns ``rpm_min`` when the
    clutch already holds at ``rpm_min``.
    """
    crossings = torque_crossings(curve, clutch_torque_at_rpm, rpm_min, rpm_max, n_grid, grid)
    a = curve.rpm_range[0] if rpm_min is None else float(rpm_min)
    if bool(holds(curve, clutch_torque_at_rpm, np.array([a]))[0]):
        return float(a)
    up = [x for x, d in crossings if d == "up"]
    return up[0] if up else None


def holds(curve: EngineCurve, clutch_torque_at_rpm, x, t=None) -> np.ndarray:
    """The clutch holds the engine at speeds ``x``: its torque is > 0 (it transmits) and
    reaches the engine torque.  (0 >= 0 where neither delivers torque is *not* holding.)
    ``t``: the clutch torques at ``x`` when already evaluated."""
    t = np.asarray(clutch_torque_at_rpm(x) if t is None else t, dtype=float)
    e = t - curve.torque_at(x)
    if np.any(np.isnan(e)):
        raise InputError("clutch torque function returned NaN")
    return (e >= 0.0) & (t > 0.0)


def torque_crossings(
    curve: EngineCurve,
    clutch_torque_at_rpm: Callable[[np.ndarray], np.ndarray],
    rpm_min: float | None = None,
    rpm_max: float | None = None,
    n_grid: int = 2001,
    grid: np.ndarray | None = None,
) -> list[tuple[float, str]]:
    """Every speed [rpm] where the clutch torque curve crosses the engine curve.

    Returns ``(rpm, direction)`` pairs in increasing rpm; ``direction`` is ``'up'`` where the
    clutch torque rises through the engine torque (a stable slip point: above it the clutch
    holds more than the engine gives) and ``'down'`` where it falls below again (possible
    with a drooping FE curve or a user engine curve with a late torque peak).  Changes of
    "holds" (:func:`holds`) are bracketed on ``grid`` (default: ``n_grid`` equal steps over
    the range) and refined to 1e-9 relative: by Brent's method where clutch minus engine
    torque changes sign strictly with the clutch transmitting at both ends (the curves are
    continuous), else by bisection of "holds" (which also works with an ``inf`` clutch
    torque and needs no continuity).  Two crossings closer
    together than the bracketing grid's spacing can be missed; :func:`slip_rpm` is the first
    ``'up'`` crossing (or ``rpm_min`` when the clutch holds from the start).
    """
    lo, hi = curve.rpm_range
    a = lo if rpm_min is None else float(rpm_min)
    b = hi if rpm_max is None else float(rpm_max)
    if not (lo <= a < b <= hi):
        raise ParameterError("rpm_min, rpm_max", (a, b), f"lo < hi inside the curve [{lo:g}, {hi:g}] rpm")
    if grid is None:
        grid = np.linspace(a, b, int(n_grid))
    else:
        grid = np.union1d(np.asarray(grid, dtype=float), [a, b])
        grid = grid[(grid >= a) & (grid <= b)]

    t = np.asarray(clutch_torque_at_rpm(grid), dtype=float)
    h = holds(curve, clutch_torque_at_rpm, grid, t)
    return [_refine(curve, clutch_torque_at_rpm, float(grid[i]), float(grid[i + 1]), t[i], t[i + 1], bool(h[i + 1]))
            for i in np.nonzero(h[1:] != h[:-1])[0]]


def first_slip_rpm(
    curve: EngineCurve,
    clutch_torque_at_rpm: Callable[[np.ndarray], np.ndarray],
    grid: np.ndarray,
) -> float | None:
    """:func:`slip_rpm` on ``grid`` without the crossings past the first upward one: the
    grid is walked upwards and the walk stops there, so a clutch torque that costs an FE
    solve per speed is not evaluated beyond the answer.  Equal to ``slip_rpm(curve, f,
    grid=grid)`` (same bracket, same refinement)."""
    lo, hi = curve.rpm_range
    grid = np.union1d(np.asarray(grid, dtype=float), [lo, hi])
    grid = grid[(grid >= lo) & (grid <= hi)]
    t_prev, h_prev = None, None
    engine = np.asarray(curve.torque_at(grid), dtype=float)
    for i, x in enumerate(grid):
        t = float(np.asarray(clutch_torque_at_rpm(np.array([x])), dtype=float)[0])
        e = t - float(engine[i])
        if math.isnan(e):
            raise InputError("clutch torque function returned NaN")
        h = e >= 0.0 and t > 0.0
        if i == 0 and h:
            return float(lo)
        if h and not h_prev:
            return _refine(curve, clutch_torque_at_rpm, float(grid[i - 1]), float(x), t_prev, t, True)[0]
        t_prev, h_prev = t, h
    return None


def _refine(curve: EngineCurve, clutch_torque_at_rpm, x0: float, x1: float, t0: float, t1: float,
            up: bool) -> tuple[float, str]:
    """The crossing in the grid bracket [x0, x1] (clutch torques t0, t1 there; ``up``: the
    clutch holds at x1 and not at x0), refined to 1e-9 relative (see :func:`torque_crossings`)."""
    f0, f1 = t0 - curve.torque_at(x0), t1 - curve.torque_at(x1)
    if t0 > 0 and t1 > 0 and np.isfinite(f0) and np.isfinite(f1) and f0 * f1 < 0:
        # a strict sign change of a continuous difference: Brent's method (a few
        # evaluations instead of ~30 halvings; each may be an FE contact solve)
        def diff(x):
            return float(np.asarray(clutch_torque_at_rpm(np.array([x])), dtype=float)[0]) - curve.torque_at(x)

        return brentq(diff, x0, x1, xtol=1e-9 * max(1.0, x1), rtol=1e-12), "up" if up else "down"
    for _ in range(60):
        xm = 0.5 * (x0 + x1)
        if bool(holds(curve, clutch_torque_at_rpm, np.array([xm]))[0]) == up:
            x1 = xm
        else:
            x0 = xm
        if x1 - x0 < 1e-9 * max(1.0, x1):
            break
    return 0.5 * (x0 + x1), "up" if up else "down"
