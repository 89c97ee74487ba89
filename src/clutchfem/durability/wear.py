"""Archard's wear along the shoe face, and its integration over many starts with a controlled
wear step (:class:`WearParams`, :func:`wear_rate`, :func:`integrate_wear`).

Archard (1953): the worn depth grows with the sliding distance s as

    dh/ds = k p / H        (k dimensionless wear coefficient, p contact pressure, H hardness),

so one start (or held-drum slip) wears node i by h_i = (k / H) int p_i v dt, the
sliding-pressure integral of :func:`~clutchfem.durability.engagement.engagement_transient`.
The drum wears too: its worn volume (k_d / H_d) int F_N v dt spreads over its whole inner
surface 2 pi R_d h (the shoes sweep it), a uniform growth of its radius, i.e. of every gap.

The answers against the number of starts depend on k / H only through n k / H (the
transient of a start does not depend on k): a k ten times larger gives the same curves at a
tenth of the starts.  The band of the life answers is therefore exact: the answers at
starts N with k at the ends of its band are those of the central k at N k_end / k.

ASSUMED values (order-of-magnitude ranges of Archard's k; the clutch runs dry, oil mist of
the chain lubrication reaches the drum):

* dry hardened steel on steel, mild (oxidative) wear: k = 1e-5, band 1e-6..1e-4
  (Archard & Hirst, Proc. R. Soc. A 236 (1956) 397; Hutchings & Shipway, *Tribology*,
  2nd ed. 2017, ch. 5: k of 1e-6..1e-4 for mild wear of steels in dry sliding; severe wear
  reaches 1e-3);
* lubricated (boundary lubrication): k = 1e-8, band 1e-9..1e-7 (same sources, ch. 5-6);
* hardness 4.4 GPa for the shoe (51CrV4 at ~45 HRC, ~445 HV x 9.81 MPa) and for the drum
  (a hardened steel drum, ASSUMED the same).

The wear step (:func:`integrate_wear`): the wear-in of a compliant shoe is a stiff problem
(a micrometre worn off the loaded tip moves MPa of pressure to its neighbours: the pressure
relaxes to a uniform wear rate within ~1e2 starts, while the life is 1e5), so an explicit
step would need thousands of FE states.  The step is linearly implicit (Rosenbrock-Euler):

    (I - dn J) dw = dn r(w),       J = dr/dw,

with J from the contact problem itself (on the active set A of each speed, dp_A/dw_A =
-diag(1/(h w_A)) G_AA^-1, weighted by the sliding distance spent at that speed), which is
stable for any dn and damps the fast relaxation as the physics does; up to ``corrections``
Newton corrections then solve the implicit Euler step w1 = w + dn r(w1) with the contact set
of the step's end (a step deeper than the elastic approach of the contact otherwise wears
the loaded nodes past the ones about to touch).  The step control: no node wears more than
the step limit in one step (dn shrunk until it holds), the smaller of ``max_step`` and,
with a ``step_limit`` (the life run's), ``step_fraction`` times the contact's elastic give
(the worn depth that would unload a loaded node, p_i / |dp_i/dw_i|, weighted by the wear
the nodes take): a step deeper than the give unloads the loaded nodes within one step and
over-wears them (the contact arc then jitters from state to state).  With a Jacobian the
step also changes the wear rate by no more than ``rate_change`` times the largest rate
(linearised: max |J dw| <= rate_change max |r|): short steps while the contact is
wearing in and the pressure moves, long ones once the wear is uniform along the arc (a
uniform wear opens every gap alike and barely moves the pressure).  First order in dn, so
halving the step halves the step error (measured: ``benchmarks/bench_life.py``).
Wear does not heal: a step's dw is clipped at 0.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import ClassVar, Literal

import numpy as np

from ..core import InputError, ParameterError, ParamSet, choice, param

__all__ = ["WearParams", "WearRun", "integrate_wear", "wear_rate"]

#: typical Archard coefficient and its band per regime (module docstring)
K_TYPICAL = {"dry": (1e-5, 1e-6, 1e-4), "lubricated": (1e-8, 1e-9, 1e-7)}


class WearParams(ParamSet):
    """Archard's wear of the shoe face and the drum (ASSUMED values with sources: module
    :mod:`clutchfem.durability.wear`) and the wear-step control.

    Parameters
    ----------
    regime : {'dry', 'lubricated'}
        Which typical wear coefficient and band apply.
    wear_coefficient : float, optional
        Archard's k of the shoe (default: the regime's typical value).
    hardness : float or str
        Shoe hardness H [Pa].
    drum_wear_coefficient : float, optional
        Archard's k of the drum (default: the shoe's).
    drum_hardness : float or str
        Drum hardness [Pa].
    max_step : float or str
        Largest worn depth of one wear step [m] (a cap).
    step_fraction : float
        Largest worn depth of one wear step as a share of the contact's elastic give (0.01..1;
        applied where :func:`integrate_wear` has a ``step_limit``).
    rate_change : float
        Largest change of the wear rate in one step (linearised, max |J dw|) as a share of the
        largest wear rate (0.01..10; applied where the rate has a Jacobian).

    Examples
    --------
    >>> import clutchfem as cf
    >>> w = cf.WearParams(regime="lubricated")
    >>> w.k, w.k_band
    (1e-08, (1e-09, 1e-07))
    >>> cf.WearParams(wear_coefficient=0)
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: wear: parameter 'wear_coefficient' = 0 is not allowed: ...
    """

    context: ClassVar[str] = "wear"
    regime: Literal["dry", "lubricated"] = choice("dry", "dry or lubricated sliding: the typical wear "
                                                  "coefficient and its band (dry 1e-5 in 1e-6..1e-4, lubricated "
                                                  "1e-8 in 1e-9..1e-7; Archard & Hirst 1956, Hutchings & Shipway "
                                                  "2017)")
    wear_coefficient: float | None = param(None, "-", 1e-12, 1e-1, "Archard's dimensionless wear coefficient k "
                                           "of the shoe (> 0; default: the regime's typical value)", "k")
    hardness: float = param(4.4e9, "Pa", 1e8, 2e10, "shoe hardness H (51CrV4 at ~45 HRC: ~445 HV = 4.4 GPa)", "H")
    drum_wear_coefficient: float | None = param(None, "-", 1e-12, 1e-1, "Archard's k of the drum (default: the "
                                                "shoe's)", "k_d")
    drum_hardness: float = param(4.4e9, "Pa", 1e8, 2e10, "drum hardness (ASSUMED a hardened steel drum)", "H_d")
    corrections: int = param(2, "-", 0, 20, "Newton corrections of each implicit wear step (0: linearly "
                             "implicit only)", "n_N")
    max_step: float = param(10e-6, "m", 1e-8, 1e-3, "largest worn depth of one wear step (the step control's "
                            "cap)", "dh_max")
    step_fraction: float = param(0.25, "-", 0.01, 1.0, "largest worn depth of one wear step as a share of the "
                                 "contact's elastic give (where integrate_wear is given a step_limit)", "f_dh")
    rate_change: float = param(0.25, "-", 0.01, 10.0, "largest change of the wear rate in one step, linearised "
                               "(max |J dw|), as a share of the largest wear rate (the life run's step control)",
                               "f_r")

    @property
    def k(self) -> float:
        """The shoe's wear coefficient in use."""
        return self.wear_coefficient if self.wear_coefficient is not None else K_TYPICAL[self.regime][0]

    @property
    def k_drum(self) -> float:
        return self.drum_wear_coefficient if self.drum_wear_coefficient is not None else self.k

    @property
    def k_band(self) -> tuple[float, float]:
        """(low, high) of k: the regime's band, or the given k with the band's ratios around it."""
        typ, lo, hi = K_TYPICAL[self.regime]
        return (lo, hi) if self.wear_coefficient is None else (self.k * lo / typ, self.k * hi / typ)

    @property
    def assumed(self) -> bool:
        return self.wear_coefficient is None


def wear_rate(pressure_sliding_Pa_m, params: WearParams, *, weight_m=None, scale: float = 1.0,
              drum_radius_m: float | None = None) -> tuple[np.ndarray, float]:
    """(worn depth of each node [m], the drum's uniform worn depth [m]) of one sliding event
    whose sliding-pressure integral per node is ``pressure_sliding_Pa_m`` [Pa m] (Archard,
    module docstring).  The drum needs the nodes' tributary lengths ``weight_m`` [m], the
    model's share of the clutch ``scale`` and ``drum_radius_m``; without them its depth is 0.

    Parameters
    ----------
    pressure_sliding_Pa_m : array (m,)
    params : WearParams
    weight_m : array (m,), optional
    scale : float
    drum_radius_m : float, optional

    Returns
    -------
    tuple of (ndarray, float)

    Examples
    --------
    >>> import clutchfem as cf
    >>> h, hd = cf.wear_rate([2e6 * 3.0], cf.WearParams(wear_coefficient=1e-5, hardness=4e9))
    >>> round(float(h[0]), 15)                        # k p s / H = 1e-5 x 2 MPa x 3 m / 4 GPa
    1.5e-08
    """
    if not isinstance(params, WearParams):
        raise ParameterError("params", type(params).__name__, "a WearParams", "wear")
    I = np.asarray(pressure_sliding_Pa_m, dtype=float)
    if not np.all(np.isfinite(I)) or np.any(I < 0):
        raise InputError("wear: the sliding-pressure integrals must be finite and >= 0 Pa m")
    h = params.k / params.hardness * I
    hd = 0.0
    if weight_m is not None and drum_radius_m is not None:
        # drum volume per unit axial length: (k_d/H_d) sum_i (w_i I_i) x scale, over 2 pi R_d
        hd = float(params.k_drum / params.drum_hardness * scale * np.dot(np.asarray(weight_m), I)
                   / (2.0 * math.pi * drum_radius_m))
    return h, hd


@dataclass
class WearRun:
    """The states of :func:`integrate_wear`: the starts at each state, the worn depths [m],
    what the rate function returned at each state, how many steps were shrunk and how many
    Newton corrections were made.

    Examples
    --------
    >>> import numpy as np, clutchfem as cf
    >>> run = cf.integrate_wear(lambda w: (np.full(1, 1e-9), None, None), np.zeros(1), 100, cf.WearParams())
    >>> run.to_json()["starts"]
    [0.0, 100.0]
    """

    starts: list[float] = field(default_factory=list)
    worn_m: list[np.ndarray] = field(default_factory=list)
    info: list[object] = field(default_factory=list)
    shrunk: int = 0
    corrections: int = 0
    limits_m: list[float] = field(default_factory=list)

    def to_json(self) -> dict:
        """Starts and worn depths [m] of every state, the step counts."""
        return {"starts": [float(n) for n in self.starts], "worn_m": [np.asarray(w).tolist() for w in self.worn_m],
                "shrunk": self.shrunk, "corrections": self.corrections, "step_limits_m": list(self.limits_m)}


def _limit(params: WearParams, step_limit, info) -> float:
    """The step limit [m] at a state: ``max_step``, or ``step_fraction`` x the elastic give
    when that is smaller (a give of None, 0 or not finite: no contact, ``max_step``)."""
    if step_limit is None:
        return params.max_step
    give = step_limit(info)
    if give is None or not math.isfinite(give) or give <= 0:
        return params.max_step
    return min(params.max_step, params.step_fraction * float(give))


def integrate_wear(rate: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray | None, object]], w0, starts: float,
                   params: WearParams, *,
                   on_state: Callable[[float, np.ndarray, object], np.ndarray | None] | None = None,
                   step_limit: Callable[[object], float | None] | None = None,
                   max_states: int = 5000) -> WearRun:
    """Worn depths over ``starts`` starts by the linearly implicit step of the module
    docstring.

    Parameters
    ----------
    rate : callable
        ``rate(w) -> (r, J, info)``: the wear rate r = dh/dn [m per start] at worn depths
        ``w``, its Jacobian J = dr/dw (None: explicit Euler) and anything to keep about that
        state (e.g. its answers).
    w0 : array
        Worn depths at the start [m].
    starts : float
        Number of starts to integrate over.
    params : WearParams
        ``max_step``.
    on_state : callable, optional
        ``on_state(n, w, info) -> w or None`` after every step (e.g. a rebuild of the part
        that maps the depths to a new model).
    step_limit : callable, optional
        ``step_limit(info) -> depth [m] or None``: the contact's elastic give at a state (its
        ``info``); a step then wears no node deeper than ``step_fraction`` times it (nor
        than ``max_step``).
    max_states : int
        Refuse a run that needs more steps.

    Returns
    -------
    WearRun

    Examples
    --------
    >>> import numpy as np, clutchfem as cf
    >>> run = cf.integrate_wear(lambda w: (np.full(2, 1e-9), None, None), np.zeros(2), 1e4, cf.WearParams())
    >>> round(float(run.worn_m[-1][0]), 12), run.starts[-1]
    (1e-05, 10000.0)
    """
    if isinstance(starts, bool) or not isinstance(starts, (int, float)) or not math.isfinite(starts) or starts < 0:
        raise ParameterError("starts", starts, "a number of starts >= 0", "wear")
    w = np.array(w0, dtype=float)
    run = WearRun()
    n = 0.0
    r, J, info = rate(w)
    while True:
        run.starts.append(n)
        run.worn_m.append(w.copy())
        run.info.append(info)
        if n >= starts * (1 - 1e-12):
            return run
        if len(run.starts) > max_states:
            raise InputError(f"wear: more than {max_states} wear steps before {starts:g} starts (at {n:.0f}); raise "
                             "the wear step's max_step")
        limit = _limit(params, step_limit, info)
        run.limits_m.append(limit)
        rmax = float(np.max(np.abs(r), initial=0.0))
        dn = starts - n if rmax <= 0 else min(starts - n, (1.0 if J is None else 10.0) * limit / rmax)
        for _ in range(30):
            dw = dn * r if J is None else np.linalg.solve(np.eye(len(w)) - dn * J, dn * r)
            big = float(np.max(np.abs(dw), initial=0.0))
            shrink = limit / big if big > limit * (1 + 1e-9) else 1.0
            if J is not None and rmax > 0:  # the wear rate's change over the step, linearised
                change = float(np.max(np.abs(J @ dw)))
                if change > params.rate_change * rmax * (1 + 1e-9):
                    shrink = min(shrink, params.rate_change * rmax / change)
            if shrink >= 1.0:
                break
            dn *= 0.9 * shrink
            run.shrunk += 1
        w1 = w + np.maximum(dw, 0.0)
        r1, J1, info1 = rate(w1)
        for _ in range(params.corrections if J is not None else 0):
            # Newton on the implicit Euler step w1 = w + dn r(w1): the contact set of the end
            # of the step, not only of its start
            F = w1 - w - dn * r1
            if float(np.max(np.abs(F))) <= 1e-3 * limit:
                break
            w1 = np.maximum(w1 - np.linalg.solve(np.eye(len(w)) - dn * J1, F), w)
            r1, J1, info1 = rate(w1)
            run.corrections += 1
        w, r, J, info = w1, r1, J1, info1
        n = starts if starts - n - dn <= 1e-9 * starts else n + dn
        if on_state is not None:
            mapped = on_state(n, w, info)
            if mapped is not None:
                w = mapped
                r, J, info = rate(w)
