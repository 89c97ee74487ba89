"""Uniform shaft pinned at two bearings with a rigid disc on its overhang: transverse
vibration, natural frequencies and the first critical (forward whirl) speed.

Mechanics shared by the seed-004 paper reproduction (:mod:`clutchfem.validation.shaft`, a
circular-saw shaft) and the chainsaw crankshaft whirl of a clutch design
(:mod:`clutchfem.clutch.crankshaft`): the crankshaft carrying the clutch and drum on its
overhang has the same layout.

Model (seed 004, eqs 1-13).  Uniform Euler-Bernoulli shaft (mass per length ``mu = rho A``,
bending stiffness ``EI``), pinned at ``x = 0`` and ``x = l1``, free end at ``x = l1 + l2``
carrying a rigid disc of mass ``M`` and rotary inertia ``J`` about a diameter.  With
``w(x, t) = W(x) cos(omega t)`` and ``beta^4 = omega^2 mu / EI`` (4) each span has
``W = C1 sin + C2 cos + C3 sinh + C4 cosh (beta x)`` (6) and eight conditions (7)-(9)::

    W1(0) = 0, W1''(0) = 0                     pin at x = 0
    W1(l1) = 0, W2(l1) = 0                     pin at x = l1 (both sides)
    W1'(l1) = W2'(l1), W1''(l1) = W2''(l1)     slope and moment continuous
    EI W2''(L) =  J omega^2 W2'(L)             disc rotary inertia (tip moment)
    EI W2'''(L) = -M omega^2 W2(L)             disc inertia force (tip shear)

The shear jumps at ``x = l1`` by the unknown support reaction, so shear continuity is *not*
a condition.  Frequency equation: ``det A(beta) = 0`` (11); ``omega = beta^2 sqrt(EI/mu)``
(13).  Note that ``beta`` depends only on ``mu, M, J, l1, l2``: the choice of ``I_z`` only
enters (13).

Well-conditioned form (ours, not the paper's): each span uses its local coordinate
``xi`` in ``[0, l]`` and the bounded basis ``sin(b xi), cos(b xi), exp(-b xi),
exp(-b (l - xi))`` (same span as sin/cos/sinh/cosh), each condition is written on
``W, W'/b, W''/b^2, W'''/b^3`` and the two tip rows are divided by ``1 + |coefficient|``.
The determinant is then an entire, O(1) function of ``beta``: no overflow of ``cosh`` and
no poles.  Roots are bracketed by a sign-change scan and refined with ``brentq``; a sign
change across which ``|det|`` does not drop (a pole, should a caller pass a meromorphic
form) is rejected.

Two systems are offered (``model``): ``"physical"``, the conditions above, and
``"as_printed"``, the seed-004 paper's system (10) exactly as printed (shear continuity at
``x = l1`` instead of ``W2(l1) = 0``, and ``+M omega^2`` at the tip): it is wrong, but it is
what reproduces the paper's tables; :mod:`clutchfem.validation.shaft` says why.

Spinning disc.  ``J`` may be negative: for a disc spinning at Omega and whirling forward
at omega = Omega (synchronous forward whirl, the critical speed that unbalance excites) the
gyroscopic moment turns ``J`` into ``I_d - I_p``.  The independent Hermite beam FE model
(:func:`fe_frequency_coefficients`) checks the determinant's roots, ``J < 0`` included.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Literal

import numpy as np
from scipy.linalg import eigh
from scipy.optimize import brentq

from ..core import ParameterError, SolverError

ShaftModel = Literal["physical", "as_printed"]


# --------------------------------------------------------------------------------------
# System definition
# --------------------------------------------------------------------------------------


def finite_param(name: str, value: float, *, positive: bool = True, allow_zero: bool = False,
                 unit: str = "") -> float:
    """``float(value)`` if finite (and > 0, or >= 0 with ``allow_zero``, unless
    ``positive=False``); else a :class:`ParameterError` naming ``name``, its value and the
    allowed range in ``unit``."""
    v = float(value)
    if not math.isfinite(v):
        raise ParameterError(name, value, f"finite number {unit}".strip())
    if positive and (v < 0 or (v == 0 and not allow_zero)):
        rel = ">= 0" if allow_zero else "> 0"
        raise ParameterError(name, value, f"{rel} {unit}, finite".strip())
    return v


@dataclass(frozen=True)
class OverhungShaft:
    """Uniform shaft pinned at x = 0 and x = l1 with a rigid disc at the free end l1 + l2.

    ``tip_rotary_inertia_kg_m2`` is the disc's rotary inertia *about a diameter* as it
    enters the tip-moment condition; it may be negative (``I_d - I_p`` for synchronous
    forward whirl of a spinning disc).  SI units throughout.
    """

    span_m: float  # l1, bearing span
    overhang_m: float  # l2
    mass_per_length_kg_m: float  # mu = rho A
    bending_stiffness_N_m2: float  # E I
    tip_mass_kg: float = 0.0  # M
    tip_rotary_inertia_kg_m2: float = 0.0  # J

    def __post_init__(self):
        finite_param("span_m", self.span_m, unit="m")
        finite_param("overhang_m", self.overhang_m, unit="m")
        finite_param("mass_per_length_kg_m", self.mass_per_length_kg_m, unit="kg/m")
        finite_param("bending_stiffness_N_m2", self.bending_stiffness_N_m2, unit="N m^2")
        finite_param("tip_mass_kg", self.tip_mass_kg, allow_zero=True, unit="kg")
        finite_param("tip_rotary_inertia_kg_m2", self.tip_rotary_inertia_kg_m2, positive=False,
                unit="kg m^2")

    @classmethod
    def round_shaft(cls, *, diameter_m: float, E: float, rho: float, span_m: float,
                    overhang_m: float, tip_mass_kg: float = 0.0,
                    tip_rotary_inertia_kg_m2: float = 0.0,
                    second_moment: Literal["diametral", "polar"] = "diametral") -> OverhungShaft:
        """Solid round shaft: ``A = pi d^2/4``, ``I = pi d^4/64`` (``"polar"``: the paper's
        ``pi d^4/32``, wrong for bending; kept to reproduce eq 13)."""
        d = finite_param("diameter_m", diameter_m, unit="m")
        finite_param("E", E, unit="Pa")
        finite_param("rho", rho, unit="kg/m^3")
        if second_moment not in ("diametral", "polar"):
            raise ParameterError("second_moment", second_moment, "'diametral' or 'polar'")
        i = math.pi * d**4 / (64 if second_moment == "diametral" else 32)
        return cls(span_m, overhang_m, rho * math.pi * d**2 / 4, E * i, tip_mass_kg,
                   tip_rotary_inertia_kg_m2)

    @property
    def length_m(self) -> float:
        return self.span_m + self.overhang_m

    def omega(self, beta):
        """Natural circular frequency [rad/s] from beta [1/m]: beta^2 sqrt(EI/mu), eq (13)."""
        return np.asarray(beta) ** 2 * math.sqrt(self.bending_stiffness_N_m2
                                                 / self.mass_per_length_kg_m)


# --------------------------------------------------------------------------------------
# (a) Exact frequency equation: 8x8 determinant
# --------------------------------------------------------------------------------------


def _basis(b: np.ndarray, xi: float, length: float) -> np.ndarray:
    """Rows W, W'/b, W''/b^2, W'''/b^3 of the bounded basis at local coordinate xi.

    Basis: sin(b xi), cos(b xi), exp(-b xi), exp(-b (l - xi)).  Shape (n, 4, 4)."""
    s, c = np.sin(b * xi), np.cos(b * xi)
    e1, e2 = np.exp(-b * xi), np.exp(-b * (length - xi))
    out = np.empty(np.shape(b) + (4, 4))
    for row, (a0, a1, a2) in enumerate(((s, c, e1), (c, -s, -e1), (-s, -c, e1), (-c, s, -e1))):
        out[..., row, 0], out[..., row, 1], out[..., row, 2], out[..., row, 3] = a0, a1, a2, e2
    return out


def frequency_matrix(beta, shaft: OverhungShaft, model: ShaftModel = "physical") -> np.ndarray:
    """Scaled 8x8 matrix of the boundary/continuity conditions, shape (n, 8, 8).

    Unknowns: the four basis amplitudes of span 1 then of span 2.  ``model="physical"`` is
    the correct system (module docstring); ``"as_printed"`` is the paper's system (10):
    shear continuity at x = l1 instead of ``W2(l1) = 0`` and ``+M omega^2`` at the tip.
    """
    if model not in ("physical", "as_printed"):
        raise ParameterError("model", model, "'physical' or 'as_printed'")
    b = np.atleast_1d(np.asarray(beta, dtype=float))
    l1, l2, mu = shaft.span_m, shaft.overhang_m, shaft.mass_per_length_kg_m
    n = b.size
    A = np.zeros((n, 8, 8))
    s10, s1l = _basis(b, 0.0, l1), _basis(b, l1, l1)
    s20, s2l = _basis(b, 0.0, l2), _basis(b, l2, l2)
    A[:, 0, :4] = s10[:, 0]  # W1(0) = 0
    A[:, 1, :4] = s10[:, 2]  # W1''(0) = 0
    A[:, 2, :4] = s1l[:, 0]  # W1(l1) = 0
    if model == "physical":
        A[:, 3, 4:] = s20[:, 0]  # W2(l1) = 0
    else:  # paper (10): shear continuity (the static reaction term drops from det)
        A[:, 3, :4] = s1l[:, 3]
        A[:, 3, 4:] = -s20[:, 3]
    A[:, 4, :4], A[:, 4, 4:] = s1l[:, 1], -s20[:, 1]  # slope continuity
    A[:, 5, :4], A[:, 5, 4:] = s1l[:, 2], -s20[:, 2]  # moment continuity
    cj = shaft.tip_rotary_inertia_kg_m2 * b**3 / mu  # J omega^2/(EI beta)
    cm = shaft.tip_mass_kg * b / mu  # M omega^2/(EI beta^3)
    sign_m = 1.0 if model == "physical" else -1.0
    A[:, 6, 4:] = (s2l[:, 2] - cj[:, None] * s2l[:, 1]) / (1 + np.abs(cj))[:, None]
    A[:, 7, 4:] = (s2l[:, 3] + sign_m * cm[:, None] * s2l[:, 0]) / (1 + np.abs(cm))[:, None]
    return A


def frequency_determinant(beta, shaft: OverhungShaft, model: ShaftModel = "physical") -> np.ndarray:
    """det of :func:`frequency_matrix` (entire, O(1) function of beta), shape (n,)."""
    return np.linalg.det(frequency_matrix(beta, shaft, model))


def bracket_roots(f, grid: np.ndarray, values: np.ndarray | None = None,
                  max_roots: int | None = None) -> list[float]:
    """Roots of a scalar function from sign changes on ``grid``, refined by brentq.

    A sign change where ``|f|`` at the refined point is not far below its values at the
    bracket ends is a pole or a jump, not a root, and is skipped.
    """
    v = np.array([f(x) for x in grid]) if values is None else np.asarray(values)
    out: list[float] = []
    for i in np.nonzero(np.sign(v[:-1]) * np.sign(v[1:]) < 0)[0]:
        a, b = float(grid[i]), float(grid[i + 1])
        r = brentq(f, a, b, xtol=1e-14, rtol=1e-13, maxiter=200)
        if abs(f(r)) <= 1e-3 * max(abs(v[i]), abs(v[i + 1])):
            out.append(r)
            if max_roots is not None and len(out) >= max_roots:
                break
    return out


def frequency_coefficients(shaft: OverhungShaft, n_roots: int = 2,
                           model: ShaftModel = "physical", points_per_pi: int = 64) -> np.ndarray:
    """First ``n_roots`` frequency coefficients beta_i [1/m] from det A(beta) = 0.

    The scan runs geometrically from ``1e-4 pi/L`` to ``pi/(points_per_pi L)`` (``L = l1 +
    l2``), then with the step ``pi/(points_per_pi L)`` (root spacing is about ``pi/L``),
    chunk by chunk until enough roots are found.
    Two roots closer than a step (possible only in the as-printed system near its lost
    root) can be missed; the physical model is cross-checked against FE in the tests.
    """
    if n_roots < 1:
        raise ParameterError("n_roots", n_roots, "integer >= 1")

    def f(x: float) -> float:
        return float(frequency_determinant(x, shaft, model)[0])

    scale = math.pi / shaft.length_m
    step = scale / points_per_pi
    # Geometric part first: a heavy disc on a light shaft puts beta_1 far below pi/L (the
    # determinant behaves like beta^p there, smooth and without spurious sign changes).
    grids = [scale * np.geomspace(1e-4, 1.0 / points_per_pi, 8 * 20 + 1)]
    roots: list[float] = []
    chunk = 8 * points_per_pi
    start = 0.0  # the end of the last grid (set after the first)
    for _ in range(400):
        grid = grids.pop() if grids else start + step * np.arange(chunk + 1)
        vals = frequency_determinant(grid, shaft, model)
        roots += bracket_roots(f, grid, vals, max_roots=n_roots - len(roots))
        if len(roots) >= n_roots:
            return np.array(roots[:n_roots])
        start = float(grid[-1])
    raise SolverError(f"found only {len(roots)} of {n_roots} roots of the frequency equation "
                      f"below beta = {start:.4g} 1/m for {shaft}")


# --------------------------------------------------------------------------------------
# (b) Independent check: Hermite cubic beam finite elements
# --------------------------------------------------------------------------------------


def _beam_matrices(h, EI: float, mu: float) -> tuple[np.ndarray, np.ndarray]:
    """Hermite beam element stiffness and consistent mass, (4, 4) each, or (4, 4, n) for
    an array of element lengths ``h``."""
    h = np.asarray(h, dtype=float)
    o = np.ones_like(h)
    k = EI / h**3 * np.array([[12 * o, 6 * h, -12 * o, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                              [-12 * o, -6 * h, 12 * o, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
    m = mu * h / 420 * np.array([[156 * o, 22 * h, 54 * o, -13 * h],
                                 [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                                 [54 * o, 13 * h, 156 * o, -22 * h],
                                 [-13 * h, -3 * h * h, -22 * h, 4 * h * h]])
    return k, m


def fe_frequency_coefficients(shaft: OverhungShaft, n_modes: int = 2, elements: int = 24,
                              richardson: bool = True) -> np.ndarray:
    """beta_i [1/m] from an Euler-Bernoulli FE model (Hermite cubics, consistent mass).

    ``elements`` are shared between the spans in proportion to length (at least 4 each);
    the disc adds ``M`` to the tip deflection and ``J`` to the tip rotation.  The
    generalised problem is solved as ``M x = (1/omega^2) K x`` (``K`` is positive definite
    with the two pins; ``M`` may be indefinite when ``J < 0``); every eigenvalue is computed,
    so no mode can be skipped.  With ``richardson`` the O(h^4) eigenvalue error is
    extrapolated from ``elements`` and ``2 elements``.
    """
    if elements < 2:
        raise ParameterError("elements", elements, "integer >= 2")
    if richardson:
        c = fe_frequency_coefficients(shaft, n_modes, elements, False)
        f = fe_frequency_coefficients(shaft, n_modes, 2 * elements, False)
        return f + (f - c) / 15.0
    EI, mu = shaft.bending_stiffness_N_m2, shaft.mass_per_length_kg_m
    K, M0, tip = _beam_system(shaft.span_m, shaft.overhang_m, EI, mu, shaft.tip_mass_kg, elements)
    M = M0.copy()
    M[tip, tip] += shaft.tip_rotary_inertia_kg_m2
    lam = eigh(M, K, eigvals_only=True)
    lam = np.sort(lam[lam > 0])[::-1][:n_modes]  # 1/omega^2, largest first
    return (mu / (EI * lam)) ** 0.25


@lru_cache(maxsize=32)
def _beam_system(l1: float, l2: float, EI: float, mu: float, tip_mass: float, elements: int):
    """(K, M, tip) of the pinned beam with the tip mass, on its free dofs (read-only; the
    disc's rotary inertia, which the gyroscopic readings change, goes on M[tip, tip])."""
    n1 = max(4, round(elements * l1 / (l1 + l2)))
    n2 = max(4, elements - n1)
    x = np.concatenate([np.linspace(0.0, l1, n1 + 1), l1 + np.linspace(0.0, l2, n2 + 1)[1:]])
    nn = x.size
    k, m = _beam_matrices(np.diff(x), EI, mu)  # (4, 4, ne) each
    # element e couples dofs 2e .. 2e+3: scatter-add every element at once
    dofs = 2 * np.arange(nn - 1)[None, :] + np.arange(4)[:, None]  # (4, ne)
    rows = np.broadcast_to(dofs[:, None, :], k.shape).ravel()
    cols = np.broadcast_to(dofs[None, :, :], k.shape).ravel()
    K = np.zeros((2 * nn, 2 * nn))
    M = np.zeros((2 * nn, 2 * nn))
    np.add.at(K, (rows, cols), k.ravel())
    np.add.at(M, (rows, cols), m.ravel())
    M[2 * (nn - 1), 2 * (nn - 1)] += tip_mass
    free = np.setdiff1d(np.arange(2 * nn), [0, 2 * n1])
    Kf, Mf = K[np.ix_(free, free)], M[np.ix_(free, free)]
    Kf.flags.writeable = Mf.flags.writeable = False
    return Kf, Mf, int(np.searchsorted(free, 2 * nn - 1))


def clear_beam_cache() -> None:
    """Forget the beam matrices cached by :func:`fe_frequency_coefficients` (they are kept
    while one design's readings share them; a new design starts from an empty cache, so that
    each pays its own assembly and the cache never holds another design's matrices)."""
    _beam_system.cache_clear()


def first_frequency_coefficient(shaft: OverhungShaft, rtol: float = 1e-5,
                                elements: int = 12) -> tuple[float, float]:
    """(beta_1 from the exact determinant, beta_1 from the FE model) [1/m].

    The FE model (``elements`` and twice as many, Richardson: ~1e-9 on a crankshaft) computes
    every eigenvalue, so its lowest one cannot skip a root; it brackets the determinant's
    first root (within ``rtol``), which ``brentq`` refines to round-off.  Should the bracket
    hold no sign change (the two models disagreeing), the determinant's own scan
    (:func:`frequency_coefficients`) answers and the caller compares the two."""
    b_fe = float(fe_frequency_coefficients(shaft, 1, elements)[0])

    def f(x: float) -> float:
        return float(frequency_determinant(x, shaft)[0])

    a, b = b_fe * (1 - rtol), b_fe * (1 + rtol)
    fa, fb = f(a), f(b)
    if fa * fb < 0:
        return float(brentq(f, a, b, xtol=1e-14, rtol=1e-13, maxiter=200)), b_fe
    return float(frequency_coefficients(shaft, 1)[0]), b_fe
