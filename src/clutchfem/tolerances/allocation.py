"""Tolerance allocation and the mass-yield trade-off on the FE model: the widest
manufacturing tolerance per dimension for a yield target, from the linearised spreads of
one sensitivities call (the algebra and its formulation: :mod:`.tolerance_algebra`).

Cost: one :func:`~.sensitivity.sensitivities` call (two morphed designs per toleranced
dimension) and, with the model-error bands, one ``analyze`` with errors (:func:`.robust.
model_bands`); no Monte Carlo in the loop.  Another yield on the same derivatives:
:meth:`Allocation.at` (no FE run).

The trade-off (:func:`yield_front`): along a given set of designs (e.g. the deterministic
and the robust optimum and the straight path between them) the predicted yield at the given
tolerances and the tolerance scale each yield allows, against the part mass.  It is **not**
the true Pareto front (one robust optimisation per yield, hundreds of designs each): its
masses are an upper bound on the front's at those yields.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

from ..core import ParameterError, clean
from ..evaluation import EvalSettings, Sensitivities, sensitivities
from ..geometry import get_concept
from ..targets import Targets
from .algebra import allocate_linear, check_yield, joint_scale
from .robust import model_bands
from .tolerancing import parse_tolerance

#: the unit each constrained answer is shown in
ANSWER_UNIT = {"engagement_rpm_with_ripple": "rpm", "slip_rpm": "rpm", "safety_factor": "-",
               "fatigue_safety_factor": "-"}
#: (scale, unit) each parameter unit is shown in
#: widths beyond this multiple of the given one are flagged as extrapolated
FAR = 2.0
#: the default yields of the trade-off
FRONT_YIELDS = (0.9, 0.95, 0.99, 0.999)


@dataclass
class Allocation:
    """What :func:`allocate_tolerances` returns (module docstring): per constraint its slack,
    spreads and budget; per dimension the given, allocated and alone-widest half-widths
    [SI: m, deg or -], the target binding each and its variance share; the common scale.

    Examples
    --------
    A hand-made linearisation (one target, one dimension; :func:`allocate_tolerances` makes
    it from the design's sensitivities); :meth:`at` re-allocates at another yield, no FE run:

    >>> from clutchfem.tolerances import Allocation
    >>> con = {"name": "engagement", "key": "engagement_rpm_with_ripple", "slack": 100.0,
    ...        "grad": {"flexure_thickness": 2.0e6}, "sigma_model": 0.0}       # rpm, rpm per m
    >>> a = Allocation("concept1", 0.99, "normal", False, 2.33, {"flexure_thickness": 5e-5},
    ...                {"flexure_thickness": "m"}, [con], [{"name": "flexure_thickness", "allocated": 6.4e-5}],
    ...                True, "", linearisation=[con])
    >>> a.allocated
    {'flexure_thickness': 6.4e-05}
    >>> [round(a.at(y)["dims"][0]["allocated"] * 1e6) for y in (0.9, 0.99, 0.999)]   # um: wider at lower yield
    [117, 64, 49]
    """

    concept: str
    yield_target: float
    dist: str
    model_error: bool
    z: float
    tolerances: dict
    units: dict
    constraints: list
    dims: list
    feasible: bool
    message: str
    scale: float | None = None
    scale_binds: str | None = None
    #: the common factor at which the joint-normal yield is the target (no Bonferroni)
    scale_joint: float | None = None
    #: the common factor by the optimal split of the failure budget (Boole)
    scale_union: float | None = None
    #: at the given widths: joint normal (:func:`joint_yield`), and the product of the
    #: per-target probabilities (targets independent, as :mod:`.robust`)
    predicted_yield: float | None = None
    predicted_yield_independent: float | None = None
    #: joint normal at the allocated widths (>= the yield asked: Bonferroni is conservative)
    allocated_yield: float | None = None
    perfect_part_yield: float | None = None
    ranking: list = field(default_factory=list)
    #: the model-error share of the variance of the target binding the scale (given widths)
    model_share: float | None = None
    derivatives: dict = field(default_factory=dict)
    methods: dict = field(default_factory=dict)
    base: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    seconds: float = 0.0
    #: the linearised constraints (slack, gradient, model sigma): :meth:`at` reuses them
    linearisation: list = field(default_factory=list)
    cost: dict | None = None

    def at(self, yield_target: float, model_error: bool | None = None) -> dict:
        """The allocation algebra (:func:`allocate_linear`) at another yield, on the same
        derivatives (no FE run); ``model_error=False`` drops the bands."""
        cons = self.linearisation
        if model_error is False:
            cons = [{**c, "sigma_model": 0.0} for c in cons]
        return allocate_linear(cons, self.tolerances, yield_target=yield_target, dist=self.dist, cost=self.cost,
                               units=self.units)

    @property
    def allocated(self) -> dict:
        """name -> allocated half-width (SI; None where no width meets the yield)."""
        return {d["name"]: d["allocated"] for d in self.dims}

    def to_json(self) -> dict:
        return clean({"allocation": {k: getattr(self, k) for k in (
            "concept", "yield_target", "dist", "model_error", "z", "tolerances", "units", "feasible", "message",
            "scale", "scale_binds", "scale_joint", "scale_union", "predicted_yield", "predicted_yield_independent", "allocated_yield",
            "perfect_part_yield", "ranking", "model_share", "constraints", "dims",
            "derivatives", "methods", "notes", "seconds")},
            "method": {"spread": "linearised: sigma^2 = sum (dA/dx t/k)^2 + (band/2)^2, k = 3 normal, sqrt(3) uniform; "
                                 "dA/dx the steeper one-sided slope where a contact event lies inside the step",
                       "yield": "Bonferroni over the constraints: z = Phi^-1(1 - (1 - Y)/m)",
                       "allocated": "min sum w_i t0_i / t_i (reciprocal cost, Chase & Greenwood 1988, ASSUMED) "
                                    "s.t. z sigma_j <= slack_j; SLSQP in ln t"}})




def linearise(settings: EvalSettings, targets: Targets, names: list[str], model_error: bool = True,
              workers=None) -> tuple[list[dict], Sensitivities]:
    """(constraints with slack, gradient and model sigma; the sensitivities) at a design: one
    :func:`~.sensitivity.sensitivities` call and, with ``model_error``, one ``analyze`` with
    errors."""
    s = sensitivities(settings, names, workers=workers)
    bands = model_bands(settings) if model_error else {}
    cons = []
    for name, key, limit, sense in targets.constraints():
        v = s.base.get(key)
        slack = None if v is None or not math.isfinite(v) else ((v - limit) if sense == ">=" else (limit - v))
        band = bands.get(key)
        cons.append({"name": name, "key": key, "limit": limit, "sense": sense, "value": v, "slack": slack,
                     "unit": ANSWER_UNIT.get(key, ""), "grad": {n: s.spread_derivative(n, key) for n in names},
                     "sigma_model": band / 2.0 if band else 0.0, "band": band})
    return cons, s


def _settings_and_tols(design, tolerances, engine, requirements):
    settings = design if isinstance(design, EvalSettings) else EvalSettings.from_design(
        design, engine=engine, requirements=requirements)
    P = get_concept(settings.concept).Params
    if not isinstance(tolerances, dict) or not tolerances:
        raise ParameterError("tolerances", tolerances, "a dict name -> half-width with at least one entry "
                             "(e.g. {'flexure_thickness': '0.05mm'})", "allocation")
    tols = {}
    for n, t in tolerances.items():
        if isinstance(t, bool) or not isinstance(t, (str, int, float)):
            raise ParameterError(n, t, "a tolerance half-width: SI number or text with its unit", "allocation")
        text = t.strip().lstrip("+-±/") if isinstance(t, str) else repr(float(t))
        name, half = parse_tolerance(P, f"{n}=+-{text}")
        tols[name] = half
    return settings, tols, P


def allocate_tolerances(design, tolerances: dict, *, yield_target: float = 0.99, dist: str = "normal",
                        model_error: bool = True, targets: Targets | None = None, cost: dict | None = None,
                        engine=None, requirements=None, workers: int | None = None) -> Allocation:
    """The widest tolerance per dimension such that every target holds for ``yield_target``
    of the parts, from the linearised spreads (module docstring).

    Parameters
    ----------
    design : Design or EvalSettings
        The nominal design (a concept's).
    tolerances : dict
        ``name -> given half-width`` (SI floats or texts with a unit, ``"0.05mm"``): the
        dimensions to allocate and the widths costs are counted against.
    yield_target : float
        Share of parts that must meet every target, in (0.5, 1).
    dist : {"normal", "uniform"}
        The tolerance at +-3 sigma of a normal (ASSUMED default) or a uniform distribution.
    model_error : bool
        Add each answer's model-error band (as +-2 sigma) to its spread.
    targets : Targets, optional
        Default: the requirement checks with safety factor >= 1.5.
    cost : dict, optional
        name -> cost weight of the dimension at its given width (default 1 each).
    engine, requirements, workers
        As :func:`~.sensitivity.sensitivities`.

    Returns
    -------
    Allocation
        ``feasible`` (False: the model-error band alone eats a margin, no width given),
        ``scale``, ``dims`` (given / allocated / alone-widest half-widths, binding target,
        variance share), ``ranking``, ``predicted_yield`` at the given widths.

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> t = cf.Targets(3510, None, None, None)                # engagement with ripple >= 3510 rpm only
    >>> a = cf.allocate_tolerances(d, {"flexure_thickness": "0.05mm"}, targets=t, model_error=False, workers=0)
    >>> a.feasible, a.allocated["flexure_thickness"] > 0      # a half-width in m
    (True, True)
    """
    t0 = time.perf_counter()
    check_yield(yield_target, dist)
    settings, tols, P = _settings_and_tols(design, tolerances, engine, requirements)
    if cost:
        for n in cost:
            if n not in tols:
                raise ParameterError(f"cost[{n}]", cost[n], "a weight of a toleranced dimension: "
                                     + ", ".join(tols), "allocation")
    nominal = targets or Targets.defaults(settings)
    cons, s = linearise(settings, nominal, list(tols), model_error, workers)
    units = {n: P.unit(n) for n in tols}
    r = allocate_linear(cons, tols, yield_target=yield_target, dist=dist, cost=cost, units=units)
    for c, row in zip(cons, r["constraints"]):
        row.update({k: c[k] for k in ("limit", "sense", "value", "unit", "band")})
    notes = [f"{n}: derivative method {s.methods[n]}" for n in tols if s.methods[n] != "central, morphed"] + list(s.notes)
    far = [d["name"] for d in r["dims"] if (d.get("ratio") or 0.0) > FAR or ((d.get("alone") or 0.0) > FAR * d["given"])]
    if far:
        notes.append(f"{', '.join(far)}: allocated or alone-widest width beyond {FAR:g} x the given one -- the spread "
                     "is linearised at the nominal (derivatives over 0.01 mm / 0.01 deg steps), so so wide a band is "
                     "an extrapolation: check it with a Monte Carlo of those widths (tolerance --n)")
    for c in cons:
        gone = [n for n, g in c["grad"].items() if g is None]
        if gone:
            notes.append(f"{c['name']}: no derivative for {', '.join(gone)} (taken as 0)")
    return Allocation(concept=settings.concept, yield_target=yield_target, dist=dist, model_error=model_error,
                      z=r["z"], tolerances=tols, units=units, constraints=r["constraints"], dims=r["dims"],
                      feasible=r["feasible"], message=r["message"], scale=r["scale"], scale_binds=r["scale_binds"],
                      scale_joint=r.get("scale_joint"), scale_union=r.get("scale_union"),
                      predicted_yield=r["predicted_yield"], perfect_part_yield=r["perfect_part_yield"],
                      predicted_yield_independent=r["predicted_yield_independent"],
                      allocated_yield=r.get("allocated_yield"),
                      ranking=r["ranking"], model_share=r.get("model_share"), derivatives={n: dict(v) for n, v in s.derivatives.items()},
                      methods=dict(s.methods), base=dict(s.base), notes=notes, seconds=time.perf_counter() - t0,
                      linearisation=cons, cost=cost)


@dataclass(frozen=True)
class YieldFront:
    """Part mass against predicted yield over a set of designs (:func:`yield_front`): one
    row per design, in the order given.

    Attributes
    ----------
    rows : tuple of dict
        Per design: ``concept``, ``set`` (its ``--set`` texts), ``mass_kg``,
        ``predicted_yield`` (joint normal), ``predicted_yield_independent``,
        ``predicted_yield_tolerances_only``, ``perfect_part_yield``, ``scale`` and
        ``scale_joint`` (yield -> allowed common factor on the widths), ``pareto``,
        ``slack`` and ``sigma_given`` per constraint (answer units).
    yields : tuple of float
        The yields whose allowed tolerance scale is reported.

    Examples
    --------
    >>> from clutchfem.tolerances import YieldFront
    >>> f = YieldFront(rows=({"mass_kg": 0.1, "predicted_yield": 0.95, "pareto": True},), yields=(0.9,))
    >>> [r["mass_kg"] for r in f.pareto], f.to_json()["yields"]
    ([0.1], [0.9])
    """

    rows: tuple
    yields: tuple

    def __len__(self) -> int:
        return len(self.rows)

    def __getitem__(self, i):
        return self.rows[i]

    def __iter__(self):
        return iter(self.rows)

    @property
    def pareto(self) -> list[dict]:
        """The rows no other design beats (lighter with at least its yield)."""
        return [r for r in self.rows if r["pareto"]]

    def to_json(self) -> dict:
        """The rows and yields as a JSON-ready dict."""
        return clean({"yields": list(self.yields), "designs": list(self.rows)})


def yield_front(designs: list, tolerances: dict, *, yields=FRONT_YIELDS, dist: str = "normal",
                model_error: bool = True, targets: Targets | None = None, engine=None, requirements=None,
                workers: int | None = None) -> YieldFront:
    """Part mass against predicted yield (and the tolerance scale each yield allows) over a
    set of designs: the trade-off of the module docstring (not the true Pareto front).

    Parameters
    ----------
    designs : list of Design or EvalSettings
        The designs (e.g. the deterministic and robust optima and points between).
    tolerances : dict
        ``name -> half-width`` as :func:`allocate_tolerances`.
    yields : sequence of float
        The yields whose allowed tolerance scale is reported.
    dist, model_error, targets, engine, requirements, workers
        As :func:`allocate_tolerances` (``targets`` default: each design's requirement
        checks).

    Returns
    -------
    YieldFront
        One row per design (indexable: ``front[0]``): ``mass_kg``, ``predicted_yield`` at the given widths (joint normal;
        ``predicted_yield_independent``: the product over the targets;
        ``predicted_yield_tolerances_only``: the bands left out), ``perfect_part_yield``,
        ``scale`` (yield -> common factor on the given widths by the Bonferroni margins,
        None where none meets it), ``scale_joint`` (the same by the joint normal),
        ``pareto`` (no other design is lighter with at least its yield), ``slack`` and
        ``sigma_given`` per constraint (answer units).

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> f = cf.yield_front([d], {"clearance": "0.02mm"}, yields=(0.9,), model_error=False, workers=0)
    >>> f[0]["mass_kg"] > 0, f[0]["pareto"]
    (True, True)
    """
    if isinstance(yields, (int, float)) or not yields:
        raise ParameterError("yields", yields, "a sequence of shares of parts in (0.5, 1)", "yield_front")
    for y in yields:
        check_yield(y, dist)
    if not designs:
        raise ParameterError("designs", designs, "at least one design", "yield_front")
    rows = []
    for d in designs:
        settings, tols, P = _settings_and_tols(d, tolerances, engine, requirements)
        nominal = targets or Targets.defaults(settings)
        cons, s = linearise(settings, nominal, list(tols), model_error, workers)
        units = {n: P.unit(n) for n in tols}
        scale, scale_joint, alloc = {}, {}, None
        for y in yields:
            r = allocate_linear(cons, tols, yield_target=y, dist=dist, units=units)
            scale[y] = r["scale"] if r["feasible"] else None
            scale_joint[y] = joint_scale(cons, tols, y, dist)
            if alloc is None:
                alloc = r
        bare = allocate_linear([{**c, "sigma_model": 0.0} for c in cons], tols, yield_target=yields[0], dist=dist,
                               units=units)
        rows.append({"concept": settings.concept, "set": list(settings.base), "mass_kg": s.base.get("mass_kg"),
                     "predicted_yield": alloc["predicted_yield"], "perfect_part_yield": alloc["perfect_part_yield"],
                     "predicted_yield_independent": alloc["predicted_yield_independent"],
                     "predicted_yield_tolerances_only": bare["predicted_yield"],
                     "scale": scale, "scale_joint": scale_joint, "slack": {c["key"] + " " + c["sense"]: c["slack"] for c in cons},
                     "sigma_given": {c["key"]: r_["sigma_given"] for c, r_ in zip(cons, alloc["constraints"])}})
    for r in rows:
        r["pareto"] = not any(o is not r and o["mass_kg"] is not None and r["mass_kg"] is not None
                              and o["mass_kg"] <= r["mass_kg"] and o["predicted_yield"] >= r["predicted_yield"]
                              and (o["mass_kg"] < r["mass_kg"] or o["predicted_yield"] > r["predicted_yield"])
                              for o in rows)
    return YieldFront(rows=tuple(rows), yields=tuple(yields))
