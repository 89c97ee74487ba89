"""Calibration to measured parts: which inputs of the part as built explain what the rig
measured, how sure that is, and which measurements no input within its prior explains.

:func:`calibrate` builds (or loads) the reduced model of a region that holds every uncertain
input's prior (:func:`clutchfem.reduce`, the inputs as its free axes), then samples the
posterior of the inputs given the measurements (:mod:`.inference`) and reports:

* per input: the posterior mean, its 95 % interval, the prior's, **how much the data narrowed
  it** (1 - posterior width / prior width of the 95 % intervals), and whether the data
  identify it: an input narrowed by less than :data:`IDENTIFIED` is said not to be
  identified, with the input it trades off against (the largest posterior correlation);
* the calibrated part's answers with their 95 % bands (the posterior's spread and the
  reduced model's band), against the measurements;
* the **check of the fit** (posterior predictive): per measurement its standardised distance
  from the best fit within the priors and from the posterior predictive distribution; a
  measurement more than :data:`SUSPECT_Z` standard deviations from the best fit any input
  within its prior gives is *not explained* -- the model or the measurement is suspect (or an
  input that is not calibrated differs) -- and is said to be so rather than forced into the
  fit (the posterior shown is then the closest the priors allow, and says so);
* the ranked explanations: the inputs by how far the data moved them from their prior
  (in prior standard deviations).

**Several parts of one design** (measurements ``PART:NAME=...``): the parts share the
inputs of :data:`SHARED` (``mu``, ``drum_wall``, ``E``, ``density``, ``drum_radius``: one
lining, one material, one rig) and each has its own geometry as built, drawn from the same
prior (the tolerance about the drawn value): the posterior holds ``mu`` once and
``flexure_thickness[p1]``, ``flexure_thickness[p2]``, ... per part; each part's answers are
reported as ``slip_rpm[p2]``.  The **process offset** of a geometry input (``offsets``: what
the process adds to every part drawn at that value) is the mean of the parts' deviations
from the drawn value, per posterior sample: with one part it is that part's deviation (its
own scatter within the tolerance cannot be told apart from the process's offset); with
several its band narrows as the parts agree (ASSUMED: the parts' deviations independent
given the offset; no separate prior on the part-to-part scatter).  Repeated readings of one
answer on one part are one combined measurement (:func:`~.inputs.combine_readings`).

**Method**: emcee (the default; 32 walkers x 5000 steps, 500 discarded, on the reduced model:
seconds; a chain shorter than 50 autocorrelation times is noted) or ``laplace`` (the mode and the Hessian: a normal, for a posterior near Gaussian;
refused where the Hessian is not positive definite).  Checked against each other in
docs/calibration.md.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..core import ParameterError
from ..core.figures import figure, save_figure
from ..reduced import OPERATING_AXES, reduce
from .inference import BAND_SIGMAS, Forward, Posterior, emcee_samples, laplace
from .inputs import (
    ANSWER_OF,
    SIMILARITY,
    Measurement,
    Uncertain,
    check_measurements,
    parse_measured,
    parse_uncertain,
)
from .readings import combine_readings
from .summary import IDENTIFIED, REPORTED, answers_of, explanations_of, show, summarise

__all__ = ["IDENTIFIED", "SHARED", "SUSPECT_Z", "Calibration", "calibrate", "is_geometry"]

#: inputs the parts of one design share (the operating inputs, the material, the rig's drum);
#: every other uncertain input is a part's own geometry as built
SHARED = (*OPERATING_AXES, *SIMILARITY, "drum_radius")


def is_geometry(name: str) -> bool:
    """True for a part's own geometry as built (not in :data:`SHARED`)."""
    return name not in SHARED

#: a measurement farther than this (in its standard deviations) from the best fit within the priors is not explained
SUSPECT_Z = 3.0
_NOT_WITH_SIMILARITY = ("slip_rpm", "torque_at_max_engine_torque_Nm", "max_von_mises_Pa", "fatigue_safety_factor")


@dataclass
class Calibration:
    """What :func:`calibrate` returns (module docstring).

    Attributes
    ----------
    concept : str
    posterior : dict
        Input name -> ``mean``, ``sd``, ``ci95`` [lo, hi] (SI, the value as built), ``prior``
        (kind, support, mean, ci95), ``narrowed`` (share), ``identified``, ``trades_off_with``
        (name and correlation, or None), ``at_edge`` (the posterior piles at a bound of the prior).
    answers : dict
        Answer name -> ``mean``, ``ci95`` (the posterior's spread and the model's band),
        ``band`` (the model's band at the mean), ``unit``, ``measured`` (or None).
    checks : list of dict
        Per measurement: ``best_fit``, ``z_best`` (standardised distance from the best fit in
        the priors), ``p_predictive`` (two-sided posterior predictive p-value), ``explained``.
    consistent : bool
        Every measurement explained.
    correlation : list of list
        The posterior correlation matrix (in the order of ``posterior``).
    explanations : list of str
        The inputs ranked by how far the data moved them, in words.
    notes : list of str
    info : dict
        Method, samples, timings, the reduced model's region and accuracy.
    samples : numpy.ndarray
        The posterior samples (n, k), SI.
    parts : list of str
        The measured parts (one part: ``[None]`` unless named).
    offsets : dict
        Geometry input -> the process offset (the mean deviation of the parts as built from
        the drawn value): ``mean``, ``ci95`` [m], ``parts``.
    design, model
        The drawn design and the reduced model (:func:`corrected_design` uses them).

    Examples
    --------
    What a calibration holds (:func:`calibrate` runs one):

    >>> import clutchfem as cf
    >>> list(cf.Calibration.__dataclass_fields__)[:5]
    ['concept', 'uncertain', 'measured', 'posterior', 'answers']
    """

    concept: str
    uncertain: list
    measured: list
    posterior: dict
    answers: dict
    checks: list
    consistent: bool
    correlation: list
    explanations: list
    notes: list = field(default_factory=list)
    info: dict = field(default_factory=dict)
    samples: np.ndarray = field(default=None, repr=False)
    prior_samples: np.ndarray = field(default=None, repr=False)
    parts: list = field(default_factory=lambda: [None])
    offsets: dict = field(default_factory=dict)
    design: object = field(default=None, repr=False)
    model: object = field(default=None, repr=False)
    inputs: list = field(default_factory=list, repr=False)  # the uncertain inputs of one part
    views: list = field(default_factory=list, repr=False)  # (part, columns of samples that are its inputs)

    def part_samples(self, part=None) -> np.ndarray:
        """The posterior samples of one part's inputs (n, len(inputs)), in :attr:`inputs`' order."""
        idx = dict(self.views)[part]
        return self.samples[:, idx]

    def offset_samples(self) -> np.ndarray:
        """Per posterior sample, each of :attr:`inputs`' deviation from the drawn value,
        averaged over the parts (zero for a shared input)."""
        drawn = np.array([u.drawn for u in self.inputs])
        geo = np.array([is_geometry(u.name) for u in self.inputs])
        dev = np.mean([self.samples[:, idx] - drawn for _, idx in self.views], axis=0)
        return np.where(geo, dev, 0.0)

    def to_json(self) -> dict:
        """One JSON-ready object: ``posterior``, ``answers``, ``checks``, ``consistent``, ... (SI)."""
        return {"concept": self.concept, "posterior": self.posterior, "answers": self.answers, "checks": self.checks,
                "consistent": self.consistent, "correlation": {"names": list(self.posterior),
                                                               "matrix": self.correlation},
                "explanations": self.explanations, "measured": [m.to_json() for m in self.measured],
                "parts": self.parts, "offsets": self.offsets, "notes": self.notes, "info": self.info}

    def write_figures(self, out) -> list[Path]:
        """The pictures into folder ``out``: per input its prior and posterior
        (``calibration_inputs.png``), the calibrated answers against the measurements
        (``calibration_answers.png``)."""
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        k = len(self.uncertain)
        fig, axes = figure(1, k, figsize=(4.0 * k, 3.6), layout="constrained", squeeze=False)
        for ax, u, j in zip(axes[0], self.uncertain, range(k)):
            sc, unit = {"m": (1e3, "mm"), "Pa": (1e-9, "GPa")}.get(u.unit, (1.0, u.unit))
            ax.hist(self.prior_samples[:, j] * sc, bins=40, density=True, alpha=0.4, color="0.5", label="prior")
            ax.hist(self.samples[:, j] * sc, bins=40, density=True, alpha=0.6, color="C0", label="posterior")
            p = self.posterior[u.name]
            for x in p["ci95"]:
                ax.axvline(x * sc, color="C0", ls="--", lw=1)
            ax.set_xlabel(f"{u.name} as built [{unit}]".replace(" [-]", " [-]"))
            ax.set_title(f"{u.name}: {p['mean'] * sc:.4g} [{p['ci95'][0] * sc:.4g}, {p['ci95'][1] * sc:.4g}]",
                         fontsize=9)
            ax.set_yticks([])
        axes[0][0].legend(loc="upper left", fontsize=8)
        paths = [save_figure(fig, out / "calibration_inputs.png")]
        meas = [m for m in self.measured if not m.is_dimension]
        if meas:
            fig, axes = figure(1, len(meas), figsize=(3.2 * len(meas) + 1, 3.6), layout="constrained", squeeze=False)
            for ax, m in zip(axes[0], meas):
                a = self.answers.get(m.key)
                label, unit, sc = REPORTED.get(m.answer, (m.name, m.unit, 1.0))
                ax.errorbar([0], [m.value * sc], yerr=[2 * m.sd * sc], fmt="o", color="k", capsize=4,
                            label="measured +- 2 u")
                if a is not None:
                    lo, hi = a["ci95"]
                    ax.errorbar([1], [a["mean"] * sc], yerr=[[(a["mean"] - lo) * sc], [(hi - a["mean"]) * sc]],
                                fmt="s", color="C0", capsize=4, label="calibrated (95 %)")
                    nom = a.get("nominal")
                    if nom is not None:
                        ax.plot([2], [nom * sc], "D", color="C3", label="drawn design")
                ax.set_xticks([0, 1, 2], ["measured", "calibrated", "drawn"])
                ax.set_xlim(-0.5, 2.5)
                ax.set_ylabel(f"{label} [{unit}]")
                ax.set_title(f"{m.name}{'' if m.part is None else ' (' + m.part + ')'}: {m.value * sc:.4g} {unit} measured", fontsize=9)
            axes[0][0].legend(loc="best", fontsize=7)
            paths.append(save_figure(fig, out / "calibration_answers.png"))
        return paths


def _as_measurements(measured, design) -> list[Measurement]:
    if isinstance(measured, (str, Measurement)):
        measured = [measured]
    out = [m if isinstance(m, Measurement) else parse_measured(m, design=design) for m in measured]
    if not out:
        raise ParameterError("measured", [], "at least one measurement (NAME=VALUE+-U)", "calibration")
    check_measurements(out)
    return out


def _as_uncertain(uncertain, design) -> list[Uncertain]:
    if isinstance(uncertain, (str, Uncertain)):
        uncertain = [uncertain]
    out = [u if isinstance(u, Uncertain) else parse_uncertain(design, u) for u in uncertain]
    if not out:
        raise ParameterError("uncertain", [], "at least one uncertain input (NAME=lo:hi or NAME=+-tol)", "calibration")
    names = [u.name for u in out]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ParameterError(dup[0], [u.text for u in out if u.name == dup[0]], "one prior per input", "calibration")
    return out


def calibrate(design, measured, uncertain, *, model=None, method: str = "emcee", n: int | None = None,
              held_out: int = 10, engine=None, requirements=None, workers: int | None = None,
              progress: bool = False, seed: int = 0, steps: int = 5000) -> Calibration:
    """The uncertain inputs of a part as built, given what the rig measured on it.

    Parameters
    ----------
    design : Design
        The drawn design (a concept's, ``fidelity`` of its operating point: the path the
        reduced model is trained on).
    measured : list of str or Measurement
        ``engagement=4191rpm+-25rpm``, ``slip=7512rpm+-40rpm``, ``torque@RPM=V+-U``, a
        measured dimension ``flexure_thickness=2.26mm+-0.01mm`` (:func:`parse_measured`).
    uncertain : list of str or Uncertain
        ``mu=0.1:0.35`` (uniform), ``flexure_thickness=+-0.1mm`` (normal, +-3 sigma about the
        drawn value), ``E=200GPa:215GPa``, ... (:func:`parse_uncertain`).
    model : ReducedModel, optional
        A reduced model whose region holds the priors (default: built or loaded by
        :func:`clutchfem.reduce` over exactly the region axes among ``uncertain``).
    method : str
        ``emcee`` (default) or ``laplace``.
    n, held_out : int
        Training and held-out designs of the reduced model's build (default 8 per axis + 8,
        and 10).
    engine, requirements, workers, progress
        As :func:`clutchfem.reduce`.
    seed : int
        The sampler's seed.
    steps : int
        emcee's steps per walker (500 of them discarded).

    Returns
    -------
    Calibration

    Examples
    --------
    On a reduced model of concept 1 fitted to hand-made rows (an engagement rising with
    the flexure thickness, a slip speed falling with mu): a part measured at a thicker
    flexure and a higher mu than drawn.

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
    >>> c = cf.calibrate(d, ["engagement=4207rpm+-20rpm", "slip=7573rpm+-40rpm"],
    ...                  ["flexure_thickness=+-0.1mm", "mu=0.1:0.35"], model=m, steps=1500)
    >>> t = c.posterior["flexure_thickness"]
    >>> bool(t["ci95"][0] < 2.265e-3 < t["ci95"][1]), bool(t["narrowed"] > 0.5), c.consistent
    (True, True, True)
    """
    t0 = time.perf_counter()
    if method not in ("emcee", "laplace"):
        raise ParameterError("method", method, "emcee or laplace", "calibration")
    if isinstance(steps, bool) or not isinstance(steps, int) or not 1000 <= steps <= 100_000:
        raise ParameterError("steps", steps, "an integer in [1000, 100000] (500 are discarded)", "calibration")
    U = _as_uncertain(uncertain, design)
    M = _as_measurements(measured, design)
    names = [u.name for u in U]
    parts = list(dict.fromkeys(m.part for m in M))
    if len(parts) > 1 and None in parts:
        m0 = next(m for m in M if m.part is None)
        raise ParameterError("measured", m0.text, f"PART:{m0.text} -- once one measurement names its part "
                             f"({', '.join(p for p in parts if p)}), every one must", "option --measured")
    for m in M:
        if m.is_dimension and m.name not in names:
            raise ParameterError(m.name, m.text, f"a measured dimension of an uncertain input ({', '.join(names)}): "
                                 f"add --uncertain {m.name}=... (its prior as built)", "option --measured")
    sim = [u.name for u in U if u.name in SIMILARITY]
    bad = [m for m in M if m.answer in _NOT_WITH_SIMILARITY]
    if sim and bad:
        raise ParameterError(sim[0], next(u.text for u in U if u.name == sim[0]),
                             f"an uncertain {sim[0]} only with measured engagement speeds and masses: it enters by "
                             f"exact similarity, which moves the {bad[0].name} to another speed than the reduced "
                             "model holds it at (leave it out, or fix it with --set/--E)", "option --uncertain")
    axes = [u for u in U if u.axis == "region"]
    if not axes:
        raise ParameterError("uncertain", names, "at least one input the reduced model has as an axis (a shape "
                             "parameter, mu or drum_wall)", "calibration")
    if model is None:
        ranges = {u.name: (u.lo, u.hi) for u in axes}
        d = len(axes)
        model = reduce(design, free=list(ranges), ranges=ranges, n=n if n is not None else 8 * d + 8,
                       held_out=held_out, engine=engine, requirements=requirements, workers=workers,
                       progress=progress)
    reg = model.region
    for u in axes:
        lo, hi = reg.bounds(u.name) if u.name in reg.names else (None, None)
        if lo is None or lo > u.lo + 1e-12 * max(1.0, abs(u.lo)) or hi < u.hi - 1e-12 * max(1.0, abs(u.hi)):
            raise ParameterError(u.name, u.text, f"a prior inside the reduced model's region ({reg.describe()})",
                                 "calibration")
    t_model = time.perf_counter() - t0
    fw = Forward(model, U, design)
    for m in M:
        if not m.is_dimension and m.answer not in fw.answers:
            raise ParameterError(m.name, m.text, "a measurement of an answer the reduced model gives ("
                                 + ", ".join(a for a in ANSWER_OF if ANSWER_OF[a][0] in fw.answers) + ")",
                                 "option --measured")
        if m.name == "torque":
            rpm = float(reg.settings.engine().rpm_max_torque)
            if abs(m.at_rpm - rpm) > 1.0:
                raise ParameterError("torque", m.text, f"a torque at {rpm:.0f} rpm, the engine's maximum-torque speed "
                                     "where the reduced model holds it (read a curve there: --torque-csv)",
                                     "option --measured")
    M, reading_notes = combine_readings(M)
    # the inputs of the posterior: the shared ones once, each part's geometry per part
    if len(parts) == 1:
        UF, views = list(U), [(parts[0], list(range(len(U))))]
    else:
        UF = [u for u in U if not is_geometry(u.name)]
        views = [(p, []) for p in parts]
        for p, idx in views:
            for u in U:
                if is_geometry(u.name):
                    UF.append(replace(u, name=f"{u.name}[{p}]", text=f"{p}:{u.text}"))
                    idx.append(len(UF) - 1)
                else:
                    idx.append(next(i for i, v in enumerate(UF) if v.name == u.name))
    names_f = [u.name for u in UF]
    col = {}  # measurement -> the column of a measured dimension
    for m in M:
        if m.is_dimension:
            col[id(m)] = dict(views)[m.part][names.index(m.name)]
    post = Posterior(fw, UF, M, views)
    rng = np.random.default_rng(seed)
    t1 = time.perf_counter()
    mode = post.best(rng)
    notes = list(reading_notes)
    if method == "emcee":
        S, info = emcee_samples(post, seed=seed, steps=steps)
    else:
        S, info = laplace(post, seed=seed, mode=mode)
        if not info["gaussian"]:
            raise ParameterError("method", "laplace", "emcee here: the posterior is not near Gaussian (the Hessian "
                                 "of -log posterior at its mode is not positive definite: a ridge or a mode on the "
                                 "prior's edge)", "calibration")
    info["sample_s"] = time.perf_counter() - t1
    if method == "emcee" and not info["chain_long_enough"]:
        notes.append(f"the chain ({steps - info['burn']} steps kept) is shorter than 50 autocorrelation times "
                     f"({info['autocorr_steps']:.0f} steps each): the intervals are rough; more --steps")
    prior_S = np.column_stack([u.sample(np.random.default_rng(seed + 1), len(S)) for u in UF])
    posterior, corr = summarise(UF, S, prior_S)
    z_best, s_best, ans_best, _ = post.residuals(mode[None, :])
    # the posterior predictive: answers over the samples, each measurement's replicate
    sub = S[:: max(1, len(S) // 4000)]
    zs, ss, ans_s, _ = post.residuals(sub)
    checks = []
    for k, m in enumerate(M):
        pred = sub[:, col[id(m)]] if m.is_dimension else ans_s[m.key]
        rep = pred + rng.normal(0.0, ss[:, k])
        p = 2.0 * min(np.mean(rep <= m.value), np.mean(rep >= m.value))
        best = float(mode[col[id(m)]]) if m.is_dimension else float(ans_best[m.key][0])
        z = float(-z_best[0, k])  # (best fit - measured) / sigma
        checks.append({"measured": m.name, "part": m.part, "readings": m.readings, "text": m.text, "value": m.value, "unit": m.unit, "best_fit": best,
                       "sigma": float(s_best[0, k]), "z_best": z, "p_predictive": float(p),
                       "explained": bool(abs(z) <= SUSPECT_Z)})
    consistent = all(c["explained"] for c in checks)
    for c in checks:
        if not c["explained"]:
            notes.append(f"NOT EXPLAINED: {c['text']} -- the best fit any input within its prior gives is "
                         f"{show(c['best_fit'], c['unit'])} ({c['z_best']:+.1f} sigma of the measurement and the "
                         "model together): the model, the measurement or an input not calibrated here is suspect; "
                         "the posterior shown is the closest the priors allow, not an explanation")
    for name, p in posterior.items():
        if p["at_edge"]:
            notes.append(f"{name}: the posterior piles at the {p['at_edge']} bound of its prior "
                         f"({show(p['prior'][p['at_edge']], p['prior']['unit'])}): the data push it beyond the prior")
    answers = {}
    for p, idx in views:
        for a, v in answers_of(fw, sub[:, idx], [m for m in M if m.part == p], design, model).items():
            if p is not None:
                v["label"] += f" ({p})"
            answers[a if p is None else f"{a}[{p}]"] = v
    offsets = {}
    geo = [j for j, u in enumerate(U) if is_geometry(u.name)]
    if geo:
        drawn = np.array([u.drawn for u in U])
        dev = np.mean([S[:, idx] - drawn for _, idx in views], axis=0)
        for j in geo:
            lo, hi = (float(q) for q in np.quantile(dev[:, j], [0.025, 0.975]))
            offsets[U[j].name] = {"mean": float(dev[:, j].mean()), "ci95": [lo, hi], "unit": U[j].unit,
                                  "drawn": U[j].drawn, "parts": len(views)}
    if len(views) > 1:
        notes.append(f"{len(views)} parts: {', '.join(n for n in SHARED if n in names) or 'no input'} shared, the "
                     "geometry per part; the process offset of each geometry input is the mean of the parts' "
                     "deviations (offsets); the model's error taken independent from part to part (ASSUMED)")
    info.update({"mode": dict(zip(names_f, map(float, mode))), "samples": int(len(S)), "model_s": t_model,
                 "total_s": time.perf_counter() - t0, "band_sigmas": BAND_SIGMAS,
                 "model_rel_band": {a: fw.rel_band[a] for a in post.answers},
                 "region": reg.to_json(), "accuracy": model.accuracy})
    expl = explanations_of(UF, posterior, consistent)
    return Calibration(concept=design.name, uncertain=UF, measured=M, posterior=posterior, answers=answers,
                       checks=checks, consistent=consistent, correlation=corr.tolist(), explanations=expl,
                       notes=notes, info=info, samples=S, prior_samples=prior_S, parts=parts, offsets=offsets,
                       design=design, model=model, inputs=list(U), views=views)
