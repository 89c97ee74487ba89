"""The reduced model of a region: every main answer's model, where the FE answers, the best
path's bands, and the model's own error measured on designs it was not fitted to.

Answers (:data:`ANSWERS`): the static engagement and the engagement with the 2-stroke ripple,
the slip speed, the torque at the rpm of maximum engine torque, the peak von Mises stress
at the engine's maximum speed, the fatigue safety factor, the contact arc at the rpm of
maximum engine torque, the part's and a shoe's mass.  Derived exactly from them (no model
of their own): the safety factor (yield strength / peak), the torque margin (torque - the
engine's maximum torque) and the requirement checks.

**The band of a live answer** = the best path's band + the reduced model's own error:

* the best path's band of the designs next to it (the largest relative band of the
  :data:`NEIGHBOURS` nearest training designs: the band is a property of the model and its
  mesh, it moves slowly over a region);
* the reduced model's error: the largest relative error it made on the held-out designs
  (:meth:`ReducedModel.measure`: designs drawn apart from the training ones, never fitted
  to), per answer; the 95th percentile is reported beside it.  An answer whose measured
  error is over :data:`UNUSABLE` is not given live at all (the contact arc, which jumps
  between a tip contact and a spread one: BENCHMARKS.md section 24).

An answer the FE does not give at a design (no slip speed: the clutch holds at start or
never engages; no fatigue data) is not given live either where one of the nearest training
designs lacks it: the live answer says so and the FE is asked instead.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..clutch.ripple import effective_engagement_rpms
from ..core import ParameterError
from ..geometry import get_concept
from .region import OPERATING_AXES, Region
from .surrogate import OK_PROBABILITY, AnswerModel, RippleAnswer, StatusModel, sq_distances

__all__ = ["AIMS", "ANSWERS", "MAX_FE_BAND", "NEIGHBOURS", "ReducedModel"]

#: the modelled answers: name -> (study row column, factor to SI, unit, the row's band column or None)
ANSWERS: dict[str, tuple[str, float, str, str | None]] = {
    "engagement_rpm": ("engagement_rpm", 1.0, "rpm", "engagement_err_rpm"),
    "engagement_rpm_with_ripple": ("engagement_ripple_rpm", 1.0, "rpm", "engagement_err_rpm"),
    "slip_rpm": ("slip_rpm", 1.0, "rpm", "slip_err_rpm"),
    "torque_at_max_engine_torque_Nm": ("torque_at_max_engine_torque_Nm", 1.0, "N m", "torque_err_Nm"),
    "max_von_mises_Pa": ("max_von_mises_MPa", 1e6, "Pa", "stress_err_MPa"),
    "fatigue_safety_factor": ("fatigue_safety_factor", 1.0, "-", None),
    "contact_arc_deg": ("contact_arc_deg", 1.0, "deg", None),
    "mass_kg": ("part_mass_g", 1e-3, "kg", None),
    "shoe_mass_kg": ("shoe_mass_g", 1e-3, "kg", None),
}
#: the step of the reduced model's derivatives (a share of each free parameter's box width)
DERIVATIVE_STEP = 1e-3
#: the nearest training designs a live answer's best-path band and availability come from
NEIGHBOURS = 3
#: the quantile of the held-out relative errors reported beside the largest (the band takes the
#: largest: with 30 held-out designs the 95th percentile would leave the band short on ~5 % of
#: new designs by construction)
QUANTILE = 0.95
#: an answer whose measured error is above this is not given live (the FE is asked): the
#: contact arc jumps between a tip contact and a spread one (BENCHMARKS.md section 24)
UNUSABLE = 0.10
#: the relative error each answer's model is aimed at (issue 36's targets): the weights of the
#: adaptive training designs (:meth:`ReducedModel.most_uncertain`)
AIMS: dict[str, float] = {"engagement_rpm": 0.003, "slip_rpm": 0.003, "torque_at_max_engine_torque_Nm": 0.005,
                          "max_von_mises_Pa": 0.015}
#: the engagement with ripple is derived from the static one where the training rows agree with that
#: derivation to this (relative; they agree to 1e-13 where the error step did not refine the
#: engagement, and within ~1e-4 where it did: it scales the ripple's answer by the static one's ratio)
RIPPLE_MATCH = 1e-4
#: a training design whose best-path band of an answer is wider than this (relative) is left out
#: of that answer's fit: the FE says its value is not known to better than that.  Found on concept
#: 1 (BENCHMARKS.md section 24): 6 of 150 designs had a peak-stress band of 24-199 % (the error
#: step's refined mesh found its peak at a degenerate element where a zone line left the slot's
#: fillet tangentially -- moved since -- so the peak was not extrapolated), and fitting them bent
#: the peak's model into short length scales: held-out error 2.56 % with them, 1.02 % without.
#: Such a design still counts as a neighbour: a live answer next to it carries its wide band.
MAX_FE_BAND = 0.10


def ripple_derived(rows: list[dict]) -> bool:
    """Whether the training rows' engagement with ripple is the FE's derivation from their static
    engagement (the default ripple model, 3 sigma) to within :data:`RIPPLE_MATCH` on every row
    that has both: then the live one is derived the same way (:class:`~.surrogate.RippleAnswer`),
    else it gets a model of its own."""
    pairs = np.array([(row_value(r, "engagement_rpm"), row_value(r, "engagement_rpm_with_ripple")) for r in rows
                      if r.get("status") == "ok"], dtype=float).reshape(-1, 2)
    pairs = pairs[np.isfinite(pairs).all(axis=1)]
    if not len(pairs):
        return False
    return bool(np.max(np.abs(effective_engagement_rpms(pairs[:, 0], k_sigma=3.0) / pairs[:, 1] - 1.0)) <= RIPPLE_MATCH)


def diagonal(U: np.ndarray, F: np.ndarray) -> bool:
    """Whether the rule dimensions ``F`` (n, k) run across the box's axes: each one's linear fit
    in the unit-box coordinates ``U`` (n, d) moves with at least two of them by 10 % of its
    largest slope or more.  Only then is it a direction an axis-aligned kernel does not have
    (along one axis it would repeat that coordinate: two inputs of one line, whose lengths the
    likelihood cannot tell apart)."""
    if U.shape[1] < 2 or len(U) < U.shape[1] + 2:
        return False
    A = np.hstack([np.ones((len(U), 1)), U])
    c, *_ = np.linalg.lstsq(A, F, rcond=None)
    slopes = np.abs(c[1:])  # (d, k)
    return bool(np.all((slopes >= 0.1 * slopes.max(axis=0)).sum(axis=0) >= 2))


def wide_band(row: dict, answer: str) -> bool:
    """Whether a study row's best-path band of ``answer`` is wider than :data:`MAX_FE_BAND`."""
    return (row_band(row, answer) or 0.0) > MAX_FE_BAND


def rule_coords(u: np.ndarray, F: np.ndarray, span) -> np.ndarray:
    """The unit-box points ``u`` (m, d) with their rule dimensions ``F`` (m, k) scaled over
    ``span`` = (min, max) of the training designs' (:meth:`ReducedModel.coords`)."""
    lo, hi = span
    return np.hstack([u, (F - lo) / (hi - lo)])


def row_value(row: dict, answer: str) -> float | None:
    """An answer of a study row in SI (None where the row has none)."""
    col, scale, _, _ = ANSWERS[answer]
    v = row.get(col)
    if v is None:
        return None
    v = float(v) * scale
    return v if math.isfinite(v) and v > 0 else None


def row_band(row: dict, answer: str) -> float | None:
    """The best path's relative band of an answer in a study row (None: not estimated)."""
    col, scale, _, band = ANSWERS[answer]
    if band is None or row.get(band) is None or not row.get(col):
        return None
    return abs(float(row[band]) / float(row[col]))


@dataclass
class ReducedModel:
    """Every main answer over a :class:`~clutchfem.reduced.Region` (module docstring).

    Attributes
    ----------
    region : Region
        Where it holds.
    models : dict
        Answer name -> its :class:`~clutchfem.reduced.AnswerModel`.
    status : StatusModel
        Where the full FE answers at all.
    accuracy : dict
        Answer name -> its measured error on held-out designs: ``n``, ``p95_rel``,
        ``max_rel``, ``mean_rel``, ``within`` (the share of held-out designs whose FE answer
        the live band holds).

    Examples
    --------
    Fitted to study rows (here made by hand: the engagement speed of six designs of a
    one-parameter region) and measured on two others:

    >>> import json, clutchfem as cf
    >>> from clutchfem.reduced import ReducedModel, Region
    >>> r = Region.around(cf.Design.from_concept("concept1", fidelity="live"), free=["flexure_thickness"])
    >>> row = lambda t: {"status": "ok", "point_json": json.dumps({"flexure_thickness": t}),
    ...                  "engagement_rpm": 2.0e6 * t, "engagement_err_rpm": 20.0}
    >>> m = ReducedModel.fit(r, [row(t) for t in (2.1e-3, 2.13e-3, 2.17e-3, 2.2e-3, 2.26e-3, 2.3e-3)])
    >>> acc = m.measure([row(2.15e-3), row(2.25e-3)])
    >>> bool(acc["engagement_rpm"]["max_rel"] < 1e-3), acc["engagement_rpm"]["within"]
    (True, 1.0)
    """

    region: Region
    models: dict
    status: StatusModel
    U: np.ndarray
    rows: list = field(repr=False)
    accuracy: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)
    #: the concept's rule dimensions' (min, max) over the training designs: each one more
    #: coordinate of the answer models, scaled to [0, 1] over them (:meth:`coords`); None: none
    rule_span: tuple | None = None

    def coords(self, u: np.ndarray) -> np.ndarray:
        """The coordinates the answer models see at the unit-box points ``u`` (m, d): the
        box's, and the concept's rule dimensions (:meth:`Region.rule_dimensions
        <clutchfem.reduced.Region.rule_dimensions>`; concept 1's hub post: its peak stress
        falls steeply as the post thins towards its 3 mm rule, which the box's coordinates
        saw only as length scales of 0.08 of the box) scaled over the training designs."""
        u = np.atleast_2d(np.asarray(u, dtype=float))
        if self.rule_span is None:  # (also a model pickled before rule dimensions: the class default)
            return u
        return rule_coords(u, self.region.rule_dimensions(u)[1], self.rule_span)

    @classmethod
    def fit(cls, region: Region, rows: list[dict], *, seed: int = 0, like: "ReducedModel | None" = None
            ) -> "ReducedModel":
        """Fit to the study rows of the region's training designs (each row's ``point_json``
        holds its parameters); an answer's fit leaves out the rows whose best-path band of it
        is wider than :data:`MAX_FE_BAND` (counted in ``info["left_out_wide_band"]``); ``like``:
        a model of the same region whose kernels are kept (:meth:`AnswerModel.fit`)."""
        t0 = time.perf_counter()
        U = np.array([region.unit_of(json.loads(r["point_json"])) for r in rows])
        ok = np.array([r.get("status") == "ok" for r in rows])
        status = StatusModel.fit(U, ok, seed=seed)
        dim_names, F = region.rule_dimensions(U)
        span = None
        if dim_names and diagonal(U, F):
            lo, hi = F.min(axis=0), F.max(axis=0)
            span = (lo, np.where(hi > lo, hi, lo + 1.0))
        else:
            dim_names = ()
        X = rule_coords(U, F, span) if span is not None else U
        models, left_out = {}, {}
        derived = ripple_derived(rows)
        for a in ANSWERS:
            if a == "engagement_rpm_with_ripple" and derived and "engagement_rpm" in models:
                models[a] = RippleAnswer(models["engagement_rpm"])
                continue
            y = np.array([row_value(r, a) if r.get("status") == "ok" else None for r in rows], dtype=float)
            wide = np.array([wide_band(r, a) for r in rows])
            have = np.isfinite(y) & ~wide
            if wide.any():
                left_out[a] = int((np.isfinite(y) & wide).sum())
            if have.sum() >= region.dim + 2:  # a trend (d + 1 coefficients) and one more
                prior = like.models.get(a) if like is not None else None
                models[a] = AnswerModel.fit(X[have], y[have], seed=seed,
                                            like=prior if isinstance(prior, AnswerModel) else None)
        m = cls(region=region, models=models, status=status, U=U, rows=list(rows), rule_span=span)
        m.info = {"fit_s": time.perf_counter() - t0, "n_train": len(rows), "n_ok": int(ok.sum()),
                  "left_out_wide_band": left_out, "rule_dimensions": list(dim_names)}
        return m

    # -- answers --------------------------------------------------------------------------
    def neighbours(self, u: np.ndarray) -> np.ndarray:
        """Indices of the :data:`NEIGHBOURS` nearest training designs of each point of ``u``
        (m, d) that the FE answered."""
        ok = np.array([r.get("status") == "ok" for r in self.rows])
        idx = np.flatnonzero(ok)
        d2 = sq_distances(u, self.U[idx])
        k = min(NEIGHBOURS, len(idx))
        return idx[np.argpartition(d2, k - 1, axis=1)[:, :k]]

    def _row_arrays(self, answer: str) -> tuple[np.ndarray, np.ndarray]:
        """(relative band, has a value) of ``answer`` at every training design, read from the
        rows once per model (a live optimiser asks for thousands of predictions)."""
        cache = self.__dict__.setdefault("_row_cache", {})
        if answer not in cache:
            cache[answer] = (np.array([row_band(r, answer) or 0.0 for r in self.rows]),
                             np.array([row_value(r, answer) is not None for r in self.rows]))
        return cache[answer]

    def own_error(self, answer: str) -> float:
        """The reduced model's own relative error of ``answer``: the largest it made on the
        held-out designs (NaN: not measured)."""
        return float(self.accuracy.get(answer, {}).get("max_rel", np.nan))

    def predict(self, u: np.ndarray, answers=None) -> dict:
        """The answers at the unit-box points ``u`` (m, d), vectorised: ``value`` (answer ->
        array, NaN where not given live), ``band`` (answer -> absolute band: the best path's
        band of the nearest training designs plus :meth:`own_error`), ``p_ok`` (the
        probability that the FE answers there), ``why`` (answer -> per point the reason of a
        missing value, or '').  ``answers``: only these (default: every modelled answer; an
        optimiser asks for the few its targets need, each answer a kernel evaluation)."""
        u = np.atleast_2d(np.asarray(u, dtype=float))
        p_ok = self.status.probability(u)
        nb = self.neighbours(u)
        x = self.coords(u)
        out = {"value": {}, "band": {}, "p_ok": p_ok, "why": {}}
        raw = {}
        for a, model in self.models.items():
            if answers is not None and a not in answers:
                continue
            band_rows, have_rows = self._row_arrays(a)
            fe_band = band_rows[nb].max(axis=1)
            own = self.own_error(a)
            if isinstance(model, RippleAnswer) and "engagement_rpm" in raw:  # (its static value, not again)
                v = model.from_static(raw["engagement_rpm"])
            else:
                v = model.predict(x)
            raw[a] = v
            why = np.where(p_ok < OK_PROBABILITY, "the full FE gives no answer near here", "")
            why = np.where((why == "") & ~have_rows[nb].all(axis=1), "a design next to it has no such answer", why)
            if own > UNUSABLE:
                why = np.where(why == "", f"its reduced model's measured error is {100 * own:.0f} %", why)
            v = np.where(why == "", v, np.nan)
            out["value"][a] = v
            # the own error is relative to the FE's value: |live - FE| <= own |FE| <= own/(1 - own) |live|
            # (1 + 1e-12 and 1e-13: the design of the largest error sits on the band's edge, up to
            # round-off, which is 1e-16 of the value: against an own error of 1e-8, the shoe mass's,
            # a relative margin alone was too small)
            rel = own / (1.0 - own) * (1.0 + 1e-12) + 1e-13 if math.isfinite(own) and own < 1.0 else np.inf
            out["band"][a] = np.abs(v) * (fe_band + rel)
            out["why"][a] = why
        return out

    def sensitivities(self, design, names=None, *, h: float = DERIVATIVE_STEP):
        """Derivatives of the live answers of ``design`` (a concept's design in the region)
        with respect to the free parameters ``names`` (default: all): central
        differences of the fitted model over ``h`` of each parameter's box width (one-sided at
        the box's faces), in SI per SI unit, as :func:`clutchfem.sensitivities` gives them from
        morphed FE designs (a :class:`~clutchfem.evaluation.Sensitivities`; the methods say
        "reduced model").  The model is smooth by construction (a Matern 5/2 process on a
        linear trend), so where the FE answers have a kink at a contact event these are the
        slopes of the smoothed answer: the FE derivatives see the kink (``kinks``), these do not.
        The safety factor's derivative follows from the peak's."""
        reg = self.region
        if isinstance(h, bool) or not isinstance(h, (int, float)) or not 0 < h <= 0.25:
            raise ParameterError("h", h, "a step in (0, 0.25] of each parameter's box width", "reduced model "
                                 "sensitivities")
        names = list(reg.names) if names is None else list(names)
        bad = [n for n in names if n not in reg.names]
        if bad:
            raise ParameterError("names", bad, f"free parameters of the region: {', '.join(reg.names)}",
                                 "reduced model sensitivities")
        values = reg.design_values(design)
        if design.name != reg.concept or not reg.contains(values):
            raise ParameterError("design", design.label, f"a {reg.concept} design in the region ({reg.describe()})",
                                 "reduced model sensitivities")
        u0 = reg.unit_of(values)
        rows = [u0]
        for n in names:
            i = reg.names.index(n)
            up, um = u0.copy(), u0.copy()
            up[i], um[i] = min(u0[i] + h, 1.0), max(u0[i] - h, 0.0)
            rows += [um, up]
        pred = self.predict(np.array(rows))["value"]
        ys = float(design.op.material.yield_strength)
        base = {a: float(v[0]) for a, v in pred.items()}
        from ..evaluation.sensitivity import Sensitivities  # (its home is the FE's sensitivities)

        out = Sensitivities(concept=reg.concept, base=base, values={}, steps={}, units={}, derivatives={}, methods={},
                            notes=[f"derivatives of the reduced model of {reg.describe()} (central differences over "
                                   f"{h:g} of each width); its own error per answer: " + ", ".join(
                                       f"{a} {100 * self.own_error(a):.2g} %" for a in pred
                                       if math.isfinite(self.own_error(a)))])
        P = get_concept(reg.concept).Params
        for k, n in enumerate(names):
            i = reg.names.index(n)
            width = reg.hi[i] - reg.lo[i]
            im, ip = 1 + 2 * k, 2 + 2 * k
            dx = (rows[ip][i] - rows[im][i]) * width
            der = {a: float((v[ip] - v[im]) / dx) if np.isfinite(v[ip]) and np.isfinite(v[im]) else None
                   for a, v in pred.items()}
            peak, dpeak = base.get("max_von_mises_Pa"), der.get("max_von_mises_Pa")
            if math.isfinite(ys) and peak and dpeak is not None:
                der["safety_factor"] = -ys / peak**2 * dpeak
            out.values[n] = reg.lo[i] + u0[i] * width
            out.steps[n] = h * width
            out.units[n] = OPERATING_AXES[n] if n in OPERATING_AXES else P.unit(n)
            out.kinds[n] = "parameter"
            out.derivatives[n] = der
            out.methods[n] = ("central" if 0 < rows[im][i] and rows[ip][i] < 1 else "one-sided") + ", reduced model"
        return out

    # -- where it knows least ---------------------------------------------------------------
    def most_uncertain(self, pool: np.ndarray, k: int, *, aims: dict | None = None, admissible=None) -> list[int]:
        """The ``k`` points of ``pool`` (m, d unit-box points) where FE answers would teach the
        model most: a greedy batch of the largest posterior variance of the answers' processes
        (their fitted kernels), each variance weighted by ``1 / aim**2`` (``aims``: answer ->
        the relative error it is aimed at, default :data:`AIMS`; the models are of ``log y``,
        so a variance is a relative error squared), and after each pick the variances updated
        as if its answer were known (the variance does not depend on the answer: the batch
        needs no FE).  ``admissible(i)``: whether pool point ``i`` makes a part (asked only of
        the points picked; one that does not is passed over).

        Why (BENCHMARKS.md section 24): a space-filling sample of nine dimensions leaves the
        box's corners far from every training design (0.65 of the box's width at concept 4's
        worst held-out design), where the trend is extrapolated; the process's variance is
        largest there, so these picks go to the corners and faces.

        Examples
        --------
        A one-parameter region trained on its lower half: the first pick is its far end, the
        next ones fill the gap.

        >>> import json, numpy as np, clutchfem as cf
        >>> from clutchfem.reduced import ReducedModel, Region
        >>> r = Region.around(cf.Design.from_concept("concept1", fidelity="live"), free=["flexure_thickness"])
        >>> lo, hi = r.bounds("flexure_thickness")
        >>> row = lambda t: {"status": "ok", "point_json": json.dumps({"flexure_thickness": t}),
        ...                  "engagement_rpm": 3e3 * (t / lo) ** 1.5}
        >>> m = ReducedModel.fit(r, [row(lo + f * (hi - lo)) for f in (0.0, 0.1, 0.2, 0.3, 0.4, 0.5)])
        >>> pool = np.linspace(0.0, 1.0, 101)[:, None]
        >>> first, second = (float(pool[i, 0]) for i in m.most_uncertain(pool, 2))
        >>> first, 0.6 < second < 0.9
        (1.0, True)
        """
        P = self.coords(pool)
        parts = []
        for a, aim in (AIMS if aims is None else aims).items():
            am = self.models.get(a)
            if am is None:
                continue
            K = am.kernel(am.X, am.X) + (am.noise + 1e-10 * am.amplitude) * np.eye(len(am.X))
            V = np.linalg.solve(np.linalg.cholesky(K), am.kernel(am.X, P))  # L^-1 K(X, P)
            var = np.maximum(am.amplitude - (V * V).sum(axis=0), 0.0)
            parts.append({"m": am, "V": V, "var": var, "C": np.zeros((0, len(P))), "w": 1.0 / aim**2})
        passed = np.zeros(len(P), dtype=bool)
        picked: list[int] = []
        while parts and len(picked) < k and not passed.all():
            score = sum(p["w"] * p["var"] for p in parts)
            j = int(np.argmax(np.where(passed, -np.inf, score)))
            passed[j] = True
            if admissible is not None and not admissible(j):
                continue
            picked.append(j)
            for p in parts:  # the posterior covariance with point j, then the rank-one update
                am = p["m"]
                c = am.kernel(P, P[j:j + 1])[:, 0] - p["V"].T @ p["V"][:, j] - p["C"].T @ p["C"][:, j]
                c = c / math.sqrt(max(float(p["var"][j]), 1e-300) + am.noise)
                p["C"] = np.vstack([p["C"], c])
                p["var"] = np.maximum(p["var"] - c * c, 0.0)
        return picked

    # -- its own error ----------------------------------------------------------------------
    def measure(self, rows: list[dict]) -> dict:
        """Measure the model's error on held-out designs (study rows it was not fitted to):
        per answer the relative error's mean, 95th percentile (the largest with fewer than 20
        designs), largest, and the share of designs whose FE answer the live band holds; where
        some designs' own FE band is wider than :data:`MAX_FE_BAND`, their count and the largest
        error without them (the band keeps the largest of all)."""
        ok_rows = [r for r in rows if r.get("status") == "ok"]
        u = np.array([self.region.unit_of(json.loads(r["point_json"])) for r in ok_rows])
        acc = {}
        if not len(ok_rows):
            return acc
        pred = self.predict(u)
        for a in self.models:
            fe = np.array([row_value(r, a) for r in ok_rows], dtype=float)
            live = pred["value"][a]
            sel = np.isfinite(fe) & np.isfinite(live)
            if not sel.any():
                continue
            e = np.abs(live[sel] / fe[sel] - 1.0)
            q = float(np.quantile(e, QUANTILE)) if sel.sum() >= 20 else float(e.max())
            acc[a] = {"n": int(sel.sum()), "mean_rel": float(e.mean()), "p95_rel": q, "max_rel": float(e.max()),
                      "unit": ANSWERS[a][2]}
            # the designs whose own FE band is wider than MAX_FE_BAND: counted, and the largest error
            # without them beside the largest of all (which the band takes: conservative)
            wide = np.array([wide_band(r, a) for r in ok_rows])[sel]
            if wide.any():
                acc[a]["n_wide_fe_band"] = int(wide.sum())
                acc[a]["max_rel_narrow_fe_band"] = float(e[~wide].max()) if (~wide).any() else None
        self.accuracy = acc
        pred = self.predict(u)  # the bands with the measured error in them
        for a in acc:
            fe = np.array([row_value(r, a) for r in ok_rows], dtype=float)
            live, band = pred["value"][a], pred["band"][a]
            sel = np.isfinite(fe) & np.isfinite(live)
            acc[a]["within"] = float(np.mean(np.abs(live[sel] - fe[sel]) <= band[sel])) if sel.any() else None
            if not sel.any():
                acc[a]["live"] = False  # not given live (its error is over UNUSABLE)
        # where the FE answers: the status model against the held-out designs' own status
        p = self.status.probability(np.array([self.region.unit_of(json.loads(r["point_json"])) for r in rows]))
        st = np.array([r.get("status") == "ok" for r in rows])
        acc["status"] = {"n": len(rows), "agree": float(np.mean((p >= OK_PROBABILITY) == st)),
                         "fe_answers": int(st.sum())}
        return acc

    def to_json(self) -> dict:
        """The region, the measured accuracy and the build's figures (JSON-ready)."""
        return {"region": self.region.to_json(), "answers": sorted(self.models), "accuracy": self.accuracy,
                "info": self.info}
