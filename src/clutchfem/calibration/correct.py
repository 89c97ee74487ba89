"""The corrected design for the next part: the drawn values that make the part *as built*
(the calibrated process offset added, at the calibrated operating inputs) give the targets.

What is known after a calibration (:func:`clutchfem.calibrate`): the shared inputs (``mu``,
``drum_wall``, ``E``, ``density``) as they are on the rig, and per geometry input the
**process offset** d (a part drawn at t came out at t + d: the mean deviation of the measured
parts, :attr:`Calibration.offsets`).  The next part drawn at x comes out at x + d.  So
:func:`corrected_design` chooses the drawn values x of the inputs to ``adjust`` (geometry
inputs that were calibrated) that bring the answers of the next part as built -- the
reduced model at (x + d, the calibrated shared inputs), averaged over the posterior -- to
the ``targets``:

    min_x  sum_a ((E[f_a(x + d, theta)] - target_a) / target_a)^2

over the posterior samples of (d, theta), within the reduced model's region for the part as
built (the model is not extrapolated).  The start is the plain offset correction x = drawn -
d.  **Targets**: by default the drawn design's own predicted answers of every answer measured
(what the design was drawn for: the original prediction); or given (``engagement=4000rpm``).
With as many inputs to adjust as targets a target is met exactly where it is reachable;
with fewer, the relative misfit is shared.  A target the adjusted inputs cannot reach within
the region is said to be so (``met`` False: its value outside the prediction's 95 % band).

**The bands**: the corrected design's answers over the posterior samples (the offset's and
the shared inputs' uncertainty) plus the reduced model's band (as the calibrated answers).
Not in them: the next part's own scatter about the process offset (the tolerance: run
``clutchfem tolerance`` on the corrected design for that).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from ..core import ParameterError, param_bounds, parse_quantity
from ..core.units import UnitError
from ..loadcase import Design
from .calibrate import is_geometry
from .inference import Forward
from .inputs import ANSWER_OF
from .summary import REPORTED, show

__all__ = ["Correction", "corrected_design", "parse_target"]

#: posterior samples the search averages over (the bands use all of them, thinned to 4000)
SEARCH_SAMPLES = 400
#: share of the posterior samples whose part as built must lie in the reduced model's region
INSIDE_SHARE = 0.9


def parse_target(text: str) -> tuple[str, float]:
    """A target of the corrected design from ``NAME=VALUE`` (a measured answer's name).

    Parameters
    ----------
    text : str
        ``engagement=4000rpm``, ``slip=7500rpm``, ``torque=5Nm``, ``mass=0.2kg``.

    Returns
    -------
    (str, float)
        The reduced model's answer and the value (SI; speeds in rpm).

    Examples
    --------
    >>> from clutchfem.calibration import parse_target
    >>> parse_target("slip=7500rpm")
    ('slip_rpm', 7500.0)
    >>> parse_target("slip=7500mm")
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: option --target: parameter 'slip' = 'slip=7500mm' is not allowed: a speed in rpm (unit suffix rpm, 1/min, rad/s, Hz)
    """
    option = "option --target"
    m = re.fullmatch(r"\s*([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(\S+)\s*", str(text))
    if not m:
        raise ParameterError("target", text, "NAME=VALUE with its unit, e.g. engagement=4000rpm, slip=7500rpm",
                             option)
    name, raw = m.groups()
    if name not in ANSWER_OF:
        raise ParameterError(name, text, "a target answer: " + ", ".join(ANSWER_OF), option)
    answer, unit, _ = ANSWER_OF[name]
    try:
        v = float(parse_quantity(raw, unit))
    except UnitError as exc:
        raise ParameterError(name, text, exc.expected, option) from None
    if not (math.isfinite(v) and v > 0):
        raise ParameterError(name, text, f"a value > 0 {unit}", option)
    return answer, v


@dataclass
class Correction:
    """What :func:`corrected_design` returns (module docstring).

    Attributes
    ----------
    concept : str
    changes : dict
        Adjusted input -> ``drawn`` (the calibrated design's), ``offset`` (the process's, its
        ``offset_ci95``), ``corrected`` (the next part's drawn value), ``as_built`` (its
        expected value as built), ``plain`` (drawn - offset: the offset correction alone),
        ``unit``; all SI.
    answers : dict
        Answer -> ``label``, ``mean``, ``ci95`` (the next part as built), ``target``,
        ``uncorrected`` (the calibrated part's mean: the drawn design made again), ``met``.
    targets : dict
        Answer -> target value, and ``target_source`` (``given`` or ``the drawn design's
        prediction``).
    met : bool
        Every target within the corrected design's 95 % band.
    set_args : list of str
        The corrected drawn values as ``--set`` texts (``flexure_thickness=2.1432mm``).
    design : Design
        The corrected drawn design (for :func:`clutchfem.export`).
    notes : list of str

    Examples
    --------
    :func:`corrected_design` makes one; what its JSON holds:

    >>> from clutchfem.calibration import Correction
    >>> k = Correction("concept1", {"flexure_thickness": {"drawn": 2.2e-3, "offset": 4.2e-5, "corrected": 2.158e-3}},
    ...                {}, {"engagement_rpm": 4000.0}, "given", True, ["flexure_thickness=2.158mm"], design=None)
    >>> sorted(k.to_json())[:4], k.to_json()["set_args"]
    (['answers', 'changes', 'concept', 'label'], ['flexure_thickness=2.158mm'])
    """

    concept: str
    changes: dict
    answers: dict
    targets: dict
    target_source: str
    met: bool
    set_args: list
    design: object = field(repr=False)
    notes: list = field(default_factory=list)

    def to_json(self) -> dict:
        """JSON-ready (SI): ``changes``, ``answers``, ``targets``, ``met``, ``set_args``, ``notes``."""
        return {"concept": self.concept, "changes": self.changes, "answers": self.answers, "targets": self.targets,
                "target_source": self.target_source, "met": self.met, "set_args": self.set_args,
                "label": self.design.label if self.design is not None else None, "notes": self.notes}


def corrected_design(calibration, *, adjust=None, targets=None, seed: int = 0) -> Correction:
    """The drawn design whose next part, as built, meets the targets (module docstring).

    Parameters
    ----------
    calibration : Calibration
        A calibration (:func:`clutchfem.calibrate`): its posterior, process offsets, design
        and reduced model.
    adjust : list of str, optional
        The drawn inputs to move: calibrated geometry inputs (default: every one).
    targets : list of str or dict, optional
        ``["engagement=4000rpm", ...]`` (:func:`parse_target`) or ``{answer: value}``;
        default: the drawn design's predicted answers of every answer measured.
    seed : int
        The seed of the search's subsample and the model band's draws.

    Returns
    -------
    Correction

    Examples
    --------
    On the hand-made reduced model of :func:`clutchfem.calibrate`'s example, a part whose
    flexure came out thicker than drawn engaged and slipped late; the next part is drawn
    thinner by about the offset, so that it engages as the drawn design was predicted to:

    >>> import json, numpy as np, clutchfem as cf
    >>> from clutchfem.reduced import ReducedModel, Region
    >>> d = cf.Design.from_concept("concept1", fidelity="live")
    >>> r = Region.around(d, free=["flexure_thickness", "mu"], ranges={"flexure_thickness": ("2.0mm", "2.4mm"),
    ...                                                                   "mu": (0.1, 0.35)})
    >>> eng = lambda t, mu: 4000 * (t / 2.2e-3) ** 1.5
    >>> slip = lambda t, mu: eng(t, mu) * (1 + 0.2 / mu)
    >>> row = lambda p: {"status": "ok", "point_json": json.dumps(dict(zip(r.names, p))),
    ...                  "engagement_rpm": eng(*p), "slip_rpm": slip(*p)}
    >>> pts = np.random.default_rng(0).random((40, 2)) * [0.4e-3, 0.25] + [2.0e-3, 0.1]
    >>> m = ReducedModel.fit(r, [row(p) for p in pts[:30]]); _ = m.measure([row(p) for p in pts[30:]])
    >>> c = cf.calibrate(d, ["engagement=4207rpm+-20rpm"], ["flexure_thickness=+-0.1mm", "mu=0.1:0.35"],
    ...                  model=m, steps=1500)
    >>> k = cf.corrected_design(c, targets=["engagement=4000rpm"])
    >>> ch = k.changes["flexure_thickness"]
    >>> bool(abs(ch["corrected"] - (2.2e-3 - ch["offset"])) < 5e-6), k.met, k.set_args[0][:20]
    (True, True, 'flexure_thickness=2.')
    """
    from scipy.optimize import minimize

    if calibration.model is None or calibration.design is None or not calibration.inputs:
        raise ParameterError("calibration", type(calibration).__name__, "a Calibration of clutchfem.calibrate "
                             "(with its design and reduced model)", "corrected design")
    U, design, model = calibration.inputs, calibration.design, calibration.model
    names = [u.name for u in U]
    geometry = [u.name for u in U if is_geometry(u.name)]
    if adjust is None:
        adjust = list(geometry)
    elif isinstance(adjust, str):
        adjust = [a.strip() for a in adjust.split(",") if a.strip()]
    adjust = list(dict.fromkeys(adjust))
    for a in adjust:
        if a not in geometry:
            raise ParameterError(a, a, "a calibrated geometry input to adjust: " + (", ".join(geometry) or
                                 "none here (calibrate a geometry input with --uncertain NAME=+-tol)"),
                                 "option --correct")
    if not adjust:
        raise ParameterError("correct", [], "a calibrated geometry input to adjust (--uncertain NAME=+-tol): "
                             "the shared inputs (" + ", ".join(n for n in names if not is_geometry(n)) + ") are not "
                             "drawn", "option --correct")
    fw = Forward(model, U, design)
    # the targets
    if targets is None or (not isinstance(targets, dict) and not list(targets)):
        measured = list(dict.fromkeys(m.answer for m in calibration.measured if not m.is_dimension))
        tg = {}
        for a in measured:
            nom = next((v.get("nominal") for k, v in calibration.answers.items() if k.split("[")[0] == a), None)
            if nom is not None:
                tg[a] = float(nom)
        if not tg:
            raise ParameterError("target", None, "a target (--target engagement=4000rpm): no answer was measured "
                                 "whose drawn prediction would be the default", "option --target")
        source = "the drawn design's prediction"
    else:
        items = targets.items() if isinstance(targets, dict) else (parse_target(t) for t in
                                                                    ([targets] if isinstance(targets, str)
                                                                     else targets))
        tg = {}
        for a, v in items:
            if a in tg:
                raise ParameterError(a, v, "one target per answer", "option --target")
            tg[a] = float(v)
        source = "given"
    for a in tg:
        if a not in fw.answers:
            raise ParameterError(a, tg[a], "an answer the reduced model gives (" + ", ".join(
                n for n, v in ANSWER_OF.items() if v[0] in fw.answers) + ")", "option --target")
    if "slip_rpm" in tg and "engagement_rpm" in tg and tg["slip_rpm"] <= tg["engagement_rpm"]:
        raise ParameterError("slip", tg["slip_rpm"], f"a slip target above the engagement target "
                             f"({tg['engagement_rpm']:.0f} rpm): a clutch slips only once it has engaged",
                             "option --target")
    # the next part as built: per posterior sample, the shared inputs and drawn + offset
    S = calibration.samples
    S = S[:: max(1, len(S) // 4000)]
    off_all = calibration.offset_samples()
    off = off_all[:: max(1, len(calibration.samples) // 4000)][: len(S)]
    base_view = calibration.part_samples(calibration.parts[0])[:: max(1, len(calibration.samples) // 4000)][: len(S)]
    drawn = np.array([u.drawn for u in U])
    theta0 = np.where([is_geometry(n) for n in names], drawn + off, base_view)
    j_adj = [names.index(a) for a in adjust]
    off_mean = off_all[:, j_adj].mean(axis=0)
    reg = model.region
    lo, hi = [], []
    for a, m_off in zip(adjust, off_mean):
        rlo, rhi = reg.bounds(a)
        plo, phi = param_bounds(type(design.params), a)
        lo.append(max(rlo - m_off, plo if plo is not None else -math.inf))
        hi.append(min(rhi - m_off, phi if phi is not None else math.inf))
    lo, hi = np.array(lo), np.array(hi)
    rng = np.random.default_rng(seed)
    sub = theta0[rng.choice(len(theta0), min(SEARCH_SAMPLES, len(theta0)), replace=False)]
    tnames = list(tg)
    tv = np.array([tg[a] for a in tnames])

    def at(x, th):
        t = th.copy()
        t[:, j_adj] += np.asarray(x) - drawn[j_adj]
        return t

    def cost(z):
        x = lo + (hi - lo) * np.clip(z, 0.0, 1.0)
        ans, ok = fw(at(x, sub), tnames)
        if ok.mean() < INSIDE_SHARE:
            return 1e3 * (1.0 + INSIDE_SHARE - ok.mean())
        pred = np.array([np.mean(ans[a][ok]) for a in tnames])
        return float(np.sum(((pred - tv) / tv) ** 2))

    plain = np.clip(drawn[j_adj] - off_mean, lo, hi)
    starts = [(plain - lo) / (hi - lo)] + list(rng.random((4, len(adjust))))
    best = None
    for z0 in starts:
        r = minimize(cost, z0, method="L-BFGS-B", bounds=[(0.0, 1.0)] * len(adjust))
        if best is None or r.fun < best.fun:
            best = r
    x = lo + (hi - lo) * np.clip(best.x, 0.0, 1.0)
    # the corrected design's answers with bands, against the targets and the design made again
    shown = [a for a in REPORTED if a in fw.answers]
    built = at(x, theta0)
    ans, ok = fw(built, shown)
    # per adjusted input, the share of the next parts as built beyond the region (the search's edge)
    outside = [float(np.mean((built[:, j] < reg.bounds(a)[0]) | (built[:, j] > reg.bounds(a)[1])))
               for a, j in zip(adjust, j_adj)]
    unc, ok0 = fw(theta0, shown)
    notes = []
    if ok.mean() < INSIDE_SHARE:
        notes.append(f"only {100 * ok.mean():.0f} % of the posterior's parts as built lie in the reduced model's "
                     f"region ({reg.describe()}): the answers are from those; widen the prior to reach further")
    band_rng = np.random.default_rng(seed + 7)
    answers, met = {}, True
    for a in shown:
        v = ans[a][ok & np.isfinite(ans[a])]
        if not len(v):
            continue
        rep = v + band_rng.normal(0.0, 1.0, len(v)) * fw.sigma_model(a, v)
        ci = [float(q) for q in np.quantile(rep, [0.025, 0.975])]
        label, unit, sc = REPORTED[a]
        u0 = unc[a][ok0 & np.isfinite(unc[a])]
        entry = {"label": label, "mean": float(v.mean()), "ci95": ci, "unit": {"max_von_mises_Pa": "Pa",
                                                                              "mass_kg": "kg"}.get(a, unit),
                 "uncorrected": float(u0.mean()) if len(u0) else None, "target": tg.get(a)}
        if a in tg:
            entry["met"] = bool(ci[0] <= tg[a] <= ci[1])
            met &= entry["met"]
            if not entry["met"]:
                at_bound = [n for n, xv, lv, hv, ob in zip(adjust, x, lo, hi, outside)
                            if min(xv - lv, hv - xv) < 1e-3 * (hv - lv) or ob > 0.01]
                notes.append(f"NOT REACHED: {a} {entry['mean']:.5g} (95 % {ci[0]:.5g} .. {ci[1]:.5g}) against the "
                             f"target {tg[a]:.5g} {entry['unit']}" + (
                                 f": {', '.join(at_bound)} at the bound of the reduced model's region for the part "
                                 "as built -- widen the prior (the region) or adjust more inputs" if at_bound else
                                 ": the adjusted inputs cannot meet every target at once -- adjust more inputs"))
        answers[a] = entry
    changes, params = {}, {}
    for a, j, xv, mo in zip(adjust, j_adj, x, off_mean):
        u = U[j]
        o = calibration.offsets.get(a, {})
        changes[a] = {"drawn": u.drawn, "offset": float(mo), "offset_ci95": o.get("ci95"), "corrected": float(xv),
                      "as_built": float(xv + mo), "plain": float(u.drawn - mo), "unit": u.unit}
        params[a] = float(xv)
    set_args = [f"{a}={show(v, U[names.index(a)].unit, 6).replace(' ', '')}" for a, v in params.items()]
    P = type(design.params)
    try:
        new_params = P(**{**design.params.model_dump(), **params})
    except Exception as exc:  # the concept's own rules (pydantic): said, not a traceback
        raise ParameterError(adjust[0], set_args, f"a design the concept's rules allow ({exc})",
                             "corrected design") from None
    new = Design.from_concept(design.concept, new_params, design.op, design.mesh_settings)
    if len(adjust) < len(tg):
        notes.append(f"{len(adjust)} input(s) adjusted for {len(tg)} targets: the relative misfit is shared "
                     "(least squares); adjust more inputs to meet each")
    notes.append("the bands hold the posterior's uncertainty (offset and shared inputs) and the reduced model's; "
                 "not the next part's own scatter within the tolerance (run tolerance on the corrected design)")
    return Correction(concept=calibration.concept, changes=changes, answers=answers, targets=tg,
                      target_source=source, met=bool(met), set_args=set_args, design=new, notes=notes)
