"""Design sensitivities: the derivative of every main answer with respect to the concept's
parameters, by central differences on meshes morphed from the design's own mesh.

Method (issue 21).  The design is the morph reference (:mod:`clutchfem.mesh.morph`); for each
parameter x_i the designs x_i +- h_i are evaluated on the study engine with their meshes
*morphed* from the design's, so both share its mesh connectivity and the difference

    dA/dx_i ~ (A(x + h_i e_i) - A(x - h_i e_i)) / (2 h_i)            (central, O(h^2))

carries no remeshing noise.  Where a rule of the concept refuses one side, the one-sided
difference against the design itself is used (O(h), said in ``method``); where a morph is
refused (the curves change, or the elements would be too distorted) that side was meshed
from scratch and the derivative carries remeshing noise (said in ``method`` and ``notes``).

Step h_i: lengths 0.01 mm (1e-5 m; exact as a ``--set`` text, :mod:`.values`), angles 0.01
deg, dimensionless values 1e-3 of the value (at least 1e-6).  Measured over h = 1e-3 ..
1e-1 mm on concept 4 (``benchmarks/bench_sensitivity.py``, BENCHMARKS.md, "Robust design"):
on morphed meshes the engagement and mass derivatives scatter by 0-0.15 %, the peak stress's
by 0.02-7 % (remeshed: 6-120 %); slip speed (0.1-0.9 %) and torque (1.5-3 %) scatter as much
as on remeshed designs: the answers are smooth to 1e-10 of their value, but piecewise -- each
time a contact node enters or leaves, the slope jumps by ~2 % on the default rigid drum
(``benchmarks/bench_derivative_smoothness.py``: a resolved contact zone or an elastic drum
makes them smoother), which morphing does not remove.

Kinks (contact events).  The contact answers are smooth between contact events but not
across them: where a contact node enters or leaves the zone at the speed an answer is read at
(slip speed; rpm of maximum engine torque for the torque and the contact arc; engine's
maximum speed for the peak stress and its safety factor; both of these for the fatigue
factor), that answer's slope jumps (by
0.2-4 % on concept 4; BENCHMARKS.md, "Robust design").  Designs morphed from one reference
share the contact nodes' numbering, so every evaluated row carries the loaded nodes at those
speeds (study column ``contact_sets``), and where the sets at x - h and x + h differ the
derivative straddles an event: ``kinks[name][answer]`` then gives the one-sided slopes on
each side (``left`` = (A(x) - A(x - h)) / h, ``right`` = (A(x + h) - A(x)) / h), their jump
relative to the central difference, and the nodes on each side, and
:meth:`Sensitivities.spread_derivative` -- what the linearised tolerance spreads use (robust
optimisation, tolerance allocation) -- takes the steeper side, so a spread is not
under-estimated across the kink.  The central difference stays the derivative (the secant
over the step: a generalised gradient for the optimiser).  Not detected where a side was
meshed from scratch (the numbering differs): ``notes`` says so.

Answers (SI units): engagement speed, engagement with ripple, slip speed [rpm], torque at the
engine's maximum torque [N m], peak von Mises stress at the engine's maximum speed [Pa], its
safety factor against yield [-], fatigue safety factor [-], part mass, mass of one shoe [kg],
contact arc at the rpm of maximum engine torque [deg] (it moves in steps of one contact node:
its derivative is 0 or a jump, read it as such).

Operating inputs (:data:`OPERATING`): the real-valued inputs that leave the geometry alone --
the friction coefficient mu [-], the elastic drum's wall [m] (only where the drum is elastic:
a rigid drum has no wall to differentiate), the idle speed [rpm] (the engine's, or
``EvalSettings.idle_rpm``) -- are differentiated on the *same mesh* as the design (the
design's own, no geometry change): the central difference above with steps 1 % of mu, 0.01
mm of wall, 10 rpm of idle (method ``central, same mesh (operating input)``).  The idle speed
enters no answer above but the engagement limit a x idle (d limit / d idle = a, exact), the
fatigue duty and the requirement checks: its derivatives are zero where the analysis does not
use it, and are reported as computed.  The material (a choice) and the axial thickness (a
concept parameter) are not operating inputs here.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from ..analysis import CONTACT_SPEED_OF, idle_speed
from ..core import ParameterError
from ..core import values as V
from ..loadcase import Design
from .batch import evaluate_many, shared_cluster
from .settings import EvalSettings

#: (row key, unit) of the differentiated answers
ANSWERS: tuple[tuple[str, str], ...] = (
    ("engagement_rpm", "rpm"), ("engagement_rpm_with_ripple", "rpm"), ("slip_rpm", "rpm"),
    ("torque_at_max_engine_torque_Nm", "N m"), ("max_von_mises_Pa", "Pa"), ("safety_factor", "-"),
    ("fatigue_safety_factor", "-"),
    ("mass_kg", "kg"), ("shoe_mass_kg", "kg"), ("contact_arc_deg", "deg"))
#: finite-difference step per parameter unit (module docstring); dimensionless: relative
STEP = {"m": 1e-5, "deg": 0.01}
REL_STEP = 1e-3
#: operating inputs differentiated on the design's own mesh: name -> (unit, step, relative?)
OPERATING: dict[str, tuple[str, float, bool]] = {"mu": ("-", 1e-2, True), "drum_wall": ("m", 1e-5, False),
                                                 "idle_rpm": ("rpm", 10.0, False)}
#: the method of an operating input's derivative
SAME_MESH = "same mesh (operating input)"


@dataclass
class Sensitivities:
    """What :func:`sensitivities` returns: the answers at the design (``base``), and per
    parameter or operating input its value, step, unit, derivative of every answer [answer
    unit / parameter unit, SI], the method used (``central, morphed`` where both sides were
    morphed; ``central, same mesh (operating input)``) and its kind (``parameter`` or
    ``operating input``).

    Examples
    --------
    A hand-made record (:func:`sensitivities` computes one): engagement +1000 rpm per mm of
    flexure, and a contact event inside the step.

    >>> from clutchfem.evaluation import Sensitivities
    >>> s = Sensitivities("concept1", base={"engagement_rpm": 4000.0}, values={"flexure_thickness": 2.2e-3},
    ...                   steps={"flexure_thickness": 1e-5}, units={"flexure_thickness": "m"},
    ...                   derivatives={"flexure_thickness": {"engagement_rpm": 1.0e6}},
    ...                   methods={"flexure_thickness": "central, morphed"},
    ...                   kinks={"flexure_thickness": {"engagement_rpm": {"left": 0.8e6, "right": 1.3e6}}})
    >>> round(s.elasticity("flexure_thickness", "engagement_rpm"), 3)     # % per % (x / A dA/dx)
    0.55
    >>> s.spread_derivative("flexure_thickness", "engagement_rpm")         # the steeper side
    1300000.0
    """

    concept: str
    base: dict
    values: dict
    steps: dict
    units: dict
    derivatives: dict
    methods: dict
    notes: list = field(default_factory=list)
    kinds: dict = field(default_factory=dict)
    #: name -> answer -> the contact event inside the step (module docstring, "Kinks"): the
    #: speed it is at, the one-sided slopes ``left`` / ``right`` [answer unit / SI unit], their
    #: ``jump`` (right - left) / |central| and the loaded contact nodes at x - h, x, x + h
    kinks: dict = field(default_factory=dict)

    def spread_derivative(self, name: str, answer: str) -> float | None:
        """dA/dx for a linearised spread: the central difference, or where a contact event
        lies inside the step (``kinks``) the one-sided slope of larger magnitude, with the
        central difference's sign (conservative across the kink)."""
        d = self.derivatives.get(name, {}).get(answer)
        k = self.kinks.get(name, {}).get(answer)
        if d is None or not k:
            return d
        m = max(abs(v) for v in (d, k["left"], k["right"]) if v is not None)
        return math.copysign(m, d) if d else m

    def elasticity(self, name: str, answer: str) -> float | None:
        """(x / A) dA/dx: the % change of ``answer`` per % change of parameter ``name``."""
        d = self.derivatives.get(name, {}).get(answer)
        a = self.base.get(answer)
        if d is None or not a:
            return None
        return d * self.values[name] / a

    def table(self) -> str:
        """A text table: derivatives per parameter (per mm, per deg or per unit of the value)."""
        head = "parameter".ljust(22) + "".join(k.replace("_with_ripple", "+ripple")[:18].rjust(20) for k, _ in ANSWERS)
        lines = [head, "".ljust(22) + "".join(f"[{u}/unit]".rjust(20) for _, u in ANSWERS)]
        for n, der in self.derivatives.items():
            scale, unit = {"m": (1e-3, "mm"), "deg": (1.0, "deg"), "rpm": (1.0, "rpm")}.get(self.units[n], (1.0, "-"))
            cells = "".join(("-" if der.get(k) is None else f"{der[k] * scale:.5g}").rjust(20) for k, _ in ANSWERS)
            kink = f"; kink: {', '.join(self.kinks[n])}" if self.kinks.get(n) else ""
            lines.append(f"{n} /{unit}".ljust(22) + cells + f"   ({self.methods[n]}{kink})")
        return "\n".join(lines)

    def to_json(self) -> dict:
        return dataclasses.asdict(self)


def step_for(P, name: str, value: float) -> float:
    """The finite-difference step of parameter ``name`` at ``value`` (module docstring)."""
    unit = P.unit(name)
    if unit in STEP:
        return STEP[unit]
    return max(abs(value) * REL_STEP, 1e-6)


def operating_inputs(es: EvalSettings) -> dict[str, float]:
    """The operating inputs of ``es`` that can be differentiated, with their values (mu [-],
    drum_wall [m] only where the drum is elastic, idle_rpm [rpm])."""
    op = es.operating_point()
    out = {"mu": float(op.mu)}
    if op.drum_wall_m:
        out["drum_wall"] = float(op.drum_wall_m)
    out["idle_rpm"] = float(idle_speed(es.engine(), es.idle_rpm)[0])
    return out


def _with_input(es: EvalSettings, name: str, value: float) -> EvalSettings:
    """``es`` with operating input ``name`` at ``value`` (the same geometry and mesh)."""
    if name == "idle_rpm":
        return dataclasses.replace(es, idle_rpm=value)
    return dataclasses.replace(es, op={**es.op, name: value})


def _evaluate_input(es: EvalSettings, name: str, value: float) -> dict:
    """The row of the design with operating input ``name`` at ``value`` (refused: its reason)."""
    try:
        v = _with_input(es, name, value)
        v.study()  # the operating point's own checks (mu >= 0, wall >= 0)
    except ParameterError as exc:
        return {"params": {name: value}, "status": "refused", "message": str(exc)}
    return evaluate_many([{}], v)[0]


def sensitivities(design, names: list[str] | None = None, *, engine=None, requirements=None,
                  workers: int | None = None, morph: bool = True, steps: dict | None = None,
                  scheduler: str | None = None) -> Sensitivities:
    """Derivatives of the main answers of ``design`` with respect to its concept parameters
    and its operating inputs.

    Parameters
    ----------
    design : Design or EvalSettings
        A concept's design (``Design.from_concept``) or the study settings of one: the point
        of the derivatives and the morph reference.
    names : list of str, optional
        Real-valued concept parameters and operating inputs (``mu``, ``drum_wall`` where the
        drum is elastic, ``idle_rpm``) to differentiate (default: every real-valued parameter
        of the concept but the drum radius, the axial thickness and the table profile's
        clearances, and every operating input).
    engine, requirements : optional
        The engine curve and requirement factors of the answers (defaults as ``analyze``).
    workers : int, optional
        Study engine workers (None: one per core; 0: this process).
    morph : bool
        Morph the meshes (default).  False meshes every design from scratch: for measuring
        what morphing buys (the derivatives then carry remeshing noise).
    steps : dict, optional
        name -> finite-difference step in SI units (default: :func:`step_for`; operating
        inputs :data:`OPERATING`).
    scheduler : str, optional
        An existing Dask scheduler's address (instead of ``workers``).

    Returns
    -------
    Sensitivities
        ``derivatives[name][answer]`` in SI units (per rpm for the idle speed),
        ``elasticity(name, answer)``, ``table()``, ``methods`` and ``kinds``.

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> s = cf.sensitivities(d, ["flexure_thickness", "mu"], workers=0)
    >>> s.methods["flexure_thickness"], s.methods["mu"]
    ('central, morphed', 'central, same mesh (operating input)')
    >>> s.derivatives["flexure_thickness"]["engagement_rpm"] > 0    # rpm per m: stiffer beam
    True
    >>> s.derivatives["mu"]["torque_at_max_engine_torque_Nm"] > 0   # N m per unit of mu
    True
    """
    if isinstance(design, EvalSettings):
        es, p0, label = design, design.params(), design.concept
    elif isinstance(design, Design) and design.params is not None:
        es = EvalSettings.from_design(design, engine=engine, requirements=requirements)
        p0, label = design.params, design.name
    else:
        raise ParameterError("design", type(design).__name__, "a concept's Design (Design.from_concept): a user "
                             "mesh has no parameters to differentiate")
    P = type(p0)
    floats = [n for n, f in P.model_fields.items() if f.annotation is float]
    default = [n for n in floats if not n.startswith("table_c") and n not in ("drum_radius", "thickness")]
    inputs = operating_inputs(es)
    names = list(default + list(inputs) if names is None else names)
    for n in names:
        if n == "drum_wall" and n not in inputs:
            raise ParameterError(n, None, "an elastic drum to differentiate its wall (this design's drum is rigid: "
                                 "set drum_wall, e.g. 2mm, or fidelity best)", label)
        if n not in floats and n not in inputs:
            raise ParameterError(n, None, "a real-valued parameter of the concept (" + ", ".join(default)
                                 + ", ...) or an operating input (" + ", ".join(inputs) + ")", label)
    if len(set(names)) != len(names):
        raise ParameterError("names", ",".join(names), "each name once", label)
    if morph:
        es = dataclasses.replace(es, morph=tuple(sorted(es.values().items())))
    points: list[dict] = [{}]
    plan, ops = [], []
    for n in names:
        x = float(inputs[n] if n in inputs else getattr(p0, n))
        h = (steps or {}).get(n)
        if h is None:
            h = step_for(P, n, x) if n not in inputs else (max(abs(x) * OPERATING[n][1], 1e-6) if OPERATING[n][2]
                                                          else OPERATING[n][1])
        h = float(h)
        if not h > 0:
            raise ParameterError(f"steps[{n}]", h, "a positive step in SI units", label)
        lo, hi = V.round12(x - h), V.round12(x + h)
        if n in inputs:
            ops.append((n, x, h, lo, hi))
            continue
        plan.append((n, x, h, len(points), len(points) + 1))
        points += [{n: V.exact_text(P, n, lo)}, {n: V.exact_text(P, n, hi)}]
    with shared_cluster(workers, scheduler):
        rows = evaluate_many(points, es)
        for n, x, h, lo, hi in ops:  # one batch per value: each is another operating point
            plan.append((n, x, h, len(rows), len(rows) + 1))
            rows += [_evaluate_input(es, n, lo), _evaluate_input(es, n, hi)]
    base = rows[0]
    if base["status"] != "ok":
        raise ParameterError("design", label, f"a design the analysis can evaluate ({base['message']})")
    out = Sensitivities(concept=es.concept, base={k: base.get(k) for k, _ in ANSWERS}, values={}, steps={},
                        units={}, derivatives={}, methods={})
    for n, x, h, im, ip in plan:
        rm, rp = rows[im], rows[ip]
        ok_m, ok_p = rm["status"] == "ok", rp["status"] == "ok"
        pairs = ((rm, rp, 2 * h, "central") if ok_m and ok_p else (base, rp, h, "one-sided (+)") if ok_p
                 else (rm, base, h, "one-sided (-)") if ok_m else None)
        out.values[n], out.steps[n] = x, h
        out.units[n] = OPERATING[n][0] if n in inputs else P.unit(n)
        out.kinds[n] = "operating input" if n in inputs else "parameter"
        if pairs is None:
            out.derivatives[n] = {k: None for k, _ in ANSWERS}
            out.methods[n] = "not evaluated: " + (rm.get("message") or rp.get("message") or "")
            continue
        a, b, dx, how = pairs
        used = [r for r in (a, b) if r is not base]
        morphed = False
        if n in inputs:
            out.methods[n] = f"{how}, {SAME_MESH}"
            if any(r.get("elements") != base.get("elements") for r in used):
                out.notes.append(f"{n}: the mesh differs from the design's (element counts "
                                 f"{[r.get('elements') for r in used]} against {base.get('elements')})")
        else:
            morphed = all(r.get("mesh_morphed") == 1 for r in used) if morph else False
            out.methods[n] = f"{how}, " + ("morphed" if morphed else "meshed from scratch")
            if morph and not morphed:
                out.notes.append(f"{n}: " + "; ".join(r.get("morph_note") or "" for r in used))
        out.derivatives[n] = {k: _diff(a.get(k), b.get(k), dx) for k, _ in ANSWERS}
        if how == "central":
            same_nodes = n in inputs or morphed
            kinks = _kinks(rm, base, rp, h, out.derivatives[n]) if same_nodes else None
            if kinks is None and morph:
                out.notes.append(f"{n}: contact events not checked (a side was meshed from scratch, or a row has no "
                                 "contact sets: the contact nodes cannot be compared)")
            elif kinks:
                out.kinks[n] = kinks
                out.notes.append(f"{n}: a contact node enters or leaves within +-{_step_text(h, out.units[n])} at the "
                                 + ", ".join(sorted({k['speed'] for k in kinks.values()}))
                                 + " speed: " + ", ".join(kinks) + " kink there (one-sided slopes in kinks)")
    if not morph:
        out.notes.append("contact events not checked: every design was meshed from scratch (morph=False)")
    if "idle_rpm" in out.derivatives:
        out.notes.append("idle_rpm: the idle speed enters the engagement limit a x idle (d limit / d idle = "
                         f"{es.a:g}, exact) and the requirement checks; the answers move only where the analysis "
                         "uses it (fatigue duty)")
    return out


def _step_text(h: float, unit: str) -> str:
    return f"{h * 1e3:g} mm" if unit == "m" else f"{h:g} {unit}" if unit != "-" else f"{h:g}"


def _kinks(rm: dict, base: dict, rp: dict, h: float, central: dict) -> dict | None:
    """The answers whose contact set changes between x - h and x + h (module docstring,
    "Kinks"); None where the rows' sets cannot be compared (a side meshed from scratch, or a
    row without them)."""
    sets = [r.get("contact_sets") for r in (rm, base, rp)]
    if any(s is None for s in sets):
        return None
    out = {}
    for key, speeds in CONTACT_SPEED_OF.items():
        changed = [sp for sp in speeds if None not in (sets[0].get(sp), sets[1].get(sp), sets[2].get(sp))
                   and not sets[0][sp] == sets[1][sp] == sets[2][sp]]
        if not changed:
            continue
        side = [{sp: s[sp] for sp in changed} if len(changed) > 1 else s[changed[0]] for s in sets]
        speed = " and ".join(changed)
        left, right = _diff(rm.get(key), base.get(key), h), _diff(base.get(key), rp.get(key), h)
        c = central.get(key)
        if left is None or right is None or c is None:
            continue
        out[key] = {"speed": speed, "left": left, "right": right,
                    "jump": (right - left) / abs(c) if c else None,
                    "nodes": {"-": side[0], "0": side[1], "+": side[2]}}
    return out


def _diff(a, b, dx: float) -> float | None:
    if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)):
        return None
    return (b - a) / dx
