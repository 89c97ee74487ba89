"""Guidelines of a live design: the elasticities from the derivatives of the cached reduced
model whose region holds it (:meth:`clutchfem.reduced.ReducedModel.sensitivities`), in
milliseconds, each with its band, and the full FE's morphed finite differences for a few
parameters as a check.

**The band of a live elasticity** E = (x0 / A) dA/dx: the reduced model's measured error e
of answer A (the largest relative error on its held-out designs) propagated to the slope,
on the assumption that that error varies no faster than across the region's width W (the
model is fitted to designs spread over the box; a faster wiggle would have shown up as a
larger held-out error): |d(error)/dx| <= 2 e |A| / W, so

    band(E) = 2 e x0 / W       (+-5 % region: W = 0.1 x0, band = 20 e)

An estimate, not a bound: hence the **FE check** -- the ``check`` parameters with the
largest engagement elasticity are differentiated by the full FE (central differences on
meshes morphed from the design, :func:`clutchfem.sensitivities`, best path) and each row of
them says whether the FE's elasticity lies within the live one's band plus the stability
rule's 0.05 + 10 % (``fe_check``: agrees / differs / no FE answer).  The model is smooth by
construction: where the FE has a kink inside its step (a contact node entering the zone),
the two differ and the FE's one-sided values are the ones to use.
"""

from __future__ import annotations

import math

from ..core import ParameterError
from ..evaluation import sensitivities
from ..reduced import find
from .elasticity import ANSWERS, SENSITIVITY_KEY, STABLE_ABS, STABLE_REL, GuidelineResult

__all__ = ["DEFAULT_CHECK", "live_guidelines"]

#: parameters checked against the full FE by default
DEFAULT_CHECK = 2


def live_guidelines(design, *, params=None, engine=None, requirements=None, check: int = DEFAULT_CHECK,
                    workers: int | None = 0) -> GuidelineResult:
    """The guidelines of a live ``design`` from the reduced model whose cached region holds it
    (module docstring).

    Parameters
    ----------
    design : Design
        A concept's design whose operating point's fidelity is ``"live"``.
    params : list of str, optional
        The parameters (default: the region's free parameters).
    engine, requirements : optional
        The engine curve and requirement factors the region was built against.
    check : int
        Parameters also differentiated by the full FE (the strongest first; 0: none).
    workers : int, optional
        The study engine's workers for the FE check (0: in this process).

    Returns
    -------
    GuidelineResult
        One row per parameter and answer: ``E``, its ``E_band``, ``own_error`` and, for the
        checked parameters, ``E_fe`` and ``fe_check``; the ranking; the notes say what answered.

    Examples
    --------
    A design no cached region holds is refused, naming what builds one:

    >>> import os, tempfile, clutchfem as cf
    >>> from clutchfem.guidelines.live import live_guidelines
    >>> os.environ["CLUTCHFEM_CACHE"] = tempfile.mkdtemp()
    >>> live_guidelines(cf.Design.from_concept("concept1", fidelity="live"))
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: ...
    """
    if design.params is None or design.op.fidelity != "live":
        raise ParameterError("fidelity", design.op.fidelity, "live, for a concept's design", "live guidelines")
    if isinstance(check, bool) or not isinstance(check, int) or not 0 <= check <= 50:
        raise ParameterError("check", check, "an integer in [0, 50]: parameters also differentiated by the FE",
                             "live guidelines")
    model = find(design, engine=engine, requirements=requirements)
    if model is None:
        raise ParameterError("fidelity", "live", f"a design a cached reduced model holds (none holds "
                             f"{design.label}: `clutchfem reduce {design.name} --set ...` builds one around it, "
                             "minutes; or --fidelity best)", "guidelines")
    reg = model.region
    names = list(reg.names) if params is None else list(params)
    s = model.sensitivities(design, names)  # refuses names outside the region, naming them
    rows = []
    for n in names:
        i = reg.names.index(n)
        width = reg.hi[i] - reg.lo[i]
        x0 = s.values[n]
        for ans, _ in ANSWERS:
            key = SENSITIVITY_KEY[ans]
            e = s.elasticity(n, key)
            own = model.own_error(key)
            band = 2.0 * own * abs(x0) / width if math.isfinite(own) else math.nan
            rows.append({"parameter": n, "answer": ans, "unit": s.units[n], "x0": x0,
                         "E": math.nan if e is None else float(e), "E_band": band, "own_error": own,
                         "method": s.methods[n], "verdict": "no answer" if e is None else "unchecked"})
    strength = {n: max((abs(r["E"]) for r in rows if r["parameter"] == n and math.isfinite(r["E"])), default=0.0)
                for n in names}
    ranking = sorted(names, key=lambda n: -strength[n])
    eng = {r["parameter"]: abs(r["E"]) for r in rows if r["answer"] == "engagement_rpm" and math.isfinite(r["E"])}
    checked = sorted(eng, key=lambda n: -eng[n])[:check]
    notes = [f"live: elasticities from the reduced model of {reg.concept} over {reg.describe()} (region "
             f"{reg.key()}), central differences of the fitted model; the band E_band = 2 e x0 / W: its own "
             "measured error e propagated over the region's width W (an estimate: see the FE check)"]
    if checked:
        fd = sensitivities(design.with_fidelity("best"), checked, workers=workers)
        for r in rows:
            if r["parameter"] not in checked:
                continue
            ef = fd.elasticity(r["parameter"], SENSITIVITY_KEY[r["answer"]])
            r["E_fe"] = math.nan if ef is None else float(ef)
            if not (math.isfinite(r["E_fe"]) and math.isfinite(r["E"])):
                r["fe_check"] = "no FE answer" if math.isfinite(r["E"]) else "no answer"
                continue
            tol = (r["E_band"] if math.isfinite(r["E_band"]) else 0.0) + STABLE_ABS + STABLE_REL * abs(r["E_fe"])
            r["fe_check"] = "agrees" if abs(r["E"] - r["E_fe"]) <= tol else "differs"
            r["verdict"] = "stable" if r["fe_check"] == "agrees" else "unstable"
            kink = fd.kinks.get(r["parameter"], {}).get(SENSITIVITY_KEY[r["answer"]])
            if kink:
                r["kink"] = f"the FE has a contact event inside its step (at the {kink['speed']} speed)"
        agree = sum(r.get("fe_check") == "agrees" for r in rows)
        done = sum("fe_check" in r and r["fe_check"] in ("agrees", "differs") for r in rows)
        notes.append(f"FE check ({', '.join(checked)}: central differences on morphed meshes, best path): {agree} of "
                     f"{done} elasticities within the live band + {STABLE_ABS} + {STABLE_REL:.0%}"
                     + ("; the others: fe_check 'differs' (verdict unstable), E_fe beside them" if agree < done else ""))
    else:
        notes.append("no FE check (check = 0): the verdicts are 'unchecked'")
    return GuidelineResult(concept=reg.concept, base=dict(zip(names, (s.values[n] for n in names))), step=0.0,
                           table=rows, ranking=ranking, oat=None, notes=notes,
                           methods={n: s.methods[n] for n in names})
